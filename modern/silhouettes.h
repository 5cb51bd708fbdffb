// modern/silhouettes.h — silhouette edges of closed meshes with respect to a point light, found
// on the CPU from edge adjacency, and the shadow-volume geometry built from them (module-internal
// header shared by modern.volumes, modern.hybrid and modern.smoothies).
//
//   Everitt & Kilgard 2002, "Practical and Robust Stenciled Shadow Volumes": possible silhouette
//     edges, extrusion to infinity (w = 0), light-facing front cap and extruded back cap.
//   Chan 2004, §3.1 (blockers closed and manifold) and §4.2 step 2 (a silhouette edge is an edge
//     whose one triangle faces the light and whose other triangle faces away; brute force over
//     all edges).
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/scene.h"

namespace sl::modern {

// A closed mesh with its positions welded (flat-shaded primitives repeat corner positions) and
// every undirected edge paired with its two triangles.
struct EdgeAdjacency {
  struct Edge {
    unsigned a = 0, b = 0;  // welded vertex ids; triangle `first` uses the edge as a -> b
    unsigned first = 0;     // triangle that walks a -> b
    unsigned second = 0;    // triangle that walks b -> a
  };
  std::vector<glm::vec3> positions;   // welded, object space (exactly the mesh's values)
  std::vector<glm::uvec3> triangles;  // welded ids, the mesh's winding (counter-clockwise = out)
  std::vector<Edge> edges;
};

// Builds the adjacency of a closed 2-manifold mesh; throws InputError naming `objectName` when
// an edge is not shared by exactly two oppositely oriented triangles.
EdgeAdjacency buildEdgeAdjacency(const Mesh& mesh, const std::string& objectName);

// The closed shadow casters of a scene with their adjacency (built once per frame, before any
// timed pass: it depends on the mesh only, not on the light). Open casters (the ground planes
// of the built-in scenes) cannot bound a shadow volume or carry smoothies: they are counted.
struct ClosedCaster {
  const Object* object = nullptr;
  EdgeAdjacency adjacency;
};
struct SceneCasters {
  std::vector<ClosedCaster> closed;
  int openSkipped = 0;
  std::string openNames;  // comma separated, for messages
};
SceneCasters collectClosedCasters(const Scene& scene);

// The triangles that face a point light and the silhouette edges between facing and non-facing
// triangles, each oriented as it runs in its light-facing triangle (so the blocker lies to the
// left of a -> b when seen from the light).
struct Silhouette {
  std::vector<bool> facesLight;                      // per triangle
  std::vector<std::pair<unsigned, unsigned>> edges;  // (a, b) welded ids
};
// Chan §4.2 step 2 / Everitt–Kilgard: a triangle faces the light when the light lies on the
// positive side of its plane. `light` is in the mesh's object space.
Silhouette findSilhouette(const EdgeAdjacency& mesh, const glm::vec3& light);

// The closed shadow volume of one blocker in object-space homogeneous coordinates, as a
// triangle list with every face oriented outwards (Everitt–Kilgard §"Shadow volume
// construction"): front cap = light-facing triangles (w = 1); back cap = the other triangles
// projected to infinity away from the light (w = 0); one quad per silhouette edge from the edge
// to infinity.
std::vector<glm::vec4> buildShadowVolume(const EdgeAdjacency& mesh, const Silhouette& silhouette,
                                         const glm::vec3& light);

}  // namespace sl::modern
