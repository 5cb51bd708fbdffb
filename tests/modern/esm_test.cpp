// modern.esm (ours, after Annen et al. 2008, not in shared/papers) against the exponential test
// computed here on the analytic scene (one occluder depth over a plane at a known depth), the
// clamp of the exponent to the storage format, its refusals, and no NaN/Inf on stiff settings.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/errors.h"
#include "core/base/metrics.h"
#include "filtered_shadows_util.h"
#include "modern/exponential_shadow_map.h"

namespace sl {
namespace {
using namespace sl::testing_filtered;

// Linear light depth (the technique's, lightDepthRange) of the point (0, y, 0).
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

// The mirror of esm_shadow.frag on hand-computed values.
TEST(Esm, CpuMirrorOfTheTest) {
  constexpr double c = 10.0, z = 0.3;
  // A receiver at the blocker's own depth is lit, one behind it darkened by exp(-c (d - z)).
  EXPECT_DOUBLE_EQ(modern::esmVisibility(c, std::exp(c * z), z), 1.0);
  EXPECT_NEAR(modern::esmVisibility(c, std::exp(c * z), 0.5), std::exp(-2.0), 1e-12);
  // In front of every blocker: the product exceeds 1 and is clamped.
  EXPECT_DOUBLE_EQ(modern::esmVisibility(c, std::exp(c * z), 0.1), 1.0);
  // Half the footprint at the receiver's depth, half far in front: about half lit.
  const double d = 0.8, half = 0.5 * std::exp(c * d) + 0.5 * std::exp(c * 0.1);
  EXPECT_NEAR(modern::esmVisibility(c, half, d), 0.5, 1e-3);  // exp(-7)/2 = 4.6e-4 from blocker
}

// A plane under one flat occluder: every texel of the umbra's footprint holds the occluder's
// depth z, the ground is at d, so visibility = exp(-c (d - z)) exactly (up to fp32).
TEST(Esm, UmbraOnAPlaneIsTheExponentialOfTheDepthGap) {
  const Scene scene = builtinScene("analytic");
  const double z = linearDepthOfY(scene, float(occluderTopY(scene)));
  const double d = linearDepthOfY(scene, 0.0f);
  ASSERT_GT(d - z, 0.05) << "the analytic scene's gap should be a sizeable part of the range";
  // Exponents that keep exp(-c (d - z)) well above fp32 rounding (the gap is ~0.2 of the range).
  for (const double c : {2.0, 5.0, 10.0}) {
    const RenderParams p =
        smallParams(160, 120, 256, {{"exponent", std::to_string(c)}, {"blur", "5"}});
    const Frame frame = renderByName("modern.esm", scene, p);
    const double expected = std::exp(-c * (d - z));
    const glm::ivec2 umbra = pixelOf(scene, p, {0.0f, 0.0f, 0.25f});  // see csm_test.cpp
    const glm::ivec2 lit = pixelOf(scene, p, {1.8f, 0.0f, 0.3f});
    // float32 exp(c z) blurred and mip-mapped: relative error ~1e-6; the visibility buffer is
    // float. 1e-4 absolute leaves room for the rasterised depth of the occluder's top face.
    constexpr double kTolerance = 1e-4;
    EXPECT_NEAR(frame.visibility.at(umbra.x, umbra.y), expected, kTolerance) << "c " << c;
    EXPECT_NEAR(frame.visibility.at(lit.x, lit.y), 1.0, kTolerance) << "c " << c;
    EXPECT_DOUBLE_EQ(frame.counters.at("exponent"), c);
  }
}

// exp(c) of depth 1 must fit the storage: c is clamped to 10.5 in fp16 (ln 65504 = 11.09) and
// kept as asked in fp32 up to 88 (ln FLT_MAX = 88.7).
TEST(Esm, ExponentIsClampedToTheStorageFormat) {
  const Scene scene = builtinScene("analytic");
  EXPECT_DOUBLE_EQ(modern::esmEffectiveExponent(80.0, true), 10.5);
  EXPECT_DOUBLE_EQ(modern::esmEffectiveExponent(80.0, false), 80.0);
  EXPECT_LT(std::exp(modern::kEsmMaxExponentFloat16), 65504.0);
  EXPECT_LT(std::exp(modern::kEsmMaxExponentFloat32), 3.4e38);
  const Frame half = renderByName(
      "modern.esm", scene, smallParams(80, 60, 128, {{"storage", "16"}, {"exponent", "80"}}));
  EXPECT_DOUBLE_EQ(half.counters.at("exponent"), modern::kEsmMaxExponentFloat16);
  const Frame full =
      renderByName("modern.esm", scene, smallParams(80, 60, 128, {{"exponent", "80"}}));
  EXPECT_DOUBLE_EQ(full.counters.at("exponent"), 80.0);
}

// The stiffest settings each storage allows render finite visibility in [0, 1] on the scenes
// with a grazing ground and several depth layers.
TEST(Esm, NoNanOrInfAtTheLargestExponent) {
  for (const char* sceneName : {"analytic", "brabec", "fence"}) {
    const Scene scene = builtinScene(sceneName);
    for (const char* storage : {"16", "float"}) {
      const Frame f = renderByName(
          "modern.esm", scene,
          smallParams(96, 72, 128, {{"storage", storage}, {"exponent", "88"}, {"blur", "7"}}));
      EXPECT_TRUE(allFinite(f.visibility)) << sceneName << " storage " << storage;
      EXPECT_TRUE(allFinite(f.color)) << sceneName << " storage " << storage;
      for (const PassImage& image : f.intermediates)
        EXPECT_TRUE(allFinite(image.image)) << sceneName << " " << image.name;
      for (float v : f.visibility.data) {
        ASSERT_GE(v, 0.0f) << sceneName;
        ASSERT_LE(v, 1.0f) << sceneName;
      }
    }
  }
}

TEST(Esm, BadParametersAreInputErrors) {
  const Scene scene = builtinScene("analytic");
  for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{
           {"blur", "4"}, {"exponent", "0"}, {"exponent", "89"}, {"storage", "8"}}) {
    EXPECT_THROW(renderByName("modern.esm", scene, smallParams(32, 32, 32, {{key, value}})),
                 InputError)
        << key << "=" << value;
  }
}

}  // namespace
}  // namespace sl
