// imaging_fuzz — the long run of the imaging subset's differential fuzzer
// (tests/parity/imaging_fuzz.h): N sequences from seeds S, S+1, ..., each run on the emulation
// and on the reference Mesa 7.8.2 and compared under the documented tie rules and departures.
// Each sequence with an unexplained difference is minimised and written to DIR as
// seed_<seed>.c (its differences, then paste-able C). Prints one summary: the sequences run,
// the seeds, the time, the explained differences by name and the unexplained count.
// Exit 0 when every difference is explained, 1 otherwise; bad arguments: one line, exit 2.
// --print writes the sequences as C instead of running them (a seed's case, replayed).
// Usage: build/bin/imaging_fuzz --sequences N [--seed S] [--out DIR] [--print]
#include "parity/imaging_fuzz.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

namespace {

bool parseCount(const char* text, unsigned long long& out) {
  if (text == nullptr || *text == '\0' || *text == '-') return false;
  char* end = nullptr;
  out = std::strtoull(text, &end, 10);
  return end != nullptr && *end == '\0';
}

int usage(const std::string& why) {
  std::fprintf(stderr, "imaging_fuzz: %s (try: imaging_fuzz --help)\n", why.c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  unsigned long long count = 0, seed = 1;
  bool print = false;
  std::string countText, seedText, out = "imaging_fuzz_cases";
  CLI::App app{"the imaging subset's differential fuzzer against Mesa 7.8.2 (docs/imaging.md)",
               "imaging_fuzz"};
  app.add_option("--sequences", countText, "how many sequences to run (from --seed on)")
      ->required()
      ->type_name("N");
  app.add_option("--seed", seedText, "the first sequence's seed [1]")->type_name("S");
  app.add_option("--out", out, "directory for the unexplained cases [imaging_fuzz_cases]")
      ->type_name("DIR");
  app.add_flag("--print", print, "write the sequences as C instead of running them");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  } catch (const CLI::ParseError& e) {
    return usage(e.what());
  }
  if (!parseCount(countText.c_str(), count) || count == 0)
    return usage("--sequences needs a positive integer, got '" + countText + "'");
  if (!seedText.empty() && !parseCount(seedText.c_str(), seed))
    return usage("--seed needs a non-negative integer, got '" + seedText + "'");
  if (out.empty()) return usage("--out needs a directory");
  if (print) {  // the sequences as C, nothing run
    for (unsigned long long k = 0; k < count; ++k)
      std::fputs(sl::imaging::fuzz::toC(sl::imaging::fuzz::generate(seed + k)).c_str(), stdout);
    return 0;
  }
  if (sl::referenceGlPath().empty()) {
    std::fprintf(stderr, "imaging_fuzz: the reference GL (Mesa 7.8.2) is not available\n");
    return 2;
  }
  namespace fuzz = sl::imaging::fuzz;
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) return usage("cannot create '" + out + "': " + ec.message());
  const auto start = std::chrono::steady_clock::now();
  std::map<std::string, long long> explained;
  long long differing = 0, unexplained = 0;
  for (unsigned long long k = 0; k < count; ++k) {
    const fuzz::Sequence s = fuzz::generate(seed + k);
    const fuzz::Verdict v = fuzz::compare(s, fuzz::runAll(s));
    for (const auto& [name, n] : v.explained) explained[name] += n;
    if (!v.agree()) {
      ++differing;
      unexplained += v.unexplainedCount;
      const fuzz::Sequence m = fuzz::minimise(s);
      const fuzz::Verdict mv = fuzz::compare(m, fuzz::runAll(m));
      std::ofstream f(out + "/seed_" + std::to_string(seed + k) + ".c");
      f << "// seed " << seed + k << ": " << v.unexplainedCount
        << " unexplained differences; minimised (" << s.calls.size() << " -> " << m.calls.size()
        << " calls):\n";
      for (const auto& l : mv.unexplained) f << "//   " << l << "\n";
      f << fuzz::toC(m);
    }
    if ((k + 1) % 10000 == 0)
      std::fprintf(stderr, "imaging_fuzz: %llu sequences, %lld with unexplained differences\n",
                   k + 1, differing);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("imaging_fuzz: %llu sequences (seeds %llu..%llu) in %.0f s\n", count, seed,
              seed + count - 1, seconds);
  std::printf("explained differences (values):\n");
  if (explained.empty()) std::printf("  none\n");
  for (const auto& [name, n] : explained) std::printf("  %lld  %s\n", n, name.c_str());
  std::printf("sequences with unexplained differences: %lld (%lld values), written to %s\n",
              differing, unexplained, out.c_str());
  return differing == 0 ? 0 : 1;
}
