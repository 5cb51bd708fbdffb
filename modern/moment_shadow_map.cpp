// modern.msm — Moment Shadow Maps with the Hamburger 4-moment reconstruction: ours, after
// Peters C., Klein R.: "Moment Shadow Mapping", ACM Symposium on Interactive 3D Graphics and
// Games (I3D) 2015 (not in shared/papers; nothing here quotes it). The map stores the moments
// (z, z^2, z^3, z^4) of the linear light depth, through an affine quantisation in 16-bit storage;
// blurred and mip-mapped as modern.vsm's, it holds their means over the footprint, and the camera
// pass takes the sharpest lower bound on the shadow that four moments allow (the weight in front
// of the receiver of a 3-point distribution with the same moments). It bleeds far less than VSM
// at the price of a Cholesky solve and a quadratic per pixel.
//
// Passes:
//   1. renderMomentsFromLight   — (z, z^2, z^3, z^4), quantised in 16-bit storage; RGBA layer
//   2. blurMoments              — separable Gaussian 3x3 / 5x5 / 7x7 (as Annen 2007 §4.1)
//   3. buildMomentMipmaps       — mip-maps, tri-linear + anisotropic filtering
//   4. hamburgerInCameraPass    — bias, Cholesky, quadratic, 3-point shadow intensity;
//                                 msm_shadow.frag
// The passes are declared once in msmPasses().
#include "modern/moment_shadow_map.h"

#include <glm/glm.hpp>

#include "core/base/errors.h"
#include "core/technique/pass_capture.h"
#include "core/technique/passes.h"
#include "modern/camera_pass.h"
#include "modern/filtered_map_passes.h"
#include "modern/prefiltered_maps.h"

namespace sl::modern {
using namespace sl::gl;

namespace {
constexpr double kMaxMomentBias = 0.5;  // beyond it the bias, not the map, decides
constexpr int kDefaultBlurTaps = 3;     // same default as modern.csm and modern.vsm

PassTable msmPasses() {
  return {
      {.id = "1",
       .name = "four moments from light",
       .reference = "ours, after Peters & Klein 2015 (not in shared/papers): the moments "
                    "(z, z^2, z^3, z^4) of the linear light depth z, in 16-bit storage through "
                    "their optimised quantisation",
       .writes = {{.name = "moments-mean", .caption = "filtered mean depth E[z]"}},
       .shaders = {"msm-map"}},
      {.id = "2",
       .name = "separable Gaussian",  // + " NxN"
       .reference = "Annen et al. 2007 §4.1: \"a separable Gaussian filter kernel\" (binomial "
                    "weights), horizontal then vertical, on the four moments",
       .shaders = {"gaussian"}},
      {.id = "3",
       .name = "mip-maps",
       .reference = "Annen et al. 2007 §4.1 (\"build a mip-map\"), applied to the four moments "
                    "as for the CSM basis",
       .shaders = {"downsample"},
       .deviations = {kDrawnMipChainDeviation}},
      {.id = "4",
       .name = "camera pass, Hamburger 4-moment reconstruction",
       .reference = "ours, after Peters & Klein 2015 (not in shared/papers): moment bias, "
                    "Cholesky solve, quadratic roots, 3-point shadow intensity",
       .writes = cameraPassBuffers("4",
                                   "msm_shadow.frag: the Hamburger reconstruction from "
                                   "the filtered moments"),
       .shaders = {"msm-test"},
       .deviations = {"DEVIATION (Peters & Klein 2015, not in shared/papers; public "
                      "implementations bias towards (1/2, 1/2, 1/2, 1/2)): the moment bias "
                      "points to (1/2, 1/3, 1/4, 1/5), the moments of depths uniform on [0, 1], "
                      "whose Hankel matrix is positive definite; towards the moments of depths 0 "
                      "and 1 a footprint of the empty map (depth 1) stays singular and the "
                      "Cholesky solve divides 0 by 0"}},
  };
}

const PassTable& passTable() {
  static const PassTable table = msmPasses();
  return table;
}

struct MsmSettings {
  double momentBias = kMsmDefaultMomentBias;
  bool quantize = true;  // 16-bit storage through the optimised quantisation
  GLenum format = GL_RGBA16;
  int blurTaps = kDefaultBlurTaps;
  MapFiltering filtering;
};

// The --params of modern.msm, declared once (Technique::params).
ParamSpec momentBiasParam() {
  return numberParam("moment-bias", kMsmDefaultMomentBias, 0.0, kMaxMomentBias,
                     "alpha of b' = (1 - alpha) b + alpha (1/2, 1/3, 1/4, 1/5), the moments of "
                     "depths uniform on [0, 1]");
}
ParamSpec storageParam() {
  return choiceParam("storage", "16", {"16", "float"},
                     "moment texture format: 16-bit unsigned normalised or 32-bit float");
}
ParamSpec quantizationParam() {
  return choiceParam("quantization", "optimized", {"optimized", "plain"},
                     "16-bit storage: Peters & Klein 2015's affine map of the moments "
                     "(optimized) or the moments as they are (plain)");
}

MsmSettings parseSettings(const GlContext& context, const RenderParams& params) {
  MsmSettings s;
  s.momentBias = params.number(momentBiasParam());
  const bool half = params.text(storageParam()) == "16";
  s.format = half ? GL_RGBA16 : GL_RGBA32F;
  s.quantize = half && params.text(quantizationParam()) == "optimized";
  s.blurTaps = parseBlurTaps(params, blurParam(kDefaultBlurTaps));
  s.filtering = parseFiltering(context, params);
  return s;
}

// The quantisation q = Q b + o as a GL matrix (column i = the coefficients of b_i) and offset.
glm::mat4 quantization() {
  glm::mat4 q(0.0f);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) q[i][j] = float(kMsmQuantization[i][j]);
  return q;
}
const glm::vec4 kOffset(float(kMsmQuantizationOffset), 0.0f, 0.0f, 0.0f);

// Pass 1: the four moments of the linear light depth; no caster = depth 1.
LayeredMap renderMomentsFromLight(Passes& passes, const GpuScene& gpu, const RenderParams& params,
                                  const MsmSettings& s) {
  LayeredMap map;
  passes.run("1", [&] {
    const glm::vec4 far = s.quantize ? quantization() * glm::vec4(1.0f) + kOffset : glm::vec4(1.0f);
    const float clear[4] = {far.x, far.y, far.z, far.w};
    map = renderWarpedDepthFromLight(gpu, params, s.format, s.filtering.mipmaps,
                                     "msm_map.frag.glsl", clear, [&](const Program& program) {
                                       program.set("uQuantize", s.quantize ? 1 : 0);
                                       program.set("uQuantization", quantization());
                                       program.set("uQuantizationOffset", kOffset);
                                     });
  });
  return map;
}

// Pass 2: the same separable Gaussian as modern.csm, on the four moments.
void blurMoments(Passes& passes, const LayeredMap& map, const MsmSettings& s) {
  if (s.blurTaps == 0) return;
  const std::string taps = std::to_string(s.blurTaps);
  passes.run(
      "2", [&] { blurLayers(map, s.blurTaps); }, {}, " " + taps + "x" + taps);
}

// Pass 3: mip-maps and filtering state.
void buildMomentMipmaps(Passes& passes, const LayeredMap& map, const MsmSettings& s) {
  passes.run("3", [&] { buildMipmapsAndSetFiltering(map, s.filtering); });
}

// Pass 4: the Hamburger 4-moment reconstruction in the camera view.
void hamburgerInCameraPass(Passes& passes, const GpuScene& gpu, const RenderParams& params,
                           const LayeredMap& map, const MsmSettings& s) {
  passes.run("4", [&] {
    shadeWithFilteredMap(
        gpu, params, map, "msm_shadow.frag.glsl",
        [&](const Program& program) {
          program.set("uQuantize", s.quantize ? 1 : 0);
          program.set("uDequantization", glm::inverse(quantization()));
          program.set("uQuantizationOffset", kOffset);
          program.set("uMomentBias", float(s.momentBias));
        },
        passes.frame());
  });
}

Frame render(GlContext& context, const Scene& scene, const RenderParams& params) {
  const MsmSettings s = parseSettings(context, params);
  Frame frame;
  Passes passes(frame, params, passTable());
  GpuScene gpu(scene);
  const LayeredMap map = renderMomentsFromLight(passes, gpu, params, s);
  blurMoments(passes, map, s);
  passes.capture("1", "moments-mean", [&] {
    if (!s.quantize) return channel(readLayer(map, 0, 1.0f, 0.0f), 0);
    // E[z] from the stored q: the first row of the inverse quantisation.
    const Image raw = readLayer(map, 0, 1.0f, 0.0f);  // UNORM: already in [0, 1]
    const glm::mat4 inverse = glm::inverse(quantization());
    Image mean(raw.width, raw.height, 1);
    for (int y = 0; y < raw.height; ++y)
      for (int x = 0; x < raw.width; ++x) {
        const glm::vec4 q(raw.at(x, y, 0), raw.at(x, y, 1), raw.at(x, y, 2), raw.at(x, y, 3));
        mean.at(x, y) = std::clamp((inverse * (q - kOffset)).x, 0.0f, 1.0f);
      }
    return mean;
  });
  buildMomentMipmaps(passes, map, s);
  hamburgerInCameraPass(passes, gpu, params, map, s);
  captureCameraPass(passes, "4");
  frame.counters["anisotropy"] = s.filtering.anisotropy;
  return frame;
}
}  // namespace

Technique momentShadowMapTechnique() {
  Technique t;
  t.name = "modern.msm";
  t.paper = "ours, after Peters & Klein 2015, Moment Shadow Mapping (not in shared/papers)";
  t.summary =
      "four moments of depth blurred and mip-mapped, Hamburger 4-moment reconstruction; "
      "little bleeding";
  t.status = "complete";
  t.needs.profile = Profile::kCore;
  t.params = {momentBiasParam(),           storageParam(),   quantizationParam(),
              blurParam(kDefaultBlurTaps), filteringParam(), anisotropyParam()};
  t.reads = {.shadowMap = true};
  t.edge = Technique::Edge::kFiltered;  // blurred, mip-mapped moments
  t.plan.prefilter = PlanTraits::Prefilter::kVariance;
  t.passes = passTable();
  t.render = render;
  return t;
}

}  // namespace sl::modern
