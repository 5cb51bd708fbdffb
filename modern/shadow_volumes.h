// modern/shadow_volumes.h — modern.volumes (Everitt & Kilgard 2002 z-fail stencil shadow
// volumes) and the pieces of it that modern.hybrid (Chan 2004 ch. 3) reuses.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/technique/technique.h"
#include "modern/gl_objects.h"
#include "modern/silhouettes.h"

namespace sl::modern {

Technique shadowVolumesTechnique();

// ---- shared with modern.hybrid (module-internal) ----

// Stencil layout: the low 7 bits count volume crossings (modulo 128); bit 7 is the computation
// mask of modern.hybrid where the driver has no depth bounds test.
constexpr GLuint kStencilCountBits = 0x7F;
constexpr GLuint kStencilMaskBit = 0x80;

// One blocker's shadow volume in a vertex buffer (object space, vec4 positions).
struct GpuVolume {
  VertexArray vao;
  Buffer vertices;
  GLsizei vertexCount = 0;
  glm::mat4 model{1.0f};
};
struct SceneVolumes {
  std::vector<GpuVolume> volumes;
  long long silhouetteEdges = 0;
  long long triangles = 0;
};
// Everitt–Kilgard: silhouette edges on the CPU and the capped volumes, uploaded.
SceneVolumes buildSceneVolumes(const SceneCasters& casters, const glm::vec3& lightWorld);
void drawVolumes(const SceneVolumes& volumes, const Program& program);

// Everitt–Kilgard's infinite far plane: the camera projection with far -> infinity (tweaked by
// kInfinityEpsilon so that w = 0 vertices do not clip), so the volumes' back caps are never
// clipped away.
glm::mat4 infiniteCameraViewProjection(const Scene& scene, const RenderParams& params);

// The camera target with a depth-stencil attachment (DEPTH24_STENCIL8): colour 0 = shaded,
// 1 = visibility (R32F), then `extraColor` formats.
RenderTarget makeStencilCameraTarget(const RenderParams& params,
                                     const std::vector<GLenum>& extraColor = {});

// Z-fail stencil counting (Everitt–Kilgard): back faces increment, front faces decrement where
// the volume fragment fails the depth test. Colour and depth writes off. When `maskBit` is not
// 0, only pixels whose stencil has that bit set are touched (the computation mask).
void countVolumesZFail(const SceneVolumes& volumes, const Program& volumeProgram, GLuint maskBit);

// Final shading from the stencil: shadowed where the count is non-zero, lit where it is zero
// (restricted to mask-bit pixels when `maskBit` is not 0). Depth test LEQUAL, no depth writes.
void shadeFromStencil(const GpuScene& gpu, const Program& shadeProgram, GLuint maskBit);

// Chan §3.1 step 4: "draw and shade the scene only at pixels with stencil values equal to zero"
// — one draw, lit, where the count is zero (and the mask bit set when `maskBit` is not 0); the
// shadowed pixels keep what an earlier pass wrote. Depth test LEQUAL, no depth writes.
void shadeLitFromStencil(const GpuScene& gpu, const Program& shadeProgram, GLuint maskBit);

// Chan §3.3.2 / Figure 3-10: how many shadow-polygon fragments are rasterised. Draws every
// volume with depth test and stencil test off (`maskBit` 0) or restricted to the mask bit,
// additive into a float buffer; returns the per-pixel overdraw image.
struct VolumeFill {
  double fragments = 0;      // shadow-polygon pixels
  double coveredPixels = 0;  // pixels with at least one
  Image overdraw;            // per pixel
};
VolumeFill measureVolumeFill(const RenderTarget& cameraTarget, const SceneVolumes& volumes,
                             const glm::mat4& viewProjection, GLuint maskBit, bool depthBoundsMask);

// Capture (Chan Figs. 3-1c and 3-9c): the stencil buffer of a camera target made by
// makeStencilCameraTarget, as Chan shows it: black where the crossing count (the low 7 bits) is
// non-zero (in shadow), white where it is zero. Reads the stencil; changes no GL state that a
// later pass relies on (the read framebuffer binding only).
Image stencilCountImage(const RenderTarget& cameraTarget);

// Puts the counters every shadow-volume technique reports into frame.counters.
void reportVolumeCounters(const SceneCasters& casters, const SceneVolumes& volumes,
                          const VolumeFill& fill, const RenderParams& params, Frame& frame);

// frame.counters["volume_pass_fs_invocations"]: `invocations` (from countFragmentInvocations)
// per image pixel; nothing when the driver had no query (invocations < 0).
void reportVolumePassInvocations(double invocations, const RenderParams& params, Frame& frame);

}  // namespace sl::modern
