// modern.pcf — Brabec & Seidel 2001 §3: percentage-closer filtering (Reeves et al. 1987) by
// jittered channel packing, the colour table and the colour matrix, as shaders. Twin of
// legacy_gl's legacy.pcf.
//
// Passes:
//   1. renderJitteredLightPasses — footprint n x n: n^2 light passes, each with the image plane
//                                  jittered to one stratum of the texel (Figure 3) and writing
//                                  one colour channel (glColorMask); four samples per RGBA map
//   2. shadowTestAndShade        — pcf_shadow.frag: the fragment depth replicated over four
//                                  channels minus each packed map, colour table (0 or 64, 63 in
//                                  red) and colour matrix sum into alpha (Figure 4); groups summed
//                                  as the accumulation buffer does (3x3, 4x4); shading
// --param bias=normal-offset (modern/pcf_bias.h; ours, after Holbert 2011): texgen.vert moves
// the camera pass's point along its normal before texgen; constant, the default, moves nothing.
// The passes are declared once in pcfPasses().
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

constexpr int kSamplesPerMap = 4;  // R, G, B, A
constexpr int kLargestFootprint = 4;

// The passes, declared once: names, the paper's text, the buffers a dump shows, the GLSL they
// run and the passes of legacy.pcf (legacy_gl/pcf.cpp) they replace.
PassTable pcfPasses() {
  return {
      {.id = "1",
       .name = "jittered light passes",
       .reference = "Brabec & Seidel 2001 §3, Fig. 3",
       .writes = {{.name = "packed-jittered-map-{group}",
                   .caption = "jittered light passes packed in R, G, B, A (Figure 3)"}},
       .shaders = {"encode-depth"},
       .replaces = {"1"}},
      {.id = "2",
       .name = "camera pass = legacy passes 2-6: depth, subtract, colour table, colour matrix, "
               "accumulate, shade (pcf_shadow.frag)",
       .reference = "Brabec & Seidel 2001 §3 Figs. 3-4, §5",
       .writes =
           cameraPassBuffers("2", "pcf_shadow.frag: shadow test, colour table, colour matrix (§3)"),
       .shaders = {"vertex-normal-offset-bias", "camera-depth", "subtract-and-count", "accumulate",
                   "float-shadow", "shade"},
       .replaces = {"2", "2s", "2r", "3", "4", "5a", "5b", "6"},
       .deviations = {bs::kNormalOffsetDeviation}},
  };
}

const PassTable& passTable() {
  static const PassTable table = pcfPasses();
  return table;
}

// Figure 3: sample (i, j) of an n x n footprint (row by row from the bottom left, as
// legacy.pcf numbers them) lies at the centre of stratum (i, j) of the texel; the image plane
// moves by minus that position, so texel (x, y) stores the depth seen at its sample.
glm::vec2 jitterTexels(int i, int j, int n) {
  const glm::vec2 sample((float(i) + 0.5f) / float(n) - 0.5f, (float(j) + 0.5f) / float(n) - 0.5f);
  return -sample;
}

// Pass 1 (§3, Figure 3): n^2 jittered light passes packed four to a map, one channel each.
std::vector<RenderTarget> renderJitteredLightPasses(Passes& passes, const GpuScene& gpu,
                                                    const RenderParams& params, const Texture& ramp,
                                                    int n) {
  const int samples = n * n;
  std::vector<RenderTarget> maps;
  passes.run(
      "1",
      [&] {
        for (int k = 0; k < samples; ++k) {
          if (k % kSamplesPerMap == 0) maps.push_back(bs::makeEncodedDepthTarget(params));
          const int channel = k % kSamplesPerMap;
          const glm::bvec4 mask(channel == 0, channel == 1, channel == 2, channel == 3);
          bs::renderEncodedDepth(gpu, params, ramp, maps.back(), mask,
                                 jitterTexels(k % n, k / n, n));
        }
      },
      {}, " (" + std::to_string(samples) + ")");
  return maps;
}

// Pass 2 (§3 Figs. 3-4, §5): legacy passes 2-6 in one camera pass, numbered 2, after the first
// pass it replaces.
// --param bias=normal-offset: the point moved along its normal in texgen.vert (ours, after
// Holbert 2011).
void shadowTestAndShade(Passes& passes, const GpuScene& gpu, const RenderParams& params,
                        const Texture& ramp, const std::vector<bs::SampleGroup>& groups) {
  const pcf_bias::Settings bias = pcf_bias::settings("modern.pcf", params, bs::kBiasOffer);
  passes.run("2", [&] { bs::shadowTestAndShade(gpu, params, ramp, groups, passes.frame(), bias); });
}

Frame render(GlContext&, const Scene& scene, const RenderParams& params) {
  const int n = params.filter;
  if (n < 1 || n > kLargestFootprint)
    throw InputError("modern.pcf takes footprints 1..4 (--filter), got " + std::to_string(n));
  Frame frame;
  Passes passes(frame, params, passTable());
  GpuScene gpu(scene);
  const Texture ramp = bs::makeRampTexture(params);
  const std::vector<RenderTarget> maps = renderJitteredLightPasses(passes, gpu, params, ramp, n);
  std::vector<bs::SampleGroup> groups;
  for (size_t g = 0; g < maps.size(); ++g) {
    const int samples = std::min(kSamplesPerMap, n * n - int(g) * kSamplesPerMap);
    groups.push_back({maps[g].color[0].id(), samples, glm::vec2(0.0f)});
    passes.capture("1", "packed-jittered-map-{group}", [&] { return readAttachment(maps[g], 0); },
                   {}, {{"group", std::to_string(g)}});
  }
  shadowTestAndShade(passes, gpu, params, ramp, groups);
  captureCameraPass(passes, "2");
  return frame;
}

}  // namespace

Technique percentageCloserFilteringTechnique() {
  Technique t;
  t.name = "modern.pcf";
  t.paper = "Brabec & Seidel 2001, §3 (as GLSL)";
  t.summary = "jittered 4-channel packing, colour table + colour matrix in a shader; 2x2..4x4";
  t.status = "complete";
  t.needs.profile = Profile::kCore;
  t.params = bs::params();
  for (const ParamSpec& spec : pcf_bias::params(bs::kBiasOffer)) t.params.push_back(spec);
  t.plan.samples = PlanTraits::SampleGrouping::kFourPerPass;  // the twin of legacy.pcf (§3)
  t.reads = {.shadowMap = true, .filter = true, .precision = true};
  t.edge = Technique::Edge::kFiltered;  // PCF over the --filter footprint
  t.passes = passTable();
  t.render = render;
  return t;
}

}  // namespace sl::modern
