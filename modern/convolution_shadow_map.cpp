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
//   With --param skip-error > 0 (the default) and a map of 2 texels or more, pass 5 runs as:
//   5a. computeDepthBounds        — min/max pyramid of z and its dilated copy
//                                   (csm_depth_bounds.frag); not in the paper (DEVIATION there)
//   5b. classifyInCameraPass      — camera pass (csm_shadow.frag, CLASSIFY 1): pixels whose
//                                   footprint depths decide Eq. 13 within skip-error are shaded
//                                   lit or umbra (Eq. 8, 13), the others marked with stencil 1
//   5c. reconstructInCameraPass   — Eq. 13 with attenuation (§3.2.1), offset and scale
//                                   (§3.2.2), clamp to [0, 1] (§4.1), at stencil-1 pixels only;
//                                   csm_shadow.frag
//   With skip-error = 0 (or a 1-texel map):
//   5.  reconstructInCameraPass   — the same reconstruction at every pixel
// The passes are declared once in csmPasses().
#include "modern/convolution_shadow_map.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/base/errors.h"
#include "core/technique/pass_capture.h"
#include "core/technique/passes.h"
#include "core/technique/plan.h"
#include "modern/camera_pass.h"
#include "modern/prefiltered_maps.h"
#include "modern/shadow_volumes.h"

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
// --param skip-error: the most a skipped pixel's visibility may differ from the clamped series
// (a visibility difference, 0..1). 0.025 covers the attenuated series' ringing on most of the
// lit and umbra ranges of t for M >= 4 at alpha = 1 (largest dip below 1 on [offset, 0.8]:
// M = 4: 0.020, 8: 0.023, 16: 0.019; largest bump above 0 on [-0.8, -2 offset]: M = 4: 0.036,
// 8: 0.014, 16: 0.011), so that most receivers decide without the M terms.
constexpr double kDefaultSkipError = 0.025;
constexpr double kMaxSkipError = 0.5;
constexpr int kSkipIntervalSteps = 40000;  // grid points of csmSkipIntervals on [-1, 1]
// The filter footprint's radius in depth texels, for the depth bounds of the classification:
// kFootprintScale times the pixel's texels per pixel (tri-linear reads +-1 texel of a level whose
// texel is at most twice that: +-2 x; llvmpipe's anisotropic probes spread over half the major
// axis each side, each a tri-linear lookup of a finer level: <= 2.5 x; 3 leaves room for its
// per-quad level choice), plus
// the bilinear reach and the blur's radius, plus one texel for rounding.
constexpr float kFootprintScale = 3.0f;
constexpr float kFootprintRoundingTexels = 1.0f;
// The coarsest level of the depth-bounds pyramid (2^4 = 16 depth texels a texel): footprints
// wider than it allows (csm_shadow.frag, depthBoundsAround: about 3 texels per pixel) are not
// decided by the bounds.
constexpr int kDepthBoundsLevel = 4;
constexpr int kSmallestClassifiedMap = 2;  // texels: the pyramid's first level is level 1
// glPolygonOffset factor and units (depth-slope and resolvable-depth steps) that the
// reconstruction pass 5c moves its fragments forward by, so that it meets the classification's
// depth although its program interpolates depth in different generated code.
constexpr float kReconstructionDepthOffset = 2.0f;
const char* const kWorkspaceKey = "modern.csm.workspace";  // GL objects kept between frames

// The DEVIATION comments of the passes below (and csm_shadow.frag's), for the pass table.
constexpr const char* kMipmapsAutoDeviation =
    "DEVIATION (Annen et al. 2007, §4.1: \"we then build a mip-map of this texture\"): with "
    "mipmaps=auto (the default) the chain is built only when the planner finds that the view "
    "minifies the map (core/technique/plan.h, more than one shadow-map texel per pixel at the 95th "
    "percentile of the receivers' pixels). Where no pixel minifies, GL samples level 0 with the "
    "magnification filter (lambda <= 0, glspec §3.8.8) and the chain is never read, so leaving "
    "it out changes nothing but the time (on llvmpipe the mip chain of M/2 layers is a large "
    "share of the frame). mipmaps=always builds it regardless.";
constexpr const char* kBasisWithBlurDeviation =
    "DEVIATION (Annen et al. 2007, §4.1 stores the basis, then blurs it): the same sums in "
    "another order, one write and one read of M/2 layers fewer; with 8-bit storage the basis is "
    "no longer rounded to 8 bits before the horizontal weights (one rounding fewer, closer to "
    "Eq. 8).";
constexpr const char* kDepthBoundsDeviation =
    "DEVIATION (Annen et al. 2007, §4.1 has no such pass): it exists only to skip Eq. 13 where "
    "the bounds decide the series (see classifyInCameraPass); skip-error=0 leaves it out.";
constexpr const char* kClassificationDeviation =
    "DEVIATION (Annen et al. 2007, Eq. 13 from the filtered basis at every pixel): Eq. 13 of a "
    "filtered footprint is the same convex combination of the series at the footprint's depths "
    "(Eq. 8), so where every depth lies in an interval on which the clamped series is within "
    "skip-error of 1 or 0 (csmSkipIntervals), the pixel needs none of the 2M filtered lookups: it "
    "gets the mean of the series at the four depth texels around it with the lookup's bilinear "
    "weights (csm_shadow.frag, reconstructFromDepth): Eq. 13's own value where the footprint's "
    "depth is constant, within skip-error of it otherwise, so that decided and reconstructed "
    "pixels agree. On llvmpipe the stencil test of pass 5c then skips the "
    "reconstruction's shader for whole 4x4 blocks; a branch in the shader would not (llvmpipe "
    "evaluates both sides of a non-uniform branch).";
constexpr const char* kSeriesOfDepthsDeviation =  // csm_shadow.frag, CLASSIFY 1
    "DEVIATION (Annen et al. 2007, Eq. 13 from the filtered 8-bit basis): the series of the "
    "depths themselves, so without the basis' 8-bit rounding (on ground that casts nothing, "
    "squares at M = 16: 0.0013 from the reconstruction, a third of an 8-bit grey level), and "
    "weighted by the bilinear weights only (where the depth varies across the blur's or the mip "
    "level's wider footprint: within the skip error, as both are means over the interval).";

// The passes, declared once: names, the paper's text, the buffers a dump shows, shaders and
// deviations. Pass 4's name says whether the mip chain is built (`mipmaps`), hence two tables.
PassTable csmPasses(bool mipmaps) {
  const std::string reconstruction =
      "Annen et al. 2007 §3.1 Eq. 13 with the coefficients of Eq. 14, offset and scale of §3.2.2 "
      "(Fig. 3), clamped (§4.1)";
  const std::vector<PassBuffer> cameraPass =
      cameraPassBuffers("5", "csm_shadow.frag: Eq. 13 reconstruction");
  return {
      {.id = "1",
       .name = "linear depth from light",
       .reference = "Annen et al. 2007 §4.1: \"rendering the depth values from the light's point "
                    "of view\", linear depth [BAS03]",
       .writes = {{.name = "linear-depth", .caption = "linear light-space depth z(p) (§4.1)"}},
       .shaders = {"linear-depth"}},
      {.id = "2",
       .name = "basis textures",  // + " + horizontal Gaussian (MRT)" or " (MRT)"
       .reference = "Annen et al. 2007 §4.1: the basis B_i(z) = sin(c_k z), cos(c_k z) of Eq. 14 "
                    "(Eq. 7) into textures (Fig. 5); the Gaussian's first direction (DEVIATION)",
       // Fig. 5: every basis layer (four k per RGBA layer: M/4 sine and M/4 cosine layers) as
       // this pass leaves it: unblurred, or after the horizontal Gaussian only (then pass 3
       // shows them after the whole blur).
       .writes = {{.name = "basis-sin-{range}", .caption = "sin(c_k z), {range}, {stage} (Fig. 5)"},
                  {.name = "basis-cos-{range}", .caption = "cos(c_k z), {range}, {stage}"}},
       .shaders = {"basis"},
       .deviations = {kBasisWithBlurDeviation},
       .keyState = {"draw buffers", "uOrder", "uWeights"}},
      {.id = "3",
       .name = "vertical Gaussian",  // + " NxN"
       .reference = "Annen et al. 2007 §4.1: the separable Gaussian's second direction",
       .writes = {{.name = "basis-sin-{range}",
                   .caption = "sin(c_k z), {range}, after the whole Gaussian (Fig. 5)"},
                  {.name = "basis-cos-{range}",
                   .caption = "cos(c_k z), {range}, after the whole Gaussian"}},
       .shaders = {"gaussian"},
       .keyState = {"uWeights", "uStep"}},
      {.id = "4",
       .name = mipmaps ? "mip-maps" : "sampling state (no mip-maps)",
       .reference = "Annen et al. 2007 §4.1: \"build a mip-map\" of the basis, trilinear or "
                    "anisotropic filtering (Figs. 7, 10)",
       .writes = {{.name = "basis-sin-k1-4-level{level}",
                   .caption = "sin(c_k z), k1-4, mip level {level} ({size}x{size}): the mean of "
                              "the basis over {texels} texels, what trilinear filtering reads "
                              "where the view minifies the map (Fig. 7)"}},
       .shaders = {"downsample"},
       .deviations = {kMipmapsAutoDeviation, kDrawnMipChainDeviation},
       .keyState = {"GL_TEXTURE_MIN_FILTER", "GL_TEXTURE_BASE_LEVEL", "glViewport"}},
      {.id = "5a",
       .name = "depth bounds (min/max pyramid of z)",
       .reference = "not in Annen et al. 2007: bounds of z under each footprint, so that the "
                    "classification can skip Eq. 13 where they decide the series",
       .shaders = {"csm-depth-bounds"},
       .deviations = {kDepthBoundsDeviation}},
      {.id = "5b",
       .name = "camera pass: classification (depth bounds)",
       .reference = "Annen et al. 2007 Eq. 8 and 13: where every depth under the footprint puts "
                    "the series within skip-error of 1 or 0, the pixel gets the series at its "
                    "depths (Eq. 8) without Eq. 13's filtered lookups",
       .shaders = {"csm-classify", "csm-test"},
       .deviations = {kClassificationDeviation, kSeriesOfDepthsDeviation}},
      {.id = "5c",
       .name = "camera pass, Eq. 13 where undecided",
       .reference = reconstruction,
       .writes = cameraPass,
       .shaders = {"reconstruct", "csm-test"}},
      // skip-error = 0 (or a 1-texel map): no classification, Eq. 13 at every pixel.
      {.id = "5",
       .name = "camera pass, Eq. 13 reconstruction",
       .reference = reconstruction,
       .writes = cameraPass,
       .shaders = {"reconstruct", "csm-test"}},
  };
}

const PassTable& passTable(bool mipmaps) {
  static const PassTable withMipmaps = csmPasses(true);
  static const PassTable withoutMipmaps = csmPasses(false);
  return mipmaps ? withMipmaps : withoutMipmaps;
}

struct CsmSettings {
  int order = kDefaultOrder;  // M
  double alpha = kDefaultAlpha;
  double offset = 0.0;         // subtracted from d (§3.2.2)
  double scale = 1.0;          // multiplies f (§3.2.2)
  GLenum format = GL_RGBA8;    // storage of the basis layers
  bool encodeUnsigned = true;  // 8-bit: [-1, 1] stored as 0.5 + 0.5 v
  int blurTaps = kDefaultBlurTaps;
  MapFiltering filtering;
  bool mipmapsSkipped = false;           // mipmaps=auto and the view does not minify the map
  double skipError = kDefaultSkipError;  // 0: Eq. 13 at every pixel
  int sinLayers() const { return (order + kChannelsPerLayer - 1) / kChannelsPerLayer; }
  int layers() const { return 2 * sinLayers(); }
  // Linear depth is stored scaled by 1 - offset, so that t = z - d + offset stays inside one
  // period (-1, 1] of the square wave S(t) of Eq. 10 for every z, d in the map.
  float depthScale() const { return float(1.0 - offset); }
};

// The --params of modern.csm, declared once (Technique::params).
ParamSpec orderParam() {
  return integerParam(
      "order", kDefaultOrder, 1, kMaxOrder,
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
ParamSpec skipErrorParam() {
  return numberParam("skip-error", kDefaultSkipError, 0.0, kMaxSkipError,
                     "pixels whose filter footprint the depth bounds decide (the clamped series "
                     "within this of 1 or 0) skip Eq. 13; 0 = reconstruct every pixel");
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
  s.skipError = params.number(skipErrorParam());
  // The classification writes the stencil reference from the shader and gathers the depths
  // around a decided pixel (csm_shadow.frag, reconstructFromDepth).
  if (!context.caps().hasExtension("GL_ARB_shader_stencil_export") ||
      !context.caps().hasExtension("GL_ARB_texture_gather"))
    s.skipError = 0.0;
  // DEVIATION (Annen et al. 2007, §4.1: "we then build a mip-map of this texture"): with
  // mipmaps=auto (the default) the chain is built only when the planner finds that the view
  // minifies the map (core/technique/plan.h, more than one shadow-map texel per pixel at the 95th
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
const RenderTarget& renderLinearDepthFromLight(Passes& passes, const GpuScene& gpu,
                                               const RenderParams& params, const CsmSettings& s,
                                               const DepthRange& range, PrefilterWorkspace& work) {
  passes.run("1", [&] {
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
  });
  return work.depth;
}

// Pass 2 (§4.1, Eq. 14): the basis images B_i(z(p)), as many layers per pass as the
// context has draw buffers ("with four MRTs only two additional render passes"). With a blur,
// this pass also applies its horizontal half (pass 3): the basis of the kernel's row of depth
// texels, weighted, so that the unblurred layers are neither stored nor read back.
// DEVIATION (Annen et al. 2007, §4.1 stores the basis, then blurs it): the same sums in another
// order, one write and one read of M/2 layers fewer; with 8-bit storage the basis is no
// longer rounded to 8 bits before the horizontal weights (one rounding fewer, closer to Eq. 8).
const LayeredMap& computeBasisTextures(Passes& passes, const RenderTarget& depth,
                                       const CsmSettings& s, PrefilterWorkspace& work) {
  const std::string suffix = s.blurTaps > 0 ? " + horizontal Gaussian (MRT)" : " (MRT)";
  passes.run(
      "2",
      [&] {
        const LayeredMap& basis =
            reuseLayeredMap(work.map, depth.width, s.layers(), s.format, s.filtering.mipmaps);
        // Blurred: the horizontal pass's output goes to the scratch map, the vertical one to
        // `basis`.
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
        int draws = 0;
        for (int first = 0; first < basis.layers; first += perPass, ++draws) {
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
        passes.frame().counters["basis render passes"] = draws;
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
      },
      {}, suffix);
  return work.map;
}

// Pass 3 (§4.1): "a separable Gaussian filter kernel on the textures": the vertical half (the
// horizontal one was applied with the basis, pass 2).
void blurBasisTextures(Passes& passes, const LayeredMap& basis, const CsmSettings& s,
                       PrefilterWorkspace& work) {
  if (s.blurTaps == 0) return;
  const std::string taps = std::to_string(s.blurTaps);
  passes.run(
      "3",
      [&] {
        blurLayersOneDirection(work.scratch, basis, s.blurTaps, BlurDirection::kVertical, work.fbo);
      },
      {}, " " + taps + "x" + taps);
}

// Pass 4 (§4.1): "we then build a mip-map of this texture" and switch on tri-linear (and
// anisotropic) filtering: "no shader magic is needed".
void buildBasisMipmaps(Passes& passes, const LayeredMap& basis, const CsmSettings& s) {
  passes.run("4", [&] { buildMipmapsAndSetFiltering(basis, s.filtering); });
}

// The footprint margin in depth texels (csm_shadow.frag, uFootprintMargin): the bilinear reach,
// the blur's radius and one texel for rounding.
float footprintMargin(const CsmSettings& s) {
  return 1.0f + float(s.blurTaps / 2) + kFootprintRoundingTexels;
}

// The finest level of the depth-bounds pyramid that the classification can use away from the
// map's border: a box of radius r texels (r >= the margin) spans hi - lo >= floor(2 r) + 1
// texels (csm_shadow.frag, depthBoundsAround), and level L decides it only where that is at most
// 3 * 2^L - 1 (its block and the two neighbours). Finer levels are never built: at the border,
// where clamping makes a box narrower, this level's texel still bounds it (a box that spans at
// most 3 blocks of level L spans at most 3 of level L + 1), only less tightly.
int firstDepthBoundsLevel(const CsmSettings& s, int levels) {
  const int minimumSpan = int(std::floor(2.0f * footprintMargin(s))) + 1;
  int level = 1;  // level 0 never: the margin is at least 2 texels (span >= 5 > 3 * 2^0 - 1)
  while (level < levels - 1 && minimumSpan > 3 * (1 << level) - 1) ++level;
  return level;
}

// Pass 5a: the min/max pyramid of the linear depth z(p) up to kDepthBoundsLevel, and its dilated
// copy (each texel the bounds of its 3x3 neighbourhood in its level) (csm_depth_bounds.frag),
// read by the classification (5b) to bound the depths under each pixel's filter footprint.
// DEVIATION (Annen et al. 2007, §4.1 has no such pass): it exists only to skip Eq. 13 where the
// bounds decide the series (see classifyInCameraPass); skip-error=0 leaves it out.
const Texture& computeDepthBounds(Passes& passes, const RenderTarget& depth, const CsmSettings& s,
                                  PrefilterWorkspace& work) {
  passes.run("5a", [&] {
    const int n = depth.width;
    if (work.depthBoundsSize != n || work.depthBounds.id() == 0) {
      int levels = 1;
      while (levels <= kDepthBoundsLevel && (n >> levels) >= 1) ++levels;
      for (Texture* t : {&work.depthBounds, &work.depthBoundsDilated}) {
        *t = makeTexture();
        glBindTexture(GL_TEXTURE_2D, t->id());
        glTexStorage2D(GL_TEXTURE_2D, levels, GL_RG32F, n, n);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      }
      work.depthBoundsSize = n;
      work.depthBoundsLevels = levels;
    }
    if (work.fbo.id() == 0) work.fbo = makeFramebuffer();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glBindFramebuffer(GL_FRAMEBUFFER, work.fbo.id());
    const GLenum buffer = GL_COLOR_ATTACHMENT0;
    glDrawBuffers(1, &buffer);
    const FullScreenTriangle triangle;
    glActiveTexture(GL_TEXTURE0);
    // Reads `source` at `level` only (BASE_LEVEL = MAX_LEVEL = level: no feedback loop, glspec
    // §4.4.3; texelFetch's level 0 is then that level) while `target` level `targetLevel` is drawn.
    auto draw = [&](const char* mode, GLuint source, int level, GLuint target, int targetLevel) {
      const Program& program =
          cachedProgram("fullscreen.vert.glsl", "csm_depth_bounds.frag.glsl", {{mode, "1"}});
      program.use();
      program.set("uSource", 0);
      glBindTexture(GL_TEXTURE_2D, source);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, level);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, level);
      glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target,
                             targetLevel);
      const int size = std::max(n >> targetLevel, 1);
      glViewport(0, 0, size, size);
      triangle.draw();
    };
    const GLuint pyramid = work.depthBounds.id(), dilated = work.depthBoundsDilated.id();
    // Level 1 straight from the R32F depth map (level 0 would be (z, z), a copy); levels finer
    // than the first the classification can use are neither dilated nor read.
    const int first = firstDepthBoundsLevel(s, work.depthBoundsLevels);
    draw("FROM_DEPTH", depth.color[0].id(), 0, pyramid, 1);
    for (int level = 2; level < work.depthBoundsLevels; ++level)
      draw("REDUCE", pyramid, level - 1, pyramid, level);
    for (int level = first; level < work.depthBoundsLevels; ++level)
      draw("DILATE", pyramid, level, dilated, level);
    passes.frame().counters["depth bounds first level"] = first;
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindTexture(GL_TEXTURE_2D, depth.color[0].id());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 1000);  // GL's initial value
    glBindTexture(GL_TEXTURE_2D, dilated);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, work.depthBoundsLevels - 1);
    glBindTexture(GL_TEXTURE_2D, 0);
    checkGl("modern.csm depth bounds");
  });
  return work.depthBoundsDilated;
}

// The uniforms the classification (CLASSIFY 1) and the reconstruction (CLASSIFY 0) share: the
// same spotlight, light-space transform, depth normalisation and early-outs (csm_shadow.frag).
void setCameraPassUniforms(const Program& program, const Scene& scene, const RenderParams& params,
                           const CsmSettings& s, const DepthRange& range, float nearestCaster) {
  program.use();
  program.set("uViewProjection", cameraViewProjection(scene, params));
  program.set("uWorldToShadowMap", worldToShadowMap(scene));
  setLinearDepthUniforms(program, scene, range);
  program.set("uNearestCaster", nearestCaster);
  program.set("uDepthScale", s.depthScale());
  program.set("uOffset", float(s.offset));
  program.set("uScale", float(s.scale));
  setLightingUniforms(program, scene);
}

// Pass 5b: the camera view, classified (csm_shadow.frag with CLASSIFY 1): pixels that the
// early-outs of pass 5c or the depth bounds decide are shaded here; the others get stencil 1.
// DEVIATION (Annen et al. 2007, Eq. 13 from the filtered basis at every pixel): Eq. 13 of a
// filtered footprint is the same convex combination of the series at the footprint's depths
// (Eq. 8), so where every depth lies in an interval on which the clamped series is within
// skip-error of 1 or 0 (csmSkipIntervals), the pixel needs none of the 2M filtered lookups: it
// gets the mean of the series at the four depth texels around it with the lookup's bilinear
// weights (csm_shadow.frag, reconstructFromDepth): Eq. 13's own value where the footprint's
// depth is constant, within skip-error of it otherwise, so that decided and reconstructed
// pixels agree. On llvmpipe the stencil test of pass 5c then skips the reconstruction's shader
// for whole 4x4 blocks; a branch in the shader would not (llvmpipe evaluates both sides of a
// non-uniform branch).
void classifyInCameraPass(Passes& passes, const GpuScene& gpu, const RenderParams& params,
                          const Texture& linearDepth, const Texture& depthBounds,
                          int depthBoundsLevels, const CsmSkipIntervals& skip, const CsmSettings& s,
                          const DepthRange& range, float nearestCaster) {
  passes.run("5b", [&] {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glEnable(GL_STENCIL_TEST);
    glStencilMask(0xFF);
    glStencilFunc(GL_ALWAYS, 0, 0xFF);  // the reference comes from gl_FragStencilRefARB
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    const Program& program =
        cachedProgram("scene.vert.glsl", "csm_shadow.frag.glsl",
                      {{"ORDER", std::to_string(s.order)},
                       {"ENCODE_UNSIGNED", "0"},
                       {"CLASSIFY", "1"},
                       {"DEPTH_BOUNDS_LEVELS", std::to_string(depthBoundsLevels)},
                       {"FIRST_DEPTH_BOUNDS_LEVEL",
                        std::to_string(firstDepthBoundsLevel(s, depthBoundsLevels))}});
    setCameraPassUniforms(program, gpu.scene(), params, s, range, nearestCaster);
    program.set("uLitInterval", glm::vec2(float(skip.litLo), float(skip.litHi)));
    program.set("uUmbraInterval", glm::vec2(float(skip.umbraLo), float(skip.umbraHi)));
    program.set("uFootprintScale", s.filtering.mipmaps ? kFootprintScale : 0.0f);
    program.set("uFootprintMargin", footprintMargin(s));
    program.set("uDepthMapTexels", params.shadowMapTexels);
    const std::vector<float> weights = termWeights(s);
    glUniform4fv(program.uniform("uWeights"), GLsizei(s.sinLayers()), weights.data());
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, depthBounds.id());
    program.set("uDepthBounds", 1);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, linearDepth.id());
    program.set("uLinearDepth", 2);
    gpu.draw([](const Object&) { return true; },
             [&](const Object& o) { setObjectUniforms(program, o); });
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE0);
  });
}

// Pass 5 (Eq. 13, §3.2, §4.1): the camera view with the reconstructed, filtered shadow test; with
// the classification (skip-error > 0), at the pixels it left undecided only (pass 5c: stencil 1,
// depth equal to the classification's).
void reconstructInCameraPass(Passes& passes, const GpuScene& gpu, const RenderParams& params,
                             const LayeredMap& basis, const CsmSettings& s, const DepthRange& range,
                             float nearestCaster, const Texture& linearDepth,
                             const Texture* depthBounds, int depthBoundsLevels,
                             const CsmSkipIntervals& skip) {
  const Scene& scene = gpu.scene();
  const bool classified = depthBounds != nullptr;
  RenderTarget target =
      classified ? makeStencilCameraTarget(params, {}) : makeCameraTarget(params, true);
  if (classified) {
    classifyInCameraPass(passes, gpu, params, linearDepth, *depthBounds, depthBoundsLevels, skip, s,
                         range, nearestCaster);
  } else {
    clearCameraTarget(target);
  }
  passes.run(classified ? "5c" : "5", [&] {
    glEnable(GL_DEPTH_TEST);
    if (classified) {
      // The same vertex shader and uniforms, but llvmpipe interpolates depth inside each fragment
      // shader's generated code, so the two programs' depths can differ in the last bits (dots of
      // undecided pixels on grazing ground with GL_EQUAL): less-or-equal, pulled forward by
      // kReconstructionDepthOffset units and slope.
      glDepthFunc(GL_LEQUAL);
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(-kReconstructionDepthOffset, -kReconstructionDepthOffset);
      glDepthMask(GL_FALSE);
      glStencilFunc(GL_EQUAL, 1, 0xFF);
      glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    }
    // One program per (M, storage): constant loop bounds and indices (the shader's header).
    const Program& program = cachedProgram("scene.vert.glsl", "csm_shadow.frag.glsl",
                                           {{"ORDER", std::to_string(s.order)},
                                            {"ENCODE_UNSIGNED", s.encodeUnsigned ? "1" : "0"},
                                            {"CLASSIFY", "0"}});
    setCameraPassUniforms(program, scene, params, s, range, nearestCaster);
    const std::vector<float> weights = termWeights(s);
    glUniform4fv(program.uniform("uWeights"), GLsizei(s.sinLayers()), weights.data());
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D_ARRAY, basis.texture.id());
    program.set("uBasis", 0);
    gpu.draw([](const Object&) { return true; },
             [&](const Object& o) { setObjectUniforms(program, o); });
    readCameraTarget(target, passes.frame());
    if (classified) {
      glDisable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(0.0f, 0.0f);
      glDisable(GL_STENCIL_TEST);
      glDepthFunc(GL_LESS);
      glDepthMask(GL_TRUE);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  });
}

// --dump-passes, as Fig. 5: all 2M basis values (M/4 sine and M/4 cosine RGBA layers, four k
// each) of `map` as pass `id` leaves them, the stored values with [-1, 1] shown as [0, 1].
void captureBasisLayers(Passes& passes, const std::string& id, const LayeredMap& map,
                        const CsmSettings& s, const std::string& stage) {
  const float scale = s.encodeUnsigned ? 1.0f : 0.5f;
  const float bias = s.encodeUnsigned ? 0.0f : 0.5f;
  auto range = [&](int layer) {
    const int first = kChannelsPerLayer * layer + 1;
    return "k" + std::to_string(first) + "-" +
           std::to_string(std::min(first + kChannelsPerLayer - 1, s.order));
  };
  for (const char* function : {"sin", "cos"})
    for (int layer = 0; layer < s.sinLayers(); ++layer) {
      const int stored = function[0] == 's' ? layer : s.sinLayers() + layer;
      passes.capture(id, std::string("basis-") + function + "-{range}",
                     [&] { return readLayer(map, stored, scale, bias); }, {},
                     {{"range", range(layer)}, {"stage", stage}});
    }
}

// --dump-passes: the linear depth of pass 1 and the basis layers of passes 2 and 3: pass 2's
// output (the horizontal Gaussian's, in the scratch map, when there is a blur) and pass 3's.
void captureDepthAndBasis(Passes& passes, const RenderTarget& depth, const LayeredMap& basis,
                          const CsmSettings& s, const LayeredMap& horizontal) {
  if (!passes.capturing()) return;
  passes.capture("1", "linear-depth", [&] { return channel(readAttachment(depth, 0), 0); });
  if (s.blurTaps == 0) {
    captureBasisLayers(passes, "2", basis, s, "unblurred");
    return;
  }
  captureBasisLayers(passes, "2", horizontal, s, "after the horizontal Gaussian only");
  captureBasisLayers(passes, "3", basis, s, "");
}

// --dump-passes: the first sine layer at the first mip levels pass 4 built (none when the
// mip chain is left out).
void captureBasisMipLevels(Passes& passes, const LayeredMap& basis, const CsmSettings& s) {
  constexpr int kShownMipLevels = 3;  // levels 1-3: 2x2, 4x4 and 8x8 texel means
  if (!passes.capturing() || !s.filtering.mipmaps) return;
  const float scale = s.encodeUnsigned ? 1.0f : 0.5f;
  const float bias = s.encodeUnsigned ? 0.0f : 0.5f;
  for (int level = 1; level <= std::min(kShownMipLevels, basis.levels - 1); ++level) {
    const int size = std::max(basis.size >> level, 1);
    const int side = 1 << level;
    passes.capture("4", "basis-sin-k1-4-level{level}",
                   [&] { return readLayer(basis, 0, scale, bias, level); }, {},
                   {{"level", std::to_string(level)},
                    {"size", std::to_string(size)},
                    {"texels", std::to_string(side) + "x" + std::to_string(side)}});
  }
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
  Passes passes(frame, params, passTable(s.filtering.mipmaps));
  GpuScene gpu(scene);
  const DepthRange range = work.fittedRange;
  const RenderTarget& depth = renderLinearDepthFromLight(passes, gpu, params, s, range, work);
  const LayeredMap& basis = computeBasisTextures(passes, depth, s, work);
  blurBasisTextures(passes, basis, s, work);
  captureDepthAndBasis(passes, depth, basis, s, work.scratch);
  buildBasisMipmaps(passes, basis, s);
  captureBasisMipLevels(passes, basis, s);
  // The pyramid starts at level 1 (computeDepthBounds): a 1-texel map is not classified.
  const bool classify = s.skipError > 0.0 && params.shadowMapTexels >= kSmallestClassifiedMap;
  const Texture* bounds = classify ? &computeDepthBounds(passes, depth, s, work) : nullptr;
  // The skip intervals depend on the settings only: computed once for them, kept.
  if (std::vector<double> key = {double(s.order), s.alpha, s.offset, s.scale, s.skipError};
      key != work.skipKey) {
    const CsmSkipIntervals k = csmSkipIntervals(s.order, s.alpha, s.offset, s.scale, s.skipError);
    work.skipIntervals = {k.litLo, k.litHi, k.umbraLo, k.umbraHi};
    work.skipKey = std::move(key);
  }
  const CsmSkipIntervals skip{work.skipIntervals[0], work.skipIntervals[1], work.skipIntervals[2],
                              work.skipIntervals[3]};
  reconstructInCameraPass(passes, gpu, params, basis, s, range, work.nearestCaster, depth.color[0],
                          bounds, work.depthBoundsLevels, skip);
  captureCameraPass(passes, classify ? "5c" : "5");
  frame.counters["light near"] = range.nearPlane;
  frame.counters["light far"] = range.farPlane;
  frame.counters["order M"] = s.order;
  frame.counters["offset"] = s.offset;
  frame.counters["scale"] = s.scale;
  frame.counters["basis layers"] = s.layers();
  frame.counters["anisotropy"] = s.filtering.anisotropy;
  frame.counters["mip-maps"] = s.filtering.mipmaps ? 1 : 0;
  frame.counters["skip error"] = s.skipError;
  frame.counters["skip lit t from"] = skip.litLo;
  frame.counters["skip lit t to"] = skip.litHi;
  frame.counters["skip umbra t from"] = skip.umbraLo;
  frame.counters["skip umbra t to"] = skip.umbraHi;
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

CsmSkipIntervals csmSkipIntervals(int order, double alpha, double offset, double scale,
                                  double maxError) {
  CsmSkipIntervals out;
  if (maxError <= 0.0) return out;
  const int n = kSkipIntervalSteps;
  const double h = 2.0 / n;
  // Between two grid points the clamped series moves by at most (h / 2) * max |d/dt|, and
  // |d/dt scale f| <= scale * sum_k w_k 2 <= 2 M scale (Eq. 14: d/dt (2/c_k) sin(c_k t) =
  // 2 cos(c_k t), w_k <= 1).
  const double margin = 0.5 * h * 2.0 * order * scale;
  std::vector<double> g(size_t(n) + 1);
  for (int i = 0; i <= n; ++i)
    g[size_t(i)] = std::clamp(scale * csmReconstructedStep(-1.0 + i * h, order, alpha), 0.0, 1.0);
  auto run = [&](double seed, auto&& inside, double& lo, double& hi) {
    const int start = std::clamp(int(std::lround((seed + 1.0) / h)), 0, n);
    if (!inside(g[size_t(start)])) return;
    int a = start, b = start;
    while (a > 0 && inside(g[size_t(a - 1)])) --a;
    while (b < n && inside(g[size_t(b + 1)])) ++b;
    lo = -1.0 + a * h;
    hi = -1.0 + b * h;
  };
  run(
      offset, [&](double v) { return v >= 1.0 - maxError + margin; }, out.litLo, out.litHi);
  run(
      -0.5, [&](double v) { return v <= maxError - margin; }, out.umbraLo, out.umbraHi);
  return out;
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
              mipmapsParam(),
              skipErrorParam()};
  t.reads = {.shadowMap = true};
  t.edge = Technique::Edge::kFiltered;  // a blurred, mip-mapped basis
  t.plan.prefilter = PlanTraits::Prefilter::kConvolution;
  t.passes = passTable(true);
  // Without a mip chain (a filtering that does not mip-map; with mipmaps=auto also a view that
  // does not minify the map) pass 4 sets the sampling state only.
  t.passVariants = {{{{filteringParam().key, "bilinear"}}, passTable(false)}};
  t.render = render;
  return t;
}

}  // namespace sl::modern
