#include "core/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>

#include "core/base/errors.h"

namespace sl {
namespace {
// When the fitted near plane would reach the light (geometry around or behind it), keep the
// near/far ratio at this value: beyond it a 24-bit depth buffer has no precision left.
constexpr float kMinNearOverFar = 1e-4f;
// Fitted depth ranges are widened by this share so that boundary geometry is not clipped.
constexpr float kDepthRangeMargin = 0.02f;
// A scene flat in light space (one receiver facing the light) still gets a depth range of this
// share of its distance: without it near == far in float and the projection divides by zero.
constexpr float kMinDepthSpanShare = 1e-3f;

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
    const float span = std::max(zMax - std::max(zMin, 0.0f), kMinDepthSpanShare * zMax);
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
  // depth buffer no steps between the objects: hw and GPU Gems PCF drew every receiver lit.
  // Such a range is narrowed to the part of it that holds geometry: nothing
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

float lightDepthRoundoffScale(const Scene& scene) {
  const DepthRange r = lightDepthRange(scene);
  return std::max(1.0f, 2.0f * r.nearPlane / (r.farPlane - r.nearPlane));
}

glm::mat4 lightProjection(const Scene& scene) {
  const DepthRange r = lightDepthRange(scene);
  return glm::perspective(glm::radians(scene.light.coneDegrees), 1.0f, r.nearPlane, r.farPlane);
}

namespace {

// One mesh's own consistency: what every technique indexes without checking again.
void validateMesh(const Mesh& mesh, const std::string& where) {
  if (mesh.indices.empty()) throw InputError(where + " has no triangles");
  if (mesh.indices.size() % 3 != 0)
    throw InputError(where + " has " + std::to_string(mesh.indices.size()) +
                     " indices, not a multiple of 3");
  if (mesh.normals.size() != mesh.positions.size())
    throw InputError(where + " has " + std::to_string(mesh.normals.size()) + " normals for " +
                     std::to_string(mesh.positions.size()) + " positions");
  const size_t n = mesh.positions.size();
  for (unsigned index : mesh.indices)
    if (index >= n)
      throw InputError(where + " has vertex index " + std::to_string(index) + " of " +
                       std::to_string(n) + " vertices");
  for (size_t i = 0; i < n; ++i)
    if (!finite(mesh.positions[i]) || !finite(mesh.normals[i]))
      throw InputError(where + " has a non-finite vertex");
}

// `up` must be a direction that is not (nearly) parallel to the view direction.
void validateUp(const glm::vec3& up, const glm::vec3& from, const glm::vec3& to,
                const std::string& what) {
  const float length = glm::length(up);
  if (!(length > 0.0f)) throw InputError(what + " must not be [0, 0, 0]");
  const glm::vec3 view = glm::normalize(to - from);
  if (glm::length(glm::cross(up / length, view)) < kMinUpViewSine)
    throw InputError(what + " is parallel to the view direction (target - position)");
}

bool withinCoordinateCap(const glm::vec3& v) {
  return finite(v) && std::fabs(v.x) <= kMaxSceneCoordinate &&
         std::fabs(v.y) <= kMaxSceneCoordinate && std::fabs(v.z) <= kMaxSceneCoordinate;
}

}  // namespace

void validateScene(const Scene& scene) {
  const std::string where = "scene '" + scene.name + "': ";
  if (scene.objects.empty()) throw InputError(where + "has no objects");
  const Camera& c = scene.camera;
  if (!finite(c.position) || !finite(c.target) || !finite(c.up))
    throw InputError(where + "camera has a non-finite vector");
  if (glm::length(c.target - c.position) <= 0.0f)
    throw InputError(where + "camera position equals its target");
  validateUp(c.up, c.position, c.target, where + "camera.up");
  if (!(c.fovyDegrees > 0.0f && c.fovyDegrees < 180.0f))
    throw InputError(where + "camera fov must be in (0, 180) degrees");
  if (!(c.nearPlane > 0.0f && c.farPlane > c.nearPlane && std::isfinite(c.farPlane)))
    throw InputError(where + "camera needs 0 < near < far");
  const SpotLight& l = scene.light;
  if (!finite(l.position) || !finite(l.target) || !finite(l.up) || !finite(l.color))
    throw InputError(where + "light has a non-finite vector");
  if (glm::length(l.target - l.position) <= 0.0f)
    throw InputError(where + "light position equals its target");
  // A light `up` parallel to the view is replaced in lightView (any side vector will do for a
  // square frustum); a zero one has no direction at all.
  if (!(glm::length(l.up) > 0.0f)) throw InputError(where + "light.up must not be [0, 0, 0]");
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
  if (scene.objects.size() > size_t(kMaxSceneObjects))
    throw InputError(where + "has " + std::to_string(scene.objects.size()) + " objects; at most " +
                     std::to_string(kMaxSceneObjects));
  size_t triangles = 0;
  for (const Object& o : scene.objects) {
    const std::string what = where + "object '" + o.name + "'";
    if (!o.mesh) throw InputError(what + " has no triangles");
    validateMesh(*o.mesh, what);
    triangles += o.mesh->triangleCount();
    if (triangles > kMaxSceneTriangles)
      throw InputError(where + "has more than " + std::to_string(kMaxSceneTriangles) +
                       " triangles in all; at most " + std::to_string(kMaxSceneTriangles));
    for (int i = 0; i < 4; ++i)
      if (!finite(glm::vec3(o.model[i])) || !std::isfinite(o.model[i][3]))
        throw InputError(what + " has a non-finite transform");
    const Bounds b = worldBounds(o);
    if (!withinCoordinateCap(b.lo) || !withinCoordinateCap(b.hi))
      throw InputError(what + " reaches beyond " + formatNumber(kMaxSceneCoordinate) +
                       " scene units from the origin (ray and shadow-volume tests overflow "
                       "float from about 2e13)");
  }
  if (!withinCoordinateCap(c.position) || !withinCoordinateCap(c.target) ||
      !withinCoordinateCap(l.position) || !withinCoordinateCap(l.target))
    throw InputError(where + "camera and light must lie within " +
                     formatNumber(kMaxSceneCoordinate) + " scene units of the origin");
  // The light frustum's depth range as the techniques will use it: a far plane given alone can
  // fall in front of the fitted near plane (and a near plane given alone behind the fitted far).
  const DepthRange r = lightDepthRange(scene);
  if (!(r.nearPlane > 0.0f && r.farPlane > r.nearPlane && std::isfinite(r.farPlane))) {
    const std::string field = l.farPlane ? "light.far" : "light.near";
    throw InputError(where + field + " leaves the light an empty depth range (near " +
                     formatNumber(r.nearPlane) + ", far " + formatNumber(r.farPlane) +
                     "): give both light.near and light.far, or neither");
  }
  // Stiff light/camera ranges -------------------------------------
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
  // ------------------------------------------------------------------------------------------
}

void adjustScene(Scene& scene, const SceneAdjustments& a) {
  if (a.cameraDistance) {
    if (!(*a.cameraDistance > 0.0f && std::isfinite(*a.cameraDistance)))
      throw InputError("camera distance must be a positive factor, got " +
                       std::to_string(*a.cameraDistance));
    Camera& c = scene.camera;
    c.position = c.target + (c.position - c.target) * *a.cameraDistance;
    c.farPlane *= std::max(1.0f, *a.cameraDistance);  // what was in view stays in view
  }
  if (a.lightRadius) {
    if (!(*a.lightRadius >= 0.0f && std::isfinite(*a.lightRadius)))
      throw InputError("light radius must be >= 0 (world units)");
    scene.light.radius = *a.lightRadius;
  }
  if (a.lightPosition) scene.light.position = *a.lightPosition;
  try {
    validateScene(scene);
  } catch (const InputError& e) {
    throw InputError(std::string("the adjusted scene is unusable: ") + e.what());
  }
}

}  // namespace sl
