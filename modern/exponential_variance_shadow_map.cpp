// modern.evsm2 and modern.evsm4 — Exponential Variance Shadow Maps: ours, after Lauritzen A.,
// McCool M.: "Layered Variance Shadow Maps", Graphics Interface 2008, where the exponential
// warp of VSM is introduced (not in shared/papers; nothing here quotes it). The linear light
// depth z is mapped to x = 2 z - 1 and warped by p = exp(c+ x) (and, EVSM4, n = -exp(-c- x));
// the map stores the first two moments of each warp, is blurred and mip-mapped as modern.vsm's,
// and the camera pass takes Chebyshev's bound (Donnelly & Lauritzen 2006, as modern.vsm) on each
// warp and keeps the smaller. The positive warp squeezes the depths in front of a receiver
// towards 0 relative to it, which shrinks VSM's light bleeding; the negative warp does the same
// for the depths behind it.
//
// Passes:
//   1. renderWarpedMomentsFromLight — (p, p^2, n, n^2) of the warped linear depth, float layer
//   2. blurWarpedMoments            — separable Gaussian 3x3 / 5x5 / 7x7 (as Annen 2007 §4.1)
//   3. buildWarpedMomentMipmaps     — mip-maps, tri-linear + anisotropic filtering
//   4. chebyshevOnEachWarp          — min of the bounds of both warps; evsm_shadow.frag
// The passes are declared once in evsmPasses().
#include "modern/exponential_variance_shadow_map.h"

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
// Defaults: the largest fp32 exponent for the positive warp; a small negative one (ours: the
// negative warp only has to catch receivers in front of the mean, its exponent trades that
// against its own bleeding).
constexpr double kDefaultPositiveExponent = 42.0;
constexpr double kDefaultNegativeExponent = 5.0;
constexpr double kMinExponent = 0.5;  // below it the warp is nearly linear: plain VSM
// (linear depth)^2, scaled into each warp by its slope at the mean: modern.vsm's default.
constexpr double kDefaultMinVariance = 1e-5;
constexpr double kMaxMinVariance = 0.25;  // the largest variance of values in [0, 1]
constexpr double kDefaultBleedReduction = 0.0;
constexpr double kMaxBleedReduction = 0.99;  // 1 would divide by zero
constexpr int kDefaultBlurTaps = 3;          // same default as modern.csm and modern.vsm

PassTable evsmPasses(bool negative) {
  const std::string what =
      negative ? "(p, p^2, n, n^2) of p = exp(c+ x), n = -exp(-c- x)" : "(p, p^2) of p = exp(c+ x)";
  return {
      {.id = "1",
       .name = "warped moments from light",
       .reference = "ours, after Lauritzen & McCool 2008 (not in shared/papers): " + what +
                    ", x = 2 z - 1 of the linear light depth z",
       .writes = {{.name = "warped-mean",
                   .caption = "filtered E[p] / exp(c+), the positive warp's mean"}},
       .shaders = {"evsm-map"}},
      {.id = "2",
       .name = "separable Gaussian",  // + " NxN"
       .reference = "Annen et al. 2007 §4.1: \"a separable Gaussian filter kernel\" (binomial "
                    "weights), horizontal then vertical, on the warped moments",
       .shaders = {"gaussian"}},
      {.id = "3",
       .name = "mip-maps",
       .reference = "Annen et al. 2007 §4.1 (\"build a mip-map\"), applied to the warped "
                    "moments as for the CSM basis",
       .shaders = {"downsample"},
       .deviations = {kDrawnMipChainDeviation}},
      {.id = "4",
       .name = negative ? "camera pass, Chebyshev on both warps" : "camera pass, Chebyshev",
       .reference = std::string("ours, after Lauritzen & McCool 2008 (not in shared/papers): "
                                "Chebyshev's bound (Donnelly & Lauritzen 2006) on ") +
                    (negative ? "each warp's moments, the smaller" : "the warp's moments"),
       .writes = cameraPassBuffers("4",
                                   "evsm_shadow.frag: Chebyshev's bound on the warped "
                                   "moments"),
       .shaders = {"evsm-test"}},
  };
}

struct EvsmSettings {
  double positiveExponent = kDefaultPositiveExponent;  // after the clamp to the format
  double negativeExponent = 0.0;                       // 0: EVSM2
  double minVariance = kDefaultMinVariance;
  double bleedReduction = kDefaultBleedReduction;
  GLenum format = GL_RGBA32F;
  int blurTaps = kDefaultBlurTaps;
  MapFiltering filtering;
};

// The --params of modern.evsm2 / evsm4, declared once (Technique::params).
ParamSpec positiveExponentParam() {
  return numberParam("positive-exponent", kDefaultPositiveExponent, kMinExponent,
                     kEvsmMaxExponentFloat32,
                     "c+ of p = exp(c+ x), x = 2 z - 1; clamped to 5.54 with storage=16 "
                     "(exp(2 c) within fp16)");
}
ParamSpec negativeExponentParam() {
  return numberParam("negative-exponent", kDefaultNegativeExponent, kMinExponent,
                     kEvsmMaxExponentFloat32,
                     "c- of n = -exp(-c- x); clamped to 5.54 with storage=16");
}
ParamSpec minVarianceParam() {
  return numberParam("min-variance", kDefaultMinVariance, 0.0, kMaxMinVariance,
                     "lower bound of the variance in (linear depth)^2, scaled by each warp's "
                     "slope at the mean");
}
ParamSpec bleedReductionParam() {
  return numberParam("bleed-reduction", kDefaultBleedReduction, 0.0, kMaxBleedReduction,
                     "a Chebyshev bound below this counts as shadow (light-bleeding reduction)");
}
ParamSpec storageParam() {
  return choiceParam("storage", "float", {"16", "float"},
                     "moment texture format: 16 or 32-bit float (the exponents are clamped to "
                     "it)");
}

EvsmSettings parseSettings(const GlContext& context, const RenderParams& params, bool negative) {
  EvsmSettings s;
  const bool half = params.text(storageParam()) == "16";
  s.format = half ? GL_RGBA16F : GL_RGBA32F;
  s.positiveExponent = evsmEffectiveExponent(params.number(positiveExponentParam()), half);
  if (negative)
    s.negativeExponent = evsmEffectiveExponent(params.number(negativeExponentParam()), half);
  s.minVariance = params.number(minVarianceParam());
  s.bleedReduction = params.number(bleedReductionParam());
  s.blurTaps = parseBlurTaps(params, blurParam(kDefaultBlurTaps));
  s.filtering = parseFiltering(context, params);
  return s;
}

// Pass 1: the moments of the warped linear light depth; no caster = depth 1 (x = 1).
LayeredMap renderWarpedMomentsFromLight(Passes& passes, const GpuScene& gpu,
                                        const RenderParams& params, const EvsmSettings& s) {
  LayeredMap map;
  passes.run("1", [&] {
    const float p = float(std::exp(s.positiveExponent)), n = -float(std::exp(-s.negativeExponent));
    const float far[4] = {p, p * p, n, n * n};
    map = renderWarpedDepthFromLight(gpu, params, s.format, s.filtering.mipmaps,
                                     "evsm_map.frag.glsl", far, [&](const Program& program) {
                                       program.set("uPositiveExponent", float(s.positiveExponent));
                                       program.set("uNegativeExponent", float(s.negativeExponent));
                                     });
  });
  return map;
}

// Pass 2: the same separable Gaussian as modern.csm, on the warped moments.
void blurWarpedMoments(Passes& passes, const LayeredMap& map, const EvsmSettings& s) {
  if (s.blurTaps == 0) return;
  const std::string taps = std::to_string(s.blurTaps);
  passes.run(
      "2", [&] { blurLayers(map, s.blurTaps); }, {}, " " + taps + "x" + taps);
}

// Pass 3: mip-maps and filtering state.
void buildWarpedMomentMipmaps(Passes& passes, const LayeredMap& map, const EvsmSettings& s) {
  passes.run("3", [&] { buildMipmapsAndSetFiltering(map, s.filtering); });
}

// Pass 4: Chebyshev's bound on each warp in the camera view, the smaller one.
void chebyshevOnEachWarp(Passes& passes, const GpuScene& gpu, const RenderParams& params,
                         const LayeredMap& map, const EvsmSettings& s) {
  passes.run("4", [&] {
    shadeWithFilteredMap(
        gpu, params, map, "evsm_shadow.frag.glsl",
        [&](const Program& program) {
          program.set("uPositiveExponent", float(s.positiveExponent));
          program.set("uNegativeExponent", float(s.negativeExponent));
          program.set("uUseNegative", s.negativeExponent > 0.0 ? 1 : 0);
          program.set("uMinVariance", float(s.minVariance));
          program.set("uBleedReduction", float(s.bleedReduction));
        },
        passes.frame());
  });
}

Frame renderEvsm(GlContext& context, const Scene& scene, const RenderParams& params,
                 const PassTable& table, bool negative) {
  const EvsmSettings s = parseSettings(context, params, negative);
  Frame frame;
  Passes passes(frame, params, table);
  GpuScene gpu(scene);
  const LayeredMap map = renderWarpedMomentsFromLight(passes, gpu, params, s);
  blurWarpedMoments(passes, map, s);
  passes.capture("1", "warped-mean", [&] {
    // E[p] / exp(c+) = E[exp(c+ (x - 1))], in (0, 1]: 1 where no caster is.
    return channel(readLayer(map, 0, float(std::exp(-s.positiveExponent)), 0.0f), 0);
  });
  buildWarpedMomentMipmaps(passes, map, s);
  chebyshevOnEachWarp(passes, gpu, params, map, s);
  captureCameraPass(passes, "4");
  frame.counters["anisotropy"] = s.filtering.anisotropy;
  frame.counters["positive_exponent"] = s.positiveExponent;
  if (negative) frame.counters["negative_exponent"] = s.negativeExponent;
  return frame;
}

Technique evsmTechnique(bool negative) {
  Technique t;
  t.name = negative ? "modern.evsm4" : "modern.evsm2";
  t.paper =
      "ours, after Lauritzen & McCool 2008, exponential variance shadow maps (not in "
      "shared/papers)";
  t.summary = negative ? "moments of positive and negative exponential warps, min of two "
                         "Chebyshev bounds; little bleeding"
                       : "moments of a positive exponential warp of depth, Chebyshev bound; "
                         "less bleeding than VSM";
  t.status = "complete";
  t.needs.profile = Profile::kCore;
  t.params = {positiveExponentParam()};
  if (negative) t.params.push_back(negativeExponentParam());
  for (ParamSpec p : {minVarianceParam(), bleedReductionParam(), storageParam(),
                      blurParam(kDefaultBlurTaps), filteringParam(), anisotropyParam()})
    t.params.push_back(std::move(p));
  t.reads = {.shadowMap = true};
  t.edge = Technique::Edge::kFiltered;  // blurred, mip-mapped warped moments
  t.plan.prefilter = PlanTraits::Prefilter::kVariance;
  t.passes = evsmPasses(negative);
  t.render = [table = t.passes, negative](GlContext& context, const Scene& scene,
                                          const RenderParams& params) {
    return renderEvsm(context, scene, params, table, negative);
  };
  return t;
}
}  // namespace

Technique evsm2Technique() { return evsmTechnique(false); }
Technique evsm4Technique() { return evsmTechnique(true); }

}  // namespace sl::modern
