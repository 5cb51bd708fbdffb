// parity.DifferentialFuzz: the differential fuzzer (imaging_fuzz.h) on a fixed set of seeds.
// Each seed's sequence runs on the emulation and on the reference (Mesa 7.8.2); every value
// must agree under the documented tie rules and departures. The long run is the developer
// tool build/bin/imaging_fuzz (docs/imaging.md); what it finds becomes a case in
// fuzz_regressions_test.cpp.
#include "parity/imaging_fuzz.h"
#include "parity/parity_util.h"

namespace sl::imaging::testing {
namespace {

// Seeds per test: 2,500 sequences take about 2 s here (small images, contexts kept), so the
// four blocks stay well under a minute on two cores.
constexpr uint64_t kSeedsPerBlock = 2500;

void runSeeds(uint64_t first) {
  SL_REQUIRE_REFERENCE();
  // Through the drop-in library (interpose.parity_through_preloaded_library) the fuzzer would
  // still make its own in-process contexts: nothing of the library's is exercised.
  if (preloadedPath()) GTEST_SKIP() << "the differential fuzzer runs in process only";
  for (uint64_t seed = first; seed < first + kSeedsPerBlock; ++seed) {
    const fuzz::Sequence s = fuzz::generate(seed);
    const fuzz::Verdict v = fuzz::compare(s, fuzz::runAll(s));
    if (!v.agree()) {
      std::string lines;
      for (const auto& l : v.unexplained) lines += "  " + l + "\n";
      ADD_FAILURE() << "seed " << seed << ": " << v.unexplainedCount << " unexplained\n"
                    << lines << fuzz::toC(s);
    }
  }
}

TEST(DifferentialFuzz, SeedsBlock0) { runSeeds(1); }
TEST(DifferentialFuzz, SeedsBlock1) { runSeeds(1 + kSeedsPerBlock); }
TEST(DifferentialFuzz, SeedsBlock2) { runSeeds(1 + 2 * kSeedsPerBlock); }
TEST(DifferentialFuzz, SeedsBlock3) { runSeeds(1 + 3 * kSeedsPerBlock); }

// The generator is a pure function of the seed (a found case is replayed by its seed).
TEST(DifferentialFuzz, GeneratorIsDeterministic) {
  for (uint64_t seed : {1ull, 77ull, 123456789ull}) {
    EXPECT_EQ(fuzz::toC(fuzz::generate(seed)), fuzz::toC(fuzz::generate(seed)));
  }
  EXPECT_NE(fuzz::toC(fuzz::generate(1)), fuzz::toC(fuzz::generate(2)));
}

}  // namespace
}  // namespace sl::imaging::testing
