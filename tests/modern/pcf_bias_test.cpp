// --param bias of the GPU Gems PCF family (modern/gems_pcf.cpp, modern/shaders/pcf_bias.glsl):
// the receiver-plane depth bias (ours, after Isidoro 2006, Dou et al. 2014) on an analytic
// tilted plane, the normal offset (ours, after Holbert 2011) by the distance a shadow edge
// moves, and the declarations and refusals of the parameters.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/base/errors.h"
#include "core/scene/primitives.h"
#include "filtered_shadows_util.h"

namespace sl {
namespace {
using namespace sl::testing_filtered;

constexpr int kWidth = 160;
constexpr int kHeight = 120;
constexpr int kMapTexels = 512;

Object makeObject(const std::string& name, Mesh mesh, const glm::mat4& model, bool casts) {
  Object o;
  o.name = name;
  o.mesh = std::make_shared<const Mesh>(std::move(mesh));
  o.model = model;
  o.castsShadow = casts;
  o.receivesShadow = true;
  return o;
}

// One flat ground that casts and receives, lit at `degrees` from its normal, seen from above:
// every pixel is ground, within 0.6 units of the light's target, and nothing can shadow it.
// Any shadowed pixel is acne.
Scene tiltedPlane(float degrees) {
  Scene s;
  s.name = "tilted plane";
  s.objects.push_back(makeObject("ground", makePlane(4, 4, 8), glm::mat4(1), true));
  s.camera.position = {0, 2.0f, 0.01f};
  s.camera.target = {0, 0, 0};
  s.camera.up = {0, 0, -1};
  s.camera.fovyDegrees = 30;
  s.camera.nearPlane = 0.5f;
  s.camera.farPlane = 10;
  const float a = glm::radians(degrees);
  constexpr float kLightDistance = 5.0f;
  s.light.position = {kLightDistance * std::sin(a), kLightDistance * std::cos(a), 0};
  s.light.target = {0, 0, 0};
  s.light.up = {0, 1, 0};
  s.light.coneDegrees = 60;
  return s;
}

// A pixel of the fully lit plane darkened by more than the 8-bit visibility's rounding and the
// hardware compare's blending of a texel at exactly the receiver's depth: acne.
constexpr float kLit = 0.95f;
double darkenedShare(const Image& visibility) {
  long long darkened = 0;
  for (float v : visibility.data) darkened += v < kLit;
  return double(darkened) / double(visibility.data.size());
}

// Constant and receiver-plane bias at the same constant (bias-texels 0.5, 4 depth units) and no
// slope-scaled polygon offset: the plane's depth grows by tan 75 = 3.7 texel widths per texel
// across the light's view, the 4x4 region reaches 2.5 texels from the lookup point, so the
// constant bias shadows the plane; the receiver plane compares each lookup with the plane's own
// depth there and leaves it lit.
TEST(PcfBias, ReceiverPlaneRemovesAcneThatTheSameConstantLeaves) {
  const Scene scene = tiltedPlane(75);
  for (const char* kernel : {"box", "bicubic"}) {
    std::map<std::string, std::string> extra = {
        {"offset-factor", "0"}, {"bias-texels", "0.5"}, {"kernel", kernel}};
    const Frame constant =
        renderByName("modern.gems16", scene, smallParams(kWidth, kHeight, kMapTexels, extra));
    extra["bias"] = "receiver-plane";
    const Frame plane =
        renderByName("modern.gems16", scene, smallParams(kWidth, kHeight, kMapTexels, extra));
    ASSERT_TRUE(allFinite(plane.visibility));
    // The constant bias: the plane darkens itself over much of its area (the lookups on the
    // light's side of the point, half the region, reach texels shallower than the point by more
    // than the constant); a tenth is far below that and far above the receiver plane's.
    EXPECT_GT(darkenedShare(constant.visibility), 0.1) << kernel;
    // The receiver plane: no acne at all; 0.2% allows the few pixels of a 2x2 quad whose
    // derivatives straddle two triangles of the tessellated plane (the plane is one plane, so
    // none are expected; measured 0).
    EXPECT_LT(darkenedShare(plane.visibility), 0.002) << kernel;
  }
}

// ------------------------------------------------------------------------ normal offset
// A thin slab above the ground, its edge parallel to z, lit from x < 0 by a light at height h.
// The normal offset moves the ground point P up by o; the light ray through P + o n meets the
// ground at P + o tan(a) in x (to first order in o / h, 1% here), a the light's angle from the
// normal at P, so every pixel shows the shadow of the ground point o tan(a) further from the
// light: the shadow's edge moves o tan(a) towards the light. o = normal-offset-texels texel
// footprints at P's distance r from the light, a footprint being r 2 tan(cone / 2) / size.
constexpr float kEdgeLightDegrees = 45;
constexpr float kEdgeCone = 60;
Scene edgeScene() {
  Scene s;
  s.name = "slab edge";
  s.objects.push_back(makeObject("ground", makePlane(4, 4, 8), glm::mat4(1), false));
  s.objects.push_back(makeObject("slab", makeBox({1.0f, 0.02f, 2.0f}),
                                 glm::translate(glm::mat4(1), {-0.5f, 0.5f, 0}), true));
  s.camera.position = {0.5f, 1.5f, 0.01f};  // above the shadow's edge at x = 0.5
  s.camera.target = {0.5f, 0, 0};
  s.camera.up = {0, 0, -1};
  s.camera.fovyDegrees = 20;
  s.camera.nearPlane = 0.5f;
  s.camera.farPlane = 10;
  const float a = glm::radians(kEdgeLightDegrees);
  s.light.position = {-3.0f * std::sin(a), 3.0f * std::cos(a), 0};
  s.light.target = {0, 0, 0};
  s.light.up = {0, 1, 0};
  s.light.coneDegrees = kEdgeCone;
  return s;
}

// The world x where row y's visibility first rises through 0.5 (lit to the right), linearly
// interpolated between the pixel centres; nothing if the row has no such crossing.
std::optional<float> edgeX(const Scene& scene, const RenderParams& p, const Image& v, int y) {
  for (int x = 0; x + 1 < v.width; ++x) {
    const float a = v.at(x, y), b = v.at(x + 1, y);
    if (a < 0.5f && b >= 0.5f) {
      const float t = (0.5f - a) / (b - a);
      const glm::vec3 g0 = groundPointOf(scene, p, float(x), float(y));
      const glm::vec3 g1 = groundPointOf(scene, p, float(x + 1), float(y));
      return g0.x + t * (g1.x - g0.x);
    }
  }
  return std::nullopt;
}

TEST(PcfBias, NormalOffsetMovesTheLookupByTheExpectedWorldDistance) {
  const Scene scene = edgeScene();
  constexpr float kOffsetTexels = 6;
  constexpr int kTexels = 1024;
  // bicubic: the B-spline is symmetric, so the 0.5 crossing of a straight edge follows the
  // edge; the same kernel in both renders.
  const RenderParams base = smallParams(kWidth, kHeight, kTexels, {{"kernel", "bicubic"}});
  RenderParams moved = base;
  moved.extra["bias"] = "normal-offset";
  moved.extra["normal-offset-texels"] = std::to_string(kOffsetTexels);
  const Frame before = renderByName("modern.gems16", scene, base);
  const Frame after = renderByName("modern.gems16", scene, moved);
  ASSERT_TRUE(allFinite(after.visibility));
  const float footprintPerDistance =
      2.0f * std::tan(glm::radians(kEdgeCone) * 0.5f) / float(kTexels);
  int rows = 0;
  for (int y = kHeight / 4; y < 3 * kHeight / 4; ++y) {
    const std::optional<float> x0 = edgeX(scene, base, before.visibility, y);
    const std::optional<float> x1 = edgeX(scene, moved, after.visibility, y);
    if (!x0 || !x1) continue;
    ++rows;
    const glm::vec3 edge(*x0, 0, groundPointOf(scene, base, 0, float(y)).z);
    const glm::vec3 toLight = scene.light.position - edge;
    const float r = glm::length(toLight);
    const float offset = kOffsetTexels * r * footprintPerDistance;
    const float tanAngle = std::sqrt(toLight.x * toLight.x + toLight.z * toLight.z) / toLight.y;
    const float expected = -offset * tanAngle;
    // The crossing of each render lies within a small fraction of a texel of the edge (the
    // texel grid sits differently under the two lookups) and is read to a fraction of a
    // pixel: a quarter of the expected move (1.5 of its 6 texels) bounds both; no offset, or
    // one not scaled by the footprint (o = 6 world units), is far outside it.
    EXPECT_NEAR(*x1 - *x0, expected, 0.25f * std::abs(expected)) << "row " << y;
  }
  EXPECT_GT(rows, kHeight / 4) << "the edge must cross most rows";
}

// With normal-offset-by-angle the move is scaled by 1 - N.L, N.L the cosine of the light's angle
// from the ground's normal at the edge.
TEST(PcfBias, NormalOffsetByAngleScalesByOneMinusNDotL) {
  const Scene scene = edgeScene();
  constexpr int kTexels = 1024;
  const RenderParams base = smallParams(kWidth, kHeight, kTexels, {{"kernel", "bicubic"}});
  RenderParams plain = base, scaled = base;
  plain.extra = {{"kernel", "bicubic"}, {"bias", "normal-offset"}, {"normal-offset-texels", "8"}};
  scaled.extra = plain.extra;
  scaled.extra["normal-offset-by-angle"] = "on";
  const Frame f0 = renderByName("modern.gems16", scene, base);
  const Frame f1 = renderByName("modern.gems16", scene, plain);
  const Frame f2 = renderByName("modern.gems16", scene, scaled);
  double movePlain = 0, moveScaled = 0, oneMinusNDotL = 0;
  int rows = 0;
  for (int y = kHeight / 4; y < 3 * kHeight / 4; ++y) {
    const auto x0 = edgeX(scene, base, f0.visibility, y), x1 = edgeX(scene, base, f1.visibility, y),
               x2 = edgeX(scene, base, f2.visibility, y);
    if (!x0 || !x1 || !x2) continue;
    movePlain += *x1 - *x0;
    moveScaled += *x2 - *x0;
    const glm::vec3 edge(*x0, 0, groundPointOf(scene, base, 0, float(y)).z);
    oneMinusNDotL += 1.0 - glm::normalize(scene.light.position - edge).y;
    ++rows;
  }
  ASSERT_GT(rows, kHeight / 4);
  const double expectedRatio = oneMinusNDotL / rows;
  // Averaged over the rows; the scaled move is about 3 of its 8 texel footprints, each render's
  // edge read to a fraction of a pixel (a footprint is about one pixel here): a third of the
  // ratio; without the scaling the ratio is 1, with N.L instead of 1 - N.L about 1.5 times it.
  EXPECT_NEAR(moveScaled / movePlain, expectedRatio, expectedRatio / 3);
}

// ------------------------------------------------------------------------ declarations
TEST(PcfBias, DeclaredOnEveryGemsTechniqueWithConstantAsDefault) {
  for (const char* name : {"modern.gems16", "modern.gems4"}) {
    const Technique& t = findTechnique(name);
    const ParamSpec* bias = findParam(t, "bias");
    ASSERT_NE(bias, nullptr) << name;
    EXPECT_EQ(bias->choices,
              (std::vector<std::string>{"constant", "receiver-plane", "normal-offset"}));
    EXPECT_EQ(bias->defaultText(), "constant") << "today's images stay the default";
    ASSERT_NE(findParam(t, "normal-offset-texels"), nullptr) << name;
    EXPECT_NE(describeParam(*findParam(t, "normal-offset-texels")).find("texel"),
              std::string::npos);
    ASSERT_NE(findParam(t, "normal-offset-by-angle"), nullptr) << name;
  }
}

TEST(PcfBias, BadValuesAreInputErrors) {
  const Scene scene = builtinScene("analytic");
  auto render = [&](std::map<std::string, std::string> extra) {
    renderByName("modern.gems4", scene, smallParams(32, 32, 32, std::move(extra)));
  };
  EXPECT_THROW(render({{"bias", "slope"}}), InputError);
  EXPECT_THROW(render({{"bias", "normal-offset"}, {"normal-offset-texels", "-1"}}), InputError);
  EXPECT_THROW(render({{"bias", "normal-offset"}, {"normal-offset-texels", "9"}}), InputError);
  EXPECT_THROW(render({{"bias", "normal-offset"}, {"normal-offset-by-angle", "maybe"}}),
               InputError);
  // The normal offset's keys with another method would be silently ignored: refused, but for
  // their defaults (every render accepts a technique's declared defaults).
  EXPECT_THROW(render({{"normal-offset-texels", "2"}}), InputError);
  EXPECT_THROW(render({{"bias", "receiver-plane"}, {"normal-offset-by-angle", "on"}}), InputError);
  EXPECT_NO_THROW(render({{"bias", "receiver-plane"}, {"normal-offset-texels", "2.5"}}));
  EXPECT_NO_THROW(render({{"bias", "normal-offset"}, {"normal-offset-texels", "8"}}));
}

// The command line: one line on stderr, exit status 2.
TEST(PcfBias, CommandLineRefusesABadBiasWithOneLineAndExitTwo) {
  const std::string err = outputPath("pcf-bias-cli.err");
  for (const char* params :
       {"--param bias=slope", "--param bias=normal-offset --param normal-offset-texels=100"}) {
    const std::string command = std::string(SHADOWLAB_BINARY) +
                                " render --scene analytic --technique modern.gems16 --size 32x24 " +
                                params + " --out " + outputPath("pcf-bias-cli.png") +
                                " >/dev/null 2>" + err;
    const int raw = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(raw));
    EXPECT_EQ(WEXITSTATUS(raw), 2) << params;
    std::ifstream in(err);
    std::string text;
    std::getline(in, text, '\0');
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << "one line: " << text;
  }
}

}  // namespace
}  // namespace sl
