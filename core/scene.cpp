#include "core/scene.h"

#include <algorithm>
#include <cmath>

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
  DepthRange r;
  if (light.nearPlane && light.farPlane) {
    r.nearPlane = *light.nearPlane;
    r.farPlane = *light.farPlane;
    return r;
  }
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
  float farPlane = zMax + kDepthRangeMargin * span;
  float nearPlane = std::max(zMin - kDepthRangeMargin * span, farPlane * kMinNearOverFar);
  r.nearPlane = light.nearPlane.value_or(nearPlane);
  r.farPlane = light.farPlane.value_or(farPlane);
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
}

}  // namespace sl
