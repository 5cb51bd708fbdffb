// --param bias of the PCF family (measure/bias_table.h) on the stability suite's grazing case:
// with no slope-scaled polygon offset in GPU Gems PCF's light pass (the Brabec–Seidel twins have
// none), so that the method alone copes with the ground's slope, the receiver-plane depth bias
// (ours, after Isidoro 2006, Dou et al. 2014) and the normal offset (ours, after Holbert 2011)
// leave less acne than the constant bias at the same constant, and light no more of the shadow
// (peter-panning). docs/bias.md holds the whole table (tools/bias_table.cpp).
#include <gtest/gtest.h>

#include <cctype>
#include <string>

#include "measure/bias_table.h"

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
  const Row constant = measure("grazing80", v, factor, "constant");
  ASSERT_TRUE(constant.finite);
  for (const std::string& method : biasMethods(v)) {
    if (method == "constant") continue;
    const Row r = measure("grazing80", v, factor, method);
    ASSERT_TRUE(r.finite) << method;
    EXPECT_LT(r.acne, constant.acne) << method << " on " << v.technique << " " << v.kernel;
    EXPECT_LE(r.peterPanning, constant.peterPanning + kPeterPanningSlack)
        << method << " on " << v.technique << " " << v.kernel;
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
