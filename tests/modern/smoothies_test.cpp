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

#include "core/base/errors.h"
#include "core/scene/primitives.h"
#include "core/scene/scene_library.h"
#include "modern/silhouettes.h"
#include "registry/registry.h"
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

TEST(Smoothies, OriginalAlphaIsLinearAndOccludedBehindTheReceiver) {
  // --param remap=off (§4.2.1 before Eq. 4.1, Fig. 4-4b): a' = a whatever b/r, except that a
  // smoothie pixel behind its receiver is discarded (Fig. 4-7: "If b/r > 1, smoothie pixel is
  // occluded"), i.e. 1 under minimum blending. remap=on is Eq. 4.1 (remapSmoothieAlpha).
  for (float a : {0.0f, 0.1f, 0.5f, 1.0f})
    for (float f : {0.0f, 0.5f, 0.9f, 0.999f}) {
      EXPECT_EQ(modern::smoothieAlpha(a, f, false), a) << a << " " << f;
      EXPECT_EQ(modern::smoothieAlpha(a, f, true), modern::remapSmoothieAlpha(a, f));
    }
  for (float f : {1.0f, 1.5f}) EXPECT_EQ(modern::smoothieAlpha(0.2f, f, false), 1.0f);
}

// The profile of the penumbra beyond the analytic occluder's +x edge, expected from Chan's
// definitions alone (see the test below); `remap` chooses Eq. 4.1 or the original linear alpha.
struct Profile {
  Frame frame;
  Image expected;  // -1 where the pixel is not checked
  int checked = 0, penumbra = 0;
  double worst = 0;
};
Profile penumbraProfile(bool remap) {
  const Scene scene = builtinScene("analytic");
  RenderParams p = smallParams(512);
  const double t = 0.2;
  p.extra["width"] = "0.2";
  p.extra["remap"] = remap ? "on" : "off";
  Profile out;
  out.frame = renderTechnique(findTechnique("modern.smoothies"), scene, p);
  out.expected = Image(p.width, p.height, 1, -1.0f);
  const double tanHalf = std::tan(glm::radians(double(scene.light.coneDegrees) / 2));
  const auto u = [&](double x, double y) { return 0.5 + 0.5 * x / ((4.0 - y) * tanHalf); };
  const double bOverR = (4.0 - testing::kOccluderTop) / 4.0;
  const double uEdge = u(testing::kOccluderHalfSide, testing::kOccluderTop);
  const double texel = 1.0 / p.shadowMapTexels;
  const double kink = remap ? t * (1.0 - bOverR) : t;  // d where a' reaches 1
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      auto g = testing::groundPoint(scene, p.width, p.height, x + 0.5f, y + 0.5f);
      if (!g || std::abs(g->z) > 0.3 || g->x < 0.3) continue;
      const double d = u(g->x, 0.0) - uEdge;
      if (std::abs(d) < 2 * texel || std::abs(d - kink) < 2 * texel) continue;
      const double a = d / t;
      const double alpha = d < 0 ? 0.0 : std::min(1.0, remap ? a / (1.0 - bOverR) : a);
      const double expected = d < 0 ? 0.0 : (1.0 - std::cos(glm::pi<double>() * alpha)) / 2;
      out.expected.at(x, y) = float(expected);
      out.worst = std::max(out.worst, std::abs(out.frame.visibility.at(x, y) - expected));
      ++out.checked;
      if (expected > 0.02 && expected < 0.98) ++out.penumbra;
    }
  return out;
}

TEST(Smoothies, PenumbraProfileAcrossAnAnalyticEdgeFollowsTheFalloff) {
  // Analytic scene: light at (0,4,0) looking straight down (light x = world x), occluder top face
  // at y = 1.01, ground at y = 0. Along the ground beyond the occluder's +x edge (|z| small, away
  // from the corners) the expected visibility is computed here from Chan's definitions alone:
  //   light screen u = 0.5 + 0.5 x / (depth tan(cone/2)), depth = 4 - y;
  //   d = u(ground) - u(edge) (map units), a = d / t, b/r = (4 - 1.01) / 4,
  //   a' = min(1, a / (1 - b/r)) (remapped, Eq. 4.1) or min(1, a) (remap=off),
  //   v = (1 - cos(pi a')) / 2; v = 0 where d < 0 (umbra).
  // Bilinear interpolation of a function linear in the map is exact, so away from the two kinks
  // (d = 0 and a' = 1, excluded within 2 shadow-map texels) the only errors are float round-off
  // of the world position (~1e-4 world units, slope <= 6 per unit) and the 256-texel falloff
  // table (< 1e-4): 0.002 bounds both (6e-4 + 1e-4) with margin.
  for (bool remap : {true, false}) {
    const Profile pr = penumbraProfile(remap);
    for (int y = 0; y < pr.expected.height; ++y)
      for (int x = 0; x < pr.expected.width; ++x)
        if (pr.expected.at(x, y) >= 0) {
          EXPECT_NEAR(pr.frame.visibility.at(x, y), pr.expected.at(x, y), 0.002)
              << "remap=" << remap << " pixel " << x << "," << y;
        }
    EXPECT_GT(pr.checked, 500) << "remap=" << remap;
    // The ramp spans several pixels: t(1 - b/r) = 0.05 of the map remapped, t = 0.2 not.
    EXPECT_GT(pr.penumbra, 40) << "remap=" << remap;
    RecordProperty(remap ? "worst_profile_error" : "worst_profile_error_remap_false",
                   std::to_string(pr.worst));
  }
}

TEST(Smoothies, RemapFalseWidensThePenumbraByOneOverOneMinusBOverR) {
  // Chan Fig. 4-4b vs 4-4d: on the analytic ground b/r = 0.7475, so the original alpha's ramp is
  // 1 / (1 - b/r) ~ 4 times as wide as the remapped one. In the remapped ramp the two masks
  // differ (at its middle the remapped v is 0.5, the original about 0.04); the original mask still
  // has penumbra where the remapped one is fully lit, and never more light than it.
  const Profile remapped = penumbraProfile(true);
  const Profile original = penumbraProfile(false);
  int differing = 0, onlyOriginalPenumbra = 0;
  for (int y = 0; y < remapped.frame.visibility.height; ++y)
    for (int x = 0; x < remapped.frame.visibility.width; ++x) {
      const float vr = remapped.frame.visibility.at(x, y), vo = original.frame.visibility.at(x, y);
      // a' is larger when remapped (a / (1 - b/r) >= a) and the falloff increases: vo <= vr, up to
      // float round-off of the two renders (1e-5).
      EXPECT_LE(vo, vr + 1e-5f) << x << "," << y;
      if (vr - vo > 0.1f) ++differing;
      if (vr > 0.999f && vo < 0.9f) ++onlyOriginalPenumbra;
    }
  EXPECT_GT(differing, 40);
  EXPECT_GT(onlyOriginalPenumbra, 40);
  EXPECT_GT(original.penumbra, 2 * remapped.penumbra);
}

TEST(Smoothies, SmoothieDepthCaptureIsTheOccludersLinearDepth) {
  // Fig. 4-1b: the captured smoothie depth (2-smoothie-depth) is linear from the light's near to
  // far plane. On the analytic scene every smoothie is built at the occluder's top edges, at
  // distance 4 - 1.01 along the light's axis, so every texel the smoothies cover holds
  // (4 - 1.01 - near) / (far - near); uncovered texels hold 1. Tolerance 1e-3: the 24-bit depth
  // buffer's step near 3 units from the light is far below it, and the depth-to-distance
  // inversion is exact up to float round-off.
  const Scene scene = builtinScene("analytic");
  RenderParams p = smallParams(256);
  p.extra["width"] = "0.1";
  p.capturePasses = true;
  const Frame f = renderTechnique(findTechnique("modern.smoothies"), scene, p);
  const Image* depth = nullptr;
  const Image* alpha = nullptr;
  for (const PassImage& i : f.intermediates) {
    if (i.name == "2-smoothie-depth") depth = &i.image;
    if (i.name == "3-smoothie-alpha") alpha = &i.image;
  }
  ASSERT_NE(depth, nullptr);
  ASSERT_NE(alpha, nullptr);
  const DepthRange range = lightDepthRange(scene);
  const float expected =
      (4.0f - testing::kOccluderTop - range.nearPlane) / (range.farPlane - range.nearPlane);
  int covered = 0;
  for (int y = 0; y < depth->height; ++y)
    for (int x = 0; x < depth->width; ++x) {
      const float d = depth->at(x, y);
      if (d >= 1.0f) continue;
      ++covered;
      EXPECT_NEAR(d, expected, 1e-3) << x << "," << y;
    }
  EXPECT_GT(covered, 100);
  // Where the alpha is strictly inside the ramp, a smoothie is there.
  for (int y = 0; y < alpha->height; ++y)
    for (int x = 0; x < alpha->width; ++x)
      if (alpha->at(x, y) > 0.05f && alpha->at(x, y) < 0.95f) {
        EXPECT_LT(depth->at(x, y), 1.0f) << x << "," << y;
      }
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
