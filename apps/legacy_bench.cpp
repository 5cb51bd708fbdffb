// legacy_bench — Brabec & Seidel 2001 §5 in the paper's configuration, per pass, beside the
// paper's Octane VPro/8 frame rates. Prints a markdown table (docs/legacy.md).
//   legacy_bench [--backend osmesa|reference] [--frames N] [--quick] [--technique T]
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/scene_library.h"
#include "legacy_gl/benchmark.h"

int main(int argc, char** argv) {
  try {
    sl::legacy::BenchmarkOptions options;
    std::string only;  // --technique: keep the variants of one technique
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--backend" && i + 1 < argc) {
        options.backend = sl::parseBackend(argv[++i]);
      } else if (a == "--frames" && i + 1 < argc) {
        options.frames.timed = std::stoi(argv[++i]);
        if (options.frames.timed < 1) throw sl::InputError("--frames must be at least 1");
      } else if (a == "--technique" && i + 1 < argc) {
        only = argv[++i];
      } else if (a == "--quick") {
        options.frames = sl::kQuickFrames;
      } else {
        throw sl::InputError(
            "usage: legacy_bench [--backend osmesa|reference] [--frames N] [--quick] "
                             "[--technique legacy.ramp|legacy.pcf|legacy.fast-pcf]");
      }
    }
    std::vector<sl::legacy::BenchmarkVariant> variants;
    for (const auto& v : sl::legacy::paperVariants())
      if (only.empty() || v.technique == only) variants.push_back(v);
    if (variants.empty()) throw sl::InputError("no benchmark variant of technique '" + only + "'");
    const auto results =
        sl::legacy::benchmarkBrabecSeidel(sl::builtinScene("brabec"), options, variants);
    std::cout << sl::legacy::benchmarkMarkdown(results);
    return 0;
  } catch (const sl::InputError& e) {
    std::cerr << "legacy_bench: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "legacy_bench: " << e.what() << "\n";
    return 1;
  }
}
