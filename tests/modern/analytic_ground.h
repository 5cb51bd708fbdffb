// tests/modern/analytic_ground.h — where a camera pixel of the analytic scene lands, computed
// from the camera matrices alone (independently of any technique): ray through the pixel centre
// (or a sub-pixel position), intersected with the ground plane y = 0 and the occluder slab.
#pragma once

#include <glm/glm.hpp>
#include <optional>

#include "core/scene/scene.h"

namespace sl::testing {

// The analytic scene's occluder: a box of size (1, 0.02, 1) centred at (0, 1, 0).
constexpr float kOccluderHalfSide = 0.5f;
constexpr float kOccluderTop = 1.01f;
constexpr float kOccluderBottom = 0.99f;

struct PixelRay {
  glm::vec3 origin;
  glm::vec3 direction;
};

// Ray through window position (px, py) (pixels, y up, pixel centres at +0.5).
inline PixelRay pixelRay(const Scene& scene, int width, int height, float px, float py) {
  const glm::mat4 inv = glm::inverse(cameraProjection(scene.camera, float(width) / height) *
                                     cameraView(scene.camera));
  const glm::vec2 ndc(2.0f * px / width - 1.0f, 2.0f * py / height - 1.0f);
  glm::vec4 n = inv * glm::vec4(ndc, -1.0f, 1.0f);
  glm::vec4 f = inv * glm::vec4(ndc, 1.0f, 1.0f);
  const glm::vec3 a = glm::vec3(n) / n.w, b = glm::vec3(f) / f.w;
  return {a, glm::normalize(b - a)};
}

// The ground point seen at (px, py), or nothing when the ray meets the occluder first (with a
// margin of `margin` world units around it) or misses the ground.
inline std::optional<glm::vec3> groundPoint(const Scene& scene, int width, int height, float px,
                                            float py, float margin = 0.02f) {
  const PixelRay r = pixelRay(scene, width, height, px, py);
  if (r.direction.y >= 0.0f) return std::nullopt;
  // The slab between y = bottom - margin and top + margin.
  for (float y : {kOccluderTop + margin, kOccluderBottom - margin}) {
    const float s = (y - r.origin.y) / r.direction.y;
    const glm::vec3 p = r.origin + s * r.direction;
    if (std::abs(p.x) <= kOccluderHalfSide + margin && std::abs(p.z) <= kOccluderHalfSide + margin)
      return std::nullopt;
  }
  const float s = -r.origin.y / r.direction.y;
  return r.origin + s * r.direction;
}

}  // namespace sl::testing
