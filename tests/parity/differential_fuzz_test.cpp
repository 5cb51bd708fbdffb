// parity.DifferentialFuzz: the differential fuzzer (imaging_fuzz.h) on a fixed set of seeds.
// Each seed's sequence runs on the emulation and on the reference (Mesa 7.8.2); every value
// must agree under the documented tie rules and departures. The long run is the developer
// tool build/bin/imaging_fuzz (docs/imaging.md); what it finds becomes a case in
// fuzz_regressions_test.cpp.
#include "parity/imaging_fuzz.h"
#include "parity/parity_util.h"

namespace sl::imaging::testing {
namespace {

// Seeds per test: sized so that the whole group takes well under a minute on two cores.
constexpr uint64_t kSeedsPerBlock = 150;

void runSeeds(uint64_t first) {
  SL_REQUIRE_REFERENCE();
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

// The generator is a pure function of the seed (a found case is replayed by its seed).
TEST(DifferentialFuzz, GeneratorIsDeterministic) {
  for (uint64_t seed : {1ull, 77ull, 123456789ull}) {
    EXPECT_EQ(fuzz::toC(fuzz::generate(seed)), fuzz::toC(fuzz::generate(seed)));
  }
  EXPECT_NE(fuzz::toC(fuzz::generate(1)), fuzz::toC(fuzz::generate(2)));
}

}  // namespace
}  // namespace sl::imaging::testing
