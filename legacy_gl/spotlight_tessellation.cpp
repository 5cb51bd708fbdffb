#include "legacy_gl/spotlight_tessellation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <glm/glm.hpp>
#include <memory>
#include <unordered_map>
#include <vector>

#include "core/gl/context.h"

namespace sl::legacy {
namespace {

// Below this fraction of the scene's size an edge is never split (float positions stop being
// distinct long before; it also bounds the depth of splitting near a tiny camera near plane).
constexpr double kMinEdgeFractionOfScene = 1e-5;

// How the camera and the spotlight see one edge, from its world-space end points alone.
class EdgeJudge {
 public:
  EdgeJudge(const Scene& scene, int width, int height) {
    const Camera& c = scene.camera;
    view_ = cameraView(c);
    const glm::mat4 viewProjection = cameraProjection(c, float(width) / float(height)) * view_;
    // The six frustum planes (Gribb & Hartmann): row 3 +- row i of the view-projection matrix.
    const glm::mat4 t = glm::transpose(viewProjection);
    for (int i = 0; i < 3; ++i) {
      planes_[2 * i] = t[3] + t[i];
      planes_[2 * i + 1] = t[3] - t[i];
    }
    for (glm::vec4& p : planes_) p /= glm::length(glm::vec3(p));
    near_ = c.nearPlane;
    // Pixels per world unit at eye depth 1 (vertical field of view over the window height).
    pixelsAtUnitDepth_ = 0.5 * height / std::tan(0.5 * glm::radians(double(c.fovyDegrees)));
    apex_ = scene.light.position;
    axis_ = glm::normalize(scene.light.target - scene.light.position);
    cosHalfAngle_ = std::cos(0.5 * glm::radians(double(scene.light.coneDegrees)));
    sinHalfAngle_ = std::sin(0.5 * glm::radians(double(scene.light.coneDegrees)));
    const Bounds b = sceneBounds(scene);
    minEdge_ = b.empty() ? 0.0 : kMinEdgeFractionOfScene * glm::length(b.hi - b.lo);
  }

  // Whether the edge (a, b) of an object must be split; symmetric in a and b. `specular`: the
  // object has a specular term (its highlight needs vertices inside the cone).
  bool split(const glm::vec3& a, const glm::vec3& b, bool specular) const {
    const glm::vec3 center = (a + b) * 0.5f;
    const double radius = 0.5 * double(glm::length(a - b));
    if (2.0 * radius <= minEdge_) return false;
    for (const glm::vec4& p : planes_)
      if (double(glm::dot(glm::vec3(p), center) + p.w) < -radius) return false;  // off screen
    const double limit = pixelLimit(center, radius, specular);
    if (limit <= 0.0) return false;
    return projectedPixels(a, b, radius) > limit;
  }

  // The edge's length on screen in pixels: exact for an edge in front of the near plane (a
  // segment projects to a segment); otherwise its bounding sphere's size at its nearest depth.
  double projectedPixels(const glm::vec3& a, const glm::vec3& b, double radius) const {
    const glm::vec4 ea = view_ * glm::vec4(a, 1.0f), eb = view_ * glm::vec4(b, 1.0f);
    const double da = -double(ea.z), db = -double(eb.z);
    if (da >= near_ && db >= near_) {
      const glm::dvec2 pa = glm::dvec2(ea.x, ea.y) / da, pb = glm::dvec2(eb.x, eb.y) / db;
      return glm::length(pa - pb) * pixelsAtUnitDepth_;
    }
    const double nearest = std::max(0.5 * (da + db) - radius, double(near_));
    return 2.0 * radius * pixelsAtUnitDepth_ / nearest;
  }

 private:
  // The most pixels the edge may cover: kLitInteriorPixels where the edge's bounding sphere
  // reaches into the spotlight cone (GL lighting's cone, glspec121 §2.13.1, now the projected
  // cone texture of projected_spotlight.h) and the edge subtends more than
  // kMaxDiffuseEdgeRadians (kMaxSpecularEdgeRadians on a specular object) at the light; else 0,
  // never split. The cone's edge itself needs no vertices: the projected texture cuts it per
  // pixel.
  double pixelLimit(const glm::vec3& center, double radius, bool specular) const {
    const glm::dvec3 v = glm::dvec3(center) - glm::dvec3(apex_);
    const double distance = glm::length(v);
    if (distance <= radius) return kLitInteriorPixels;  // the apex is inside the sphere
    // alpha: the centre's angle off the axis; beta: the sphere's angular radius; theta: the
    // cutoff. The sphere reaches into the cone when alpha - beta <= theta, i.e. the centre is
    // inside or cos(alpha - theta) >= cos(beta).
    const double cosAlpha = std::clamp(glm::dot(v, glm::dvec3(axis_)) / distance, -1.0, 1.0);
    const double sinAlpha = std::sqrt(1.0 - cosAlpha * cosAlpha);
    const double sinBeta = radius / distance;
    const double cosBeta = std::sqrt(1.0 - sinBeta * sinBeta);
    const bool centreInside = cosAlpha > cosHalfAngle_;
    const bool meetsSurface = cosAlpha * cosHalfAngle_ + sinAlpha * sinHalfAngle_ >= cosBeta;
    if (!centreInside && !meetsSurface) return 0.0;  // outside the cone: ambient only, constant
    // The angle the edge subtends at the light bounds how far the diffuse (and specular) term
    // departs from its linear interpolation between the edge's ends.
    const double subtended = 2.0 * radius / (distance - radius);
    return subtended > (specular ? kMaxSpecularEdgeRadians : kMaxDiffuseEdgeRadians)
               ? kLitInteriorPixels
               : 0.0;
  }

  glm::mat4 view_{1.0f};
  std::array<glm::vec4, 6> planes_{};
  float near_ = 0.0f;
  double pixelsAtUnitDepth_ = 0.0;
  glm::vec3 apex_{0.0f};
  glm::vec3 axis_{0.0f, 0.0f, -1.0f};
  double cosHalfAngle_ = 1.0;
  double sinHalfAngle_ = 0.0;
  double minEdge_ = 0.0;
};

// Splits one mesh; the vertex at an edge's midpoint is made once and shared.
class MeshSplitter {
 public:
  MeshSplitter(const Mesh& mesh, const glm::mat4& model, bool specular, const EdgeJudge& judge)
      : judge_(judge), model_(model), specular_(specular) {
    out_.positions = mesh.positions;
    out_.normals = mesh.normals;
    out_.closed = mesh.closed;
    world_.reserve(mesh.positions.size());
    for (const glm::vec3& p : mesh.positions) world_.push_back(toWorld(p));
  }

  // False when the split mesh would exceed kMaxTessellatedTriangles.
  bool run(const Mesh& mesh) {
    std::vector<std::array<unsigned, 3>> stack;
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      stack.push_back({mesh.indices[3 * t], mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]});
      while (!stack.empty()) {
        const auto tri = stack.back();
        stack.pop_back();
        if (!splitTriangle(tri, stack)) emit(tri);
        if (out_.indices.size() / 3 + stack.size() > kMaxTessellatedTriangles) return false;
      }
    }
    return true;
  }

  Mesh take() { return std::move(out_); }

 private:
  glm::vec3 toWorld(const glm::vec3& p) const { return glm::vec3(model_ * glm::vec4(p, 1.0f)); }

  bool needsSplit(unsigned a, unsigned b) const {
    return judge_.split(world_[a], world_[b], specular_);
  }

  unsigned midpoint(unsigned a, unsigned b) {
    const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
    const auto found = midpoints_.find(key);
    if (found != midpoints_.end()) return found->second;
    const glm::vec3 p = (out_.positions[a] + out_.positions[b]) * 0.5f;
    glm::vec3 n = out_.normals[a] + out_.normals[b];
    n = glm::length(n) > 0.0f ? glm::normalize(n) : out_.normals[a];
    const unsigned index = unsigned(out_.positions.size());
    out_.positions.push_back(p);
    out_.normals.push_back(n);
    world_.push_back(toWorld(p));
    midpoints_.emplace(key, index);
    return index;
  }

  // Pushes the pieces of `tri` (winding kept) and returns true, or false when no edge splits.
  bool splitTriangle(const std::array<unsigned, 3>& tri,
                     std::vector<std::array<unsigned, 3>>& stack) {
    const bool s[3] = {needsSplit(tri[0], tri[1]), needsSplit(tri[1], tri[2]),
                       needsSplit(tri[2], tri[0])};
    const int count = int(s[0]) + int(s[1]) + int(s[2]);
    if (count == 0) return false;
    if (count == 3) {
      const unsigned m01 = midpoint(tri[0], tri[1]), m12 = midpoint(tri[1], tri[2]),
                     m20 = midpoint(tri[2], tri[0]);
      stack.push_back({tri[0], m01, m20});
      stack.push_back({m01, tri[1], m12});
      stack.push_back({m20, m12, tri[2]});
      stack.push_back({m01, m12, m20});
      return true;
    }
    // Rotate so that edge (v0, v1) splits and, for two splits, (v1, v2) too.
    int r = 0;
    if (count == 1) {
      while (!s[r]) ++r;
    } else {
      while (!(s[r] && s[(r + 1) % 3])) ++r;
    }
    const unsigned v0 = tri[r], v1 = tri[(r + 1) % 3], v2 = tri[(r + 2) % 3];
    const unsigned m01 = midpoint(v0, v1);
    if (count == 1) {
      stack.push_back({v0, m01, v2});
      stack.push_back({m01, v1, v2});
      return true;
    }
    const unsigned m12 = midpoint(v1, v2);
    stack.push_back({m01, v1, m12});
    stack.push_back({v0, m01, m12});
    stack.push_back({v0, m12, v2});
    return true;
  }

  void emit(const std::array<unsigned, 3>& tri) {
    out_.indices.insert(out_.indices.end(), tri.begin(), tri.end());
  }

  const EdgeJudge& judge_;
  glm::mat4 model_;
  bool specular_;
  Mesh out_;
  std::vector<glm::vec3> world_;
  std::unordered_map<std::uint64_t, unsigned> midpoints_;
};

}  // namespace

Scene tessellateForSpotlight(const Scene& scene, int width, int height, TessellationStats* stats) {
  Scene out = scene;
  const EdgeJudge judge(scene, width, height);
  TessellationStats counted;
  for (Object& o : out.objects) {
    counted.trianglesIn += o.mesh->triangleCount();
    MeshSplitter splitter(*o.mesh, o.model, o.specular > 0.0f, judge);
    if (splitter.run(*o.mesh)) o.mesh = std::make_shared<const Mesh>(splitter.take());
    counted.trianglesOut += o.mesh->triangleCount();
  }
  if (stats) *stats = counted;
  return out;
}

namespace {

// Everything tessellateForSpotlight reads. Holding the input meshes' shared_ptrs keeps them
// alive, so an equal pointer is the same immutable mesh (its address cannot be reused).
struct TessellationKey {
  struct ObjectKey {
    std::shared_ptr<const Mesh> mesh;
    glm::mat4 model{1.0f};
    bool specular = false;
    bool operator==(const ObjectKey& o) const {
      return mesh == o.mesh && model == o.model && specular == o.specular;
    }
  };
  int width = 0, height = 0;
  Camera camera;
  glm::vec3 lightPosition{0.0f}, lightTarget{0.0f};
  float lightConeDegrees = 0.0f;
  std::vector<ObjectKey> objects;

  TessellationKey(const Scene& scene, int w, int h)
      : width(w),
        height(h),
        camera(scene.camera),
        lightPosition(scene.light.position),
        lightTarget(scene.light.target),
        lightConeDegrees(scene.light.coneDegrees) {
    for (const Object& o : scene.objects) objects.push_back({o.mesh, o.model, o.specular > 0.0f});
  }
  bool operator==(const TessellationKey& k) const {
    const Camera& a = camera;
    const Camera& b = k.camera;
    return width == k.width && height == k.height && a.position == b.position &&
           a.target == b.target && a.up == b.up && a.fovyDegrees == b.fovyDegrees &&
           a.nearPlane == b.nearPlane && a.farPlane == b.farPlane &&
           lightPosition == k.lightPosition && lightTarget == k.lightTarget &&
           lightConeDegrees == k.lightConeDegrees && objects == k.objects;
  }
};

struct CachedTessellation {
  TessellationKey key;
  std::vector<std::shared_ptr<const Mesh>> meshes;  // per object, in scene order
  TessellationStats stats;
};

// Per context (GlContext::setLayerState), newest first.
struct TessellationCache {
  std::deque<CachedTessellation> entries;
};
constexpr const char* kTessellationCacheKey = "legacy.spotlight-tessellation";

TessellationCache* contextCache() {
  GlContext* context = GlContext::current();
  if (context == nullptr) return nullptr;
  auto* cache = static_cast<TessellationCache*>(context->layerState(kTessellationCacheKey));
  if (cache == nullptr) {
    auto fresh = std::make_shared<TessellationCache>();
    cache = fresh.get();
    context->setLayerState(kTessellationCacheKey, fresh);
  }
  return cache;
}

// The split scene: `scene` with its meshes replaced by the cached split meshes.
Scene withMeshes(const Scene& scene, const std::vector<std::shared_ptr<const Mesh>>& meshes) {
  Scene out = scene;
  for (size_t i = 0; i < out.objects.size(); ++i) out.objects[i].mesh = meshes[i];
  return out;
}

}  // namespace

namespace {

// The split scene for this frame (from the context's cache when the key matches).
Scene splitForSpotlight(const Scene& scene, const RenderParams& params, Frame& frame) {
  TessellationCache* cache = contextCache();
  TessellationKey key(scene, params.width, params.height);
  const CachedTessellation* hit = nullptr;
  if (cache != nullptr)
    for (const CachedTessellation& entry : cache->entries)
      if (entry.key == key) hit = &entry;
  Scene split;
  TessellationStats stats;
  if (hit != nullptr) {
    split = withMeshes(scene, hit->meshes);
    stats = hit->stats;
  } else {
    split = tessellateForSpotlight(scene, params.width, params.height, &stats);
    if (cache != nullptr) {
      std::vector<std::shared_ptr<const Mesh>> meshes;
      for (const Object& o : split.objects) meshes.push_back(o.mesh);
      cache->entries.push_front({std::move(key), std::move(meshes), stats});
      if (cache->entries.size() > kCachedTessellations) cache->entries.pop_back();
    }
  }
  frame.counters["camera-pass triangles"] = double(stats.trianglesOut);
  frame.counters["scene triangles"] = double(stats.trianglesIn);
  return split;
}

}  // namespace

PassSpec meshFeedingPass() {
  return {.id = "mesh",
          .name = "mesh feeding: triangles split for per-vertex spotlight lighting",
          .reference =
              "ours, not a paper's pass (run before the camera passes, listed first): "
              "fixed-function lighting is evaluated per vertex, so the receivers are split "
              "until it matches the modern twins' per-pixel lighting",
          .floor = PassFloor::kCpuOnly,
          .role = PassRole::kMesh};
}

bool backFacesHiddenFrom(const Object& object, const Camera& camera) {
  if (!object.mesh || !object.mesh->closed) return false;
  const Mesh& m = *object.mesh;
  double volume6 = 0.0;  // six times the signed volume (divergence theorem)
  for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const glm::dvec3 a(m.positions[m.indices[t]]), b(m.positions[m.indices[t + 1]]),
        c(m.positions[m.indices[t + 2]]);
    volume6 += glm::dot(a, glm::cross(b, c));
  }
  if (!(volume6 > 0.0)) return false;  // wound inward (or flat): its "back" faces face out
  const Bounds b = worldBounds(object);
  const glm::vec3 grow(camera.nearPlane);
  const glm::vec3 lo = b.lo - grow, hi = b.hi + grow;
  const glm::vec3& e = camera.position;
  const bool inside =
      e.x >= lo.x && e.x <= hi.x && e.y >= lo.y && e.y <= hi.y && e.z >= lo.z && e.z <= hi.z;
  return !inside;
}

void markHiddenBackFaces(Scene& split, const Scene& scene) {
  // Judged on the scene's own meshes: the split keeps their geometry.
  for (size_t i = 0; i < split.objects.size() && i < scene.objects.size(); ++i)
    split.objects[i].backFacesHidden = backFacesHiddenFrom(scene.objects[i], scene.camera);
}

Scene cameraPassScene(const Scene& scene, const RenderParams& params, Passes& passes) {
  Scene split;
  passes.run("mesh", [&] {
    split = splitForSpotlight(scene, params, passes.frame());
    markHiddenBackFaces(split, scene);
  });
  return split;
}

}  // namespace sl::legacy
