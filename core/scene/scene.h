// core/scene/scene.h — what every technique renders: meshes, a camera and one spotlight.
//
// A scene is plain data. Built-in scenes are made procedurally (core/scenes.cpp); scene files
// are JSON under assets/scenes/ (core/scene_file.cpp); meshes come from OBJ/PLY through Assimp
// (core/scene/mesh_io.cpp) or from the primitive generators in core/scene/primitives.h.
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sl {

// Scene caps, checked by validateScene before anything is drawn; a scene beyond
// them is an InputError that names the cap. Primitive and mesh-file caps live beside their
// generators (core/scene/primitives.h, core/scene/mesh_io.h).
constexpr int kMaxSceneObjects = 4096;             // draw calls per pass stay bounded
constexpr size_t kMaxSceneTriangles = 16'000'000;  // ~1 GB of vertex data in every technique
// Coordinates (positions, targets, translations, world-space vertices) at most this far from
// the origin. Ray-triangle tests (Embree's, the reference's) and the shadow volumes multiply
// coordinates, whose products overflow float (3.4e38) at large enough scales. Measured on the
// boxes scene scaled up: with coordinates up to 1.2e13 every technique matched the unscaled
// scene; at 2.4e13 modern.volumes and modern.hybrid put every receiver in umbra, and from 4e13
// reference.hard lost shadows. The cap keeps a factor of 10 below the first failure.
constexpr double kMaxSceneCoordinate = 1e12;
// A camera or light `up` must make at least this sine with the view direction (0.06 degrees):
// closer to parallel, lookAt has no side vector and the image is black.
constexpr float kMinUpViewSine = 1e-3f;

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
  // Set by a view that checked it (legacy_gl/spotlight_tessellation.h cameraPassScene): the mesh
  // is closed and wound outward and the camera sees it only from outside, so its back faces are
  // hidden behind its own front faces and drawing them costs fragments, not pixels (but for a
  // pixel centre exactly on a silhouette edge, which the rasteriser's tie rule may give to the
  // back face).
  bool backFacesHidden = false;
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
// How many times its own float round-off the projective light depth r/q carries. The depth is
// (A z + B) / z with A = (f + n) / (f - n) and B = 2 f n / (f - n); when the depth range is
// narrow compared with its distance from the light (a far light fitted tightly to its scene),
// the two terms are large and cancel, and r/q keeps about 2n / (f - n) times the round-off of
// a wide range. Polygon-offset constants and peeling epsilons, which exist to cover that
// round-off, are multiplied by this factor (at least 1, so wide ranges are unchanged).
// DEVIATION (Everitt et al. 2001, "Polygon offset"): the paper tunes one constant per scene;
// without the factor a flat ground under a light 20 units up was all umbra.
float lightDepthRoundoffScale(const Scene& scene);
// That DEVIATION as the pass tables declare it, for the passes whose polygon offset or peeling
// epsilon the factor scales (legacy and modern hw, woo and second-depth).
inline constexpr char kDepthRoundoffScaleDeviation[] =
    "DEVIATION (Everitt et al. 2001, \"Polygon offset\"): the paper tunes one constant per "
    "scene; without the factor a flat ground under a light 20 units up was all umbra.";

// The scene-level knobs a figure turns and `render`/`compare`/`plan` expose (--camera-distance,
// --light-radius, --light-position) and `figures --set` overrides.
struct SceneAdjustments {
  // Times the camera's distance from its target, moving it along its view direction (> 1:
  // farther, minification as in Annen et al. Figs. 1 and 10); the far plane grows with it.
  std::optional<float> cameraDistance;
  std::optional<float> lightRadius;        // world units; read by reference.soft (Chan Fig. 4-9)
  std::optional<glm::vec3> lightPosition;  // world; the light keeps aiming at its target
  bool empty() const { return !cameraDistance && !lightRadius && !lightPosition; }
};
// Applies `a` to `scene` and validates the result (validateScene): an adjustment that leaves the
// scene unusable (light on its target, a negative radius) is an InputError naming the knob.
void adjustScene(Scene& scene, const SceneAdjustments& a);

// Validates a scene (finite numbers, non-degenerate camera and light, at least one object);
// throws InputError naming the problem.
void validateScene(const Scene& scene);

}  // namespace sl
