// --param bias of the PCF family (measure/bias_table.h) on the stability suite's grazing case:
// with no slope-scaled polygon offset in GPU Gems PCF's light pass (the Brabec–Seidel twins have
// none), so that the method alone copes with the ground's slope, the receiver-plane depth bias
// (ours, after Isidoro 2006, Dou et al. 2014) and the normal offset (ours, after Holbert 2011)
// leave less acne than the constant bias at the same constant, and light no more of the shadow
// (peter-panning). docs/bias.md holds the whole table (tools/bias_table.cpp).
#include <gtest/gtest.h>

#include <cctype>
#include <ostream>
#include <string>
#include <vector>

#include "measure/bias_table.h"

namespace sl::measure::bias {
// The test's name says the variant; gtest prints this instead of the struct's bytes.
void PrintTo(const Variant& v, std::ostream* os) {
  *os << v.technique << (v.kernel.empty() ? "" : " kernel=" + v.kernel);
}
}  // namespace sl::measure::bias

namespace sl {
namespace {
using namespace sl::measure::bias;

// A method may light a few more of the post's shadow pixels than the constant bias where the
// shadow's outline runs just outside the 2-pixel band: 0.5% of the shadowed pixels, a handful
// at 160x120, where acne is measured in tens of percent.
constexpr double kPeterPanningSlack = 0.005;

class BiasMethods : public ::testing::TestWithParam<Variant> {};

TEST_P(BiasMethods, SlopeAwareMethodsHaveLessAcneOnGrazing80AtNoMorePeterPanning) {
  const Variant v = GetParam();
  // GPU Gems PCF without its slope-scaled polygon offset; the Brabec–Seidel twins have none.
  const double factor = offsetFactors(v).back();
  const Row constant = measure::bias::measure("grazing80", v, factor, "constant");
  ASSERT_TRUE(constant.finite);
  for (const std::string& method : biasMethods(v)) {
    if (method == "constant") continue;
    const Row r = measure::bias::measure("grazing80", v, factor, method);
    ASSERT_TRUE(r.finite) << method;
    EXPECT_LT(r.acne, constant.acne) << method << " on " << v.technique << " " << v.kernel;
    EXPECT_LE(r.peterPanning, constant.peterPanning + kPeterPanningSlack)
        << method << " on " << v.technique << " " << v.kernel;
  }
}

// With the edge band counted too, the receiver plane without GPU Gems PCF's slope-scaled polygon
// offset lights no more of the post's shadow than the technique's default (the constant bias with
// its polygon offset, factor 4), and has no more acne: the plane replaces the slope offset. (The
// constant bias without the slope offset lights less of the shadow's outline, because its acne
// darkens it too; the normal offset lights more of the contact case's outline: docs/bias.md.)
// Slack: two of the ~180 shadowed pixels counted on grazing80 at 160x120, where the two
// lookups' texels round differently at the outline.
constexpr double kTwoShadowedPixels = 0.012;
// Acne, band included, is a share of the ~15000 lit pixels: 0.1% lets gems4's dither put a dozen
// pixels either way along the post's outline.
constexpr double kDitherAlongTheOutline = 0.001;

TEST(BiasMethodsGemsPcf, ReceiverPlaneWithoutSlopeOffsetMatchesTheDefaultOnGrazing80BandIncluded) {
  for (const Variant& v : biasVariants()) {
    const std::vector<double> factors = offsetFactors(v);
    if (factors.front() == kNoOffsetFactor) continue;  // no polygon offset to replace
    const Row defaults = measure::bias::measure("grazing80", v, factors.front(), "constant");
    const Row plane = measure::bias::measure("grazing80", v, factors.back(), "receiver-plane");
    EXPECT_LE(plane.acneWithBand, defaults.acneWithBand + kDitherAlongTheOutline) << v.technique;
    EXPECT_LE(plane.peterPanningWithBand, defaults.peterPanningWithBand + kTwoShadowedPixels)
        << v.technique << " " << v.kernel;
  }
}

INSTANTIATE_TEST_SUITE_P(GemsPcf, BiasMethods, ::testing::ValuesIn(biasVariants()),
                         [](const auto& info) {
                           std::string name = info.param.technique + info.param.kernel;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace sl
