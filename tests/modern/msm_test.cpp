// modern.msm (ours, after Peters & Klein 2015, not in shared/papers): the Hamburger 4-moment
// reconstruction mirrored here against hand-computed two-occluder cases, the optimised 16-bit
// quantisation, the rendered umbra of the analytic scene against the mirror, refusals, and no
// NaN/Inf on stiff settings.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "core/base/errors.h"
#include "filtered_shadows_util.h"
#include "modern/moment_shadow_map.h"

namespace sl {
namespace {
using namespace sl::testing_filtered;
using modern::msmShadowIntensity;

std::array<double, 4> momentsOf(const std::vector<std::pair<double, double>>& weightedDepths) {
  std::array<double, 4> b{0, 0, 0, 0};
  for (const auto& [w, z] : weightedDepths)
    for (int k = 0; k < 4; ++k) b[size_t(k)] += w * std::pow(z, k + 1);
  return b;
}

// Two occluders, 40% of the footprint at z = 0.2 and 60% at z = 0.5. Four moments of a 2-point
// distribution determine it, so in the limit of no bias the reconstruction is exact: nothing in
// front of a receiver at 0.1, the near occluder's 40% in front of one at 0.35, all of it in front
// of one at 0.7 (worked by hand: the 3-point distribution on {zf, z2, z3} with these moments is
// the 2-point one itself, with weight 0 at zf).
TEST(Msm, HamburgerReconstructionIsExactOnTwoOccluders) {
  const std::array<double, 4> b = momentsOf({{0.4, 0.2}, {0.6, 0.5}});
  constexpr double kTinyBias = 1e-9;  // the bias only keeps the Hankel matrix invertible
  // Error of order the bias over the smallest pivot (~1e-9 / 1e-3): 1e-5 is ample.
  constexpr double kTolerance = 1e-5;
  EXPECT_NEAR(msmShadowIntensity(b, 0.1, kTinyBias), 0.0, kTolerance);
  EXPECT_NEAR(msmShadowIntensity(b, 0.35, kTinyBias), 0.4, kTolerance);
  EXPECT_NEAR(msmShadowIntensity(b, 0.7, kTinyBias), 1.0, kTolerance);
  // The default bias 3e-5 costs a little of the shadow, never more than a percent here.
  EXPECT_NEAR(msmShadowIntensity(b, 0.7, modern::kMsmDefaultMomentBias), 1.0, 0.01);
  EXPECT_NEAR(msmShadowIntensity(b, 0.35, modern::kMsmDefaultMomentBias), 0.4, 0.01);
}

// VSM's bleeding case: a blocker near the light and one just in front of the receiver, half the
// footprint each. Chebyshev's bound on (z, z^2) lets 0.40 through (evsm_test.cpp); four moments
// know that both are in front: the shadow intensity is about 1.
TEST(Msm, TwoBlockersInFrontShadowFully) {
  const std::array<double, 4> b = momentsOf({{0.5, 0.1}, {0.5, 0.55}});
  EXPECT_GT(msmShadowIntensity(b, 0.6, modern::kMsmDefaultMomentBias), 0.95);
}

// Peters & Klein §4.3's map takes the moments of every depth in [0, 1] into [0, 1] (16-bit UNORM
// keeps them), depth 0 to (o, 0, 0, 0) and depth 1 to about (1, 1, 0.89, 0), and is invertible.
TEST(Msm, OptimisedQuantisationStaysInTheUnitRange) {
  for (double z = 0.0; z <= 1.0; z += 1.0 / 64) {
    const std::array<double, 4> b = momentsOf({{1.0, z}});
    for (int j = 0; j < 4; ++j) {
      double q = j == 0 ? modern::kMsmQuantizationOffset : 0.0;
      for (int i = 0; i < 4; ++i) q += b[size_t(i)] * modern::kMsmQuantization[i][j];
      // 1e-6: the published constants are rounded to about 10 digits.
      EXPECT_GE(q, -1e-6) << "z " << z << " q" << j;
      EXPECT_LE(q, 1.0 + 1e-6) << "z " << z << " q" << j;
    }
  }
}

double linearDepthOfY(const Scene& scene, float y) {
  const DepthRange range = lightDepthRange(scene);
  const glm::vec4 v = lightView(scene.light) * glm::vec4(0.0f, y, 0.0f, 1.0f);
  return (double(-v.z) - range.nearPlane) / (double(range.farPlane) - range.nearPlane);
}

// The analytic scene's umbra: one occluder depth under the footprint (moments z, z^2, z^3, z^4),
// the ground behind it: the rendered visibility is 1 - the mirror's intensity.
TEST(Msm, UmbraOnAPlaneIsTheMirroredReconstruction) {
  const Scene scene = builtinScene("analytic");
  double top = 0.0;
  for (const Object& o : scene.objects)
    if (o.name == "occluder") top = worldBounds(o).hi.y;
  const double z = linearDepthOfY(scene, float(top)), d = linearDepthOfY(scene, 0.0f);
  for (const char* storage : {"float", "16"}) {
    for (const double bias : {1e-3, 1e-2}) {  // large enough to dominate fp32 and 16-bit noise
      const RenderParams p =
          smallParams(160, 120, 256,
                      {{"storage", storage}, {"moment-bias", std::to_string(bias)}, {"blur", "5"}});
      const Frame frame = renderByName("modern.msm", scene, p);
      const double expected = 1.0 - msmShadowIntensity(momentsOf({{1.0, z}}), d, bias);
      const glm::ivec2 umbra = pixelOf(scene, p, {0.0f, 0.0f, 0.25f});  // see csm_test.cpp
      const glm::ivec2 lit = pixelOf(scene, p, {1.8f, 0.0f, 0.3f});
      // 16-bit moments round to 1.5e-5, which the bias (>= 1e-3) dwarfs; 2e-3 absolute.
      constexpr double kTolerance = 2e-3;
      // The umbra's visibility is only what the bias lets through (~1e-3): relative, 10% of it
      // (16-bit rounding of the moments moves the reconstruction by a few %).
      EXPECT_NEAR(frame.visibility.at(umbra.x, umbra.y), expected, 1e-5 + 0.1 * expected)
          << storage << " bias " << bias;
      // Lit: the empty map (depth 1) behind the ground; the bias spreads alpha over [0, 1],
      // which the reconstruction partly counts as shadow (under alpha).
      const double lit1 = 1.0 - msmShadowIntensity(momentsOf({{1.0, 1.0}}), d, bias);
      EXPECT_NEAR(frame.visibility.at(lit.x, lit.y), lit1, kTolerance) << storage;
    }
  }
}

TEST(Msm, NoNanOrInfOnStiffSettings) {
  for (const char* sceneName : {"analytic", "brabec", "fence"})
    for (const char* storage : {"16", "float"})
      for (const char* bias : {"0", "3e-05"}) {
        const Frame f = renderByName(
            "modern.msm", builtinScene(sceneName),
            smallParams(96, 72, 128, {{"storage", storage}, {"moment-bias", bias}, {"blur", "7"}}));
        EXPECT_TRUE(allFinite(f.visibility)) << sceneName << " " << storage << " " << bias;
        EXPECT_TRUE(allFinite(f.color)) << sceneName << " " << storage << " " << bias;
        for (const PassImage& image : f.intermediates)
          EXPECT_TRUE(allFinite(image.image)) << sceneName << " " << image.name;
        for (float v : f.visibility.data) {
          ASSERT_GE(v, 0.0f) << sceneName;
          ASSERT_LE(v, 1.0f) << sceneName;
        }
      }
}

TEST(Msm, BadParametersAreInputErrors) {
  const Scene scene = builtinScene("analytic");
  for (const auto& [key, value] :
       std::vector<std::pair<std::string, std::string>>{{"blur", "4"},
                                                        {"moment-bias", "-1"},
                                                        {"moment-bias", "0.6"},
                                                        {"storage", "8"},
                                                        {"quantization", "fancy"}}) {
    EXPECT_THROW(renderByName("modern.msm", scene, smallParams(32, 32, 32, {{key, value}})),
                 InputError)
        << key << "=" << value;
  }
}

}  // namespace
}  // namespace sl
