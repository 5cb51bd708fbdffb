// legacy_gl/spotlight_tessellation.h — the meshes the legacy camera passes draw: OpenGL 1.x
// lights per vertex (glspec121 §2.13), so the diffuse and specular terms of a triangle that is
// large as seen from the light are interpolated linearly between its vertices where the modern
// twins evaluate them per pixel. The camera-view passes draw the scene with the triangles inside
// the spotlight cone split where they subtend a large angle at the light. The cone's edge needs
// no splitting: the projected cone texture (projected_spotlight.h) cuts it per pixel. The
// passes' GL calls stay those of the papers (module-internal header).
#pragma once

#include <cstddef>

#include "core/scene/scene.h"
#include "core/technique/passes.h"
#include "core/technique/technique.h"

namespace sl::legacy {

// Inside the cone an edge is split (down to kLitInteriorPixels on screen) while it subtends more
// than these angles at the light. A cosine interpolated linearly over an angle t departs from
// itself by at most t^2/8: 0.25 rad keeps the diffuse term within 0.008 (2 8-bit steps), which
// a two-triangle quad close to the light (the analytic scene's occluder, 3 units below the
// light) misses by 8 steps. The specular term (shininess 32) bends about 32 times faster;
// 0.1 rad keeps it within about 10 steps at a highlight's peak without splitting every
// specular mesh many times.
constexpr double kMaxDiffuseEdgeRadians = 0.25;
constexpr double kMaxSpecularEdgeRadians = 0.1;
constexpr double kLitInteriorPixels = 4.0;
// An object whose split mesh would exceed this many triangles keeps its own mesh (a guard for
// pathological cameras, e.g. a near plane of 1e-5 on a large ground).
constexpr std::size_t kMaxTessellatedTriangles = 1'000'000;

struct TessellationStats {
  std::size_t trianglesIn = 0;
  std::size_t trianglesOut = 0;
};

// The scene with every object's mesh split for per-vertex spotlight lighting as seen by the
// camera in a width x height window. Splits are decided per edge from its world position alone
// (never from the triangle), so two triangles sharing an edge split it alike: no T-junctions,
// no cracks. Geometry, normals and bounds are unchanged (new vertices lie on the old
// triangles), so depth and texgen coordinates agree with the unsplit scene up to rounding.
Scene tessellateForSpotlight(const Scene& scene, int width, int height,
                             TessellationStats* stats = nullptr);

// tessellateForSpotlight as a timed pass of `frame` ("mesh feeding: ..."), for the camera passes
// of a legacy technique; the light passes keep drawing `scene` itself. The split meshes are
// static data: the current GL context keeps the last kCachedTessellations results
// (GlContext::setLayerState), keyed by everything the split reads (each object's mesh, by the
// shared immutable Mesh it points to, its model matrix and whether it is specular; the camera;
// the light's position, target and cone; the window size), and a later frame with the same key
// draws the same meshes again instead of splitting anew. Without a current context it splits.
constexpr std::size_t kCachedTessellations = 4;
// Runs as the pass "mesh" of the technique's table (meshFeedingPass(), which every legacy
// technique that lights per vertex lists first). It also marks the objects whose back faces the
// camera cannot see (Object::backFacesHidden, backFacesHiddenFrom): drawScene culls those, as
// their back faces cost the camera passes fragments and change no pixel (legacy_bench
// --split-cost counts the fragments).
Scene cameraPassScene(const Scene& scene, const RenderParams& params, Passes& passes);
// A closed mesh wound outward (positive signed volume, glspec121 §2.6.1's counter-clockwise
// front faces) whose world bounds, grown by the near-plane distance, leave the camera outside:
// every back face lies behind a front face of the same mesh and none is cut open by the near
// plane.
bool backFacesHiddenFrom(const Object& object, const Camera& camera);
// Sets Object::backFacesHidden on every object of `split` (tessellateForSpotlight of `scene`,
// object for object) as backFacesHiddenFrom judges the scene's own object from its camera.
void markHiddenBackFaces(Scene& split, const Scene& scene);
Scene cameraPassScene(const Scene& scene, const RenderParams& params, Passes& passes);
PassSpec meshFeedingPass();

}  // namespace sl::legacy
