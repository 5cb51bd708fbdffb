// core/scene.h — what every technique renders: meshes, a camera and one spotlight.
//
// A scene is plain data. Built-in scenes are made procedurally (core/scenes.cpp); scene files
// are JSON under assets/scenes/ (core/scene_file.cpp); meshes come from OBJ/PLY through Assimp
// (core/mesh_io.cpp) or from the primitive generators in core/primitives.h.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace sl {

struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // one per position
  std::vector<unsigned> indices;   // triangles
  bool closed = false;             // every edge shared by exactly two triangles (2-manifold)
  size_t triangleCount() const { return indices.size() / 3; }
};

struct Bounds {
  glm::vec3 lo{1e30f};
  glm::vec3 hi{-1e30f};
  bool empty() const { return lo.x > hi.x; }
  void extend(const glm::vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  glm::vec3 center() const { return 0.5f * (lo + hi); }
};

struct Object {
  std::string name;
  std::shared_ptr<const Mesh> mesh;
  glm::mat4 model{1.0f};
  glm::vec3 diffuse{0.8f};
  float specular = 0.0f;  // specular reflectance (Phong), 0 = matte
  bool castsShadow = true;
  bool receivesShadow = true;
};

struct Camera {
  glm::vec3 position{0.0f, 2.0f, 5.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fovyDegrees = 45.0f;
  float nearPlane = 0.1f;
  float farPlane = 100.0f;
};

struct SpotLight {
  glm::vec3 position{0.0f, 5.0f, 0.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 0.0f, -1.0f};
  float coneDegrees = 60.0f;  // full opening angle of the light frustum
  // Light frustum depth range; fitted tightly to the scene's casters and receivers when unset.
  std::optional<float> nearPlane;
  std::optional<float> farPlane;
  float radius = 0.05f;  // for the soft-shadow reference (reference.soft) and smoothies
  glm::vec3 color{1.0f};
  float ambient = 0.2f;  // the ambient that remains in shadow (Kilgard's note in Everitt §4)
};

struct Scene {
  std::string name;
  std::string description;
  std::vector<Object> objects;
  Camera camera;
  SpotLight light;
};

Bounds worldBounds(const Object& object);
Bounds sceneBounds(const Scene& scene);

// Matrices shared by legacy and modern code (OpenGL conventions, right-handed, -z forward).
glm::mat4 cameraView(const Camera& camera);
glm::mat4 cameraProjection(const Camera& camera, float aspect);
glm::mat4 lightView(const SpotLight& light);
// The light's perspective frustum: cone angle, aspect 1, and [near, far] from the scene when
// the light does not fix them (fitted to the bounds of every object in light space, near/far
// at least 1e-4). A given range with near/far below 1e-4 is narrowed to the part of it that
// holds geometry: a 24-bit depth buffer has no precision left below that.
struct DepthRange {
  float nearPlane = 0.1f;
  float farPlane = 100.0f;
};
DepthRange lightDepthRange(const Scene& scene);
glm::mat4 lightProjection(const Scene& scene);

// Validates a scene (finite numbers, non-degenerate camera and light, at least one object);
// throws InputError naming the problem.
void validateScene(const Scene& scene);

}  // namespace sl
