// modern.vsm — Variance Shadow Maps. Donnelly W., Lauritzen A.: "Variance Shadow Maps",
// Symposium on Interactive 3D Graphics and Games 2006 — as Annen et al. 2007 compare against
// it (§2: "a statistical upper bound ... noticeable artifacts (light leaking)", Fig. 9).
// The filtering (blur, mip-maps, anisotropy) is the same as modern.csm's, so the two differ
// only in what the map stores and how the shadow test is reconstructed.
//
// Passes:
//   1. renderMomentsFromLight — (d, d^2) of linear light depth into an RG float layer
//   2. blurMoments            — separable Gaussian 3x3 / 5x5 / 7x7 (as Annen §4.1), optional
//   3. buildMomentMipmaps     — mip-maps, tri-linear + anisotropic filtering
//   4. chebyshevInCameraPass  — p_max = s^2 / (s^2 + (d - mu)^2) with a minimum variance and
//                               optional light-bleeding reduction; vsm_shadow.frag
// The passes are declared once in vsmPasses().
#include "modern/variance_shadow_map.h"

#include "core/base/errors.h"
#include "core/technique/pass_capture.h"
#include "core/technique/passes.h"
#include "modern/camera_pass.h"
#include "modern/prefiltered_maps.h"

namespace sl::modern {
using namespace sl::gl;

namespace {
constexpr double kDefaultMinVariance = 1e-5;  // (linear depth)^2: ~ (0.3% of the range)^2
constexpr double kMaxMinVariance = 0.25;      // the largest variance of values in [0, 1]
constexpr double kDefaultBleedReduction = 0.0;
constexpr double kMaxBleedReduction = 0.99;  // 1 would divide by zero
constexpr int kDefaultBlurTaps = 3;          // same default as modern.csm

// The passes, declared once: names, sources, the buffers a dump shows, shaders, deviations.
PassTable vsmPasses() {
  return {
      {.id = "1",
       .name = "moments from light",
       .reference = "Donnelly & Lauritzen 2006 (not in shared/papers), as Annen et al. 2007 §2 "
                    "describe it: the moments (d, d^2) of the linear light depth",
       .writes = {{.name = "moments-mean", .caption = "filtered mean depth E[z]"}},
       .shaders = {"moments"}},
      {.id = "2",
       .name = "separable Gaussian",  // + " NxN"
       .reference = "Annen et al. 2007 §4.1: \"a separable Gaussian filter kernel\" (binomial "
                    "weights), horizontal then vertical",
       .shaders = {"gaussian"}},
      {.id = "3",
       .name = "mip-maps",
       .reference = "Annen et al. 2007 §4.1 (\"build a mip-map\"), applied to the moments as for "
                    "the CSM basis (the comparison of Fig. 9)",
       .shaders = {"downsample"},
       .deviations = {kDrawnMipChainDeviation}},
      {.id = "4",
       .name = "camera pass, Chebyshev bound",
       .reference = "Donnelly & Lauritzen 2006: Chebyshev's one-tailed bound from the filtered "
                    "moments; its light leaking: Annen et al. 2007 §2, Fig. 9(a)",
       .writes =
           cameraPassBuffers("4", "vsm_shadow.frag: Chebyshev's bound on the filtered moments"),
       .shaders = {"chebyshev"}},
  };
}

const PassTable& passTable() {
  static const PassTable table = vsmPasses();
  return table;
}

struct VsmSettings {
  double minVariance = kDefaultMinVariance;
  double bleedReduction = kDefaultBleedReduction;
  GLenum format = GL_RGBA32F;
  int blurTaps = kDefaultBlurTaps;
  MapFiltering filtering;
};

// The --params of modern.vsm, declared once (Technique::params).
ParamSpec minVarianceParam() {
  return numberParam(
      "min-variance", kDefaultMinVariance, 0.0, kMaxMinVariance,
      "lower bound of the variance, (linear depth)^2 (ours, after Donnelly & Lauritzen 2006)");
}
ParamSpec bleedReductionParam() {
  return numberParam("bleed-reduction", kDefaultBleedReduction, 0.0, kMaxBleedReduction,
                     "Chebyshev bound below this counts as shadow (light-bleeding reduction)");
}
ParamSpec storageParam() {
  // 8-bit moments cannot hold d^2 - d^2 differences: VSM needs float storage.
  return choiceParam("storage", "float", {"16", "float"},
                     "moment texture format: 16 or 32-bit float");
}

VsmSettings parseSettings(const GlContext& context, const RenderParams& params) {
  VsmSettings s;
  s.minVariance = params.number(minVarianceParam());
  s.bleedReduction = params.number(bleedReductionParam());
  s.format = params.text(storageParam()) == "16" ? GL_RGBA16F : GL_RGBA32F;
  s.blurTaps = parseBlurTaps(params, blurParam(kDefaultBlurTaps));
  s.filtering = parseFiltering(context, params);
  return s;
}

// Pass 1: the first two moments of the linear light depth.
LayeredMap renderMomentsFromLight(Passes& passes, const GpuScene& gpu, const RenderParams& params,
                                  const VsmSettings& s) {
  LayeredMap moments;
  passes.run("1", [&] {
    const int n = params.shadowMapTexels;
    moments = makeLayeredMap(n, 1, s.format, s.filtering.mipmaps);
    const Framebuffer fbo = makeFramebuffer();
    attachLayers(fbo, moments, 0, 1);
    const Renderbuffer depth = makeRenderbuffer();
    glBindRenderbuffer(GL_RENDERBUFFER, depth.id());
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, n, n);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth.id());
    const float far[4] = {1, 1, 0, 1};  // no blocker: depth 1, depth^2 1
    glClearBufferfv(GL_COLOR, 0, far);
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    const Program& program = cachedProgram("scene.vert.glsl", "vsm_moments.frag.glsl");
    program.use();
    program.set("uViewProjection", lightProjection(gpu.scene()) * lightView(gpu.scene().light));
    setLinearDepthUniforms(program, gpu.scene());
    gpu.draw([](const Object& o) { return o.castsShadow; },
             [&](const Object& o) { program.set("uModel", o.model); });
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  });
  return moments;
}

// Pass 2: the same separable Gaussian as modern.csm.
void blurMoments(Passes& passes, const LayeredMap& moments, const VsmSettings& s) {
  if (s.blurTaps == 0) return;
  const std::string taps = std::to_string(s.blurTaps);
  passes.run(
      "2", [&] { blurLayers(moments, s.blurTaps); }, {}, " " + taps + "x" + taps);
}

// Pass 3: mip-maps and filtering state.
void buildMomentMipmaps(Passes& passes, const LayeredMap& moments, const VsmSettings& s) {
  passes.run("3", [&] { buildMipmapsAndSetFiltering(moments, s.filtering); });
}

// Pass 4: Chebyshev's one-tailed inequality in the camera view.
void chebyshevInCameraPass(Passes& passes, const GpuScene& gpu, const RenderParams& params,
                           const LayeredMap& moments, const VsmSettings& s) {
  passes.run("4", [&] {
    const Scene& scene = gpu.scene();
    RenderTarget target = makeCameraTarget(params, true);
    clearCameraTarget(target);
    glEnable(GL_DEPTH_TEST);
    const Program& program = cachedProgram("scene.vert.glsl", "vsm_shadow.frag.glsl");
    program.use();
    program.set("uViewProjection", cameraViewProjection(scene, params));
    program.set("uWorldToShadowMap", worldToShadowMap(scene));
    setLinearDepthUniforms(program, scene);
    program.set("uMinVariance", float(s.minVariance));
    program.set("uBleedReduction", float(s.bleedReduction));
    setLightingUniforms(program, scene);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D_ARRAY, moments.texture.id());
    program.set("uMoments", 0);
    gpu.draw([](const Object&) { return true; },
             [&](const Object& o) { setObjectUniforms(program, o); });
    readCameraTarget(target, passes.frame());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  });
}

Frame render(GlContext& context, const Scene& scene, const RenderParams& params) {
  const VsmSettings s = parseSettings(context, params);
  Frame frame;
  Passes passes(frame, params, passTable());
  GpuScene gpu(scene);
  const LayeredMap moments = renderMomentsFromLight(passes, gpu, params, s);
  blurMoments(passes, moments, s);
  passes.capture("1", "moments-mean",
                 [&] { return channel(readLayer(moments, 0, 1.0f, 0.0f), 0); });
  buildMomentMipmaps(passes, moments, s);
  chebyshevInCameraPass(passes, gpu, params, moments, s);
  captureCameraPass(passes, "4");
  frame.counters["anisotropy"] = s.filtering.anisotropy;
  return frame;
}
}  // namespace

Technique varianceShadowMapTechnique() {
  Technique t;
  t.name = "modern.vsm";
  t.paper = "Donnelly & Lauritzen 2006, Variance Shadow Maps (Annen et al. 2007's comparison)";
  t.summary = "moments (d, d^2) blurred and mip-mapped, Chebyshev upper bound; leaks light";
  t.status = "complete";
  t.needs.profile = Profile::kCore;
  t.params = {minVarianceParam(),          bleedReductionParam(), storageParam(),
              blurParam(kDefaultBlurTaps), filteringParam(),      anisotropyParam()};
  t.reads = {.shadowMap = true};
  t.edge = Technique::Edge::kFiltered;  // blurred, mip-mapped moments
  t.plan.prefilter = PlanTraits::Prefilter::kVariance;
  t.passes = passTable();
  t.render = render;
  return t;
}

}  // namespace sl::modern
