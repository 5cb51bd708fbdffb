// legacy_gl/projected_spotlight.h: the spotlight cone projected from the light cuts the cone's
// edge per pixel (at any tessellation: here one quad) where the modern twins' test
// `dot(-toLight, axis) >= cos(cone / 2)` does, and lights nothing behind the light.
#include "legacy_gl/projected_spotlight.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <memory>

#include "core/base/errors.h"
#include "core/gl/context.h"
#include "core/scene/scene_library.h"
#include "legacy_gl/fixed_function.h"

namespace sl::legacy {
namespace {

using namespace sl::gl;

TEST(ProjectedSpotlight, ConeAlphaIsHalfOnTheConeEdge) {
  EXPECT_FLOAT_EQ(coneTextureAlpha(0.0, 0.0), 1.0f);
  EXPECT_FLOAT_EQ(coneTextureAlpha(1.0, 0.0), kConeEdgeAlpha);
  EXPECT_FLOAT_EQ(coneTextureAlpha(0.6, 0.8), kConeEdgeAlpha);
  EXPECT_FLOAT_EQ(coneTextureAlpha(kConeTextureExtent, 0.0), 0.0f) << "the margin reads outside";
  EXPECT_GT(coneTextureAlpha(0.99, 0.0), kConeEdgeAlpha);
  EXPECT_LT(coneTextureAlpha(1.01, 0.0), kConeEdgeAlpha);
}

// A world point on the cone's surface lands on the disc's edge: (s/q, t/q) at 1 / (2E) from the
// texture's centre; q > 0 in front of the light, < 0 behind it.
TEST(ProjectedSpotlight, ConeSurfaceMapsToTheDiscEdge) {
  const Scene scene = builtinScene("brabec");
  const glm::mat4 m = worldToConeTexture(scene);
  const glm::mat4 lightToWorld = glm::inverse(lightView(scene.light));
  const double half = glm::radians(0.5 * double(scene.light.coneDegrees));
  constexpr double kDistance = 4.0;
  constexpr double kFloatRounding = 1e-5;  // float matrices, relative to the unit radius
  for (const double turn : {0.0, 0.7, 2.0, 4.1}) {
    const glm::vec4 eye(float(kDistance * std::tan(half) * std::cos(turn)),
                        float(kDistance * std::tan(half) * std::sin(turn)), float(-kDistance), 1);
    const glm::vec4 st = m * (lightToWorld * eye);
    ASSERT_GT(st.w, 0.0f);
    const double x = (st.x / st.w - 0.5) * 2.0 * kConeTextureExtent;
    const double y = (st.y / st.w - 0.5) * 2.0 * kConeTextureExtent;
    EXPECT_NEAR(std::hypot(x, y), 1.0, kFloatRounding) << "turn " << turn;
    const glm::vec4 behind = m * (lightToWorld * glm::vec4(glm::vec3(eye) * -1.0f, 1.0f));
    EXPECT_LT(behind.w, 0.0f);
  }
}

constexpr int kSide = 160;

// One quad perpendicular to `axisSign` x the light's axis at kQuadDistance, drawn white from a
// camera at the light with the projected cone on; the red channel read back.
Image drawQuadThroughCone(Scene scene, float axisSign, float fovyDegrees) {
  constexpr float kQuadDistance = 5.0f;
  const glm::vec3 axis = glm::normalize(scene.light.target - scene.light.position);
  scene.camera.position = scene.light.position;
  scene.camera.target = scene.light.position + axisSign * axis;
  scene.camera.up = scene.light.up;
  scene.camera.fovyDegrees = fovyDegrees;
  scene.camera.nearPlane = 0.5f;
  scene.camera.farPlane = 50.0f;
  const float extent = 2.0f * kQuadDistance * std::tan(glm::radians(fovyDegrees));
  const glm::mat4 cameraToWorld = glm::inverse(cameraView(scene.camera));
  glClearColor(0, 0, 0, 0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  setCameraMatrices(scene, kSide, kSide);
  disableLighting();
  glDisable(GL_DEPTH_TEST);
  glColor4f(1, 1, 1, 1);
  {
    const SpotlightConeTexture texture;
    const ProjectedSpotlightCone cone(scene, texture, GL_TEXTURE1);
    glBegin(GL_QUADS);
    for (const glm::vec2 c :
         {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
      const glm::vec4 w = cameraToWorld * glm::vec4(extent * c, -kQuadDistance, 1.0f);
      glVertex3f(w.x, w.y, w.z);
    }
    glEnd();
  }
  checkGl("cone quad");
  return readRedChannel(kSide, kSide);
}

std::unique_ptr<GlContext> smallContext() {
  ContextSpec spec;
  spec.width = kSide;
  spec.height = kSide;
  spec.profile = Profile::kCompatibility;
  return GlContext::create(spec);
}

// From the light, the cone is a circle on screen: a pixel is lit exactly when its centre's
// direction lies within cone / 2 of the axis. Pixels whose centre lies within
// kEdgeTolerancePixels of the circle may go either way (the bilinear distance's contour and the
// rasteriser's float texture coordinates).
TEST(ProjectedSpotlight, LightsExactlyThePixelsInsideTheCone) {
  auto context = smallContext();
  const Scene scene = builtinScene("brabec");
  const float fovy = 1.5f * scene.light.coneDegrees;
  const Image red = drawQuadThroughCone(scene, 1.0f, fovy);
  const double radius =  // the circle's radius in pixels
      std::tan(glm::radians(0.5 * double(scene.light.coneDegrees))) /
      std::tan(glm::radians(0.5 * double(fovy))) * 0.5 * kSide;
  constexpr double kEdgeTolerancePixels = 0.05;
  int lit = 0, wrong = 0;
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      const double r = std::hypot(x + 0.5 - 0.5 * kSide, y + 0.5 - 0.5 * kSide);
      const bool shown = red.at(x, y) > 0.5f;
      lit += shown;
      if (std::fabs(r - radius) <= kEdgeTolerancePixels) continue;
      if (shown != (r < radius)) {
        ++wrong;
        ADD_FAILURE() << "pixel (" << x << ", " << y << ") at " << r - radius
                      << " px from the cone's edge is " << (shown ? "lit" : "dark");
        if (wrong > 10) return;
      }
    }
  EXPECT_GT(lit, 1000) << "the cone lit nothing";
}

// Behind the light q < 0 and (s/q, t/q) would show the cone mirrored: the clip plane removes it.
TEST(ProjectedSpotlight, LightsNothingBehindTheLight) {
  auto context = smallContext();
  const Scene scene = builtinScene("brabec");
  const Image red = drawQuadThroughCone(scene, -1.0f, 1.5f * scene.light.coneDegrees);
  float brightest = 0.0f;
  for (float v : red.data) brightest = std::max(brightest, v);
  EXPECT_EQ(brightest, 0.0f) << "a mirrored cone behind the light";
}

}  // namespace
}  // namespace sl::legacy
