// legacy.pcf — Stefan Brabec and Hans-Peter Seidel, "Hardware-accelerated Rendering of
// Antialiased Shadows with Shadow Maps", CGI 2001, §3: Reeves' percentage closer filtering with
// a constant n x n footprint, mapped onto the OpenGL imaging subset.
//
// Passes (per group of at most four footprint samples, §3 last paragraphs):
//   1. renderJitteredLightPasses — one light pass per sample, image plane jittered to the
//                                  sample's sub-texel position, written into one colour channel
//                                  (glColorMask), copied into an RGBA map (stratified sampling
//                                  and pixel packing, Fig. 3)
//   2. renderReplicatedCameraDepth — the camera pass with the light depth in all four channels
//   3. subtractPackedMap         — the packed map projected and subtracted: four-component
//                                  shadow mask (Reeves' comparison step)
//   4. countShadowedSamples      — glCopyPixels through the colour table (0 or 64; 63 in alpha,
//                                  footnote 2) and the colour matrix that sums the channels into
//                                  alpha (Fig. 4): 0, 25, 50, 75, 100 % shadow
//   5. accumulateGroups          — 3x3 and 4x4 footprints: each group's alpha weighted by its
//                                  share of the samples, summed in the accumulation buffer
//   6. shade                     — OpenGL lighting, direct light x (1 - alpha) + ambient (§5)
// Visibility = 1 - alpha (brabec_seidel.h).
#include <algorithm>
#include <memory>
#include <string>

#include "core/errors.h"
#include "core/gl.h"
#include "legacy_gl/brabec_seidel.h"
#include "legacy_gl/brabec_seidel_passes.h"
#include "legacy_gl/spotlight_tessellation.h"

namespace sl::legacy {
using namespace sl::gl;

namespace {

constexpr int kSamplesPerGroup = 4;              // R, G, B, A of one texel (§3)
constexpr float kDifferenceDisplayGain = 32.0f;  // a few depth steps made visible in dumps

struct Sample {
  glm::vec2 subTexel;  // position inside the texel, relative to its centre, in texels
  int channel;         // colour channel of its group's map
};

// Fig. 3: the n x n samples of a texel on a regular (stratified) grid, row by row from the
// bottom left; four consecutive samples share one RGBA map.
std::vector<std::vector<Sample>> footprintGroups(int side) {
  std::vector<std::vector<Sample>> groups;
  for (int k = 0; k < side * side; ++k) {
    const int i = k % side, j = k / side;
    if (k % kSamplesPerGroup == 0) groups.emplace_back();
    const glm::vec2 at((float(i) + 0.5f) / float(side) - 0.5f,
                       (float(j) + 0.5f) / float(side) - 0.5f);
    groups.back().push_back({at, k % kSamplesPerGroup});
  }
  return groups;
}

struct PcfState {
  bs::DepthEncoding enc;
  bs::RampTexture ramp;
  std::vector<std::unique_ptr<bs::ShadowMapTexture>> maps;  // one RGBA map per group
};

// Pass-name suffix " (group 2)" and file-name suffix "-group2" when there are several groups.
std::string groupTag(size_t g, size_t groups) {
  return groups == 1 ? std::string() : " (group " + std::to_string(g + 1) + ")";
}
std::string groupFileTag(size_t g, size_t groups) {
  return groups == 1 ? std::string() : "-group" + std::to_string(g + 1);
}

// Pass 1 (Fig. 3): one jittered light pass per sample into its channel, then the copy. The
// jitter moves the image plane by minus the sample's offset, so texel (x, y) stores the depth
// seen at (x + 0.5 + offset, y + 0.5 + offset) in texels.
void renderJitteredLightPasses(const Scene& scene, const RenderParams& params, PcfState& s,
                               size_t g, const std::vector<Sample>& group, Frame& frame) {
  PassTimer timer(
      frame,
      "1 light passes: jittered, one channel each + copy to texture" + groupTag(g, s.maps.size()),
      "Brabec & Seidel 2001 §3, Fig. 3: stratified sampling and pixel packing, one "
      "jittered light pass per colour channel");
  const int n = params.shadowMapTexels;
  LightTarget target(n, n <= params.width && n <= params.height, true, s.enc.mapFormat);
  target.bind();
  for (size_t k = 0; k < group.size(); ++k)
    bs::renderLightDepth(scene, s.enc, s.ramp, n, -group[k].subTexel,
                         bs::onlyChannel(group[k].channel), k == 0);
  bs::copyLightPassToMap(*s.maps[g], n);
  target.unbind();
}

// Pass 2 (§3): "we replicate the z values over all four color channels".
void renderReplicatedCameraDepth(const Scene& scene, const RenderParams& params, PcfState& s,
                                 Frame& frame, const std::string& tag) {
  PassTimer timer(frame, "2 camera pass: light depth in RGBA" + tag,
                  "Brabec & Seidel 2001 §3: \"we replicate the z values over all four color "
                  "channels\" (the ramp of §2)");
  bs::renderCameraDepth(scene, params, s.enc, s.ramp, bs::depthBias(params, s.enc),
                        bs::kAllChannels);
}

// Pass 3 (§3, Reeves' comparison step): four-component shadow mask.
void subtractPackedMap(const Scene& scene, const RenderParams& params, PcfState& s, size_t g,
                       Frame& frame, const std::string& tag) {
  PassTimer timer(frame, "3 projective pass: subtract packed map" + tag,
                  "Brabec & Seidel 2001 §3 (Reeves' comparison step, Fig. 2): the subtraction "
                  "of §2 on four channels at once");
  bs::subtractProjectedMap(scene, params, *s.maps[g], glm::vec2(0.0f), bs::kAllChannels);
}

// Pass 4 (Fig. 4): colour table + colour matrix on a framebuffer-to-framebuffer copy.
void countShadowedSamples(const RenderParams& params, PcfState& s, int samples, Frame& frame,
                          const std::string& tag) {
  PassTimer timer(frame, "4 copy: colour table + colour matrix -> alpha" + tag,
                  "Brabec & Seidel 2001 §3, Fig. 4: colour table 0 / 64 (63 in alpha), colour "
                  "matrix sums the channels into alpha");
  bs::countShadowSamplesByCopy(params, s.enc, samples);
}

// Pass 5 (§3 "summed up using the accumulation buffer [3]").
void accumulateGroup(double weight, bool first, Frame& frame, const std::string& tag) {
  PassTimer timer(frame, "5 accumulate" + tag,
                  "Brabec & Seidel 2001 §3: larger footprints in parts of four, \"summed up "
                  "using the accumulation buffer [3]\"");
  bs::accumulateGroup(weight, first);
}

// Pass 6 (§5 "normal OpenGL lighting").
void shade(const Scene& scene, const RenderParams& params, Frame& frame) {
  PassTimer timer(frame, "6 lighting x shadow term",
                  "Brabec & Seidel 2001 §5 (\"normal OpenGL lighting\"): direct light x "
                  "(1 - shadow), ambient kept");
  bs::shadeWithShadowTerm(scene, params);
}

Frame render(GlContext& context, const Scene& scene, const RenderParams& params) {
  (void)context;
  const int side = bs::footprintSide(params, "legacy.pcf");
  const auto groups = footprintGroups(side);
  const int footprintSamples = side * side;
  Frame frame;
  // The camera passes draw the scene split for per-vertex spotlight lighting (same geometry).
  const Scene camera = cameraPassScene(scene, params, frame);
  PcfState s;
  s.enc = bs::depthEncoding(params.precision);
  bs::createRampTexture(s.ramp, s.enc);
  for (size_t g = 0; g < groups.size(); ++g) {
    s.maps.push_back(std::make_unique<bs::ShadowMapTexture>());
    bs::allocateShadowMap(*s.maps.back(), s.enc, params.shadowMapTexels);
  }

  // §3: the map generation first ("16 rendering passes and four RGBA texture maps" at 4x4).
  for (size_t g = 0; g < groups.size(); ++g) {
    renderJitteredLightPasses(scene, params, s, g, groups[g], frame);
    if (params.capturePasses) {
      const Image map = bs::readShadowMap(*s.maps[g], params.shadowMapTexels);
      const std::string tag = groupFileTag(g, groups.size());
      for (size_t k = 0; k < groups[g].size(); ++k) {
        const int c = groups[g][k].channel;
        bs::capture(frame, params, "1-light-pass" + tag + "-" + bs::channelName(c) + "-channel",
                    "Pass 1: light pass " + std::to_string(g * kSamplesPerGroup + k + 1) +
                        ", image plane jittered to its sub-texel sample, written to " +
                        bs::channelName(c) + " only (Fig. 3)",
                    channel(map, c));
      }
      bs::capture(frame, params, "1-packed-shadow-map" + tag + "-rgb",
                  "The packed map: four depth samples per texel (R, G, B shown as colour)",
                  toRgb(map));
      // Fig. 3's jitter made visible: the four samples of a texel differ only where a sub-texel
      // offset moves one across a depth edge or along a slope.
      bs::capture(frame, params, "1-jittered-samples-minus-mean" + tag,
                  "The four jittered samples minus their mean (R | G | B | A), amplified " +
                      std::to_string(int(kDifferenceDisplayGain)) +
                      "x, grey = equal: the sub-texel jitter of Fig. 3",
                  bs::channelsMinusCentre(map, -1, kDifferenceDisplayGain));
    }
  }
  for (size_t g = 0; g < groups.size(); ++g) {
    const std::string tag = groupTag(g, groups.size());
    const std::string file = groupFileTag(g, groups.size());
    const int samples = int(groups[g].size());
    renderReplicatedCameraDepth(camera, params, s, frame, tag);
    if (params.capturePasses)
      bs::capture(frame, params, "2-camera-pass-z-replicated" + file,
                  "Pass 2: light depth of each visible point in all four channels",
                  toRgb(bs::readWindowRgba(params)));
    subtractPackedMap(camera, params, s, g, frame, tag);
    if (params.capturePasses) {
      const Image mask = bs::readWindowRgba(params);
      bs::capture(frame, params, "3-mask-before-colour-table" + file + "-rgba-x32",
                  "Pass 3: camera depth minus each of the four map samples (R | G | B | A), "
                  "amplified 32x: > 0 = that sample shadows the point",
                  bs::channelPanels(bs::amplified(mask, kDifferenceDisplayGain)));
      bs::capture(frame, params, "4-mask-after-colour-table" + file + "-rgba",
                  "The same read through the colour table only: 0 or 64 (63 in alpha)",
                  bs::channelPanels(bs::readThroughColorTable(params, s.enc, samples)));
    }
    countShadowedSamples(params, s, samples, frame, tag);
    if (params.capturePasses)
      bs::capture(frame, params, "4-alpha-after-colour-matrix" + file,
                  "Pass 4: alpha after the colour matrix summed the channels: share of shadowed "
                  "samples (white = all)",
                  bs::alphaOf(bs::readWindowRgba(params)));
    if (groups.size() > 1) accumulateGroup(double(samples) / footprintSamples, g == 0, frame, tag);
  }
  if (groups.size() > 1) {
    {
      PassTimer timer(frame, "5 accumulation return",
                      "Brabec & Seidel 2001 §3: the accumulation buffer's sum returned to the "
                      "colour buffer");
      bs::returnAccumulation();
    }
    if (params.capturePasses)
      bs::capture(frame, params, "5-accumulation-result-alpha",
                  "Pass 5: the groups summed in the accumulation buffer (white = all shadowed)",
                  bs::alphaOf(bs::readWindowRgba(params)));
  }
  shade(camera, params, frame);
  frame.color = readRgb(params.width, params.height);
  frame.visibility = bs::readVisibilityFromAlpha(params);
  if (params.capturePasses)
    bs::capture(frame, params, "6-shaded", "Pass 6: OpenGL lighting x (1 - shadow) + ambient",
                frame.color);
  frame.counters["footprint samples"] = footprintSamples;
  frame.counters["light passes"] = footprintSamples;
  checkGl("legacy.pcf");
  return frame;
}

}  // namespace

Technique pcfTechnique() {
  Technique t;
  t.name = "legacy.pcf";
  t.paper = "Brabec & Seidel 2001, §3";
  t.summary = "PCF: jittered light passes packed in RGBA, colour table + colour matrix count";
  t.status = "complete";
  t.needs.profile = Profile::kCompatibility;
  t.needs.accumulation = true;
  t.needs.colorFromPrecision = true;
  t.params = {bs::depthBiasParam()};
  t.reads = {.shadowMap = true, .filter = true, .precision = true};
  t.plan.samples = PlanTraits::SampleGrouping::kFourPerPass;  // §3: one sample per channel
  t.plan.colourTableCompare = true;                           // §3 Fig. 4
  t.plan.colourMatrixSum = true;
  t.render = render;
  return t;
}

}  // namespace sl::legacy
