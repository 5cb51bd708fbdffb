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
#include <string>

#include "core/errors.h"
#include "core/pass_capture.h"
#include "modern/brabec_seidel.h"
#include "modern/brabec_seidel_techniques.h"
#include "modern/camera_pass.h"

namespace sl::modern {
using namespace sl::gl;

namespace {

constexpr int kSamplesPerMap = 4;  // R, G, B, A
constexpr int kLargestFootprint = 4;

// Figure 3: sample (i, j) of an n x n footprint (row by row from the bottom left, as
// legacy.pcf numbers them) lies at the centre of stratum (i, j) of the texel; the image plane
// moves by minus that position, so texel (x, y) stores the depth seen at its sample.
glm::vec2 jitterTexels(int i, int j, int n) {
  const glm::vec2 sample((float(i) + 0.5f) / float(n) - 0.5f, (float(j) + 0.5f) / float(n) - 0.5f);
  return -sample;
}

// Pass 1 (§3, Figure 3): n^2 jittered light passes packed four to a map, one channel each.
std::vector<RenderTarget> renderJitteredLightPasses(const GpuScene& gpu, const RenderParams& params,
                                                    const Texture& ramp, int n, Frame& frame) {
  PassTimer timer(frame, "1 jittered light passes (" + std::to_string(n * n) + ")");
  const int samples = n * n;
  std::vector<RenderTarget> maps;
  for (int k = 0; k < samples; ++k) {
    if (k % kSamplesPerMap == 0) maps.push_back(bs::makeEncodedDepthTarget(params));
    const int channel = k % kSamplesPerMap;
    const glm::bvec4 mask(channel == 0, channel == 1, channel == 2, channel == 3);
    bs::renderEncodedDepth(gpu, params, ramp, maps.back(), mask, jitterTexels(k % n, k / n, n));
  }
  return maps;
}

Frame render(GlContext&, const Scene& scene, const RenderParams& params) {
  const int n = params.filter;
  if (n < 1 || n > kLargestFootprint)
    throw InputError("modern.pcf takes footprints 1..4 (--filter), got " + std::to_string(n));
  Frame frame;
  GpuScene gpu(scene);
  const Texture ramp = bs::makeRampTexture(params);
  const std::vector<RenderTarget> maps = renderJitteredLightPasses(gpu, params, ramp, n, frame);
  std::vector<bs::SampleGroup> groups;
  for (size_t g = 0; g < maps.size(); ++g) {
    const int samples = std::min(kSamplesPerMap, n * n - int(g) * kSamplesPerMap);
    groups.push_back({maps[g].color[0].id(), samples, glm::vec2(0.0f)});
    if (params.capturePasses)
      frame.intermediates.push_back({"1-packed-jittered-map-" + std::to_string(g),
                                     "jittered light passes packed in R, G, B, A (Figure 3)",
                                     readAttachment(maps[g], 0)});
  }
  {
    PassTimer timer(frame, "2 camera pass: shadow test, colour table, colour matrix");
    bs::shadowTestAndShade(gpu, params, ramp, groups, frame);
  }
  if (params.capturePasses)
    captureCameraPass(frame, 2, "pcf_shadow.frag: shadow test, colour table, colour matrix (§3)");
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
  t.plan.samples = PlanTraits::SampleGrouping::kFourPerPass;  // the twin of legacy.pcf (§3)
  t.reads = {.shadowMap = true, .filter = true, .precision = true};
  t.render = render;
  return t;
}

}  // namespace sl::modern
