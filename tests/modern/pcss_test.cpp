// modern.pcss (ours, after Fernando 2005, not in shared/papers): the penumbra formula and the
// taps, the rendered penumbra across an analytic edge against w_p computed here from the scene's
// geometry, hardening at contact against modern.smoothies and reference.soft, and finite
// visibility in [0, 1] on stiff scenes.
#include "modern/pcss.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <optional>
#include <string>

#include "core/base/errors.h"
#include "core/scene/scene_library.h"
#include "registry/registry.h"
#include "tests/modern/analytic_ground.h"

namespace sl {
namespace {

// The analytic scene: light at (0, 4, 0) looking straight down, so linear light depth is 4 - y
// and the map's u is 0.5 + 0.5 x / ((4 - y) tan(cone / 2)).
constexpr double kLightHeight = 4.0;

RenderParams pcssParams(int width, int height, int shadowMap) {
  RenderParams p;
  p.width = width;
  p.height = height;
  p.shadowMapTexels = shadowMap;
  return p;
}

TEST(Pcss, PenumbraWidthIsSimilarTriangles) {
  // w_p = (d_r - d_b) w_light / d_b: a light 0.6 wide, a blocker at 2.99 and a receiver at 4
  // (the analytic scene) give 1.01 * 0.6 / 2.99; a blocker at the receiver gives 0 (contact),
  // one behind it gives 0 too (it is no blocker).
  EXPECT_FLOAT_EQ(modern::pcssPenumbraWidth(4.0f, 2.99f, 0.6f), 1.01f * 0.6f / 2.99f);
  EXPECT_EQ(modern::pcssPenumbraWidth(4.0f, 4.0f, 0.6f), 0.0f);
  EXPECT_EQ(modern::pcssPenumbraWidth(4.0f, 4.5f, 0.6f), 0.0f);
  // Halving the blocker's distance to the light more than doubles the width.
  EXPECT_GT(modern::pcssPenumbraWidth(4.0f, 1.0f, 0.6f),
            2.0f * modern::pcssPenumbraWidth(4.0f, 2.0f, 0.6f));
}

TEST(Pcss, TapsLieInTheirRegionAndAreDeterministic) {
  for (int n : {4, 16, 36, 64}) {
    const auto poisson = modern::pcssTaps(n, modern::PcssPattern::kPoisson);
    ASSERT_EQ(int(poisson.size()), n);
    EXPECT_EQ(poisson, modern::pcssTaps(n, modern::PcssPattern::kPoisson));
    float nearest = 10.0f;
    for (size_t i = 0; i < poisson.size(); ++i) {
      EXPECT_LE(glm::length(poisson[i]), 1.0f);
      for (size_t j = 0; j < i; ++j)
        nearest = std::min(nearest, glm::distance(poisson[i], poisson[j]));
    }
    // Best-candidate points keep apart: n points in the unit disk (area pi) spread evenly are
    // about sqrt(pi / n) apart; half of that rules out clumps (uniform random points of 16 come
    // as close as 0.05).
    EXPECT_GT(nearest, 0.5f * std::sqrt(3.14159f / n)) << n;
  }
  const auto grid = modern::pcssTaps(4, modern::PcssPattern::kGrid);
  ASSERT_EQ(grid.size(), 4u);
  EXPECT_EQ(grid[0], glm::vec2(-0.5f, -0.5f));
  EXPECT_EQ(grid[3], glm::vec2(0.5f, 0.5f));
  EXPECT_THROW(modern::pcssTaps(5, modern::PcssPattern::kGrid), InputError);
  EXPECT_THROW(modern::pcssTaps(65, modern::PcssPattern::kPoisson), InputError);
}

// The occluder of the analytic scene moved to `height` (its top at height + 0.01), seen from the
// +x side, so that the ground beyond its +x edge is visible down to the contact.
Scene analyticAt(float height, float lightRadius) {
  Scene scene = builtinScene("analytic");
  scene.objects[1].model = glm::translate(glm::mat4(1), glm::vec3(0, height, 0));
  scene.light.radius = lightRadius;
  scene.camera.position = {3.0f, 2.0f, 0.0f};
  scene.camera.target = {0.6f, 0.0f, 0.0f};
  return scene;
}

// The ground point seen at pixel (px, py) of analyticAt(height): the ray's hit on y = 0 unless
// it passes through the occluder's box grown by `margin` first (slab test).
std::optional<glm::vec3> groundPointBeside(const Scene& scene, const RenderParams& p, int px,
                                           int py, float height, float margin) {
  const testing::PixelRay r = testing::pixelRay(scene, p.width, p.height, px + 0.5f, py + 0.5f);
  if (r.direction.y >= 0.0f) return std::nullopt;
  const float s = -r.origin.y / r.direction.y;
  const glm::vec3 lo(-0.5f - margin, height - 0.01f - margin, -0.5f - margin);
  const glm::vec3 hi(0.5f + margin, height + 0.01f + margin, 0.5f + margin);
  float enter = 0.0f, leave = s;
  for (int a = 0; a < 3; ++a) {
    if (r.direction[a] == 0.0f) {
      if (r.origin[a] < lo[a] || r.origin[a] > hi[a]) return r.origin + s * r.direction;
      continue;
    }
    float t0 = (lo[a] - r.origin[a]) / r.direction[a], t1 = (hi[a] - r.origin[a]) / r.direction[a];
    if (t0 > t1) std::swap(t0, t1);
    enter = std::max(enter, t0);
    leave = std::min(leave, t1);
  }
  if (enter <= leave) return std::nullopt;  // the box is in the way
  return r.origin + s * r.direction;
}

TEST(Pcss, PenumbraAcrossAnAnalyticEdgeIsTheFormulasWidth) {
  // Beyond the occluder's +x edge (|z| < 0.3, away from the corners) the ground is flat and
  // faces the light, so the receiver plane is exact (gradient 0) and each grid tap's outcome is
  // known: the tap at map u + c_i R lands in texel floor((u + c_i R) N), which holds the
  // occluder's top (z_b = 4 - 1.01) iff that texel's centre lies inside the occluder's image,
  // u < u_edge. The search finds that one depth (search taps = filter taps, and the search
  // radius r (z_r - near) / (z_r 2 near tan) is at least the filter's, near = 2.99 <= z_b), so
  // R = w_p / 2 in map units at the ground with w_p = (4 - 2.99) * 2r / 2.99 from the formula.
  // Expected v = (columns of lit taps) / 8. Tolerance: the pixel's world position carries float
  // round-off of ~1e-4 world units = 0.01 texel; the expected value is taken at u +- 0.05 texel
  // and the rendered one must lie between the two (a tap on a texel boundary may go either way).
  constexpr float kRadius = 0.3f;
  constexpr int kSide = 8;
  const Scene scene = builtinScene("analytic");
  RenderParams p = pcssParams(640, 480, 512);
  p.extra = {
      {"light-radius", "0.3"}, {"pattern", "grid"}, {"search-taps", "64"}, {"filter-taps", "64"}};
  const Frame f = renderTechnique(findTechnique("modern.pcss"), scene, p);
  const double tanHalf = std::tan(glm::radians(double(scene.light.coneDegrees) / 2));
  const auto u = [&](double x, double y) { return 0.5 + 0.5 * x / ((kLightHeight - y) * tanHalf); };
  const double zb = kLightHeight - testing::kOccluderTop, zr = kLightHeight;
  const double wp = (zr - zb) * 2.0 * kRadius / zb;       // world, at the ground
  const double radius = 0.5 * wp / (2.0 * zr * tanHalf);  // map units
  const double uEdge = u(testing::kOccluderHalfSide, testing::kOccluderTop);
  const int n = p.shadowMapTexels;
  const auto expected = [&](double uu) {
    int lit = 0;
    for (int i = 0; i < kSide; ++i) {
      const double c = (2.0 * i + 1.0) / kSide - 1.0;
      const double centre = (std::floor((uu + c * radius) * n) + 0.5) / n;
      if (centre >= uEdge) ++lit;
    }
    return double(lit) / kSide;
  };
  const double slack = 0.05 / n;
  int checked = 0, penumbra = 0;
  double lo = 1e9, hi = -1e9;  // ground x of the pixels inside the ramp (0 < v < 1)
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const auto g = testing::groundPoint(scene, p.width, p.height, x + 0.5f, y + 0.5f);
      if (!g || std::abs(g->z) > 0.3 || g->x < 0.3 || g->x > 1.2) continue;
      const double uu = u(g->x, 0.0);
      const double a = expected(uu - slack), b = expected(uu + slack);
      const float v = f.visibility.at(x, y);
      EXPECT_GE(v, std::min(a, b) - 1e-6) << x << "," << y << " ground x " << g->x;
      EXPECT_LE(v, std::max(a, b) + 1e-6) << x << "," << y << " ground x " << g->x;
      ++checked;
      if (v > 0.0f && v < 1.0f) {
        ++penumbra;
        lo = std::min(lo, double(g->x));
        hi = std::max(hi, double(g->x));
      }
    }
  EXPECT_GT(checked, 1000);
  EXPECT_GT(penumbra, 100);
  // The measured width: between the outermost grid columns, 2R (1 - 1/8) in map units = w_p (1 -
  // 1/8) in world units at the ground. Tolerance: one texel (the edge is quantised to texels,
  // 2 * 4 tan 35 / 512 = 0.011 world) and two pixel footprints on the ground at 640x480 (the
  // first and last ramp pixels each sit up to a footprint inside the ramp's ends, ~0.01 each).
  const double measured = hi - lo;
  const double predicted = wp * (1.0 - 1.0 / kSide);
  const double texelWorld = 2.0 * zr * tanHalf / n;
  EXPECT_NEAR(measured, predicted, texelWorld + 0.02) << "w_p " << wp;
  RecordProperty("measured_width", std::to_string(measured));
  RecordProperty("predicted_width", std::to_string(predicted));
}

// Along the ground beyond the occluder's +x edge (|z| < 0.2): where the umbra ends (the largest
// ground x with v < 0.02) and the ramp's width (ground x from there to the first v > 0.98).
struct Edge {
  double umbraEnd = -1e9;
  double litStart = 1e9;
  double width() const { return litStart - umbraEnd; }
};
Edge edgeOf(const Scene& scene, const Frame& f, const RenderParams& p, float height) {
  Edge e;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const auto g = groundPointBeside(scene, p, x, y, height, 0.005f);
      if (!g || std::abs(g->z) > 0.2 || g->x < 0.2 || g->x > 1.5) continue;
      const float v = f.visibility.at(x, y);
      if (v < 0.02f) e.umbraEnd = std::max(e.umbraEnd, double(g->x));
    }
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const auto g = groundPointBeside(scene, p, x, y, height, 0.005f);
      if (!g || std::abs(g->z) > 0.2 || g->x < e.umbraEnd || g->x > 1.5) continue;
      if (f.visibility.at(x, y) > 0.98f) e.litStart = std::min(e.litStart, double(g->x));
    }
  return e;
}

TEST(Pcss, HardensAtContactWhereSmoothiesKeepTheUmbra) {
  // The analytic occluder lowered towards the ground under a light of radius 0.3: the true
  // penumbra (reference.soft) is, by similar triangles, 2r h / (4 - h) wide for the occluder's
  // top at height h, so it shrinks to 0 at contact and its umbra ends R = w / 2
  // inside the hard shadow's edge. PCSS follows it: its ramp narrows as h -> 0 and its umbra
  // shrinks with the reference's. Smoothies (Chan §4.2, width 0.5 x radius as Fig. 4-9) only add
  // penumbra outside the shadow map's hard edge: their umbra never ends inside it.
  constexpr float kRadius = 0.3f;
  RenderParams p = pcssParams(320, 240, 512);
  p.extra = {{"light-radius", "0.3"}};
  std::vector<double> widths;
  for (float h : {0.99f, 0.3f, 0.05f}) {
    const Scene scene = analyticAt(h, kRadius);
    const double top = h + 0.01, zb = kLightHeight - top;
    const double hardEdge = testing::kOccluderHalfSide * kLightHeight / zb;
    const double trueR = kRadius * top / zb;  // half the true penumbra at the ground
    const Edge pcss = edgeOf(scene, renderTechnique(findTechnique("modern.pcss"), scene, p), p, h);
    widths.push_back(pcss.width());
    // PCSS's umbra ends inside the hard edge by about R (Poisson taps reach ~0.9 R; the pixel
    // footprint on the ground, ~0.02 at 320x240, and a texel, 0.011, blur it): within 0.3 R +
    // 0.03 of the true umbra's end.
    EXPECT_NEAR(pcss.umbraEnd, hardEdge - trueR, 0.3 * trueR + 0.03) << "h " << h;
    if (h > 0.5f) {
      RenderParams s = p;
      s.extra = {{"width", std::to_string(0.5 * kRadius)}};
      const Edge smoothies =
          edgeOf(scene, renderTechnique(findTechnique("modern.smoothies"), scene, s), s, h);
      RenderParams r = p;
      r.extra.clear();
      const Edge reference =
          edgeOf(scene, renderTechnique(findTechnique("reference.soft"), scene, r), r, h);
      // The reference's umbra ends R inside the hard edge (0.1 world units here); smoothies'
      // at the hard edge (within a texel and a pixel, 0.03); PCSS's with the reference.
      EXPECT_NEAR(reference.umbraEnd, hardEdge - trueR, 0.03);
      EXPECT_GT(smoothies.umbraEnd, hardEdge - 0.03);
      EXPECT_LT(pcss.umbraEnd, smoothies.umbraEnd - 0.5 * trueR);
      // And PCSS's ramp is as wide as the reference's within a quarter (Poisson taps and the
      // 0.02 / 0.98 thresholds cut the ramp's ends a little differently from the disk's area).
      EXPECT_NEAR(pcss.width(), reference.width(), 0.25 * reference.width()) << "h " << h;
    }
  }
  // Narrower at each step down, and at h = 0.05 under a fifth of the width at h = 0.99 (the
  // formula gives 0.013: 0.06 / 3.94 against 1 / 3; a texel and two pixels keep it above 0).
  EXPECT_LT(widths[1], widths[0]);
  EXPECT_LT(widths[2], widths[1]);
  EXPECT_LT(widths[2], 0.2 * widths[0]);
}

TEST(Pcss, FiniteWithinUnitRangeOnStiffScenes) {
  // Contact (brabec's box and sphere on the ground: d_b -> d_r), grazing receivers (the fence,
  // the trees), a light near plane of 1e-3 (the search radius grows as 1 / near and is clamped),
  // lights of radius 0 and 10, bias 0 and maps of 1 and 4 texels: no NaN or Inf, v in [0, 1].
  struct Run {
    std::string scene;
    int texels;
    std::map<std::string, std::string> extra;
  };
  const std::vector<Run> runs = {
      {"brabec", 256, {}},
      {"fence", 256, {}},
      {"trees", 256, {}},
      {"dueling", 256, {}},
      {"brabec", 256, {{"light-radius", "0"}}},
      {"brabec", 256, {{"light-radius", "10"}, {"bias-texels", "0"}}},
      {"analytic", 1, {}},
      {"analytic", 4, {{"pattern", "grid"}, {"filter-taps", "4"}, {"search-taps", "64"}}},
      {"near", 256, {}},
  };
  for (const Run& run : runs) {
    Scene scene = run.scene == "near" ? builtinScene("brabec") : builtinScene(run.scene);
    if (run.scene == "near") {
      scene.light.nearPlane = 1e-3f;
      scene.light.farPlane = 100.0f;
    }
    RenderParams p = pcssParams(160, 120, run.texels);
    p.extra = run.extra;
    p.capturePasses = true;
    const Frame f = renderTechnique(findTechnique("modern.pcss"), scene, p);
    ASSERT_TRUE(allFinite(f.visibility)) << run.scene << " " << run.texels;
    ASSERT_TRUE(allFinite(f.color)) << run.scene;
    for (float v : f.visibility.data) ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << run.scene;
    for (const PassImage& i : f.intermediates) ASSERT_TRUE(allFinite(i.image)) << i.name;
  }
}

TEST(Pcss, ImpossibleParametersAreInputErrors) {
  RenderParams p = pcssParams(64, 48, 64);
  p.extra = {{"pattern", "grid"}, {"filter-taps", "5"}};
  EXPECT_THROW(renderTechnique(findTechnique("modern.pcss"), builtinScene("analytic"), p),
               InputError);
  p.extra = {{"light-radius", "-1"}};
  EXPECT_THROW(renderTechnique(findTechnique("modern.pcss"), builtinScene("analytic"), p),
               InputError);
}

}  // namespace
}  // namespace sl
