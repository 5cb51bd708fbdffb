// modern.fast-pcf — Brabec & Seidel 2001 §4: fast percentage-closer filtering by packing four
// neighbouring texels of ONE light pass into a texel (the 3x3 convolution of Eq. 1, Figure 5),
// as shaders. Twin of legacy_gl's legacy.fast-pcf.
//
// Passes:
//   1. renderDepthAsColourFromLight — one light pass, encoded depth in all four channels (§4)
//   2. packNeighbours               — fast_pcf_pack.frag: Eq. (1)'s kernel gathers the lower-left,
//                                     lower-middle, middle-left and centre texels into R, G, B, A
//                                     (Figure 5); for 4x4 footprints four phases gather the
//                                     upper-left, upper-right, lower-left, lower-right regions
//   3. shadowTestAndShade           — pcf_shadow.frag with the (ds/2, dt/2) texture-coordinate
//                                     offset (Figure 6, shifted by one texel per 4x4 phase); the
//                                     phases summed as the accumulation buffer does (20 levels)
// --param bias=normal-offset (modern/pcf_bias.h; ours, after Holbert 2011): texgen.vert moves
// the camera pass's point along its normal before texgen; constant, the default, moves nothing.
// The passes are declared once in fastPcfPasses().
#include <string>

#include "core/base/errors.h"
#include "core/technique/pass_capture.h"
#include "core/technique/passes.h"
#include "modern/brabec_seidel.h"
#include "modern/brabec_seidel_techniques.h"
#include "modern/camera_pass.h"
#include "modern/pcf_bias.h"

namespace sl::modern {
using namespace sl::gl;

namespace {

constexpr int kTexelItselfChannel = 3;  // A: the upper right of the 2x2 region (Eq. (1) centre)

// The passes, declared once: names, the paper's text, the buffers a dump shows, the GLSL they
// run and the passes of legacy.fast-pcf (legacy_gl/fast_pcf.cpp) they replace.
PassTable fastPcfPasses() {
  return {
      {.id = "1",
       .name = "light pass: depth ramp in RGBA (bs_encode_depth.frag)",
       .reference = "Brabec & Seidel 2001 §4: the map rendered as in §2 (Fig. 1), the encoded "
                    "depth in all four channels; render-to-texture replaces the copy",
       .writes = {{.name = "light-pass-depth-rgba",
                   .caption = "pass 1: one light pass, encoded depth in all four channels "
                              "(channel R shown; the same in G, B, A)"}},
       .shaders = {"encode-depth"},
       .replaces = {"1"}},
      {.id = "2",
       .name = "packing by the 3x3 kernel of Eq. (1) (fast_pcf_pack.frag)",
       .reference = "Brabec & Seidel 2001 §4, Eq. (1), Fig. 5",
       // Named as legacy.fast-pcf names its packed maps (one per 4x4 phase).
       .writes = {{.name = "packed-shadow-map{part}-rgba",
                   .caption = "pass 2 (Eq. 1, Figure 5): fast_pcf_pack.frag packs four "
                              "neighbours of a 2x2 region: R = lower left, G = lower right, B = "
                              "upper left, A = upper right",
                   .centreChannel = kTexelItselfChannel,
                   .channelMeaning = {"lower left", "lower right", "upper left",
                                      "upper right{itself}"}}},
       .shaders = {"pack"},
       .replaces = {"2"}},
      {.id = "3",
       .name = "camera pass = legacy passes 3-7: depth, subtract, colour table, colour matrix, "
               "accumulate, shade (pcf_shadow.frag)",
       .reference = "Brabec & Seidel 2001 §3 Fig. 4, §4 Fig. 6, §5",
       .writes =
           cameraPassBuffers("3", "pcf_shadow.frag: shadow test, colour table, colour matrix (§4)"),
       .shaders = {"vertex-normal-offset-bias", "camera-depth", "subtract-and-count", "accumulate",
                   "float-shadow", "shade"},
       .replaces = {"3", "3s", "3r", "4", "5", "6a", "6b", "7"},
       .deviations = {bs::kNormalOffsetDeviation}},
  };
}

const PassTable& passTable() {
  static const PassTable table = fastPcfPasses();
  return table;
}

// A phase: which 2x2 region of the 3x3 neighbourhood the kernel gathers (its lower-left pixel
// relative to the centre), the lookup offset that centres the footprint (Figure 6) and the
// file tag of its packed map.
struct Phase {
  glm::ivec2 regionOrigin;
  glm::vec2 offsetTexels;
  PassPart part;
};

// 2x2: Eq. (1) gathers the region {x-1, x} x {y-1, y}, centred half a texel below-left of the
// texel, so the lookup moves by (+ds/2, +dt/2) (Figure 6).
const std::vector<Phase> kFootprint2 = {{{-1, -1}, {0.5f, 0.5f}, {}}};
// 4x4: the footprint {c-2 .. c+1}^2 around c = round(p) as four 2x2 regions. A region with
// origin -1 looked up at p - 1/2 covers {c-2, c-1}; origin 0 looked up at p + 1/2 covers {c, c+1}.
const std::vector<Phase> kFootprint4 = {{{-1, -1}, {-0.5f, -0.5f}, {"", "-lower-left", 0}},
                                        {{0, -1}, {0.5f, -0.5f}, {"", "-lower-right", 1}},
                                        {{-1, 0}, {-0.5f, 0.5f}, {"", "-upper-left", 2}},
                                        {{0, 0}, {0.5f, 0.5f}, {"", "-upper-right", 3}}};

// Pass 1 (§4): the scene from the light once, encoded depth in R, G, B and A.
RenderTarget renderDepthAsColourFromLight(Passes& passes, const GpuScene& gpu,
                                          const RenderParams& params, const Texture& ramp) {
  RenderTarget map;
  passes.run("1", [&] {
    map = bs::makeEncodedDepthTarget(params);
    bs::renderEncodedDepth(gpu, params, ramp, map, glm::bvec4(true), glm::vec2(0.0f));
  });
  return map;
}

// Pass 2 (§4, Eq. 1, Figure 5): neighbour packing, one packed map per phase.
std::vector<RenderTarget> packNeighbours(Passes& passes, const RenderParams& params,
                                         const RenderTarget& encoded,
                                         const std::vector<Phase>& phases) {
  std::vector<RenderTarget> packed;
  passes.run("2", [&] {
    const Program& program = cachedProgram("fullscreen.vert.glsl", "fast_pcf_pack.frag.glsl");
    FullScreenTriangle triangle;
    glDisable(GL_DEPTH_TEST);
    for (const Phase& phase : phases) {
      const int n = params.shadowMapTexels;
      packed.push_back(makeRenderTarget(n, n, {bs::encodedDepthFormat(params)}, false));
      packed.back().bind();
      program.use();
      glActiveTexture(GL_TEXTURE0);
      glBindTexture(GL_TEXTURE_2D, encoded.color[0].id());
      program.set("uEncodedDepth", 0);
      gl::glUniform2i(program.uniform("uRegionOrigin"), phase.regionOrigin.x, phase.regionOrigin.y);
      triangle.draw();
      bs::setMapSampling(packed.back().color[0].id());
    }
    glEnable(GL_DEPTH_TEST);
  });
  return packed;
}

// Pass 3 (§3 Fig. 4, §4 Fig. 6, §5): legacy passes 3-7 in one camera pass, numbered 3, after
// the first pass it replaces.
// --param bias=normal-offset: the point moved along its normal in texgen.vert (ours, after
// Holbert 2011).
void shadowTestAndShade(Passes& passes, const GpuScene& gpu, const RenderParams& params,
                        const Texture& ramp, const std::vector<bs::SampleGroup>& groups) {
  const pcf_bias::Settings bias = pcf_bias::settings("modern.fast-pcf", params, bs::kBiasOffer);
  passes.run("3", [&] { bs::shadowTestAndShade(gpu, params, ramp, groups, passes.frame(), bias); });
}

Frame render(GlContext&, const Scene& scene, const RenderParams& params) {
  if (params.filter != 2 && params.filter != 4)
    throw InputError("modern.fast-pcf takes footprints 2 and 4 (--filter), got " +
                     std::to_string(params.filter));
  const std::vector<Phase>& phases = params.filter == 2 ? kFootprint2 : kFootprint4;
  Frame frame;
  Passes passes(frame, params, passTable());
  GpuScene gpu(scene);
  const Texture ramp = bs::makeRampTexture(params);
  const RenderTarget encoded = renderDepthAsColourFromLight(passes, gpu, params, ramp);
  passes.capture("1", "light-pass-depth-rgba",
                 [&] { return channel(readAttachment(encoded, 0), 0); });
  const std::vector<RenderTarget> packed = packNeighbours(passes, params, encoded, phases);
  std::vector<bs::SampleGroup> groups;
  for (size_t q = 0; q < packed.size(); ++q) {
    groups.push_back({packed[q].color[0].id(), 4, phases[q].offsetTexels});
    passes.capture("2", "packed-shadow-map{part}-rgba",
                   [&] { return readAttachment(packed[q], 0); }, phases[q].part,
                   {{"itself", packed.size() == 1 ? " = the texel itself" : ""}});
  }
  shadowTestAndShade(passes, gpu, params, ramp, groups);
  captureCameraPass(passes, "3");
  return frame;
}

}  // namespace

Technique fastPercentageCloserFilteringTechnique() {
  Technique t;
  t.name = "modern.fast-pcf";
  t.paper = "Brabec & Seidel 2001, §4 (as GLSL)";
  t.summary = "neighbour packing of Eq. 1 in a shader, (ds/2, dt/2) offset; 2x2 and 4x4";
  t.status = "complete";
  t.needs.profile = Profile::kCore;
  t.params = bs::params();
  for (const ParamSpec& spec : pcf_bias::params(bs::kBiasOffer)) t.params.push_back(spec);
  t.reads = {.shadowMap = true, .filter = true, .filterSides = {2, 4}, .precision = true};
  t.edge = Technique::Edge::kFiltered;                         // PCF over the --filter footprint
  t.plan.samples = PlanTraits::SampleGrouping::kPackedPhases;  // the twin of legacy.fast-pcf (§4)
  t.passes = passTable();
  t.render = render;
  return t;
}

}  // namespace sl::modern
