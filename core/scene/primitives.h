// core/scene/primitives.h — procedural meshes for the built-in scenes (all with outward normals;
// the closed ones are 2-manifold so that shadow volumes and smoothies can use them).
#pragma once

#include "core/scene/scene.h"

namespace sl {

// Tessellation caps: every generator checks its parameters against these before it
// allocates anything and throws InputError naming the parameter and the cap. At the largest
// caps a primitive has a few million triangles, which every technique still renders here.
constexpr int kMaxPlaneDivisions = 1024;  // 2 divisions^2 triangles: 2.1 M at the cap
constexpr int kMinSphereSlices = 3;       // fewer is not a solid
constexpr int kMaxSphereSlices = 2048;    // 2 slices (stacks - 1) triangles
constexpr int kMinSphereStacks = 2;       // two pole caps, no middle band
constexpr int kMaxSphereStacks = 1024;    //   -> 4.2 M triangles at both caps
constexpr int kMinCylinderSlices = 3;
constexpr int kMaxCylinderSlices = 65536;  // 4 triangles a slice: 262 k at the cap
constexpr int kMinTorusSegments = 3;       // rings and sides
constexpr int kMaxTorusSegments = 1024;    // 2 rings sides triangles: 2.1 M at both caps
constexpr int kMaxFencePickets = 10000;    // 12 triangles a picket: 120 k at the cap
constexpr int kMaxTreeLevels = 7;          // 4 * 3^(levels - 1) tips: 2916 at the cap
// Lengths (radius, width, height, extent) must be positive and at most this (scene units):
// beyond it a float position has less than a millimetre-per-kilometre of precision left.
constexpr float kMaxPrimitiveLength = 1e6f;

Mesh makePlane(float sizeX, float sizeZ, int divisions = 1);               // y = 0, normal +y, open
Mesh makeBox(const glm::vec3& size);                                       // centred, closed
Mesh makeSphere(float radius, int slices = 32, int stacks = 16);           // closed
Mesh makeCylinder(float radius, float height, int slices = 32);            // capped, closed, y up
Mesh makeTorus(float major, float minor, int rings = 32, int sides = 16);  // closed
Mesh makeQuad(float sizeX, float sizeY);                                   // z = 0, normal +z, open
// A picket fence along x (Annen et al. Fig. 9): `pickets` closed boxes on two closed rails.
Mesh makeFence(float length, float height, int pickets);
// A stylised tree: cylinder trunk and a few spheres of foliage (closed pieces).
Mesh makeTree(float height);
// A bare tree with thin branches (Annen et al. Figs. 1, 7, 10: thin branches are what PCF
// loses under minification): a tapering trunk that splits into `levels` generations of
// branches (4 from the trunk, then 3 from each branch), each thinner and shorter than its
// parent, with a small leaf cluster at every tip. Closed pieces; `seed` varies the angles.
Mesh makeBranchedTree(float height, int levels, unsigned seed);

// Appends b (transformed) to a; keeps `closed` only if both are closed.
void appendMesh(Mesh& a, const Mesh& b, const glm::mat4& transform);
// Recomputes Mesh::closed from the index buffer (welding positions that are equal).
bool isClosedManifold(const Mesh& mesh);

}  // namespace sl
