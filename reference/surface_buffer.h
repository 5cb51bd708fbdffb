// reference/surface_buffer.h — the camera's visible surface points, rasterised with GL
// (module-internal header).
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "core/technique.h"

namespace sl::reference {

// One camera pixel's surface point. `object` < 0: the pixel sees no geometry.
struct SurfacePoint {
  glm::vec3 position{0.0f};         // world space
  glm::vec3 shadingNormal{0.0f};    // interpolated vertex normal, facing the camera
  glm::vec3 geometricNormal{0.0f};  // the triangle's plane normal, facing the camera
  int object = -1;                  // index into Scene::objects
};

// Rasterises the scene with the camera of `params` (window width x height, rows bottom-up)
// in the current core-profile context: pixel (x, y) gets the surface point that GL's
// rasterisation of pixel centre (x + 0.5, y + 0.5) sees, exactly as in the modern camera pass.
std::vector<SurfacePoint> rasteriseSurfacePoints(const Scene& scene, const RenderParams& params);

}  // namespace sl::reference
