// modern.evsm2 and modern.evsm4 (ours, after Lauritzen & McCool 2008, not in shared/papers):
// the warps and Chebyshev's bound mirrored here on hand-computed cases, the rendered umbra of the
// analytic scene against that mirror, the clamp of the exponents to the storage format, the
// refusals, and no NaN/Inf at the stiffest settings.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/errors.h"
#include "filtered_shadows_util.h"
#include "modern/exponential_variance_shadow_map.h"

namespace sl {
namespace {
using namespace sl::testing_filtered;
using modern::evsmChebyshev;
using modern::evsmNegativeWarp;
using modern::evsmPositiveWarp;

double linearDepthOfY(const Scene& scene, float y) {
  const DepthRange range = lightDepthRange(scene);
  const glm::vec4 v = lightView(scene.light) * glm::vec4(0.0f, y, 0.0f, 1.0f);
  return (double(-v.z) - range.nearPlane) / (double(range.farPlane) - range.nearPlane);
}

double occluderTopY(const Scene& scene) {
  for (const Object& o : scene.objects)
    if (o.name == "occluder") return worldBounds(o).hi.y;
  return 0.0;
}

// Chebyshev's bound without the scaling, in long double: the mirror must equal it.
double plainBound(double mean, double meanSquare, double w, double c, double minVariance) {
  if (w <= mean) return 1.0;
  const long double slope = 2.0L * c * mean;
  const long double variance =
      std::max((long double)meanSquare - (long double)mean * mean, minVariance * slope * slope);
  const long double delta = (long double)w - mean;
  return double(variance / (variance + delta * delta));
}

TEST(Evsm, WarpsIncreaseWithDepthAndTheScalingLeavesTheBoundAsItIs) {
  for (const double c : {1.0, 5.54, 42.0})
    for (double z = 0.0; z < 1.0; z += 0.125) {
      EXPECT_LT(evsmPositiveWarp(c, z), evsmPositiveWarp(c, z + 0.125)) << c << " " << z;
      EXPECT_LT(evsmNegativeWarp(c, z), evsmNegativeWarp(c, z + 0.125)) << c << " " << z;
    }
  // Two blockers (z = 0.2, 0.5) and the receiver's own surface (z = 0.7) in thirds, receiver 0.7.
  for (const double c : {2.0, 5.0}) {
    double mean = 0, meanSquare = 0;
    for (const double z : {0.2, 0.5, 0.7}) {
      mean += evsmPositiveWarp(c, z) / 3;
      meanSquare += evsmPositiveWarp(c, z) * evsmPositiveWarp(c, z) / 3;
    }
    const double w = evsmPositiveWarp(c, 0.7);
    // Relative 1e-12: doubles, a handful of operations each.
    EXPECT_NEAR(evsmChebyshev(mean, meanSquare, w, c, 1e-5, 0.0),
                plainBound(mean, meanSquare, w, c, 1e-5), 1e-12);
    // An upper bound on the true lit share (1/3): Chebyshev never says less.
    EXPECT_GE(evsmChebyshev(mean, meanSquare, w, c, 0.0, 0.0), 1.0 / 3.0 - 1e-12);
  }
}

// Light bleeding, hand-computed: half the footprint a blocker near the light (z = 0.1), half a
// blocker just in front of the receiver (z = 0.55), receiver at 0.6: nothing is lit. VSM's
// bound on the moments of z itself lets 0.40 through (variance 0.050625, gap 0.275);
// the positive warp at c = 5 squeezes the near blocker towards 0 and lets much less through.
TEST(Evsm, PositiveWarpBleedsLessThanVsmOnTwoBlockers) {
  const double zs[2] = {0.1, 0.55}, d = 0.6;
  double m1 = 0, m2 = 0;
  for (const double z : zs) m1 += z / 2, m2 += z * z / 2;
  const double vsm = (m2 - m1 * m1) / ((m2 - m1 * m1) + (d - m1) * (d - m1));
  EXPECT_NEAR(vsm, 0.050625 / (0.050625 + 0.275 * 0.275), 1e-12);  // 0.401
  constexpr double c = 5.0;
  double p1 = 0, p2 = 0;
  for (const double z : zs)
    p1 += evsmPositiveWarp(c, z) / 2, p2 += evsmPositiveWarp(c, z) * evsmPositiveWarp(c, z) / 2;
  const double evsm2 = evsmChebyshev(p1, p2, evsmPositiveWarp(c, d), c, 0.0, 0.0);
  EXPECT_LT(evsm2, 0.5 * vsm) << "vsm " << vsm << " evsm2 " << evsm2;
}

// The analytic scene's umbra: one occluder depth z under the footprint, variance 0, so the bound
// is the variance floor's: the mirror evaluated on (w(z), w(z)^2) and the ground's w(d).
TEST(Evsm, UmbraOnAPlaneIsTheMirroredBound) {
  const Scene scene = builtinScene("analytic");
  const double z = linearDepthOfY(scene, float(occluderTopY(scene)));
  const double d = linearDepthOfY(scene, 0.0f);
  constexpr double kMinVariance = 0.05;  // a large floor: a bound well above fp32 noise
  for (const char* name : {"modern.evsm2", "modern.evsm4"}) {
    for (const double c : {1.0, 3.0}) {
      const RenderParams p = smallParams(160, 120, 256,
                                         {{"positive-exponent", std::to_string(c)},
                                          {"negative-exponent", std::to_string(c)},
                                          {"min-variance", std::to_string(kMinVariance)},
                                          {"blur", "5"}});
      RenderParams q = p;
      if (std::string(name) == "modern.evsm2") q.extra.erase("negative-exponent");
      const Frame frame = renderByName(name, scene, q);
      const double pz = evsmPositiveWarp(c, z), nz = evsmNegativeWarp(c, z);
      double expected = evsmChebyshev(pz, pz * pz, evsmPositiveWarp(c, d), c, kMinVariance, 0.0);
      if (std::string(name) == "modern.evsm4")
        expected = std::min(
            expected, evsmChebyshev(nz, nz * nz, evsmNegativeWarp(c, d), c, kMinVariance, 0.0));
      const glm::ivec2 umbra = pixelOf(scene, q, {0.0f, 0.0f, 0.25f});  // see csm_test.cpp
      const glm::ivec2 lit = pixelOf(scene, q, {1.8f, 0.0f, 0.3f});
      // The bound is small here (the gap is ~0.96 of the depth range): relative, 1% of it. fp32
      // moments: E[w^2] - E[w]^2 cancels to ~1e-7 relative, far below the floor (0.05 (2c)^2
      // relative); 1e-5 absolute for the occluder face's rasterised depth.
      const double umbraTolerance = 1e-5 + 0.01 * expected;
      EXPECT_NEAR(frame.visibility.at(umbra.x, umbra.y), expected, umbraTolerance)
          << name << " " << c;
      constexpr double kTolerance = 1e-3;
      EXPECT_NEAR(frame.visibility.at(lit.x, lit.y), 1.0, kTolerance) << name << " " << c;
    }
  }
}

// exp(2 c) must fit the storage: fp16 clamps the exponents to 5.54, fp32 keeps up to 42.
TEST(Evsm, ExponentsAreClampedToTheStorageFormat) {
  EXPECT_LT(std::exp(2 * modern::kEvsmMaxExponentFloat16), 65504.0);
  EXPECT_LT(std::exp(2 * modern::kEvsmMaxExponentFloat32), 3.4e38);
  const Scene scene = builtinScene("analytic");
  const Frame half = renderByName(
      "modern.evsm4", scene,
      smallParams(80, 60, 128,
                  {{"storage", "16"}, {"positive-exponent", "42"}, {"negative-exponent", "20"}}));
  EXPECT_DOUBLE_EQ(half.counters.at("positive_exponent"), modern::kEvsmMaxExponentFloat16);
  EXPECT_DOUBLE_EQ(half.counters.at("negative_exponent"), modern::kEvsmMaxExponentFloat16);
  const Frame halfSmall =
      renderByName("modern.evsm2", scene,
                   smallParams(80, 60, 128, {{"storage", "16"}, {"positive-exponent", "3"}}));
  EXPECT_DOUBLE_EQ(halfSmall.counters.at("positive_exponent"), 3.0);  // under the limit: as asked
  const Frame full =
      renderByName("modern.evsm2", scene, smallParams(80, 60, 128, {{"positive-exponent", "42"}}));
  EXPECT_DOUBLE_EQ(full.counters.at("positive_exponent"), 42.0);
}

TEST(Evsm, NoNanOrInfAtTheStiffestSettings) {
  for (const char* name : {"modern.evsm2", "modern.evsm4"})
    for (const char* sceneName : {"analytic", "brabec", "fence"})
      for (const char* storage : {"16", "float"}) {
        std::map<std::string, std::string> extra = {{"storage", storage},
                                                    {"positive-exponent", "42"},
                                                    {"min-variance", "0"},
                                                    {"blur", "7"}};
        if (std::string(name) == "modern.evsm4") extra["negative-exponent"] = "42";
        const Frame f =
            renderByName(name, builtinScene(sceneName), smallParams(96, 72, 128, extra));
        EXPECT_TRUE(allFinite(f.visibility)) << name << " " << sceneName << " " << storage;
        EXPECT_TRUE(allFinite(f.color)) << name << " " << sceneName << " " << storage;
        for (const PassImage& image : f.intermediates)
          EXPECT_TRUE(allFinite(image.image)) << name << " " << image.name;
        for (float v : f.visibility.data) {
          ASSERT_GE(v, 0.0f) << name << " " << sceneName;
          ASSERT_LE(v, 1.0f) << name << " " << sceneName;
        }
      }
}

TEST(Evsm, BadParametersAreInputErrors) {
  const Scene scene = builtinScene("analytic");
  for (const auto& [key, value] :
       std::vector<std::pair<std::string, std::string>>{{"blur", "4"},
                                                        {"positive-exponent", "43"},
                                                        {"positive-exponent", "0"},
                                                        {"negative-exponent", "43"},
                                                        {"min-variance", "-1"},
                                                        {"bleed-reduction", "1"},
                                                        {"storage", "8"}}) {
    EXPECT_THROW(renderByName("modern.evsm4", scene, smallParams(32, 32, 32, {{key, value}})),
                 InputError)
        << key << "=" << value;
  }
  // EVSM2 has no negative warp: its exponent is not one of its params.
  EXPECT_THROW(
      renderByName("modern.evsm2", scene, smallParams(32, 32, 32, {{"negative-exponent", "5"}})),
      InputError);
}

}  // namespace
}  // namespace sl
