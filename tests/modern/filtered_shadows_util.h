// tests/modern/filtered_shadows_util.h — helpers shared by the tests of modern.gems*, modern.csm
// and modern.vsm: render a technique by name, find the pixel a world point projects to, and
// write failure artefacts.
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <map>
#include <string>

#include "core/base/image.h"
#include "core/scene/scene.h"
#include "core/scene/scene_library.h"
#include "registry/registry.h"

namespace sl::testing_filtered {

inline RenderParams smallParams(int width, int height, int shadowMapTexels,
                                std::map<std::string, std::string> extra = {}) {
  RenderParams p;
  p.width = width;
  p.height = height;
  p.shadowMapTexels = shadowMapTexels;
  p.extra = std::move(extra);
  return p;
}

inline Frame renderByName(const std::string& technique, const Scene& scene,
                          const RenderParams& params) {
  return renderTechnique(findTechnique(technique), scene, params);
}

// The window pixel (x right, y up, as Frame images) whose centre is nearest to `world`.
inline glm::ivec2 pixelOf(const Scene& scene, const RenderParams& p, const glm::vec3& world) {
  const glm::vec4 clip = cameraProjection(scene.camera, float(p.width) / float(p.height)) *
                         cameraView(scene.camera) * glm::vec4(world, 1.0f);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return glm::ivec2(int((ndc.x * 0.5f + 0.5f) * float(p.width)),
                    int((ndc.y * 0.5f + 0.5f) * float(p.height)));
}

// Where the ray through the centre of pixel (x, y) meets the plane y = planeY.
inline glm::vec3 groundPointOf(const Scene& scene, const RenderParams& p, float x, float y,
                               float planeY = 0.0f) {
  const glm::mat4 inverse = glm::inverse(
      cameraProjection(scene.camera, float(p.width) / float(p.height)) * cameraView(scene.camera));
  const glm::vec2 ndc((x + 0.5f) / float(p.width) * 2.0f - 1.0f,
                      (y + 0.5f) / float(p.height) * 2.0f - 1.0f);
  glm::vec4 nearPoint = inverse * glm::vec4(ndc, -1.0f, 1.0f);
  glm::vec4 farPoint = inverse * glm::vec4(ndc, 1.0f, 1.0f);
  const glm::vec3 a = glm::vec3(nearPoint) / nearPoint.w;
  const glm::vec3 b = glm::vec3(farPoint) / farPoint.w;
  const float s = (planeY - a.y) / (b.y - a.y);
  return a + s * (b - a);
}

// Shadow-map texel coordinates (0..size) of a world point.
inline glm::vec2 shadowTexelOf(const Scene& scene, int size, const glm::vec3& world) {
  const glm::vec4 c = lightProjection(scene) * lightView(scene.light) * glm::vec4(world, 1.0f);
  return (glm::vec2(c) / c.w * 0.5f + 0.5f) * float(size);
}

inline std::string outputPath(const std::string& name) {
  std::filesystem::create_directories(SHADOWLAB_TEST_OUTPUT_DIR);
  return std::string(SHADOWLAB_TEST_OUTPUT_DIR) + "/" + name;
}

}  // namespace sl::testing_filtered
