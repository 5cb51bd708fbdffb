// modern.esm — Exponential Shadow Maps: ours, after Annen T., Mertens T., Seidel H.-P.,
// Flerackers E., Kautz J.: "Exponential Shadow Maps", Graphics Interface 2008 (not in
// shared/papers; nothing here quotes it). The map stores exp(c z) of the linear light depth z;
// filtered, it is E[exp(c z)], and exp(-c d) E[exp(c z)] approximates the lit fraction of the
// footprint for a receiver at depth d behind planar occluders. It is the single-term limit of
// Annen et al. 2007's convolution (modern.csm), with the filtering of modern.csm and modern.vsm.
//
// Passes:
//   1. renderExponentialMapFromLight — exp(c z) of linear light depth into a float layer
//   2. blurExponentialMap            — separable Gaussian 3x3 / 5x5 / 7x7 (as Annen 2007 §4.1)
//   3. buildExponentialMipmaps       — mip-maps, tri-linear + anisotropic filtering
//   4. exponentialTestInCameraPass   — clamp(exp(-c d) E[exp(c z)], 0, 1); esm_shadow.frag
// The passes are declared once in esmPasses().
#include "modern/exponential_shadow_map.h"

#include <cmath>

#include "core/base/errors.h"
#include "core/technique/pass_capture.h"
#include "core/technique/passes.h"
#include "modern/camera_pass.h"
#include "modern/filtered_map_passes.h"
#include "modern/prefiltered_maps.h"

namespace sl::modern {
using namespace sl::gl;

namespace {
// c: 80 keeps exp(c) within fp32 and makes exp(-c (d - z)) < 1% for d - z > 0.058 of the
// light's depth range (ours, after Annen et al. 2008, not in shared/papers: a large c sharpens
// the test; the format bounds it).
constexpr double kDefaultExponent = 80.0;
constexpr double kMinExponent = 1.0;  // below it the test hardly tells blocker from receiver
constexpr int kDefaultBlurTaps = 3;   // same default as modern.csm and modern.vsm

PassTable esmPasses() {
  return {
      {.id = "1",
       .name = "exponential map from light",
       .reference = "ours, after Annen et al. 2008 (not in shared/papers): exp(c z) of the "
                    "linear light depth z (linear depth as Annen et al. 2007 §4.1)",
       .writes = {{.name = "exp-map", .caption = "filtered E[exp(c z)] / exp(c)"}},
       .shaders = {"esm-map"}},
      {.id = "2",
       .name = "separable Gaussian",  // + " NxN"
       .reference = "Annen et al. 2007 §4.1: \"a separable Gaussian filter kernel\" (binomial "
                    "weights), horizontal then vertical, on exp(c z)",
       .shaders = {"gaussian"}},
      {.id = "3",
       .name = "mip-maps",
       .reference = "Annen et al. 2007 §4.1 (\"build a mip-map\"), applied to exp(c z) as to "
                    "the CSM basis",
       .shaders = {"downsample"},
       .deviations = {kDrawnMipChainDeviation}},
      {.id = "4",
       .name = "camera pass, exponential test",
       .reference = "ours, after Annen et al. 2008 (not in shared/papers): visibility = "
                    "clamp(exp(-c d) E[exp(c z)], 0, 1)",
       .writes = cameraPassBuffers("4",
                                   "esm_shadow.frag: the exponential test on the filtered "
                                   "map"),
       .shaders = {"esm-test"}},
  };
}

const PassTable& passTable() {
  static const PassTable table = esmPasses();
  return table;
}

struct EsmSettings {
  double exponent = kDefaultExponent;  // after the clamp to the format
  GLenum format = GL_RGBA32F;
  int blurTaps = kDefaultBlurTaps;
  MapFiltering filtering;
};

// The --params of modern.esm, declared once (Technique::params).
ParamSpec exponentParam() {
  return numberParam("exponent", kDefaultExponent, kMinExponent, kEsmMaxExponentFloat32,
                     "c of exp(c z), z the linear light depth in [0, 1]; clamped to 10.5 with "
                     "storage=16 (exp(c) within fp16)");
}
ParamSpec storageParam() {
  return choiceParam("storage", "float", {"16", "float"},
                     "map texture format: 16 or 32-bit float (8 bits cannot hold exp(c z))");
}

EsmSettings parseSettings(const GlContext& context, const RenderParams& params) {
  EsmSettings s;
  const bool half = params.text(storageParam()) == "16";
  s.format = half ? GL_RGBA16F : GL_RGBA32F;
  s.exponent = esmEffectiveExponent(params.number(exponentParam()), half);
  s.blurTaps = parseBlurTaps(params, blurParam(kDefaultBlurTaps));
  s.filtering = parseFiltering(context, params);
  return s;
}

// Pass 1: exp(c z) of the linear light depth; no caster = depth 1.
LayeredMap renderExponentialMapFromLight(Passes& passes, const GpuScene& gpu,
                                         const RenderParams& params, const EsmSettings& s) {
  LayeredMap map;
  passes.run("1", [&] {
    const float far[4] = {float(std::exp(s.exponent)), 0, 0, 1};
    map = renderWarpedDepthFromLight(
        gpu, params, s.format, s.filtering.mipmaps, "esm_map.frag.glsl", far,
        [&](const Program& program) { program.set("uExponent", float(s.exponent)); });
  });
  return map;
}

// Pass 2: the same separable Gaussian as modern.csm, on exp(c z).
void blurExponentialMap(Passes& passes, const LayeredMap& map, const EsmSettings& s) {
  if (s.blurTaps == 0) return;
  const std::string taps = std::to_string(s.blurTaps);
  passes.run(
      "2", [&] { blurLayers(map, s.blurTaps); }, {}, " " + taps + "x" + taps);
}

// Pass 3: mip-maps and filtering state.
void buildExponentialMipmaps(Passes& passes, const LayeredMap& map, const EsmSettings& s) {
  passes.run("3", [&] { buildMipmapsAndSetFiltering(map, s.filtering); });
}

// Pass 4: the exponential test in the camera view.
void exponentialTestInCameraPass(Passes& passes, const GpuScene& gpu, const RenderParams& params,
                                 const LayeredMap& map, const EsmSettings& s) {
  passes.run("4", [&] {
    shadeWithFilteredMap(
        gpu, params, map, "esm_shadow.frag.glsl",
        [&](const Program& program) { program.set("uExponent", float(s.exponent)); },
        passes.frame());
  });
}

Frame render(GlContext& context, const Scene& scene, const RenderParams& params) {
  const EsmSettings s = parseSettings(context, params);
  Frame frame;
  Passes passes(frame, params, passTable());
  GpuScene gpu(scene);
  const LayeredMap map = renderExponentialMapFromLight(passes, gpu, params, s);
  blurExponentialMap(passes, map, s);
  passes.capture("1", "exp-map", [&] {
    // E[exp(c z)] / exp(c) = E[exp(c (z - 1))], in (0, 1]: 1 where no caster is.
    return channel(readLayer(map, 0, float(std::exp(-s.exponent)), 0.0f), 0);
  });
  buildExponentialMipmaps(passes, map, s);
  exponentialTestInCameraPass(passes, gpu, params, map, s);
  captureCameraPass(passes, "4");
  frame.counters["anisotropy"] = s.filtering.anisotropy;
  frame.counters["exponent"] = s.exponent;
  return frame;
}
}  // namespace

Technique exponentialShadowMapTechnique() {
  Technique t;
  t.name = "modern.esm";
  t.paper = "ours, after Annen et al. 2008, Exponential Shadow Maps (not in shared/papers)";
  t.summary = "exp(c z) blurred and mip-mapped, test exp(-c d) E[exp(c z)]; leaks near contact";
  t.status = "complete";
  t.needs.profile = Profile::kCore;
  t.params = {exponentParam(), storageParam(), blurParam(kDefaultBlurTaps), filteringParam(),
              anisotropyParam()};
  t.reads = {.shadowMap = true};
  t.edge = Technique::Edge::kFiltered;  // blurred, mip-mapped exp(c z)
  t.plan.prefilter = PlanTraits::Prefilter::kVariance;
  t.passes = passTable();
  t.render = render;
  return t;
}

}  // namespace sl::modern
