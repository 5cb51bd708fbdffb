// modern.hybrid — Eric Chan, "Hardware-Accelerated Rendering of Hard and Soft Shadows", MIT
// 2004, chapter 3: "Hybrid Shadow Rendering Using Computation Masks" (after Chan & Durand 2004).
// A shadow map finds the pixels near shadow silhouettes; z-fail shadow volumes (Everitt &
// Kilgard 2002, modern.volumes) are rasterised only there, through a computation mask; the
// shadow map decides every other pixel.
//
// Passes (§3.1 steps 1-4, §3.2):
//   1. renderShadowMap          — step 1: depth from the light, hardware 2x2 compare
//   2. findSilhouettesAndBuildVolumes — CPU silhouette edges and capped volumes (as modern.volumes)
//   3. classifySilhouettePixels — step 2, Figure 3-3: camera pass; 2x2 compare strictly between
//                                 0 and 1 on a light-facing surface = silhouette pixel; others
//                                 are shaded from the shadow map; fills the depth buffer
//   4. buildComputationMask     — §3.2: EXT_depth_bounds_test where the driver has it (depth of
//                                 non-silhouette pixels := 0, bounds [eps, 1]); otherwise a
//                                 stencil bit (same effect: no stencil update off the mask)
//   5. drawVolumesThroughMask   — step 3: z-fail stencil counting at silhouette pixels only
//   6. shadeSilhouettePixels    — step 4: silhouette pixels shaded from the stencil count
//   (then, untimed: counters of Figures 3-9 and 3-10 — overdraw with and without the mask, the
//    share of silhouette pixels)
#include "modern/hybrid_shadows.h"

#include <algorithm>

#include "core/errors.h"
#include "modern/camera_pass.h"
#include "modern/hardware_shadow_map.h"
#include "modern/shadow_volumes.h"

namespace sl::modern {
using namespace sl::gl;

namespace {
constexpr float kDefaultOffsetFactor = 2.0f;  // as modern.hw (Everitt et al. Fig. 3)
constexpr float kDefaultOffsetUnits = 4.0f;
// §3.2: "set the depth bounds to [eps, 1] for some small constant eps ~ 0.001".
constexpr double kDepthBoundsMin = 0.001;
constexpr double kDepthBoundsMax = 1.0;

enum class MaskKind { kDepthBounds, kStencil };

// Pass 1 (§3.1 step 1): an ordinary shadow map, read with the hardware 2x2 compare.
RenderTarget renderShadowMap(const GpuScene& gpu, const RenderParams& params,
                             const Program& program, float factor, float units, Frame& frame) {
  PassTimer timer(frame, "1 shadow map");
  const int n = params.shadowMapTexels;
  RenderTarget map = makeRenderTarget(n, n, {}, true, GL_DEPTH_COMPONENT24);
  map.bind();
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(factor, units);
  program.use();
  program.set("uViewProjection", lightProjection(gpu.scene()) * lightView(gpu.scene().light));
  // Every caster: each one has a shadow volume (open ones two-sided), so both halves of the
  // hybrid see the same blockers.
  gpu.draw([](const Object& o) { return o.castsShadow; },
           [&](const Object& o) { program.set("uModel", o.model); });
  glDisable(GL_POLYGON_OFFSET_FILL);
  // GL_LINEAR with compare mode = the 2x2 percentage-closer filter of Figure 3-3.
  setDepthCompareParameters(map.depth.id(), /*linear=*/true);  // hardware 2x2 compare
  glBindTexture(GL_TEXTURE_2D, 0);
  return map;
}

// Pass 2 (§3.1 step 3 needs them; Everitt–Kilgard): silhouette edges on the CPU, volumes.
SceneVolumes findSilhouettesAndBuildVolumes(const Scene& scene, const SceneCasters& casters,
                                            Frame& frame) {
  PassTimer timer(frame, "2 silhouettes and volumes (CPU)");
  return buildSceneVolumes(casters, scene.light.position);
}

// Pass 3 (§3.1 step 2, Figure 3-3): shade from the shadow map and tag silhouette pixels; the
// depth buffer keeps the nearest surfaces for the volumes (same vertex shader as the volumes).
void classifySilhouettePixels(const GpuScene& gpu, const RenderTarget& target,
                              const RenderTarget& map, const Program& program,
                              const glm::mat4& viewProjection, Frame& frame) {
  PassTimer timer(frame, "3 classify silhouette pixels");
  const Scene& scene = gpu.scene();
  target.bind();
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  program.use();
  program.set("uViewProjection", viewProjection);
  const glm::mat4 S = glm::mat4(0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 0.5f, 0, 0.5f, 0.5f, 0.5f, 1);
  program.set("uWorldToShadowMap", S * lightProjection(scene) * lightView(scene.light));
  setLightingUniforms(program, scene);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, map.depth.id());
  program.set("uShadowMap", 0);
  gpu.draw([](const Object&) { return true; },
           [&](const Object& o) { setObjectUniforms(program, o); });
}

// Pass 4 (§3.2): the computation mask from the silhouette tags.
void buildComputationMask(const RenderTarget& target, const Program& program, MaskKind kind,
                          Frame& frame) {
  PassTimer timer(frame, "4 computation mask");
  target.bind();
  program.use();
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, target.color[2].id());
  program.set("uSilhouette", 0);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  if (kind == MaskKind::kDepthBounds) {
    // Chan's set-up: non-silhouette depth := 0, then bounds [eps, 1] discard them early.
    program.set("uMode", 0);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
  } else {
    // DEVIATION (Chan §3.2): without EXT_depth_bounds_test (llvmpipe) the mask is stencil bit 7,
    // set at silhouette pixels; later passes test it. Setting depth to 0 instead would not do:
    // z-fail counts exactly the fragments that fail the depth test.
    program.set("uMode", 1);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, GLint(kStencilMaskBit), kStencilMaskBit);
    glStencilMask(kStencilMaskBit);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
  }
  const FullScreenTriangle triangle;
  triangle.draw();
  // The tags are an attachment of the bound framebuffer: leaving them bound to a texture unit
  // would make the driver synchronise every later draw (llvmpipe flushes per draw).
  glBindTexture(GL_TEXTURE_2D, 0);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glDisable(GL_STENCIL_TEST);
  glStencilMask(0xFF);
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
}

GLuint maskBitFor(MaskKind kind) {
  return kind == MaskKind::kStencil ? kStencilMaskBit : 0u;
}

// Pass 5 (§3.1 step 3): z-fail stencil updates only at silhouette pixels.
void drawVolumesThroughMask(const SceneVolumes& volumes, const Program& volumeProgram,
                            MaskKind kind, Frame& frame) {
  PassTimer timer(frame, "5 shadow volumes at silhouette pixels");
  if (kind == MaskKind::kDepthBounds) {
    glEnable(GL_DEPTH_BOUNDS_TEST_EXT);
    glDepthBoundsEXT(kDepthBoundsMin, kDepthBoundsMax);
  }
  countVolumesZFail(volumes, volumeProgram, maskBitFor(kind));
  if (kind == MaskKind::kDepthBounds) glDisable(GL_DEPTH_BOUNDS_TEST_EXT);
}

// Pass 6 (§3.1 step 4): silhouette pixels lit where the count is zero, shadowed elsewhere.
void shadeSilhouettePixels(const GpuScene& gpu, const Program& shadeProgram, MaskKind kind,
                           Frame& frame) {
  PassTimer timer(frame, "6 shade silhouette pixels");
  if (kind == MaskKind::kDepthBounds) glEnable(GL_DEPTH_BOUNDS_TEST_EXT);
  shadeFromStencil(gpu, shadeProgram, maskBitFor(kind));
  if (kind == MaskKind::kDepthBounds) glDisable(GL_DEPTH_BOUNDS_TEST_EXT);
}

// Figure 3-5b: non-silhouette pixels red (shadow map: shadowed) / blue (lit); silhouette pixels
// black (volumes: shadowed) / green (lit).
Image classificationImage(const Image& silhouette, const Image& visibility) {
  Image out(silhouette.width, silhouette.height, 3);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const bool sil = silhouette.at(x, y) > 0.5f;
      const bool lit = visibility.at(x, y) > 0.5f;
      const glm::vec3 c = sil ? (lit ? glm::vec3(0, 1, 0) : glm::vec3(0))
                              : (lit ? glm::vec3(0.2f, 0.3f, 1) : glm::vec3(1, 0.1f, 0.1f));
      for (int k = 0; k < 3; ++k) out.at(x, y, k) = c[k];
    }
  return out;
}

Frame render(GlContext& ctx, const Scene& scene, const RenderParams& params) {
  const float factor = float(params.number("offset-factor", kDefaultOffsetFactor, -100, 100));
  const float units = float(params.number("offset-units", kDefaultOffsetUnits, -1e6, 1e6));
  const std::string maskName = params.text("mask", "auto", {"auto", "depth-bounds", "stencil"});
  const bool haveBounds = ctx.caps().depthBoundsTest();
  if (maskName == "depth-bounds" && !haveBounds)
    throw InputError(
        "modern.hybrid: --param mask=depth-bounds needs GL_EXT_depth_bounds_test, "
        "which this driver (" +
        ctx.caps().renderer + ") lacks; use mask=stencil");
  const MaskKind kind = maskName == "stencil" || (maskName == "auto" && !haveBounds)
                            ? MaskKind::kStencil
                            : MaskKind::kDepthBounds;
  Frame frame;
  const SceneCasters casters = collectCasters(scene);
  GpuScene gpu(scene);
  const glm::mat4 viewProjection = infiniteCameraViewProjection(scene, params);
  Program volumeProgram("shadow_volume.vert.glsl", "depth_only.frag.glsl");
  volumeProgram.use();
  volumeProgram.set("uViewProjection", viewProjection);
  Program shadeProgram("shadow_volume.vert.glsl", "stencil_shade.frag.glsl");
  shadeProgram.use();
  shadeProgram.set("uViewProjection", viewProjection);
  setLightingUniforms(shadeProgram, scene);
  // Programs are compiled before the timed passes.
  Program mapProgram("scene.vert.glsl", "depth_only.frag.glsl");
  Program classifyProgram("shadow_volume.vert.glsl", "hybrid_classify.frag.glsl");
  Program maskProgram("computation_mask.vert.glsl", "computation_mask.frag.glsl");
  // Colour attachment 2 = the silhouette tags (Figure 3-1b).
  RenderTarget target = makeStencilCameraTarget(params, {GL_RGBA8});

  RenderTarget map = renderShadowMap(gpu, params, mapProgram, factor, units, frame);
  const SceneVolumes volumes = findSilhouettesAndBuildVolumes(scene, casters, frame);
  classifySilhouettePixels(gpu, target, map, classifyProgram, viewProjection, frame);
  buildComputationMask(target, maskProgram, kind, frame);
  target.bind();
  drawVolumesThroughMask(volumes, volumeProgram, kind, frame);
  // The colour target has three attachments; the shading pass writes the first two.
  const GLenum shadeBuffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_NONE};
  glDrawBuffers(3, shadeBuffers);
  if (kind == MaskKind::kDepthBounds) glDepthBoundsEXT(kDepthBoundsMin, kDepthBoundsMax);
  shadeSilhouettePixels(gpu, shadeProgram, kind, frame);
  readCameraTarget(target, frame);

  // Untimed counters (Chan §3.3.2, Figures 3-9 and 3-10).
  const Image silhouette = channel(readAttachment(target, 2), 0);
  double silhouettePixels = 0;
  for (float v : silhouette.data) silhouettePixels += v > 0.5f ? 1 : 0;
  const VolumeFill all = measureVolumeFill(target, volumes, viewProjection, 0, false);
  const VolumeFill masked = measureVolumeFill(target, volumes, viewProjection, maskBitFor(kind),
                                              kind == MaskKind::kDepthBounds);
  reportVolumeCounters(casters, volumes, all, params, frame);
  const double pixels = double(params.width) * params.height;
  frame.counters["silhouette_fraction"] = silhouettePixels / pixels;
  frame.counters["masked_overdraw"] = masked.fragments / pixels;
  frame.counters["mask_depth_bounds"] = kind == MaskKind::kDepthBounds ? 1 : 0;
  if (params.capturePasses) {
    frame.intermediates.push_back(
        {"3-silhouette-pixels", "silhouette pixels (Chan Fig. 3-1b, 3-9b)", silhouette});
    frame.intermediates.push_back(
        {"6-classification",
         "red/blue: shadow map shadowed/lit; black/green: volumes shadowed/lit (Chan Fig. 3-5b)",
         classificationImage(silhouette, frame.visibility)});
    frame.intermediates.push_back(
        {"5-stencil-count",
         "stencil buffer: volumes counted at silhouette pixels only, black = non-zero (Chan Fig. "
         "3-1c, 3-9c)",
         stencilCountImage(target)});
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return frame;
}
}  // namespace

Technique hybridShadowsTechnique() {
  Technique t;
  t.name = "modern.hybrid";
  t.paper = "Chan 2004 thesis ch. 3 (hybrid shadow maps + shadow volumes, computation masks)";
  t.summary = "shadow map finds silhouette pixels; z-fail volumes only there through a mask";
  t.status = "complete (depth-bounds mask where the driver has it, stencil-bit mask otherwise)";
  t.needs.profile = Profile::kCore;
  t.paramKeys = {"offset-factor", "offset-units", "mask"};
  t.render = render;
  return t;
}

}  // namespace sl::modern
