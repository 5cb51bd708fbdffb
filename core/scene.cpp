#include "core/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>

#include "core/errors.h"

namespace sl {
namespace {
// When the fitted near plane would reach the light (geometry around or behind it), keep the
// near/far ratio at this value: beyond it a 24-bit depth buffer has no precision left.
constexpr float kMinNearOverFar = 1e-4f;
// Fitted depth ranges are widened by this share so that boundary geometry is not clipped.
constexpr float kDepthRangeMargin = 0.02f;

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
}  // namespace

Bounds worldBounds(const Object& object) {
  Bounds b;
  if (!object.mesh) return b;
  for (const glm::vec3& p : object.mesh->positions)
    b.extend(glm::vec3(object.model * glm::vec4(p, 1.0f)));
  return b;
}

Bounds sceneBounds(const Scene& scene) {
  Bounds b;
  for (const Object& o : scene.objects) {
    Bounds ob = worldBounds(o);
    if (ob.empty()) continue;
    b.extend(ob.lo);
    b.extend(ob.hi);
  }
  return b;
}

glm::mat4 cameraView(const Camera& camera) {
  return glm::lookAt(camera.position, camera.target, camera.up);
}

glm::mat4 cameraProjection(const Camera& camera, float aspect) {
  return glm::perspective(glm::radians(camera.fovyDegrees), aspect, camera.nearPlane,
                          camera.farPlane);
}

glm::mat4 lightView(const SpotLight& light) {
  glm::vec3 dir = glm::normalize(light.target - light.position);
  glm::vec3 up = light.up;
  if (std::fabs(glm::dot(glm::normalize(up), dir)) > 0.999f)
    up = std::fabs(dir.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, -1);
  return glm::lookAt(light.position, light.target, up);
}

DepthRange lightDepthRange(const Scene& scene) {
  const SpotLight& light = scene.light;
  // The range fitted to every object in front of the light.
  const auto fitted = [&] {
    const glm::mat4 view = lightView(light);
    float zMin = 1e30f, zMax = -1e30f;
    for (const Object& o : scene.objects) {
      if (!o.mesh) continue;
      const glm::mat4 m = view * o.model;
      for (const glm::vec3& p : o.mesh->positions) {
        const float z = -(m * glm::vec4(p, 1.0f)).z;  // distance along the light's view axis
        zMin = std::min(zMin, z);
        zMax = std::max(zMax, z);
      }
    }
    if (zMax <= 0.0f) {  // nothing in front of the light: any valid range will do
      zMin = 0.1f;
      zMax = 1.0f;
    }
    const float span = std::max(zMax - std::max(zMin, 0.0f), 1e-6f);
    DepthRange f;
    f.farPlane = zMax + kDepthRangeMargin * span;
    f.nearPlane = std::max(zMin - kDepthRangeMargin * span, f.farPlane * kMinNearOverFar);
    return f;
  };
  DepthRange r;
  if (light.nearPlane && light.farPlane) {
    r.nearPlane = *light.nearPlane;
    r.farPlane = *light.farPlane;
  } else {
    const DepthRange f = fitted();
    r.nearPlane = light.nearPlane.value_or(f.nearPlane);
    r.farPlane = light.farPlane.value_or(f.farPlane);
  }
  // A given range with near/far below kMinNearOverFar (near 8e-7, far 8, say) leaves a 24-bit
  // depth buffer no steps between the objects: hw and GPU Gems PCF drew every receiver lit
  // (issue 17 item 7). Such a range is narrowed to the part of it that holds geometry: nothing
  // lies between the given and the fitted planes, so no fragment changes side, and the fitted
  // range keeps near/far >= kMinNearOverFar. Where the given range holds no geometry at all,
  // it stays as given (nothing is drawn either way).
  if (r.nearPlane < r.farPlane * kMinNearOverFar) {
    const DepthRange f = fitted();
    DepthRange narrowed;
    narrowed.nearPlane = std::max(r.nearPlane, f.nearPlane);
    narrowed.farPlane = std::min(r.farPlane, f.farPlane);
    if (narrowed.nearPlane < narrowed.farPlane) r = narrowed;
  }
  return r;
}

glm::mat4 lightProjection(const Scene& scene) {
  const DepthRange r = lightDepthRange(scene);
  return glm::perspective(glm::radians(scene.light.coneDegrees), 1.0f, r.nearPlane, r.farPlane);
}

void validateScene(const Scene& scene) {
  const std::string where = "scene '" + scene.name + "': ";
  if (scene.objects.empty()) throw InputError(where + "has no objects");
  const Camera& c = scene.camera;
  if (!finite(c.position) || !finite(c.target) || !finite(c.up))
    throw InputError(where + "camera has a non-finite vector");
  if (glm::length(c.target - c.position) <= 0.0f)
    throw InputError(where + "camera position equals its target");
  if (!(c.fovyDegrees > 0.0f && c.fovyDegrees < 180.0f))
    throw InputError(where + "camera fov must be in (0, 180) degrees");
  if (!(c.nearPlane > 0.0f && c.farPlane > c.nearPlane && std::isfinite(c.farPlane)))
    throw InputError(where + "camera needs 0 < near < far");
  const SpotLight& l = scene.light;
  if (!finite(l.position) || !finite(l.target) || !finite(l.up) || !finite(l.color))
    throw InputError(where + "light has a non-finite vector");
  if (glm::length(l.target - l.position) <= 0.0f)
    throw InputError(where + "light position equals its target");
  if (!(l.coneDegrees > 0.0f && l.coneDegrees < 180.0f))
    throw InputError(where + "light cone must be in (0, 180) degrees");
  if (l.nearPlane && !(*l.nearPlane > 0.0f && std::isfinite(*l.nearPlane)))
    throw InputError(where + "light near plane must be positive");
  if (l.farPlane && !(std::isfinite(*l.farPlane) && *l.farPlane > l.nearPlane.value_or(0.0f)))
    throw InputError(where + "light far plane must lie beyond the near plane");
  if (!(l.radius >= 0.0f && std::isfinite(l.radius)))
    throw InputError(where + "light radius must be >= 0");
  if (!(l.ambient >= 0.0f && l.ambient <= 1.0f))
    throw InputError(where + "light ambient must be in [0, 1]");
  for (const Object& o : scene.objects) {
    if (!o.mesh || o.mesh->indices.empty())
      throw InputError(where + "object '" + o.name + "' has no triangles");
    for (int i = 0; i < 4; ++i)
      if (!finite(glm::vec3(o.model[i])) || !std::isfinite(o.model[i][3]))
        throw InputError(where + "object '" + o.name + "' has a non-finite transform");
  }
  // Stiff light/camera ranges (issue 17 items 7, 8, 10) -------------------------------------
  // A spotlight cone near 180 degrees: one perspective shadow map spreads its texels over
  // 2 tan(cone/2) at unit distance, so at the centre of the map a texel spans tan(cone/2) times
  // what it spans under a 90-degree cone (5.7x at 160 degrees, 1146x at 179.9, where every
  // caster fell inside one texel and every shadow-map technique drew an all-lit mask).
  // Measured on the boxes scene with a 512 map: hw 4% of pixels wrong at 160 degrees, 5.5% at
  // 170 and 13% at 175 (1.4% at 120). A wider light needs several maps (a cube map).
  constexpr float kMaxLightConeDegrees = 160.0f;
  if (l.coneDegrees > kMaxLightConeDegrees) {
    char message[200];
    std::snprintf(message, sizeof message,
                  "light.cone %g degrees is too wide for one perspective shadow map: its central "
                  "texels span %.0fx those of a 90-degree cone (at most %g degrees, %.1fx)",
                  double(l.coneDegrees), std::tan(glm::radians(0.5 * double(l.coneDegrees))),
                  double(kMaxLightConeDegrees),
                  std::tan(glm::radians(0.5 * double(kMaxLightConeDegrees))));
    throw InputError(where + message);
  }
  // The camera's depth buffer has 24 bits: at distance z it resolves about
  // z^2 / (near 2^24). At near/far 1e-5 that is 0.6% of far at far; below it surfaces z-fight
  // (near/far 5e-8: the ground showed through the boxes in every technique and the reference;
  // 5e-14: every fragment failed the depth test, and modern.volumes' z-fail counts streaked).
  // The light's range needs no such bound: lightDepthRange narrows a stiff one to the geometry.
  constexpr float kMinCameraNearOverFar = 1e-5f;
  if (c.nearPlane < c.farPlane * kMinCameraNearOverFar) {  // in float: the bound itself passes
    char message[200];
    std::snprintf(message, sizeof message,
                  "camera.near/far ratio %.3g leaves a 24-bit depth buffer no precision: at "
                  "least %g (near >= far * %g)",
                  double(c.nearPlane) / double(c.farPlane), double(kMinCameraNearOverFar),
                  double(kMinCameraNearOverFar));
    throw InputError(where + message);
  }
  // World coordinates: ray-triangle tests (Embree's, the reference's) and the shadow volumes
  // multiply coordinates, whose products overflow float (3.4e38) at large enough scales.
  // Measured on the boxes scene scaled up: with coordinates up to 1.2e13 every technique matched
  // the unscaled scene; at 2.4e13 modern.volumes and modern.hybrid put every receiver in umbra,
  // and from 4e13 reference.hard lost shadows. The bound keeps a factor of 10 below the first.
  constexpr float kMaxWorldCoordinate = 1e12f;
  const auto tooFar = [&](const glm::vec3& p) {
    return std::fabs(p.x) > kMaxWorldCoordinate || std::fabs(p.y) > kMaxWorldCoordinate ||
           std::fabs(p.z) > kMaxWorldCoordinate;
  };
  const auto refuseCoordinate = [&](const std::string& field, const glm::vec3& p) {
    char message[240];
    std::snprintf(message, sizeof message,
                  "%s reaches (%g, %g, %g): world coordinates must stay within +-%g (products "
                  "of coordinates in ray and shadow-volume tests overflow float from about 2e13)",
                  field.c_str(), double(p.x), double(p.y), double(p.z),
                  double(kMaxWorldCoordinate));
    throw InputError(where + message);
  };
  if (tooFar(c.position)) refuseCoordinate("camera.position", c.position);
  if (tooFar(l.position)) refuseCoordinate("light.position", l.position);
  for (const Object& o : scene.objects)
    for (const glm::vec3& p : o.mesh->positions) {
      const glm::vec3 w = glm::vec3(o.model * glm::vec4(p, 1.0f));
      if (tooFar(w)) refuseCoordinate("object '" + o.name + "'", w);
    }
  // ------------------------------------------------------------------------------------------
}

}  // namespace sl
