// modern.gems16, modern.gems4 — Bunnell M., Pellacini F.: "Shadow Map Antialiasing", GPU Gems
// (Fernando ed., 2004), chapter 11. Percentage-closer filtering over a fixed 4x4-texel region
// built from the hardware's own 2x2 filtered compare (GL_LINEAR on a depth texture with
// compare mode, §11.3, Fig. 11-3): 16 offset lookups (§11.3), or 4 lookups whose choice
// follows the screen position in a 2x2 dither (§11.4, Fig. 11-4). --param samples=1 gives the
// single-lookup image of Fig. 11-6. modern.gems16 --param kernel=bicubic weights its 16 samples
// by a cubic B-spline instead, one comparison per texel of the 4x4 region: the "bicubic (16
// samples)" PCF that Chan 2004 (§4.4, Fig. 4-8) times against smoothies (bicubic_pcf.frag).
//
// Passes:
//   1. renderDepthFromLight   — light view into a DEPTH_COMPONENT24 texture, polygon offset,
//                               compare mode and GL_LINEAR (the 2x2 hardware PCF)
//   2. filterInCameraPass     — camera view; the receiver moved towards the light by the bias,
//                               gems_pcf.frag sums offset_lookup (§11.3/§11.4), or
//                               bicubic_pcf.frag weights 16 single comparisons (kernel=bicubic)
// The passes are declared once in gemsPasses(), one table per variant (samples, kernel).
//
// --param bias (modern/pcf_bias.h, pcf_bias.glsl): pass 2 adds to the constant bias below the
// receiver-plane depth bias (ours, after Isidoro 2006, Dou et al. 2014) or the normal offset
// (ours, after Holbert 2011); constant, the default, adds nothing.
#include "modern/gems_pcf.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/base/errors.h"
#include "core/gl/shaders.h"
#include "core/technique/pass_capture.h"
#include "core/technique/passes.h"
#include "modern/camera_pass.h"
#include "modern/hardware_shadow_map.h"
#include "modern/pcf_bias.h"
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
  return std::min(biasTexels * pcf_bias::footprintPerDistance(scene, shadowMapTexels),
                  kMaxRelativeBias);
}

// --param bias (modern/pcf_bias.h): all three methods; the normal offset covers the 4x4 region's
// reach by default, 1.5 texels of lookup offset and 1 of the hardware 2x2 compare (with 1
// footprint the 80-degree stability ground kept faint stripes, looked at).
constexpr double kRegionReachTexels = 2.5;
pcf_bias::Offer biasOffer() {
  return {.receiverPlane = true, .defaultNormalOffsetTexels = kRegionReachTexels};
}

// The uniforms and the define of pcf_bias.glsl (--param bias, modern/pcf_bias.h).
void setBiasUniforms(const Program& program, const Scene& scene, const RenderParams& params,
                     const pcf_bias::Settings& bias) {
  program.set("uNormalOffsetTexels", bias.normalOffsetTexels);
  program.set("uFootprintPerDistance",
              pcf_bias::footprintPerDistance(scene, params.shadowMapTexels));
  program.set("uNormalOffsetByAngle", int(bias.normalOffsetByAngle));
}
ShaderDefines biasDefines(const pcf_bias::Settings& bias) {
  return {{"BIAS_METHOD", std::to_string(int(bias.method))}};
}

// The weights of the 16 samples (--param kernel).
enum class Kernel {
  kBox,      // GPU Gems §11.3: 16 hardware 2x2 lookups, each weighted 1/16
  kBicubic,  // Chan 2004 Fig. 4-8: 16 single comparisons weighted by a cubic B-spline
};

// The DEVIATION comments of pass 2 (above, and its shaders'), for the pass tables.
constexpr const char* kLightSpaceBiasDeviation =
    "DEVIATION (GPU Gems §11.3 gives no bias): we express it in light space, as "
    "kDefaultBiasTexels texel footprints along the light ray, and apply it to the receiver in the "
    "camera pass (the point moves towards the light by that distance before it is projected; "
    "along the ray, so its map coordinates do not change). A footprint at distance r from the "
    "light is r * 2 tan(cone / 2) / size, so the bias is the fraction kDefaultBiasTexels * 2 "
    "tan(cone / 2) / size of r: it scales with the scene, the map and the distance, and not with "
    "the light's depth range.";
constexpr const char* kGemsShaderBiasDeviation =  // gems_pcf.frag
    "DEVIATION (the chapter has no bias): the receiver moves towards the light along the light "
    "ray by uRelativeBias of its distance (gems_pcf.cpp says why); uLightPosition: lighting.glsl.";
constexpr const char* kBSplineDeviation =  // bicubic_pcf.frag
    "DEVIATION (Chan 2004 §4.4, Fig. 4-8): the thesis says only \"a version of percentage closer "
    "filtering [RSC87] with a bicubic filter\", 16 samples; it does not say which cubic or how "
    "the samples are weighted. We take the B-spline because its weights are non-negative and sum "
    "to 1, so the filtered value stays a visibility in [0, 1] (Catmull-Rom's negative lobes "
    "would not).";
constexpr const char* kBicubicShaderBiasDeviation =  // bicubic_pcf.frag
    "DEVIATION (neither Chan nor GPU Gems gives this bias): the receiver moves towards the light "
    "along the light ray by uRelativeBias of its distance, as modern.gems16 (gems_pcf.cpp says "
    "why; the 4x4 region reaches 2 texels from the lookup point here too).";

constexpr const char* kReceiverPlaneDeviation =  // gems_pcf.frag, --param bias
    "DEVIATION (GPU Gems §11.3 compares one depth in all 16 lookups): with --param "
    "bias=receiver-plane each lookup's hardware 2x2 compare is rebuilt from four single "
    "comparisons at its texel centres, weighted bilinearly as the hardware weights them, each "
    "against the receiver plane's depth at that centre (pcf_bias.glsl: ours, after Isidoro 2006 "
    "and Dou et al. 2014).";
constexpr const char* kBicubicReceiverPlaneDeviation =  // bicubic_pcf.frag, --param bias
    "DEVIATION (Chan 2004 compares one depth in all 16 comparisons): with --param "
    "bias=receiver-plane each comparison takes the receiver plane's depth at its texel centre "
    "(pcf_bias.glsl: ours, after Isidoro 2006 and Dou et al. 2014).";
constexpr const char* kNormalOffsetDeviation =  // gems_pcf.frag, bicubic_pcf.frag, --param bias
    "DEVIATION (the chapter has no bias): with --param bias=normal-offset the receiver's point "
    "moves along its normal by normal-offset-texels texel footprints before it is projected "
    "(pcf_bias.glsl: ours, after Holbert 2011).";

// The passes, each declared once: pass 1 of each kernel (the map is compared with GL_LINEAR or
// GL_NEAREST) and pass 2 of each lookup count and kernel, with the paper's text, the buffers a
// dump shows, shaders and deviations. A variant's table (gemsPasses) is one of each.
PassSpec depthFromLightPass(Kernel kernel) {
  const bool bicubic = kernel == Kernel::kBicubic;
  return {
      .id = "1",
      .name = "depth from light",
      .reference = bicubic ? "Chan 2004 §4.4, Fig. 4-8 (the bicubic PCF's map: a depth texture "
                             "with compare mode and GL_NEAREST, one comparison per lookup); "
                             "polygon offset as Everitt"
                           : "Bunnell & Pellacini 2004, GPU Gems §11.3 (a depth texture with "
                             "compare mode and GL_LINEAR: the hardware's 2x2 PCF, Fig. 11-3); "
                             "polygon offset as Everitt",
      // {range}: the drawn window-z range of the grey scale (greyDepth).
      .writes = {{.name = "light-depth",
                  .caption = std::string(bicubic ? "pass 1 (Chan 2004 Fig. 4-8, bicubic PCF): "
                                                   "depth from the light with polygon offset, "
                                                   "compared with GL_NEAREST (one comparison per "
                                                   "sample)"
                                                 : "pass 1 (GPU Gems §11.3): depth from the light "
                                                   "with polygon offset, compared with GL_LINEAR "
                                                   "(hardware 2x2 PCF)") +
                             "{range}"}},
      .shaders = {"depth-only"}};
}

PassSpec filterInCameraPassSpec(int samples, Kernel kernel) {
  if (kernel == Kernel::kBicubic)
    return {.id = "2",
            .name = "camera pass, 16-sample bicubic PCF",
            .reference =
                "Chan 2004 §4.4, Fig. 4-8: percentage-closer filtering [RSC87] with a "
                "bicubic filter, 16 samples (cubic B-spline weights over 4x4 texels; "
                "bicubic_pcf.frag)",
            .writes = cameraPassBuffers("2",
                                        "bicubic_pcf.frag, 16 comparisons weighted by the cubic "
                                        "B-spline, Chan 2004 Fig. 4-8"),
            .shaders = {"bicubic-weights", "bicubic-region"},
            .deviations = {kLightSpaceBiasDeviation, kBSplineDeviation, kBicubicShaderBiasDeviation,
                           kBicubicReceiverPlaneDeviation, kNormalOffsetDeviation}};
  const std::string n = std::to_string(samples);
  return {.id = "2",
          .name = "camera pass, " + n + "-sample PCF",
          .reference = samples == 16  ? "Bunnell & Pellacini 2004, GPU Gems §11.3: 16 "
                                        "offset_lookup calls over the 4x4-texel region (Figs. "
                                        "11-2, 11-3)"
                       : samples == 4 ? "Bunnell & Pellacini 2004, GPU Gems §11.4, Fig. 11-4: "
                                        "four of the sixteen lookups, dithered by pixel position"
                                      : "Bunnell & Pellacini 2004, GPU Gems §11.3: one hardware "
                                        "2x2 lookup (Fig. 11-6)",
          .writes = cameraPassBuffers("2", "gems_pcf.frag, " + n + " offset lookups, " +
                                               (samples == 4 ? "§11.4 Fig. 11-4 dither" : "§11.3")),
          .shaders = {"offset-lookup", "dither", "gems-region"},
          .deviations = {kLightSpaceBiasDeviation, kGemsShaderBiasDeviation,
                         kReceiverPlaneDeviation, kNormalOffsetDeviation}};
}

PassTable gemsPasses(int samples, Kernel kernel) {
  return {depthFromLightPass(kernel), filterInCameraPassSpec(samples, kernel)};
}

// The lookups --param samples takes (samplesParam); the bicubic kernel takes 16 only.
constexpr int kSampleCounts[] = {1, 4, 16};
constexpr int kBicubicSamples = 16;

// The table of each variant, made once for both techniques.
const PassTable& passTable(int samples, Kernel kernel) {
  static const std::map<std::pair<int, Kernel>, PassTable> tables = [] {
    std::map<std::pair<int, Kernel>, PassTable> out;
    for (const int n : kSampleCounts) out[{n, Kernel::kBox}] = gemsPasses(n, Kernel::kBox);
    out[{kBicubicSamples, Kernel::kBicubic}] = gemsPasses(kBicubicSamples, Kernel::kBicubic);
    return out;
  }();
  return tables.at({samples, kernel});
}

// Pass 1 (§11.3, "NVIDIA GPUs have built-in percentage-closer filtering"): the depth map
// with compare mode and linear filtering, so that one lookup is a bilinear 2x2 PCF; for the
// bicubic kernel nearest filtering, so that one lookup is one comparison (Chan 2004 Fig. 4-8).
RenderTarget renderDepthFromLight(Passes& passes, const GpuScene& gpu, const RenderParams& params,
                                  float factor, float units, Kernel kernel) {
  RenderTarget map;
  passes.run("1", [&] {
    const int n = params.shadowMapTexels;
    map = makeRenderTarget(n, n, {}, true, GL_DEPTH_COMPONENT24);
    map.bind();
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    {
      const ScopedEnable polygonOffset(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(factor, units * lightDepthRoundoffScale(gpu.scene()));
      Program program("scene.vert.glsl", "depth_only.frag.glsl");
      program.use();
      program.set("uViewProjection", lightProjection(gpu.scene()) * lightView(gpu.scene().light));
      gpu.draw([](const Object& o) { return o.castsShadow; },
               [&](const Object& o) { program.set("uModel", o.model); });
    }
    // The hardware 2x2 compare for the box kernel; one comparison per lookup for the bicubic.
    setDepthCompareParameters(map.depth.id(), /*linear=*/kernel == Kernel::kBox);
    glBindTexture(GL_TEXTURE_2D, 0);
  });
  return map;
}

// Pass 2 (Chan 2004 §4.4, Fig. 4-8, "bicubic (16 samples)"): the camera view, 16 single
// comparisons at the 4x4 texel centres around the lookup weighted by the cubic B-spline.
// --param bias: the receiver-plane or normal-offset bias (pcf_bias.glsl), ours.
void bicubicFilterInCameraPass(Passes& passes, const GpuScene& gpu, const RenderParams& params,
                               const RenderTarget& map, float relativeBias,
                               const pcf_bias::Settings& bias) {
  passes.run("2", [&] {
    const Scene& scene = gpu.scene();
    RenderTarget target = makeCameraTarget(params, true);
    clearCameraTarget(target);
    glEnable(GL_DEPTH_TEST);
    Program program("scene.vert.glsl", "bicubic_pcf.frag.glsl", biasDefines(bias));
    program.use();
    program.set("uViewProjection", cameraViewProjection(scene, params));
    program.set("uWorldToShadowMap", worldToShadowMap(scene));
    program.set("uMapSize", glm::vec2(float(map.width), float(map.height)));
    program.set("uRelativeBias", relativeBias);
    setBiasUniforms(program, scene, params, bias);
    setLightingUniforms(program, scene);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, map.depth.id());
    program.set("uShadowMap", 0);
    gpu.draw([](const Object&) { return true; },
             [&](const Object& o) { setObjectUniforms(program, o); });
    readCameraTarget(target, passes.frame());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  });
}

// Pass 2 (§11.3 16 samples, §11.4 4 dithered samples): the camera view; --param bias: the
// receiver-plane or normal-offset bias (pcf_bias.glsl), ours.
void filterInCameraPass(Passes& passes, const GpuScene& gpu, const RenderParams& params,
                        const RenderTarget& map, int samples, float relativeBias,
                        const pcf_bias::Settings& bias) {
  passes.run("2", [&] {
    const Scene& scene = gpu.scene();
    RenderTarget target = makeCameraTarget(params, true);
    clearCameraTarget(target);
    glEnable(GL_DEPTH_TEST);
    ShaderDefines defines = biasDefines(bias);
    defines.emplace_back("SAMPLES", std::to_string(samples));
    Program program("scene.vert.glsl", "gems_pcf.frag.glsl", defines);
    program.use();
    program.set("uViewProjection", cameraViewProjection(scene, params));
    program.set("uWorldToShadowMap", worldToShadowMap(scene));
    const float texel = 1.0f / float(map.width);
    program.set("uTexmapScale", glm::vec2(texel, texel));
    program.set("uRelativeBias", relativeBias);
    setBiasUniforms(program, scene, params, bias);
    setLightingUniforms(program, scene);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, map.depth.id());
    program.set("uShadowMap", 0);
    gpu.draw([](const Object&) { return true; },
             [&](const Object& o) { setObjectUniforms(program, o); });
    readCameraTarget(target, passes.frame());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  });
}

// --dump-passes: the depth map of pass 1 as grey (its caption says the drawn range) and the
// filtered camera pass.
void captureMapAndCameraPass(Passes& passes, const RenderTarget& map) {
  if (passes.capturing()) {
    const PassImage grey =
        greyDepth("", "", readDepthTexture(map.depth.id(), map.width, map.height));
    passes.capture("1", "light-depth", [&] { return grey.image; }, {}, {{"range", grey.caption}});
  }
  captureCameraPass(passes, "2");
}

// --param samples: lookups per pixel (GPU Gems §11.3: 16; §11.4: 4 dithered; 1: one lookup).
ParamSpec samplesParam(int defaultSamples) {
  return choiceParam("samples", std::to_string(defaultSamples), {"1", "4", "16"},
                     "hardware 2x2 PCF lookups per pixel: 16 (§11.3), 4 dithered (§11.4), 1");
}

// --param kernel (modern.gems16 only): how the 16 samples are weighted.
constexpr const char* kKernelBox = "box";
constexpr const char* kKernelBicubic = "bicubic";
ParamSpec kernelParam() {
  return choiceParam("kernel", kKernelBox, {kKernelBox, kKernelBicubic},
                     "weights of the 16 samples: box (GPU Gems §11.3, 16 hardware 2x2 lookups, "
                     "1/16 each) or bicubic (Chan 2004 Fig. 4-8: 16 single comparisons over 4x4 "
                     "texels weighted by a cubic B-spline; needs samples=16)");
}

// --param bias-texels: the constant bias, in shadow-map texel footprints along the light ray.
ParamSpec biasTexelsParam() {
  return numberParam("bias-texels", kDefaultBiasTexels, 0, kMaxBiasTexels,
                     "depth bias along the light ray, in shadow-map texel footprints (every "
                     "--param bias keeps it)");
}

Frame renderWithSamples(const Scene& scene, const RenderParams& params, int defaultSamples) {
  const std::string samples = params.text(samplesParam(defaultSamples));
  const pcf_bias::Settings biasMethod = pcf_bias::settings(
      defaultSamples == 16 ? "modern.gems16" : "modern.gems4", params, biasOffer());
  const float factor = float(params.number(offsetFactorParam(kDefaultOffsetFactor)));
  const float units =
      float(params.number(offsetUnitsParam(kDefaultOffsetUnits, kLargestOffsetUnits)));
  const float biasTexels = float(params.number(biasTexelsParam()));
  // Only modern.gems16 declares the kernel; modern.gems4 rejects the key as unknown.
  const bool bicubic =
      defaultSamples == 16 && params.text(kernelParam()) == std::string(kKernelBicubic);
  if (bicubic && samples != "16")
    throw InputError("modern.gems16: --param kernel=bicubic weights 16 samples; samples=" +
                     samples + " cannot take it");
  const Kernel kernel = bicubic ? Kernel::kBicubic : Kernel::kBox;
  Frame frame;
  Passes passes(frame, params, passTable(std::stoi(samples), kernel));
  GpuScene gpu(scene);
  RenderTarget map = renderDepthFromLight(passes, gpu, params, factor, units, kernel);
  const float bias = relativeBias(scene, params.shadowMapTexels, biasTexels);
  if (bicubic)
    bicubicFilterInCameraPass(passes, gpu, params, map, bias, biasMethod);
  else
    filterInCameraPass(passes, gpu, params, map, std::stoi(samples), bias, biasMethod);
  frame.counters["samples per pixel"] = std::stoi(samples);
  captureMapAndCameraPass(passes, map);
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
  for (const ParamSpec& spec : pcf_bias::params(biasOffer())) t.params.push_back(spec);
  if (samples == 16) t.params.push_back(kernelParam());
  t.reads = {.shadowMap = true};
  t.edge = Technique::Edge::kFiltered;  // 4 or 16 hardware 2x2 PCF lookups
  // The default variant's passes (samples = the technique's own, box kernel); a render with
  // other --params runs the table of its variant (passTable): the other lookup counts and, for
  // modern.gems16, the bicubic kernel.
  t.passes = passTable(samples, Kernel::kBox);
  for (const int n : kSampleCounts)
    if (n != samples)
      t.passVariants.push_back(
          {{{samplesParam(samples).key, std::to_string(n)}}, passTable(n, Kernel::kBox)});
  if (samples == kBicubicSamples)
    t.passVariants.push_back(
        {{{kernelParam().key, kKernelBicubic}}, passTable(kBicubicSamples, Kernel::kBicubic)});
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
