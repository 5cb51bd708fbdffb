// modern/silhouettes.h — silhouette edges of meshes with respect to a point light, found on the
// CPU from edge adjacency, and the shadow-volume geometry built from them (module-internal
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

#include "core/scene/scene.h"

namespace sl::modern {

// A caster's mesh with its positions welded (flat-shaded primitives repeat corner positions),
// its zero-area triangles dropped, and every undirected edge of a closed mesh paired with its two
// triangles.
struct EdgeAdjacency {
  struct Edge {
    unsigned a = 0, b = 0;  // welded vertex ids; triangle `first` uses the edge as a -> b
    unsigned first = 0;     // triangle that walks a -> b
    unsigned second = 0;    // triangle that walks b -> a
  };
  std::vector<glm::vec3> positions;   // welded, object space (exactly the mesh's values)
  std::vector<glm::uvec3> triangles;  // welded ids, the mesh's winding (counter-clockwise = out)
  std::vector<Edge> edges;            // every edge when `closed`; the paired ones otherwise
  // Judged from the topology after dropping zero-area triangles (not from Mesh::closed): every
  // edge is shared by exactly two oppositely oriented triangles (a closed 2-manifold).
  bool closed = false;
  int droppedDegenerate = 0;  // triangles with a repeated (welded) corner or collinear corners
};

// Builds the adjacency of any triangle mesh. Zero-area triangles are dropped first: they cover
// no pixel and block no ray, and their edges would break the pairing (a repeated corner walks
// an edge a -> a; collinear corners add edges no other triangle shares). Throws InputError
// naming `objectName` only for indices beyond the positions.
EdgeAdjacency buildEdgeAdjacency(const Mesh& mesh, const std::string& objectName);

// The shadow casters of a scene with their adjacency (built once per frame, before any timed
// pass: it depends on the mesh only, not on the light). Open casters (the ground plane of
// brabec, a single quad, the decimated dragon) are kept and get two-sided volumes (see
// findSilhouette); they are counted. Casters left with no triangle cast nothing and are left out.
struct ShadowCaster {
  const Object* object = nullptr;
  EdgeAdjacency adjacency;
};
struct SceneCasters {
  std::vector<ShadowCaster> casters;
  int closed = 0;         // closed 2-manifold casters: Everitt–Kilgard volumes as published
  int open = 0;           // open or non-manifold casters: two-sided volumes
  std::string openNames;  // comma separated, for messages
};
SceneCasters collectCasters(const Scene& scene);

// The triangles that face a point light and the silhouette edges, each oriented so that the
// blocker lies to the left of a -> b when seen from the light (as the edge runs in its
// light-facing triangle).
struct Silhouette {
  std::vector<bool> facesLight;                      // per triangle
  std::vector<std::pair<unsigned, unsigned>> edges;  // (a, b) welded ids, each edge once
  std::vector<int> quads;  // per edge: side quads of the volume (1; 2 at a fold of an open mesh)
  bool twoSided = false;   // the volume of an open mesh (both faces of every triangle)
};
// Closed meshes — Chan §4.2 step 2 / Everitt–Kilgard: a triangle faces the light when the light
// lies on the positive side of its plane; a silhouette edge joins a facing and a non-facing
// triangle.
//
// DEVIATION (Chan §3.1, Everitt–Kilgard §"Shadow volume construction": blockers must be closed):
// an open mesh is taken as the closed, zero-thickness solid made of both faces of each of its
// triangles. Each triangle then has one light-facing face (front cap) and one facing away (back
// cap at infinity), and the silhouette is the sum of every light-facing face's boundary loop:
// edges walked both ways cancel, so what remains is every boundary edge (always a potential
// silhouette: its two faces are the two sides of one triangle) once, and every edge where the
// surface folds over as seen from the light (one neighbour faces the light, the other away)
// twice, as the solid has two sheets there. The volume is closed, so z-fail counting is exact;
// the same works for non-manifold edges. `light` is in the mesh's object space.
Silhouette findSilhouette(const EdgeAdjacency& mesh, const glm::vec3& light);
// That DEVIATION, for the pass tables of the passes that find silhouettes
// (core/technique/pass_table.h).
extern const char* const kOpenMeshTwoSidedDeviation;

// The closed shadow volume of one blocker in object-space homogeneous coordinates, as a
// triangle list with every face oriented outwards (Everitt–Kilgard §"Shadow volume
// construction"): front cap = light-facing triangles (w = 1); back cap = the other triangles
// projected to infinity away from the light (w = 0); `quads` quads per silhouette edge from the
// edge to infinity. Two-sided (open mesh): every triangle in the front cap in its light-facing
// winding and in the back cap in the opposite one.
std::vector<glm::vec4> buildShadowVolume(const EdgeAdjacency& mesh, const Silhouette& silhouette,
                                         const glm::vec3& light);

}  // namespace sl::modern
