// modern.gems16, modern.gems4 — Bunnell M., Pellacini F.: "Shadow Map Antialiasing", GPU Gems
// (Fernando ed., 2004), chapter 11. Percentage-closer filtering over a fixed 4x4-texel region
// built from the hardware's own 2x2 filtered compare (GL_LINEAR on a depth texture with
// compare mode, §11.3, Fig. 11-3): 16 offset lookups (§11.3), or 4 lookups whose choice
// follows the screen position in a 2x2 dither (§11.4, Fig. 11-4). --param samples=1 gives the
// single-lookup image of Fig. 11-6.
//
// Passes:
//   1. renderDepthFromLight   — light view into a DEPTH_COMPONENT24 texture, polygon offset,
//                               compare mode and GL_LINEAR (the 2x2 hardware PCF)
//   2. filterInCameraPass     — camera view; the receiver moved towards the light by the bias,
//                               gems_pcf.frag sums offset_lookup (§11.3/§11.4)
#include "modern/gems_pcf.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/errors.h"
#include "core/pass_capture.h"
#include "modern/camera_pass.h"
#include "modern/hardware_shadow_map.h"
#include "modern/prefiltered_maps.h"

namespace sl::modern {
using namespace sl::gl;

namespace {
// The 4x4 region reaches 2 texels from the lookup point, where one reference depth is compared
// with the depths of neighbouring texels (the chapter does not discuss bias).
//
// Slope: a slanted receiver needs twice modern.hw's polygon-offset slope factor. The factor
// multiplies the window-space depth slope, so it is right for any depth mapping.
//
// Curvature and the texels' spread: a constant of the order of the receiver's depth change
// across a texel footprint. DEVIATION (GPU Gems §11.3 gives no bias): we express it in light
// space, as kDefaultBiasTexels texel footprints along the light ray, and apply it to the
// receiver in the camera pass (the point moves towards the light by that distance before it is
// projected; along the ray, so its map coordinates do not change). A footprint at distance r
// from the light is r * 2 tan(cone / 2) / size, so the bias is the fraction
// kDefaultBiasTexels * 2 tan(cone / 2) / size of r: it scales with the scene, the map and the
// distance, and not with the light's depth range.
//
// Why not polygon-offset units: the former default, 40000 units at 256^2, is a constant in
// window depth, and window depth resolves world depth as z^2 (f - n) / (n f). On brabec it was
// about 0.9 footprints at the spheres, but with a small near plane (near/far 1e-3, or geometry
// around the light, where the fitted near plane drops to far * 1e-4) it meant whole world
// units: every receiver moved in front of its casters and 30% of the stability suite's pixels
// came out lit in the umbra. Units keep modern.hw's 4, the depth buffer's own quantisation.
//
// Two footprints: with one, gems4 still dotted the small brabec sphere below its terminator at
// 256^2 (looked at, 4x close-up); with two that close-up matches the former default within 3%
// per pixel, and at 512^2 and 1024^2 fewer than 120 of 800x600 pixels differ from it, all on
// shadow outlines (2 footprints at 1024^2 are 0.016 world units at brabec's objects).
// All three are --params.
constexpr float kDefaultOffsetFactor = 4.0f;
constexpr float kDefaultOffsetUnits = 4.0f;  // modern.hw's constant, 24-bit depth steps
constexpr double kLargestOffsetUnits = 1e7;  // depth steps; far beyond any useful offset
constexpr float kDefaultBiasTexels = 2.0f;   // texel footprints along the light ray
constexpr float kMaxBiasTexels = 16.0f;
// A map of a few texels has footprints as wide as the light's distance (1x1 at a 70 degree
// cone: 1.4 of it); moving a receiver by more than this share of its distance would take it
// past the light's near plane or behind the light. Such a map has no meaningful bias.
constexpr float kMaxRelativeBias = 0.5f;

// The bias as a fraction of the receiver's distance to the light (see above).
float relativeBias(const Scene& scene, int shadowMapTexels, float biasTexels) {
  const float halfCone = glm::radians(scene.light.coneDegrees) * 0.5f;
  return std::min(biasTexels * 2.0f * std::tan(halfCone) / float(shadowMapTexels),
                  kMaxRelativeBias);
}

// Pass 1 (§11.3, "NVIDIA GPUs have built-in percentage-closer filtering"): the depth map
// with compare mode and linear filtering, so that one lookup is a bilinear 2x2 PCF.
RenderTarget renderDepthFromLight(const GpuScene& gpu, const RenderParams& params, float factor,
                                  float units, Frame& frame) {
  PassTimer timer(frame, "1 depth from light",
                  "Bunnell & Pellacini 2004, GPU Gems §11.3 (a depth texture with compare mode "
                  "and GL_LINEAR: the hardware's 2x2 PCF, Fig. 11-3); polygon offset as Everitt");
  timer.shaderPasses({"depth-only"});
  const int n = params.shadowMapTexels;
  RenderTarget map = makeRenderTarget(n, n, {}, true, GL_DEPTH_COMPONENT24);
  map.bind();
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(factor, units * lightDepthRoundoffScale(gpu.scene()));
  Program program("scene.vert.glsl", "depth_only.frag.glsl");
  program.use();
  program.set("uViewProjection", lightProjection(gpu.scene()) * lightView(gpu.scene().light));
  gpu.draw([](const Object& o) { return o.castsShadow; },
           [&](const Object& o) { program.set("uModel", o.model); });
  glDisable(GL_POLYGON_OFFSET_FILL);
  setDepthCompareParameters(map.depth.id(), /*linear=*/true);  // hardware 2x2 compare
  glBindTexture(GL_TEXTURE_2D, 0);
  return map;
}

// Pass 2 (§11.3 16 samples, §11.4 4 dithered samples): the camera view.
void filterInCameraPass(const GpuScene& gpu, const RenderParams& params, const RenderTarget& map,
                        int samples, float relativeBias, Frame& frame) {
  PassTimer timer(frame, "2 camera pass, " + std::to_string(samples) + "-sample PCF",
                  samples == 16  ? "Bunnell & Pellacini 2004, GPU Gems §11.3: 16 offset_lookup "
                                   "calls over the 4x4-texel region (Figs. 11-2, 11-3)"
                  : samples == 4 ? "Bunnell & Pellacini 2004, GPU Gems §11.4, Fig. 11-4: four "
                                   "of the sixteen lookups, dithered by pixel position"
                                 : "Bunnell & Pellacini 2004, GPU Gems §11.3: one hardware 2x2 "
                                   "lookup (Fig. 11-6)");
  timer.shaderPasses({"offset-lookup", "dither", "gems-region"});
  const Scene& scene = gpu.scene();
  RenderTarget target = makeCameraTarget(params, true);
  clearCameraTarget(target);
  glEnable(GL_DEPTH_TEST);
  Program program("scene.vert.glsl", "gems_pcf.frag.glsl", {{"SAMPLES", std::to_string(samples)}});
  program.use();
  program.set("uViewProjection", cameraViewProjection(scene, params));
  program.set("uWorldToShadowMap", worldToShadowMap(scene));
  const float texel = 1.0f / float(map.width);
  program.set("uTexmapScale", glm::vec2(texel, texel));
  program.set("uRelativeBias", relativeBias);
  setLightingUniforms(program, scene);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, map.depth.id());
  program.set("uShadowMap", 0);
  gpu.draw([](const Object&) { return true; },
           [&](const Object& o) { setObjectUniforms(program, o); });
  readCameraTarget(target, frame);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

// --dump-passes: the depth map of pass 1 as grey and the filtered camera pass.
void captureMapAndCameraPass(const RenderTarget& map, int samples, Frame& frame) {
  frame.intermediates.push_back(greyDepth(
      "1-light-depth",
      "pass 1 (GPU Gems §11.3): depth from the light with polygon offset, compared with GL_LINEAR "
      "(hardware 2x2 PCF)",
      readDepthTexture(map.depth.id(), map.width, map.height)));
  captureCameraPass(frame, 2,
                    "gems_pcf.frag, " + std::to_string(samples) + " offset lookups, " +
                        (samples == 4 ? "§11.4 Fig. 11-4 dither" : "§11.3"));
}

// --param samples: lookups per pixel (GPU Gems §11.3: 16; §11.4: 4 dithered; 1: one lookup).
ParamSpec samplesParam(int defaultSamples) {
  return choiceParam("samples", std::to_string(defaultSamples), {"1", "4", "16"},
                     "hardware 2x2 PCF lookups per pixel: 16 (§11.3), 4 dithered (§11.4), 1");
}

// --param bias-texels: the receiver-plane bias, in shadow-map texel footprints.
ParamSpec biasTexelsParam() {
  return numberParam("bias-texels", kDefaultBiasTexels, 0, kMaxBiasTexels,
                     "depth bias along the light ray, in shadow-map texel footprints");
}

Frame renderWithSamples(const Scene& scene, const RenderParams& params, int defaultSamples) {
  const std::string samples =
      params.text(samplesParam(defaultSamples));
  const float factor = float(params.number(offsetFactorParam(kDefaultOffsetFactor)));
  const float units = float(params.number(offsetUnitsParam(kDefaultOffsetUnits, kLargestOffsetUnits)));
  const float biasTexels =
      float(params.number(biasTexelsParam()));
  Frame frame;
  GpuScene gpu(scene);
  RenderTarget map = renderDepthFromLight(gpu, params, factor, units, frame);
  filterInCameraPass(gpu, params, map, std::stoi(samples),
                     relativeBias(scene, params.shadowMapTexels, biasTexels), frame);
  frame.counters["samples per pixel"] = std::stoi(samples);
  if (params.capturePasses) captureMapAndCameraPass(map, std::stoi(samples), frame);
  return frame;
}

Technique gemsTechnique(const std::string& name, int samples, const std::string& summary) {
  Technique t;
  t.name = name;
  t.paper = "Bunnell & Pellacini 2004, GPU Gems ch. 11, " +
            std::string(samples == 16 ? "§11.3" : "§11.4, Fig. 11-4");
  t.summary = summary;
  t.status = "complete";
  t.needs.profile = Profile::kCore;
  t.params = {samplesParam(samples), offsetFactorParam(kDefaultOffsetFactor),
              offsetUnitsParam(kDefaultOffsetUnits, kLargestOffsetUnits), biasTexelsParam()};
  t.reads = {.shadowMap = true};
  t.render = [samples](GlContext&, const Scene& scene, const RenderParams& params) {
    return renderWithSamples(scene, params, samples);
  };
  return t;
}
}  // namespace

Technique gems16Technique() {
  return gemsTechnique("modern.gems16", 16,
                       "16 hardware 2x2 PCF lookups at offsets -1.5..1.5 texels (4x4 region)");
}

Technique gems4Technique() {
  return gemsTechnique("modern.gems4", 4,
                       "4 of the 16 lookups per pixel, dithered by screen position (Fig. 11-4)");
}

}  // namespace sl::modern
