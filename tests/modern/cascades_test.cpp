// modern.cascades (parallel-split shadow maps, ours, after Zhang et al. 2006, not in
// shared/papers): the split distances against the formula, the crops against the slices they
// must cover, the stabilised crop's whole-texel offset and its size under camera rotation, the
// error on the long scene against one map of the same size, and the flicker of shadows fixed in
// the world as the camera moves, with stabilize=on against off.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>

#include "core/base/errors.h"
#include "core/base/metrics.h"
#include "filtered_shadows_util.h"
#include "modern/cascaded_shadow_maps.h"
#include "registry/shadow_error.h"

namespace sl {
namespace {
using namespace sl::testing_filtered;

constexpr int kWidth = 400;  // window of the GL tests: small, and 4:3 as the default
constexpr int kHeight = 300;
constexpr float kAspect = float(kWidth) / float(kHeight);

glm::vec2 ndcOf(const Scene& scene, const glm::vec3& world) {
  const glm::vec4 c = lightProjection(scene) * lightView(scene.light) * glm::vec4(world, 1.0f);
  return glm::vec2(c) / c.w;
}

float lightDepthOf(const Scene& scene, const glm::vec3& world) {
  return -(lightView(scene.light) * glm::vec4(world, 1.0f)).z;
}

TEST(Cascades, SplitDistancesFollowTheFormula) {
  constexpr float n = 0.5f, f = 50.0f;
  constexpr int kCount = 4;
  // lambda = 0: uniform; 1: logarithmic; 0.5: their mean. float arithmetic: 1e-5 relative.
  const auto uniform = modern::cascadeSplitDistances(n, f, kCount, 0.0f);
  const auto logarithmic = modern::cascadeSplitDistances(n, f, kCount, 1.0f);
  const auto mean = modern::cascadeSplitDistances(n, f, kCount, 0.5f);
  ASSERT_EQ(uniform.size(), size_t(kCount) + 1);
  for (int i = 0; i <= kCount; ++i) {
    const double u = n + (f - n) * double(i) / kCount;
    const double l = n * std::pow(double(f) / n, double(i) / kCount);
    EXPECT_NEAR(uniform[size_t(i)], u, 1e-5 * u) << i;
    EXPECT_NEAR(logarithmic[size_t(i)], l, 1e-5 * l) << i;
    EXPECT_NEAR(mean[size_t(i)], 0.5 * (u + l), 1e-5 * u) << i;
  }
  EXPECT_THROW(modern::cascadeSplitDistances(n, f, 0, 0.5f), InputError);
  EXPECT_THROW(modern::cascadeSplitDistances(n, f, modern::kMaxCascades + 1, 0.5f), InputError);
}

// The tight crop (stabilize=off) holds every slice corner, clamped to the scene's and the light
// frustum's rectangles, as the crop is built.
TEST(Cascades, TightCropCoversEachSlice) {
  const Scene scene = builtinScene("long");
  const auto cascades =
      modern::cascadeCrops(scene, kAspect, {.count = 4, .lambda = 0.75f, .stabilize = false});
  ASSERT_EQ(cascades.size(), 4u);
  const Bounds b = sceneBounds(scene);
  glm::vec2 sceneLo(1e30f), sceneHi(-1e30f);
  for (int i = 0; i < 8; ++i) {
    const glm::vec2 p = ndcOf(
        scene, {(i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z});
    sceneLo = glm::min(sceneLo, p);
    sceneHi = glm::max(sceneHi, p);
  }
  sceneLo = glm::max(sceneLo, glm::vec2(-1.0f));
  sceneHi = glm::min(sceneHi, glm::vec2(1.0f));
  for (const auto& c : cascades) {
    // float round-off of the projection: 1e-5 NDC.
    constexpr float kSlack = 1e-5f;
    for (const glm::vec3& corner :
         modern::frustumSliceCorners(scene.camera, kAspect, c.nearDepth, c.farDepth)) {
      const glm::vec2 p = glm::clamp(ndcOf(scene, corner), sceneLo, sceneHi);
      EXPECT_LE(glm::abs(p.x - c.centre.x), c.halfSize.x + kSlack) << c.nearDepth;
      EXPECT_LE(glm::abs(p.y - c.centre.y), c.halfSize.y + kSlack) << c.nearDepth;
    }
    EXPECT_LT(c.halfSize.x, 1.0f) << "the long scene's slices are smaller than the light frustum";
  }
  // The nearest slice is a small part of the light frustum: the point of the method.
  EXPECT_LT(cascades[0].halfSize.x * cascades[0].halfSize.y, 0.05f);
}

// The stabilised crop holds every slice point where geometry can be (light depth at least the
// scene's nearest), its centre lies on whole texels, and rotating the camera leaves its size.
TEST(Cascades, StabilisedCropCoversSlicesOnWholeTexelsWithAFixedSize) {
  Scene scene = builtinScene("long");
  constexpr int kTexels = 512;
  const modern::CascadeSettings s{
      .count = 4, .lambda = 0.75f, .stabilize = true, .texels = kTexels};
  const auto before = modern::cascadeCrops(scene, kAspect, s);
  const float nearest = lightDepthRange(scene).nearPlane;
  const auto check = [&](const Scene& sc, const std::vector<modern::CascadeCrop>& cascades) {
    // The two nearest slices of the long scene are cropped; a farther one may need the whole
    // light frustum (its sphere's projection reaches 1), which does not move at all.
    ASSERT_LT(cascades[1].halfSize.x, 1.0f);
    for (const auto& c : cascades) {
      if (c.halfSize.x >= 1.0f) {
        EXPECT_EQ(c.centre, glm::vec2(0.0f));
        continue;
      }
      const float texel = 2.0f * c.halfSize.x / kTexels;
      for (int a = 0; a < 2; ++a) {
        const float k = c.centre[a] / texel;
        // The snapped centre is k texels exactly, up to float division (1e-3 texel).
        EXPECT_NEAR(k, std::round(k), 1e-3f) << c.nearDepth;
      }
      for (const glm::vec3& corner :
           modern::frustumSliceCorners(sc.camera, kAspect, c.nearDepth, c.farDepth)) {
        if (lightDepthOf(sc, corner) < nearest) continue;  // no geometry there
        const glm::vec2 p = ndcOf(sc, corner);
        EXPECT_LE(glm::abs(p.x - c.centre.x), c.halfSize.x) << c.nearDepth;
        EXPECT_LE(glm::abs(p.y - c.centre.y), c.halfSize.y) << c.nearDepth;
      }
    }
  };
  check(scene, before);
  // Yaw the camera by 12 degrees and pitch it down by 5 about its position.
  glm::vec3 d = scene.camera.target - scene.camera.position;
  d = glm::vec3(glm::rotate(glm::mat4(1), glm::radians(12.0f), glm::vec3(0, 1, 0)) *
                glm::vec4(d, 0));
  d = glm::vec3(glm::rotate(glm::mat4(1), glm::radians(-5.0f),
                            glm::normalize(glm::cross(d, glm::vec3(0, 1, 0)))) *
                glm::vec4(d, 0));
  scene.camera.target = scene.camera.position + d;
  const auto after = modern::cascadeCrops(scene, kAspect, s);
  check(scene, after);
  ASSERT_EQ(after.size(), before.size());
  for (size_t i = 0; i < after.size(); ++i) {
    EXPECT_EQ(after[i].halfSize, before[i].halfSize) << i;  // exactly: nothing depends on yaw
    if (before[i].halfSize.x < 1.0f) EXPECT_NE(after[i].centre, before[i].centre) << i;  // moved
  }
}

RenderParams longParams(int texels, std::map<std::string, std::string> extra = {}) {
  return smallParams(kWidth, kHeight, texels, std::move(extra));
}

// On the long scene, four 1024² cascades against one 1024² map (modern.hw): lower error against
// reference.hard, over all scored pixels and in the shadow-edge band.
TEST(Cascades, LongSceneErrsLessThanOneMapOfTheSameSize) {
  if (!haveRayTracedReferences()) GTEST_SKIP() << "build without the ray tracer";
  const Scene scene = builtinScene("long");
  const RenderParams p = longParams(1024);
  const ShadowTruth truth = renderShadowTruth(scene, p, ErrorMetric::kPoint, false);
  const ShadowError one = scoreShadow(renderByName("modern.hw", scene, p).visibility, truth);
  for (const char* stabilize : {"on", "off"}) {
    const ShadowError many = scoreShadow(
        renderByName("modern.cascades", scene, longParams(1024, {{"stabilize", stabilize}}))
            .visibility,
        truth);
    std::printf(
        "long scene, 1024^2: modern.hw RMSE %.4f band %.4f; modern.cascades "
        "stabilize=%s RMSE %.4f band %.4f\n",
        one.all.rmse, one.band.rmse, stabilize, many.all.rmse, many.band.rmse);
    EXPECT_LT(many.all.rmse, one.all.rmse) << stabilize;
    EXPECT_LT(many.band.rmse, one.band.rmse) << stabilize;
  }
}

// The flicker of shadows fixed in the world as the camera moves: ground points of a fixed world
// region (near the camera, where the posts' shadows fall) are looked up in each frame at the
// pixel they project to; the mean |change| of their visibility between frames (meanAbsChange,
// the bench's temporal metric) over points that both frames see on the ground.
struct Flicker {
  double change = 0.0;
  long long points = 0;
};

Flicker cameraMotionFlicker(const std::string& technique, const Scene& scene, const RenderParams& p,
                            const glm::vec3& step, int steps) {
  constexpr float kRegionHalfWidth = 2.5f;  // world units, across the strip
  constexpr float kRegionNear = 0.5f, kRegionFar = -7.0f;
  constexpr int kPointsPerSide = 120;
  // A pixel sees the ground point when its own ray meets y = 0 this close (world units): else a
  // post or box stands in front of it.
  constexpr float kSameGroundPoint = 0.05f;
  Scene moved = scene;
  std::vector<Frame> frames;
  std::vector<Scene> scenes;
  for (int i = 0; i <= steps; ++i) {
    scenes.push_back(moved);
    frames.push_back(renderByName(technique, moved, p));
    moved.camera.position += step;
    moved.camera.target += step;
  }
  double sum = 0.0;
  long long points = 0;
  for (int i = 0; i < steps; ++i) {
    Image a(kPointsPerSide, kPointsPerSide, 1), b(kPointsPerSide, kPointsPerSide, 1),
        region(kPointsPerSide, kPointsPerSide, 1);
    for (int y = 0; y < kPointsPerSide; ++y)
      for (int x = 0; x < kPointsPerSide; ++x) {
        const glm::vec3 w(kRegionHalfWidth * (2.0f * (x + 0.5f) / kPointsPerSide - 1.0f), 0.0f,
                          kRegionNear + (kRegionFar - kRegionNear) * (y + 0.5f) / kPointsPerSide);
        float v[2];
        bool seen = true;
        for (int k = 0; k < 2; ++k) {
          const Scene& sc = scenes[size_t(i + k)];
          const glm::ivec2 px = pixelOf(sc, p, w);
          if (px.x < 0 || px.y < 0 || px.x >= p.width || px.y >= p.height) {
            seen = false;
            break;
          }
          const glm::vec3 g = groundPointOf(sc, p, float(px.x), float(px.y));
          if (glm::distance(g, w) > kSameGroundPoint) seen = false;
          v[k] = frames[size_t(i + k)].visibility.at(px.x, px.y, 0);
        }
        const size_t at = size_t(y) * kPointsPerSide + size_t(x);
        a.data[at] = seen ? v[0] : 0.0f;
        b.data[at] = seen ? v[1] : 0.0f;
        region.data[at] = seen ? 1.0f : 0.0f;
        points += seen ? 1 : 0;
      }
    sum += meanAbsChange(a, b, region);
  }
  return {sum / steps, points};
}

// Stabilised cascades flicker less than unstabilised ones as the camera walks along the strip;
// the reference's own change (the same world points looked up at other pixel centres) is the
// floor both approach.
TEST(Cascades, StabilisedCascadesFlickerLessUnderCameraMotion) {
  const Scene scene = builtinScene("long");
  // Texels a few pixels wide next to the camera (a 128² map per cascade), so that a texel grid
  // sliding under the shadows shows at the window's resolution.
  constexpr int kTexels = 128;
  const RenderParams p = longParams(kTexels);
  // A sixth of a world unit per frame along the strip and a little sideways, four frames.
  const glm::vec3 step(0.03f, 0.0f, -0.17f);
  constexpr int kSteps = 4;
  const Flicker on = cameraMotionFlicker("modern.cascades", scene,
                                         longParams(kTexels, {{"stabilize", "on"}}), step, kSteps);
  const Flicker off = cameraMotionFlicker(
      "modern.cascades", scene, longParams(kTexels, {{"stabilize", "off"}}), step, kSteps);
  std::printf(
      "camera motion flicker (mean |change| of world-fixed ground points, %lld points): "
      "stabilize=on %.5f, stabilize=off %.5f",
      on.points, on.change, off.change);
  if (haveRayTracedReferences()) {
    const Flicker ref = cameraMotionFlicker("reference.hard", scene, p, step, kSteps);
    std::printf(", reference.hard %.5f", ref.change);
  }
  std::printf("\n");
  ASSERT_GT(on.points, 1000) << "the region should be seen";
  EXPECT_LT(on.change, off.change);
}

// No NaN and sane masks on every built-in scene with 1 to 4 cascades, both ways.
TEST(Cascades, RendersEveryBuiltinSceneFinite) {
  for (const std::string& name : builtinSceneNames()) {
    const Scene scene = builtinScene(name);
    for (const char* count : {"1", "4"})
      for (const char* stabilize : {"on", "off"}) {
        const Frame f = renderByName(
            "modern.cascades", scene,
            smallParams(160, 120, 256, {{"cascades", count}, {"stabilize", stabilize}}));
        for (float v : f.visibility.data) {
          ASSERT_TRUE(std::isfinite(v)) << name;
          ASSERT_GE(v, 0.0f) << name;
          ASSERT_LE(v, 1.0f) << name;
        }
      }
  }
}

}  // namespace
}  // namespace sl
