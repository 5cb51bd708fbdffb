// modern.csm — Convolution Shadow Maps. Annen T., Mertens T., Bekaert P., Seidel H.-P.,
// Kautz J.: "Convolution Shadow Maps", Eurographics Symposium on Rendering 2007.
//
// The binary shadow test f(d, z) (Eq. 1) is expanded in a truncated Fourier series (Eq. 10-14)
// whose terms are separable in d and z, so that the basis images sin(c_k z(p)), cos(c_k z(p))
// can be filtered like any texture (Eq. 8) before the test is reconstructed per pixel.
//
// Passes:
//   1. renderLinearDepthFromLight — linear light-space depth z(p) into an R32F map (§4.1)
//   2. computeBasisTextures       — sin(c_k z), cos(c_k z), k = 1..M, packed four per RGBA
//                                   layer, written several layers at a time with MRT (§4.1)
//   3. blurBasisTextures          — separable Gaussian 3x3 / 5x5 / 7x7 (§4.1), optional
//   4. buildBasisMipmaps          — mip-maps, tri-linear + anisotropic filtering (§4, Table 1)
//   5. reconstructInCameraPass    — Eq. 13 with attenuation (§3.2.1), offset and scale
//                                   (§3.2.2), clamp to [0, 1] (§4.1); csm_shadow.frag
#include "modern/convolution_shadow_map.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/errors.h"
#include "core/pass_capture.h"
#include "core/plan.h"
#include "modern/camera_pass.h"
#include "modern/prefiltered_maps.h"

namespace sl::modern {
using namespace sl::gl;

namespace {
constexpr int kDefaultOrder = 16;      // M of Fig. 4, 5 (Table 1 also measures 4 and 8)
constexpr int kMaxOrder = 64;          // 32 RGBA layers
constexpr double kDefaultAlpha = 1.0;  // §3.2.1; removes most of the Gibbs overshoot
constexpr double kMaxAlpha = 50.0;
constexpr double kMaxOffset = 0.5;  // in linear depth units (the whole range is 1)
constexpr double kMaxScale = 8.0;
constexpr int kDefaultBlurTaps = 3;                        // 3x3 (Table 1's middle block)
constexpr int kChannelsPerLayer = 4;                       // RGBA
constexpr double kMaxMapBytes = 2.0 * 1024 * 1024 * 1024;  // refuse maps above 2 GiB
constexpr int kOffsetSearchSteps = 20000;  // resolution of the default-offset search on (0, 1]
const char* const kWorkspaceKey = "modern.csm.workspace";  // GL objects kept between frames

struct CsmSettings {
  int order = kDefaultOrder;  // M
  double alpha = kDefaultAlpha;
  double offset = 0.0;         // subtracted from d (§3.2.2)
  double scale = 1.0;          // multiplies f (§3.2.2)
  GLenum format = GL_RGBA8;    // storage of the basis layers
  bool encodeUnsigned = true;  // 8-bit: [-1, 1] stored as 0.5 + 0.5 v
  int blurTaps = kDefaultBlurTaps;
  MapFiltering filtering;
  bool mipmapsSkipped = false;  // mipmaps=auto and the view does not minify the map
  int sinLayers() const { return (order + kChannelsPerLayer - 1) / kChannelsPerLayer; }
  int layers() const { return 2 * sinLayers(); }
  // Linear depth is stored scaled by 1 - offset, so that t = z - d + offset stays inside one
  // period (-1, 1] of the square wave S(t) of Eq. 10 for every z, d in the map.
  float depthScale() const { return float(1.0 - offset); }
};

// The --params of modern.csm, declared once (Technique::params).
ParamSpec orderParam() {
  return integerParam("order", kDefaultOrder, 1, kMaxOrder,
                      "M, the number of Fourier terms of the expansion (Eq. 10; Table 1: 4, 8, 16)");
}
ParamSpec alphaParam() {
  return numberParam("alpha", kDefaultAlpha, 0.0, kMaxAlpha,
                     "attenuation of the high frequencies, against ringing (§3.2.1)");
}
ParamSpec offsetParam() {
  return autoNumberParam("offset", 0.0, kMaxOffset,
                         "depth offset subtracted from d (§3.2.2); auto = the top of the "
                         "reconstructed step");
}
constexpr const char* kOffsetRuleTop = "top";
constexpr const char* kOffsetRuleThroughOne = "through-1";
ParamSpec offsetRuleParam() {
  return choiceParam("offset-rule", kOffsetRuleTop, {kOffsetRuleTop, kOffsetRuleThroughOne},
                     "what offset=auto derives: top = the top of the reconstructed step; "
                     "through-1 = where the step first reaches 1 (§3.2.2: \"f(d, z) goes through "
                     "1\"; Figs. 6, 7)");
}
ParamSpec scaleParam() {
  return autoNumberParam("scale", 1.0, kMaxScale,
                         "scale of the reconstruction (§3.2.2); auto = lit surfaces reach 1");
}
ParamSpec storageParam() {
  return choiceParam("storage", "8", {"8", "16", "float"},
                     "basis texture format: 8-bit (the paper's), 16 or 32-bit float");
}
ParamSpec mipmapsParam() {
  return choiceParam("mipmaps", "auto", {"auto", "always"},
                     "build the mip chain only where the view minifies the map (auto) or always");
}

CsmSettings parseSettings(const GlContext& context, double texelsPerPixel,
                          const RenderParams& params) {
  CsmSettings s;
  s.order = params.integer(orderParam());
  s.alpha = params.number(alphaParam());
  // "auto" (or no value) = derived by offset-rule: the top of the reconstructed step
  // (csmDefaultOffset) or where it first reaches 1 (csmOffsetThroughOne, §3.2.2's wording).
  const bool throughOne = params.text(offsetRuleParam()) == kOffsetRuleThroughOne;
  s.offset = params.numberOrAuto(offsetParam())
                 .value_or(throughOne ? csmOffsetThroughOne(s.order, s.alpha)
                                      : csmDefaultOffset(s.order, s.alpha));
  // "auto" (or no value): 1 / f(offset) where the attenuated step tops out below 1 (small M
  // with alpha > 0: M = 1, alpha = 1 peaks at 0.73), so that lit surfaces are lit (§3.2.2:
  // "after offsetting, f goes through 1"); 1 otherwise. §3.2.2's own alternative is 2.
  s.scale = params.numberOrAuto(scaleParam())
                .value_or(std::max(1.0, 1.0 / csmReconstructedStep(s.offset, s.order, s.alpha)));
  const std::string storage = params.text(storageParam());
  s.format = storage == "8" ? GL_RGBA8 : storage == "16" ? GL_RGBA16F : GL_RGBA32F;
  s.encodeUnsigned = storage == "8";
  s.blurTaps = parseBlurTaps(params, blurParam(kDefaultBlurTaps));
  s.filtering = parseFiltering(context, params);
  // DEVIATION (Annen et al. 2007, §4.1: "we then build a mip-map of this texture"): with
  // mipmaps=auto (the default) the chain is built only when the planner finds that the view
  // minifies the map (core/plan.h, more than one shadow-map texel per pixel at the 95th
  // percentile of the receivers' pixels). Where no pixel minifies, GL samples level 0 with the
  // magnification filter (lambda <= 0, glspec §3.8.8) and the chain is never read, so leaving
  // it out changes nothing but the time (on llvmpipe the mip chain of M/2 layers is a
  // large share of the frame). mipmaps=always builds it regardless.
  const std::string mipmaps = params.text(mipmapsParam());
  if (s.filtering.mipmaps && mipmaps == "auto" && texelsPerPixel <= 1.0) {
    s.filtering.mipmaps = false;
    s.filtering.anisotropy = 1.0f;  // anisotropic filtering refines the mip footprint only
    s.mipmapsSkipped = true;
  }
  const double bytesPerTexel = storage == "8" ? 4 : storage == "16" ? 8 : 16;
  const double bytes = double(params.shadowMapTexels) * params.shadowMapTexels * s.layers() *
                       bytesPerTexel * (s.filtering.mipmaps ? 4.0 / 3.0 : 1.0);
  if (bytes > kMaxMapBytes)
    throw InputError("modern.csm: M=" + std::to_string(s.order) + " at " +
                     std::to_string(params.shadowMapTexels) + "^2 with storage=" + storage +
                     " needs " + std::to_string(int(bytes / (1024 * 1024))) +
                     " MiB of basis textures (limit 2048 MiB)");
  return s;
}

// exp(-alpha (k/M)^2) (2 / c_k), k = 1..M (§3.2.1, Eq. 14), zero-padded to kMaxOrder: the
// camera pass's per-term weights.
std::vector<float> termWeights(const CsmSettings& s) {
  std::vector<float> w(size_t(kMaxOrder), 0.0f);
  for (int k = 1; k <= s.order; ++k) {
    const double ck = std::numbers::pi * (2.0 * k - 1.0);
    const double ratio = double(k) / s.order;
    w[size_t(k - 1)] = float(std::exp(-s.alpha * ratio * ratio) * 2.0 / ck);
  }
  return w;
}

// Pass 1 (§4.1): linear depth from the light ("we use linear depth values [BAS03]"), over the
// depth range fitted to the casters and receivers (Fig. 6: "a tightly fitted light frustum").
const RenderTarget& renderLinearDepthFromLight(const GpuScene& gpu, const RenderParams& params,
                                               const CsmSettings& s, const DepthRange& range,
                                               PrefilterWorkspace& work, Frame& frame) {
  PassTimer timer(frame, "1 linear depth from light",
                  "Annen et al. 2007 §4.1: \"rendering the depth values from the light's point "
                  "of view\", linear depth [BAS03]");
  timer.shaderPasses({"linear-depth"});
  const int n = params.shadowMapTexels;
  if (work.depth.width != n || work.depth.color.empty())
    work.depth = makeRenderTarget(n, n, {GL_R32F}, true, GL_DEPTH_COMPONENT24);
  const RenderTarget& map = work.depth;
  map.bind();
  glViewport(0, 0, n, n);
  const float far[4] = {s.depthScale(), 0, 0, 1};  // no blocker: the far end of the range
  glClearBufferfv(GL_COLOR, 0, far);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  const Program& program = cachedProgram("scene.vert.glsl", "light_linear_depth.frag.glsl");
  program.use();
  program.set("uViewProjection", lightProjection(gpu.scene()) * lightView(gpu.scene().light));
  setLinearDepthUniforms(program, gpu.scene(), range);
  program.set("uDepthScale", s.depthScale());
  gpu.draw([](const Object& o) { return o.castsShadow; },
           [&](const Object& o) { program.set("uModel", o.model); });
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return map;
}

// Pass 2 (§4.1, Eq. 14): the basis images B_i(z(p)), as many layers per pass as the
// context has draw buffers ("with four MRTs only two additional render passes"). With a blur,
// this pass also applies its horizontal half (pass 3): the basis of the kernel's row of depth
// texels, weighted, so that the unblurred layers are neither stored nor read back.
// DEVIATION (Annen et al. 2007, §4.1 stores the basis, then blurs it): the same sums in another
// order, one write and one read of M/2 layers fewer; with 8-bit storage the basis is no
// longer rounded to 8 bits before the horizontal weights (one rounding fewer, closer to Eq. 8).
const LayeredMap& computeBasisTextures(const RenderTarget& depth, const CsmSettings& s,
                                       PrefilterWorkspace& work, Frame& frame) {
  PassTimer timer(
      frame,
      s.blurTaps > 0 ? "2 basis textures + horizontal Gaussian (MRT)" : "2 basis textures (MRT)",
      "Annen et al. 2007 §4.1: the basis B_i(z) = sin(c_k z), cos(c_k z) of Eq. 14 "
      "(Eq. 7) into textures (Fig. 5); the Gaussian's first direction (DEVIATION)");
  timer.shaderPasses({"basis"});
  const LayeredMap& basis =
      reuseLayeredMap(work.map, depth.width, s.layers(), s.format, s.filtering.mipmaps);
  // Blurred: the horizontal pass's output goes to the scratch map, the vertical one to `basis`.
  const LayeredMap& target =
      s.blurTaps > 0 ? reuseLayeredMap(work.scratch, depth.width, s.layers(), s.format, false)
                     : basis;
  const int taps = std::max(s.blurTaps, 1);
  const std::vector<float> weights = binomialWeights(taps);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, depth.color[0].id());
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  if (work.fbo.id() == 0) work.fbo = makeFramebuffer();
  const FullScreenTriangle triangle;
  const int perPass = layersPerPass();
  int passes = 0;
  for (int first = 0; first < basis.layers; first += perPass, ++passes) {
    const int count = std::min(perPass, basis.layers - first);
    // One program per (taps, outputs): constant loop bounds (the shader's header).
    const bool paired = first == 0 && count == basis.layers;  // all sines and cosines
    const Program& program = cachedProgram("fullscreen.vert.glsl", "csm_basis.frag.glsl",
                                           {{"TAPS", std::to_string(taps)},
                                            {"LAYERS", std::to_string(count)},
                                            {"PAIRED", paired ? "1" : "0"}});
    program.use();
    program.set("uLinearDepth", 0);
    program.set("uOrder", s.order);
    program.set("uSinLayers", s.sinLayers());
    program.set("uEncodeUnsigned", s.encodeUnsigned ? 1 : 0);
    glUniform1fv(program.uniform("uWeights"), GLsizei(weights.size()), weights.data());
    attachLayers(work.fbo, target, first, count);
    program.set("uFirstLayer", first);
    triangle.draw();
  }
  frame.counters["basis render passes"] = passes;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return basis;
}

// Pass 3 (§4.1): "a separable Gaussian filter kernel on the textures": the vertical half (the
// horizontal one was applied with the basis, pass 2).
void blurBasisTextures(const LayeredMap& basis, const CsmSettings& s, PrefilterWorkspace& work,
                       Frame& frame) {
  if (s.blurTaps == 0) return;
  PassTimer timer(
      frame, "3 vertical Gaussian " + std::to_string(s.blurTaps) + "x" + std::to_string(s.blurTaps),
      "Annen et al. 2007 §4.1: the separable Gaussian's second direction");
  timer.shaderPasses({"gaussian"});
  blurLayersOneDirection(work.scratch, basis, s.blurTaps, BlurDirection::kVertical, work.fbo);
}

// Pass 4 (§4.1): "we then build a mip-map of this texture" and switch on tri-linear (and
// anisotropic) filtering: "no shader magic is needed".
void buildBasisMipmaps(const LayeredMap& basis, const CsmSettings& s, Frame& frame) {
  PassTimer timer(frame, s.filtering.mipmaps ? "4 mip-maps" : "4 sampling state (no mip-maps)",
                  "Annen et al. 2007 §4.1: \"build a mip-map\" of the basis, trilinear or "
                  "anisotropic filtering (Figs. 7, 10)");
  timer.shaderPasses({"downsample"});
  buildMipmapsAndSetFiltering(basis, s.filtering);
}

// Pass 5 (Eq. 13, §3.2, §4.1): the camera view with the reconstructed, filtered shadow test.
void reconstructInCameraPass(const GpuScene& gpu, const RenderParams& params,
                             const LayeredMap& basis, const CsmSettings& s, const DepthRange& range,
                             float nearestCaster, Frame& frame) {
  PassTimer timer(frame, "5 camera pass, Eq. 13 reconstruction",
                  "Annen et al. 2007 §3.1 Eq. 13 with the coefficients of Eq. 14, offset and "
                  "scale of §3.2.2 (Fig. 3), clamped (§4.1)");
  timer.shaderPasses({"reconstruct", "csm-test"});
  const Scene& scene = gpu.scene();
  RenderTarget target = makeCameraTarget(params, true);
  clearCameraTarget(target);
  glEnable(GL_DEPTH_TEST);
  const Program& program = cachedProgram("scene.vert.glsl", "csm_shadow.frag.glsl");
  program.use();
  program.set("uViewProjection", cameraViewProjection(scene, params));
  program.set("uWorldToShadowMap", worldToShadowMap(scene));
  setLinearDepthUniforms(program, scene, range);
  program.set("uNearestCaster", nearestCaster);
  program.set("uDepthScale", s.depthScale());
  program.set("uOrder", s.order);
  program.set("uSinLayers", s.sinLayers());
  const std::vector<float> weights = termWeights(s);
  glUniform1fv(program.uniform("uWeights"), GLsizei(weights.size()), weights.data());
  program.set("uOffset", float(s.offset));
  program.set("uScale", float(s.scale));
  program.set("uEncodeUnsigned", s.encodeUnsigned ? 1 : 0);
  setLightingUniforms(program, scene);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D_ARRAY, basis.texture.id());
  program.set("uBasis", 0);
  gpu.draw([](const Object&) { return true; },
           [&](const Object& o) { setObjectUniforms(program, o); });
  readCameraTarget(target, frame);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
}

void capturePasses(const RenderTarget& depth, const LayeredMap& basis, const CsmSettings& s,
                   Frame& frame) {
  const Image linear = readAttachment(depth, 0);
  frame.intermediates.push_back(
      {"1-linear-depth", "linear light-space depth z(p) (§4.1)", channel(linear, 0)});
  // Fig. 5: every sine basis texture (four k per RGBA layer) and the first cosine one, the
  // stored values with [-1, 1] shown as [0, 1].
  const float scale = s.encodeUnsigned ? 1.0f : 0.5f;
  const float bias = s.encodeUnsigned ? 0.0f : 0.5f;
  auto range = [&](int layer) {
    const int first = kChannelsPerLayer * layer + 1;
    return "k" + std::to_string(first) + "-" + std::to_string(first + kChannelsPerLayer - 1);
  };
  for (int layer = 0; layer < s.sinLayers(); ++layer)
    frame.intermediates.push_back({"2-basis-sin-" + range(layer),
                                   "sin(c_k z), " + range(layer) + ", after blur (Fig. 5)",
                                   readLayer(basis, layer, scale, bias)});
  frame.intermediates.push_back({"2-basis-cos-" + range(0),
                                 "cos(c_k z), " + range(0) + ", after blur",
                                 readLayer(basis, s.sinLayers(), scale, bias)});
}

Frame render(GlContext& context, const Scene& scene, const RenderParams& params) {
  PrefilterWorkspace& work = prefilterWorkspace(context, kWorkspaceKey);
  // The fitted range and the planner's minification estimate walk every triangle: once per
  // scene and view, not once per frame.
  if (std::vector<double> key = sceneViewKey(scene, params); key != work.sceneKey) {
    work.fittedRange = csmDepthRange(scene, &work.nearestCaster);
    work.texelsPerPixel =
        planFrame(scene, convolutionShadowMapTechnique(), params).maxShadowTexelsPerPixel;
    work.sceneKey = std::move(key);
  }
  const CsmSettings s = parseSettings(context, work.texelsPerPixel, params);
  Frame frame;
  GpuScene gpu(scene);
  const DepthRange range = work.fittedRange;
  const RenderTarget& depth = renderLinearDepthFromLight(gpu, params, s, range, work, frame);
  const LayeredMap& basis = computeBasisTextures(depth, s, work, frame);
  blurBasisTextures(basis, s, work, frame);
  if (params.capturePasses) capturePasses(depth, basis, s, frame);
  buildBasisMipmaps(basis, s, frame);
  reconstructInCameraPass(gpu, params, basis, s, range, work.nearestCaster, frame);
  if (params.capturePasses) captureCameraPass(frame, 5, "csm_shadow.frag: Eq. 13 reconstruction");
  frame.counters["light near"] = range.nearPlane;
  frame.counters["light far"] = range.farPlane;
  frame.counters["order M"] = s.order;
  frame.counters["offset"] = s.offset;
  frame.counters["scale"] = s.scale;
  frame.counters["basis layers"] = s.layers();
  frame.counters["anisotropy"] = s.filtering.anisotropy;
  frame.counters["mip-maps"] = s.filtering.mipmaps ? 1 : 0;
  return frame;
}
}  // namespace

double csmReconstructedStep(double t, int order, double alpha) {
  double f = 0.5;
  for (int k = 1; k <= order; ++k) {
    const double ck = std::numbers::pi * (2.0 * k - 1.0);
    const double attenuation = std::exp(-alpha * (double(k) / order) * (double(k) / order));
    f += attenuation * (2.0 / ck) * std::sin(ck * t);
  }
  return f;
}

double csmDefaultOffset(int order, double alpha) {
  if (order < 1) throw InputError("CSM truncation order must be at least 1");
  // Walk up the step from t = 0 until it stops rising.
  double previous = csmReconstructedStep(0.0, order, alpha);
  for (int i = 1; i <= kOffsetSearchSteps; ++i) {
    const double t = double(i) / kOffsetSearchSteps;
    const double value = csmReconstructedStep(t, order, alpha);
    if (value < previous) return std::min(double(i - 1) / kOffsetSearchSteps, kMaxOffset);
    previous = value;
  }
  return kMaxOffset;
}

double csmOffsetThroughOne(int order, double alpha) {
  if (order < 1) throw InputError("CSM truncation order must be at least 1");
  const double top = csmDefaultOffset(order, alpha);
  // Walk up the step from t = 0 to its top; the first t where it reaches 1.
  for (int i = 0; i <= kOffsetSearchSteps; ++i) {
    const double t = double(i) / kOffsetSearchSteps;
    if (t >= top) break;
    if (csmReconstructedStep(t, order, alpha) >= 1.0) return t;
  }
  return top;  // the step tops out at or below 1 before reaching it: its top, as "auto"
}

DepthRange csmDepthRange(const Scene& scene, float* nearestCaster) {
  return fitShadowingDepthRange(scene, nearestCaster);
}

Technique convolutionShadowMapTechnique() {
  Technique t;
  t.name = "modern.csm";
  t.paper = "Annen, Mertens, Bekaert, Seidel & Kautz 2007, Convolution Shadow Maps";
  t.summary =
      "Fourier basis of the shadow test (Eq. 10-14) in MRT textures, blurred and mip-mapped";
  t.status = "complete";
  t.needs.profile = Profile::kCore;
  t.params = {orderParam(),
              alphaParam(),
              offsetParam(),
              offsetRuleParam(),
              scaleParam(),
              storageParam(),
              blurParam(kDefaultBlurTaps),
              filteringParam(),
              anisotropyParam(),
              mipmapsParam()};
  t.reads = {.shadowMap = true};
  t.plan.prefilter = PlanTraits::Prefilter::kConvolution;
  t.render = render;
  return t;
}

}  // namespace sl::modern
