// modern.smoothies (Chan 2004 ch. 4): the penumbra profile across one occluder edge of the
// analytic scene against Eq. 4.1 and the falloff computed here from the scene's geometry, the
// b/r -> 1 limit, and visibility within [0, 1].
#include "modern/smoothies.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <optional>

#include "apps/registry.h"
#include "core/errors.h"
#include "core/primitives.h"
#include "core/scene_library.h"
#include "modern/silhouettes.h"
#include "tests/modern/analytic_ground.h"

namespace sl {
namespace {

RenderParams smallParams(int shadowMap = 512) {
  RenderParams p;
  p.width = 320;
  p.height = 240;
  p.shadowMapTexels = shadowMap;
  return p;
}

TEST(Smoothies, RemapIsFiniteAndClampedAsBOverRApproachesOne) {
  // Eq. 4.1 a' = a / (1 - b/r), clamped to [0, 1]. Near and at b/r = 1 (a smoothie touching its
  // receiver) the naive quotient is 0/0 or x/0; ours must stay finite and in [0, 1], equal 1 at
  // and beyond b/r = 1, and equal the plain quotient where that is below 1.
  for (float a : {0.0f, 1e-7f, 0.001f, 0.3f, 1.0f})
    for (float f : {0.0f, 0.5f, 0.999f, 0.9999999f, 1.0f, 1.0000001f, 1.5f}) {
      const float r = modern::remapSmoothieAlpha(a, f);
      ASSERT_TRUE(std::isfinite(r)) << a << " " << f;
      EXPECT_GE(r, 0.0f);
      EXPECT_LE(r, 1.0f);
      if (f >= 1.0f) {
        EXPECT_EQ(r, 1.0f) << a << " " << f;
      }
      if (f < 1.0f && a / (1.0f - f) < 1.0f) {
        EXPECT_FLOAT_EQ(r, a / (1.0f - f));
      }
    }
  EXPECT_FLOAT_EQ(modern::remapSmoothieAlpha(0.1f, 0.75f), 0.4f);  // 0.1 / 0.25
}

TEST(Smoothies, FalloffIsSinusoidal) {
  // Parker et al. / Haines (§4.2.1): s(v) = (1 - cos(pi v)) / 2.
  EXPECT_FLOAT_EQ(modern::smoothieFalloff(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(modern::smoothieFalloff(1.0f), 1.0f);
  EXPECT_NEAR(modern::smoothieFalloff(0.5f), 0.5f, 1e-7);
  EXPECT_NEAR(modern::smoothieFalloff(0.25f), (1.0 - std::cos(glm::pi<double>() / 4)) / 2, 1e-7);
}

TEST(Smoothies, PenumbraProfileAcrossAnAnalyticEdgeFollowsTheFalloff) {
  // Analytic scene: light at (0,4,0) looking straight down (light x = world x), occluder top face
  // at y = 1.01, ground at y = 0. Along the ground beyond the occluder's +x edge (|z| small, away
  // from the corners) the expected visibility is computed here from Chan's definitions alone:
  //   light screen u = 0.5 + 0.5 x / (depth tan(cone/2)), depth = 4 - y;
  //   d = u(ground) - u(edge) (map units), a = d / t, b/r = (4 - 1.01) / 4,
  //   a' = min(1, a / (1 - b/r)), v = (1 - cos(pi a')) / 2; v = 0 where d < 0 (umbra).
  // Bilinear interpolation of a function linear in the map is exact, so away from the two kinks
  // (d = 0 and a' = 1, excluded within 2 shadow-map texels) the only errors are float round-off
  // of the world position (~1e-4 world units, slope <= 6 per unit) and the 256-texel falloff
  // table (< 1e-4): 0.002 bounds both (6e-4 + 1e-4) with margin.
  const Scene scene = builtinScene("analytic");
  RenderParams p = smallParams(512);
  const double t = 0.2;
  p.extra["width"] = "0.2";
  const Frame f = renderTechnique(findTechnique("modern.smoothies"), scene, p);
  const double tanHalf = std::tan(glm::radians(double(scene.light.coneDegrees) / 2));
  const auto u = [&](double x, double y) { return 0.5 + 0.5 * x / ((4.0 - y) * tanHalf); };
  const double bOverR = (4.0 - testing::kOccluderTop) / 4.0;
  const double uEdge = u(testing::kOccluderHalfSide, testing::kOccluderTop);
  const double texel = 1.0 / p.shadowMapTexels;
  const double kink = t * (1.0 - bOverR);  // d where a' reaches 1
  int penumbra = 0, checked = 0;
  double worst = 0;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      auto g = testing::groundPoint(scene, p.width, p.height, x + 0.5f, y + 0.5f);
      if (!g || std::abs(g->z) > 0.3 || g->x < 0.3) continue;
      const double d = u(g->x, 0.0) - uEdge;
      if (std::abs(d) < 2 * texel || std::abs(d - kink) < 2 * texel) continue;
      const double a = d / t;
      const double aRemapped = d < 0 ? 0.0 : std::min(1.0, a / (1.0 - bOverR));
      const double expected = d < 0 ? 0.0 : (1.0 - std::cos(glm::pi<double>() * aRemapped)) / 2;
      const double got = f.visibility.at(x, y);
      worst = std::max(worst, std::abs(got - expected));
      ++checked;
      if (expected > 0.02 && expected < 0.98) ++penumbra;
      EXPECT_NEAR(got, expected, 0.002) << "pixel " << x << "," << y << " d=" << d;
    }
  EXPECT_GT(checked, 500);
  EXPECT_GT(penumbra, 40);  // the ramp spans several pixels: t(1 - b/r) = 0.05 of the map
  RecordProperty("worst_profile_error", std::to_string(worst));
}

TEST(Smoothies, ContactAndEveryBufferStayFiniteWithinUnitRange) {
  // brabec: the box and the small sphere touch the ground, so smoothie edges along the contact
  // have b/r -> 1 (Eq. 4.1's divisor -> 0). No NaN or Inf may reach the smoothie buffer or the
  // visibility, and visibility must lie in [0, 1] everywhere, for narrow and wide smoothies.
  for (const std::string name : {"brabec", "fence", "trees", "analytic"})
    for (const std::string width : {"0.001", "0.1", "1"}) {
      RenderParams p = smallParams(256);
      p.extra["width"] = width;
      p.capturePasses = true;
      const Frame f = renderTechnique(findTechnique("modern.smoothies"), builtinScene(name), p);
      ASSERT_TRUE(allFinite(f.visibility)) << name << " " << width;
      for (float v : f.visibility.data) {
        ASSERT_GE(v, 0.0f) << name << " " << width;
        ASSERT_LE(v, 1.0f) << name << " " << width;
      }
      for (const PassImage& i : f.intermediates) {
        ASSERT_TRUE(allFinite(i.image)) << i.name;
        if (i.name == "3-smoothie-alpha") {
          for (float v : i.image.data) ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << name;
        }
      }
      EXPECT_GT(f.counters.at("smoothie_edges"), 0) << name;
      EXPECT_EQ(f.counters.at("smoothie_corners") >= 3, true) << name;
    }
}

// A closed "monkey saddle" cone: apex v with six neighbours alternating up and down, closed by a
// bottom apex. Seen from suitable light positions, the facing of the six fan triangles around v
// alternates more than twice, so v has more than two silhouette edges (Chan §4.2 step 3's
// special case).
Mesh saddleCone() {
  constexpr int kNeighbours = 6;
  constexpr float kRipple = 0.45f;  // up/down height of the neighbours
  Mesh m;
  m.positions.push_back({0, 0, 0});
  for (int k = 0; k < kNeighbours; ++k) {
    const float a = glm::two_pi<float>() * k / kNeighbours;
    m.positions.push_back({std::cos(a), (k % 2 ? -kRipple : kRipple), std::sin(a)});
  }
  m.positions.push_back({0, -1.5f, 0});
  const unsigned bottom = kNeighbours + 1;
  for (unsigned k = 0; k < kNeighbours; ++k) {
    const unsigned a = 1 + k, b = 1 + (k + 1) % kNeighbours;
    m.indices.insert(m.indices.end(), {0u, b, a, bottom, a, b});
  }
  // Outward orientation: positive signed volume (divergence theorem), else flip every triangle.
  double volume = 0;
  for (size_t t = 0; t < m.indices.size(); t += 3)
    volume += glm::dot(m.positions[m.indices[t]],
                       glm::cross(m.positions[m.indices[t + 1]], m.positions[m.indices[t + 2]]));
  if (volume < 0)
    for (size_t t = 0; t < m.indices.size(); t += 3) std::swap(m.indices[t + 1], m.indices[t + 2]);
  m.normals.assign(m.positions.size(), glm::vec3(0, 1, 0));
  m.closed = isClosedManifold(m);
  return m;
}

TEST(Smoothies, VertexWithMoreThanTwoSilhouetteEdges) {
  const Mesh cone = saddleCone();
  ASSERT_TRUE(cone.closed);
  const glm::vec3 at(0, 2.0f, 0);  // where the cone floats above the ground
  // Find a light above the cone for which the apex has more than two silhouette edges.
  const modern::EdgeAdjacency adj = modern::buildEdgeAdjacency(cone, "saddle");
  std::optional<glm::vec3> light;
  for (int i = 0; i < 40 && !light; ++i)
    for (int j = 1; j < 10 && !light; ++j) {
      const float phi = glm::two_pi<float>() * i / 40, up = 0.15f * j;
      const glm::vec3 l = 4.0f * glm::normalize(glm::vec3(std::cos(phi), up, std::sin(phi)));
      int degree = 0;
      for (const auto& [a, b] : modern::findSilhouette(adj, l).edges) degree += (a == 0) + (b == 0);
      if (degree > 2) light = l;
    }
  ASSERT_TRUE(light.has_value()) << "no light position gives the apex > 2 silhouette edges";
  Scene scene = builtinScene("analytic");
  scene.objects[1].mesh = std::make_shared<const Mesh>(cone);
  scene.objects[1].model = glm::translate(glm::mat4(1), at);
  scene.light.position = at + *light;
  scene.light.target = glm::vec3(0);
  scene.light.up = glm::vec3(0, 1, 0);
  scene.light.coneDegrees = 100;
  RenderParams p = smallParams(512);
  p.extra["width"] = "0.05";
  p.capturePasses = true;
  const Frame f = renderTechnique(findTechnique("modern.smoothies"), scene, p);
  EXPECT_GE(f.counters.at("corners_with_more_than_two_edges"), 1);
  EXPECT_GE(f.counters.at("corner_squares"), 1);
  ASSERT_TRUE(allFinite(f.visibility));
  for (float v : f.visibility.data) ASSERT_TRUE(v >= 0.0f && v <= 1.0f);
  for (const PassImage& i : f.intermediates) ASSERT_TRUE(allFinite(i.image)) << i.name;
}

TEST(Smoothies, WidthOutOfRangeIsAnInputError) {
  RenderParams p = smallParams();
  p.extra["width"] = "0";
  EXPECT_THROW(renderTechnique(findTechnique("modern.smoothies"), builtinScene("analytic"), p),
               InputError);
}

}  // namespace
}  // namespace sl
