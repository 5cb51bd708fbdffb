// legacy.hw, legacy.woo and legacy.second-depth (Everitt, Rege & Cebenoyan 2001: ARB_shadow, and
// the two alternatives to polygon offset of "Advantages and Limitations") on the analytic scene:
// away from a band of two shadow-map texels around the geometric shadow's outline the mask is
// exactly the shadow computed here by ray casting — in particular the lit ground shows no
// self-shadowing although Woo and second-depth use no polygon offset at all.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <string>

#include "core/scene/scene_library.h"
#include "legacy_gl/hardware_shadow_map.h"
#include "registry/registry.h"

namespace sl {
namespace {

constexpr int kWidth = 320;  // small window (team rule); the 256 map fits in it
constexpr int kHeight = 240;
constexpr int kMapTexels = 256;
// Two map texels (projected onto the ground) on each side of the outline: nearest sampling puts the
// stored sample up to half a texel from the point, and the rasterised occluder edge in the light
// view is itself up to half a texel off.
constexpr double kBandTexels = 2.0;

enum class Truth { kNotGround, kLit, kShadow, kNearBoundary };

// What the camera sees through window point (px, py) of the analytic scene, and whether that
// ground point sees the point light past the occluder box (ray casting in double precision).
class AnalyticTruth {
 public:
  explicit AnalyticTruth(const Scene& scene) : scene_(scene) {
    box_ = worldBounds(scene.objects.at(1));
    const Bounds ground = worldBounds(scene.objects.at(0));
    groundHalf_ = ground.hi.x;
    const double h = scene.light.position.y;
    texel_ = 2.0 * h * std::tan(glm::radians(double(scene.light.coneDegrees)) / 2.0) / kMapTexels;
    inverse_ = glm::inverse(glm::dmat4(cameraProjection(scene.camera, float(kWidth) / kHeight)) *
                            glm::dmat4(cameraView(scene.camera)));
  }

  Truth at(double px, double py) const {
    const glm::dvec4 a = inverse_ * glm::dvec4(2 * px / kWidth - 1, 2 * py / kHeight - 1, -1, 1);
    const glm::dvec4 b = inverse_ * glm::dvec4(2 * px / kWidth - 1, 2 * py / kHeight - 1, 1, 1);
    const glm::dvec3 o = glm::dvec3(a) / a.w;
    const glm::dvec3 d = glm::dvec3(b) / b.w - o;
    if (hitsBox(o, d, 1e30) || d.y >= 0) return Truth::kNotGround;
    const glm::dvec3 p = o + d * (-o.y / d.y);
    if (std::max(std::fabs(p.x), std::fabs(p.z)) > groundHalf_) return Truth::kNotGround;
    const glm::dvec3 light(scene_.light.position);
    const bool shadowed = hitsBox(p, light - p, 1.0);
    // Near the outline when a point a band's width away sees the light differently.
    for (const glm::dvec2 step :
         {glm::dvec2(1, 0), glm::dvec2(-1, 0), glm::dvec2(0, 1), glm::dvec2(0, -1)}) {
      const glm::dvec3 q = p + kBandTexels * texel_ * glm::dvec3(step.x, 0, step.y);
      if (hitsBox(q, light - q, 1.0) != shadowed) return Truth::kNearBoundary;
    }
    return shadowed ? Truth::kShadow : Truth::kLit;
  }

 private:
  // Slab test of the segment o + t d, t in (0, tMax], against the occluder box.
  bool hitsBox(const glm::dvec3& o, const glm::dvec3& d, double tMax) const {
    double t0 = 1e-9, t1 = tMax;
    for (int i = 0; i < 3; ++i) {
      if (d[i] == 0.0) {
        if (o[i] < box_.lo[i] || o[i] > box_.hi[i]) return false;
        continue;
      }
      double ta = (box_.lo[i] - o[i]) / d[i], tb = (box_.hi[i] - o[i]) / d[i];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    return t0 <= t1;
  }

  const Scene& scene_;
  Bounds box_;
  double groundHalf_ = 0, texel_ = 0;
  glm::dmat4 inverse_;
};

void expectExactShadowAwayFromOutline(const std::string& technique) {
  const Scene scene = loadScene("analytic");
  RenderParams p;
  p.width = kWidth;
  p.height = kHeight;
  p.shadowMapTexels = kMapTexels;
  p.extra["compare"] = "nearest";  // binary results (Everitt Fig. 5 left)
  const Frame f = renderTechnique(findTechnique(technique), scene, p);
  const AnalyticTruth truth(scene);
  long compared = 0, shadowed = 0, wrong = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      // The whole pixel must agree: centre and corners.
      const Truth t = truth.at(x + 0.5, y + 0.5);
      bool uniform = t == Truth::kLit || t == Truth::kShadow;
      for (const auto& [dx, dy] : {std::pair{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}})
        uniform = uniform && truth.at(x + dx, y + dy) == t;
      if (!uniform) continue;
      ++compared;
      shadowed += t == Truth::kShadow;
      // GL_NEAREST compare gives exactly 0 or 1, stored exactly in the 8-bit window.
      const float expected = t == Truth::kShadow ? 0.0f : 1.0f;
      if (f.visibility.at(x, y) != expected && wrong++ < 5)
        ADD_FAILURE() << technique << ": pixel (" << x << ", " << y << ") visibility "
                      << f.visibility.at(x, y) << ", ray casting says " << expected;
    }
  EXPECT_EQ(wrong, 0) << technique;
  // Not vacuous: most of the ground is compared and the shadow square is in view.
  EXPECT_GT(compared, long(kWidth) * kHeight / 2) << technique;
  EXPECT_GT(shadowed, 1000) << technique;
}

TEST(DepthLayerShadowMaps, HardwareShadowMapEqualsRayCastShadow) {
  expectExactShadowAwayFromOutline("legacy.hw");
}

TEST(DepthLayerShadowMaps, WooMidpointEqualsRayCastShadowWithoutPolygonOffset) {
  expectExactShadowAwayFromOutline("legacy.woo");
}

TEST(DepthLayerShadowMaps, SecondDepthEqualsRayCastShadowWithoutPolygonOffset) {
  expectExactShadowAwayFromOutline("legacy.second-depth");
}

// Everitt, "Advantages and Limitations": "make sure that the shadow test always returns
// 'shadowed' for surfaces behind the light" (the negative projection). A light 0.5 above the
// ground looking along +x: the ground at x < 0 lies behind it. Every technique that shares
// legacy.hw's camera passes, and its modern twin, must show that half fully shadowed.
TEST(DepthLayerShadowMaps, SurfacesBehindTheLightAreShadowed) {
  Scene scene = loadScene("analytic");
  scene.light.position = {0.0f, 0.5f, 0.0f};
  scene.light.target = {3.0f, 0.0f, 0.0f};
  scene.light.up = {0.0f, 1.0f, 0.0f};
  scene.camera.position = {0.0f, 6.0f, 0.01f};  // straight above, both halves in view
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  scene.camera.fovyDegrees = 60.0f;
  const glm::dmat4 inverse =
      glm::inverse(glm::dmat4(cameraProjection(scene.camera, float(kWidth) / kHeight)) *
                   glm::dmat4(cameraView(scene.camera)));
  // The ground point seen through the pixel centre (the ground is the plane y = 0).
  auto groundPoint = [&](int x, int y) {
    const glm::dvec4 a =
        inverse * glm::dvec4(2 * (x + 0.5) / kWidth - 1, 2 * (y + 0.5) / kHeight - 1, -1, 1);
    const glm::dvec4 b =
        inverse * glm::dvec4(2 * (x + 0.5) / kWidth - 1, 2 * (y + 0.5) / kHeight - 1, 1, 1);
    const glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::dvec3(b) / b.w - o;
    return o + d * (-o.y / d.y);
  };
  // Behind = at least 0.6 units behind the light plane x = 0, which keeps the 1x1 occluder
  // (|x| <= 0.5, non-receiver) out of the checked pixels.
  constexpr double kBehind = -0.6;
  for (const char* name : {"legacy.hw", "modern.hw", "legacy.woo", "modern.woo",
                           "legacy.second-depth", "modern.second-depth"}) {
    RenderParams p;
    p.width = kWidth;
    p.height = kHeight;
    p.shadowMapTexels = kMapTexels;
    const Frame f = renderTechnique(findTechnique(name), scene, p);
    long checked = 0, lit = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const glm::dvec3 g = groundPoint(x, y);
        constexpr double kGroundHalf = 3.0;  // the analytic ground is 6 x 6
        if (!(g.x < kBehind) || g.x < -kGroundHalf || std::fabs(g.z) > kGroundHalf) continue;
        ++checked;
        lit += f.visibility.at(x, y) != 0.0f;
      }
    EXPECT_GT(checked, 5000) << name;
    EXPECT_EQ(lit, 0) << name << ": surfaces behind the light must be shadowed";
  }
}

// Woo's map lies between the two layers: with --dump-passes the three depth images come back,
// and every texel of the midpoint is (z1 + z2) / 2 computed here from the other two.
TEST(DepthLayerShadowMaps, WooMapIsTheMidpointOfTheFirstTwoLayers) {
  RenderParams p;
  p.width = kWidth;
  p.height = kHeight;
  p.shadowMapTexels = kMapTexels;
  p.capturePasses = true;
  const Frame f = renderTechnique(findTechnique("legacy.woo"), loadScene("brabec"), p);
  // The first three are the layers and the map, shown on one affine grey scale (window z from
  // the nearest layer's depth to 1, core/technique/pass_capture.h), so their relations hold in grey
  // too.
  ASSERT_GE(f.intermediates.size(), 3u);
  const Image& z1 = f.intermediates[0].image;
  const Image& z2 = f.intermediates[1].image;
  const Image& mid = f.intermediates[2].image;
  long between = 0, peeled = 0;
  for (size_t i = 0; i < mid.data.size(); ++i) {
    // 1e-5: float rounding of window z (6e-8) magnified by the grey mapping (z - lo) / (1 - lo),
    // 1 / (1 - lo) <= 100 for brabec.
    EXPECT_NEAR(mid.data[i], 0.5f * (z1.data[i] + z2.data[i]), 1e-5f);
    EXPECT_LE(z1.data[i], z2.data[i]);  // the peel keeps only what lies behind z1
    between += z1.data[i] < mid.data[i] && mid.data[i] < z2.data[i];
    peeled += z2.data[i] < 1.0f;
  }
  EXPECT_GT(peeled, 1000);  // casters have back faces behind their front faces
  EXPECT_GT(between, 1000);
}

}  // namespace
}  // namespace sl
