// reference/surface_buffer.h — the camera's visible surface points, rasterised with GL
// (module-internal header).
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "core/technique/technique.h"

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

// The same pass, repeated at sub-pixel positions (the pixel-integrated references): the scene
// is uploaded once, then each rasterise(offset) draws it with the camera's projection moved so
// that pixel (x, y) gets the surface point GL sees at window position (x + 0.5 + offset.x,
// y + 0.5 + offset.y). rasterise({0, 0}) equals rasteriseSurfacePoints bit for bit; at other
// offsets (sub-pixel samples, used for shadow rays only) shadingNormal = geometricNormal.
class SurfaceRasteriser {
 public:
  SurfaceRasteriser(const Scene& scene, const RenderParams& params);
  ~SurfaceRasteriser();
  SurfaceRasteriser(const SurfaceRasteriser&) = delete;
  SurfaceRasteriser& operator=(const SurfaceRasteriser&) = delete;
  std::vector<SurfacePoint> rasterise(glm::vec2 offsetPixels);

 private:
  struct GlState;
  const Scene& scene_;
  int width_, height_;
  std::unique_ptr<GlState> gl_;
};

}  // namespace sl::reference
