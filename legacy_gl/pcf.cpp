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
//                                  (drawn once: it is the same for every group)
//   2s. saveCameraPassForGroups  — 3x3 and 4x4: the camera pass copied to a texture once
//   2r. restoreCameraPassForGroup — groups 2 on: the copy drawn back (the subtraction of pass 3
//                                  overwrites the camera pass; DEVIATION in the table)
//   3. subtractPackedMap         — the packed map projected and subtracted: four-component
//                                  shadow mask (Reeves' comparison step)
//   4. countShadowedSamples      — glCopyPixels through the colour table (0 or 64; 63 in alpha,
//                                  footnote 2) and the colour matrix that sums the channels into
//                                  alpha (Fig. 4): 0, 25, 50, 75, 100 % shadow
//   5a. accumulateGroup          — 3x3 and 4x4 footprints: each group's alpha weighted by its
//                                  share of the samples, summed in the accumulation buffer
//   5b. returnAccumulatedGroups  — 3x3 and 4x4: the sum back into the colour buffer
//   6. shade                     — OpenGL lighting, direct light x (1 - alpha) + ambient (§5)
// Visibility = 1 - alpha (brabec_seidel.h). The passes are declared once in pcfPasses().
#include <algorithm>
#include <memory>
#include <string>

#include "core/base/errors.h"
#include "core/gl/gl.h"
#include "core/technique/passes.h"
#include "legacy_gl/brabec_seidel.h"
#include "legacy_gl/brabec_seidel_passes.h"
#include "legacy_gl/projected_spotlight.h"
#include "legacy_gl/spotlight_tessellation.h"

namespace sl::legacy {
using namespace sl::gl;

namespace {

constexpr int kSamplesPerGroup = 4;              // R, G, B, A of one texel (§3)
constexpr float kDifferenceDisplayGain = 32.0f;  // a few depth steps made visible in dumps

// The passes of §3, declared once: names, the paper's text, the buffers a dump shows, floors.
PassTable pcfPasses() {
  using F = PassFloor;
  const std::string gain = std::to_string(int(kDifferenceDisplayGain));
  return {
      meshFeedingPass(),
      {.id = "1",
       .name = "light passes: jittered, one channel each + copy to texture",
       .reference = "Brabec & Seidel 2001 §3, Fig. 3: stratified sampling and pixel packing, one "
                    "jittered light pass per colour channel",
       .writes = {{.name = "light-pass{part}-{channel}-channel",
                   .caption = "Pass 1: light pass {sample}, image plane jittered to its sub-texel "
                              "sample, written to {channel} only (Fig. 3)"},
                  {.name = "packed-shadow-map{part}-rgb",
                   .caption = "The packed map: four depth samples per texel (R, G, B shown as "
                              "colour)"},
                  // Fig. 3's jitter made visible: the four samples of a texel differ only where
                  // a sub-texel offset moves one across a depth edge or along a slope.
                  {.name = "jittered-samples-minus-mean{part}",
                   .caption = "The four jittered samples minus their mean (R | G | B | A), "
                              "amplified " +
                              gain +
                              "x, grey = equal: the sub-texel jitter of "
                              "Fig. 3"}},
       .floor = F::kJitteredLightGroup,
       .role = PassRole::kLight,
       .deviations = {kOffscreenLightPassDeviation, bs::kFloatChannelsDeviation},
       .keyState = {"projection: load", "glColorMask", "glCopyTexSubImage2D"}},
      {.id = "2",
       .name = "camera pass: light depth in RGBA",
       .reference = "Brabec & Seidel 2001 §3: \"we replicate the z values over all four color "
                    "channels\" (the ramp of §2)",
       .writes = {{.name = "camera-pass-z-replicated",
                   .caption = "Pass 2: light depth of each visible point in all four "
                              "channels{again}"}},
       .floor = F::kCameraDepth,
       .role = PassRole::kCamera,
       .deviations = {bs::kDepthBiasDeviation},
       .keyState = {"texture matrix (unit 0): load", "GL_TEXTURE_1D = texture"}},
      // §3 prescribes no redraw: "another eight passes are necessary to perform the
      // subtraction" (4x4) counts a camera pass and a subtraction per group, the cost of the
      // in-place subtraction, not a step of the method; the camera pass is the same each time.
      {.id = "2s",
       .name = "camera pass saved: copy to texture",
       .reference = "ours, 3x3 and 4x4 only: the camera pass copied once (glCopyTexSubImage2D) "
                    "for groups 2 on, instead of drawing it again in each (Brabec & Seidel 2001 "
                    "§3 counts the redraws, \"another eight passes ... to perform the "
                    "subtraction\", and does not require them)",
       .floor = F::kCopyWindowToTexture,
       .role = PassRole::kCopyToTexture,
       .deviations = {bs::kCameraPassCopyDeviation}},
      {.id = "2r",
       .name = "camera pass restored from its copy",
       .reference = "ours, 3x3 and 4x4 groups 2 on: the saved camera pass drawn back as one "
                    "textured full-window quad, where §3 draws the camera pass again",
       .floor = F::kTexturedWindowQuad,
       .role = PassRole::kCamera,
       .deviations = {bs::kCameraPassCopyDeviation}},
      {.id = "3",
       .name = "projective pass: subtract packed map",
       .reference = "Brabec & Seidel 2001 §3 (Reeves' comparison step, Fig. 2): the subtraction "
                    "of §2 on four channels at once",
       .writes = {{.name = "mask-before-colour-table{part}-rgba-x" + gain,
                   .caption = "Pass 3: camera depth minus each of the four map samples (R | G | "
                              "B | A), amplified " +
                              gain +
                              "x: > 0 = that sample shadows the "
                              "point"}},
       .floor = F::kProjectiveSubtract,
       .role = PassRole::kProjective,
       .keyState = {"GL_FUNC_REVERSE_SUBTRACT", "glBlendFunc(GL_ONE, GL_ONE)",
                    "GL_TEXTURE_2D = texture", "glDepthFunc(GL_LEQUAL)"}},
      {.id = "4",
       .name = "copy: colour table + colour matrix -> alpha",
       .reference = "Brabec & Seidel 2001 §3, Fig. 4: colour table 0 / 64 (63 in alpha), colour "
                    "matrix sums the channels into alpha",
       .writes = {{.name = "mask-after-colour-table{part}-rgba",
                   .caption = "The same read through the colour table only: 0 or 64 (63 in "
                              "alpha)"},
                  {.name = "alpha-after-colour-matrix{part}",
                   .caption = "Pass 4: alpha after the colour matrix summed the channels: share "
                              "of shadowed samples (white = all)"}},
       .floor = F::kCopyPixels,
       .role = PassRole::kCopy,
       .keyState = {"GL_COLOR_TABLE [", "colour matrix: load [0 0 0 0", "glCopyPixels"}},
      {.id = "5a",
       .name = "accumulate",
       .reference = "Brabec & Seidel 2001 §3: larger footprints in parts of four, \"summed up "
                    "using the accumulation buffer [3]\"",
       .floor = F::kAccumulate,
       .role = PassRole::kAccumulate,
       .keyState = {"glAccum"}},
      {.id = "5b",
       .name = "accumulation return",
       .reference = "Brabec & Seidel 2001 §3: the accumulation buffer's sum returned to the "
                    "colour buffer",
       .writes = {{.name = "accumulation-result-alpha",
                   .caption = "Pass 5: the groups summed in the accumulation buffer (white = all "
                              "shadowed)"}},
       .floor = F::kAccumulationReturn,
       .role = PassRole::kAccumulationReturn,
       .keyState = {"glAccum(GL_RETURN"}},
      {.id = "6",
       .name = "lighting x shadow term",
       .reference = "Brabec & Seidel 2001 §5 (\"normal OpenGL lighting\"): direct light x "
                    "(1 - shadow), ambient kept",
       .writes = {{.name = "shaded",
                   .caption = "Pass 6: OpenGL lighting x (1 - shadow) + ambient"}},
       .floor = F::kLighting,
       .role = PassRole::kLighting,
       .deviations = {kProjectedConeDeviation},
       .keyState = {"GL_ONE_MINUS_DST_ALPHA", "GL_LIGHT_MODEL_AMBIENT", "GL_LIGHT0 GL_DIFFUSE"}},
  };
}

const PassTable& passTable() {
  static const PassTable table = pcfPasses();
  return table;
}

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
  bs::SavedCameraPass savedCamera;                          // 3x3, 4x4: pass 2 for groups 2 on
};

// Group g's runs of passes 1-5a: " (group 2)" and "-group2" when there are several groups.
PassPart groupPart(size_t g, size_t groups) {
  if (groups == 1) return {};
  return {"(group " + std::to_string(g + 1) + ")", "-group" + std::to_string(g + 1), int(g)};
}

// Pass 1 (Fig. 3): one jittered light pass per sample into its channel, then the copy. The
// jitter moves the image plane by minus the sample's offset, so texel (x, y) stores the depth
// seen at (x + 0.5 + offset, y + 0.5 + offset) in texels.
void renderJitteredLightPasses(Passes& passes, const Scene& scene, const RenderParams& params,
                               PcfState& s, size_t g, const std::vector<Sample>& group) {
  passes.run(
      "1",
      [&] {
        const int n = params.shadowMapTexels;
        LightTarget target(n, n <= params.width && n <= params.height, true, s.enc.mapFormat);
        target.bind();
        for (size_t k = 0; k < group.size(); ++k)
          bs::renderLightDepth(scene, s.enc, s.ramp, n, -group[k].subTexel,
                               bs::onlyChannel(group[k].channel), k == 0);
        bs::copyLightPassToMap(*s.maps[g], n);
        target.unbind();
      },
      groupPart(g, s.maps.size()));
}

// Pass 2 (§3): "we replicate the z values over all four color channels".
void renderReplicatedCameraDepth(Passes& passes, const Scene& scene, const RenderParams& params,
                                 PcfState& s) {
  passes.run("2", [&] {
    bs::renderCameraDepth(scene, params, s.enc, s.ramp, bs::depthBias(params, s.enc),
                          bs::kAllChannels);
  });
}

// Pass 2s (3x3, 4x4, group 1): the camera pass kept in a texture for the other groups.
void saveCameraPassForGroups(Passes& passes, const RenderParams& params, PcfState& s) {
  passes.run("2s", [&] {
    bs::allocateSavedCameraPass(s.savedCamera, params, s.enc);
    bs::saveCameraPass(s.savedCamera, params);
  });
}

// Pass 2r (3x3, 4x4, groups 2 on): the camera pass back from its copy (pass 3 overwrote it).
void restoreCameraPassForGroup(Passes& passes, const RenderParams& params, PcfState& s,
                               const PassPart& part) {
  passes.run(
      "2r", [&] { bs::restoreCameraPass(s.savedCamera, params); }, part);
}

// Pass 3 (§3, Reeves' comparison step): four-component shadow mask.
void subtractPackedMap(Passes& passes, const Scene& scene, const RenderParams& params, PcfState& s,
                       size_t g, const PassPart& part) {
  passes.run(
      "3",
      [&] {
        bs::subtractProjectedMap(scene, params, *s.maps[g], glm::vec2(0.0f), bs::kAllChannels);
      },
      part);
}

// Pass 4 (Fig. 4): colour table + colour matrix on a framebuffer-to-framebuffer copy.
void countShadowedSamples(Passes& passes, const RenderParams& params, PcfState& s, int samples,
                          const PassPart& part) {
  passes.run(
      "4", [&] { bs::countShadowSamplesByCopy(params, s.enc, samples); }, part);
}

// Pass 5a (§3 "summed up using the accumulation buffer [3]").
void accumulateGroup(Passes& passes, double weight, bool first, const PassPart& part) {
  passes.run(
      "5a", [&] { bs::accumulateGroup(weight, first); }, part);
}

// Pass 5b (§3): the accumulation buffer's sum back into the colour buffer.
void returnAccumulatedGroups(Passes& passes) {
  passes.run("5b", [&] { bs::returnAccumulation(); });
}

// Pass 6 (§5 "normal OpenGL lighting").
void shade(Passes& passes, const Scene& scene, const RenderParams& params) {
  const SpotlightConeTexture cone;  // untimed: the same texture for every light and scene
  passes.run("6", [&] { bs::shadeWithShadowTerm(scene, params, cone); });
}

Frame render(GlContext& context, const Scene& scene, const RenderParams& params) {
  (void)context;
  const int side = bs::footprintSide(params, "legacy.pcf");
  const auto groups = footprintGroups(side);
  const int footprintSamples = side * side;
  Frame frame;
  Passes passes(frame, params, passTable());
  // The camera passes draw the scene split for per-vertex spotlight lighting (same geometry).
  const Scene camera = cameraPassScene(scene, params, passes);
  PcfState s;
  s.enc = bs::depthEncoding(params.precision);
  bs::createRampTexture(s.ramp, s.enc);
  for (size_t g = 0; g < groups.size(); ++g) {
    s.maps.push_back(std::make_unique<bs::ShadowMapTexture>());
    bs::allocateShadowMap(*s.maps.back(), s.enc, params.shadowMapTexels);
  }
  // §3: the map generation first ("16 rendering passes and four RGBA texture maps" at 4x4).
  for (size_t g = 0; g < groups.size(); ++g) {
    const PassPart part = groupPart(g, groups.size());
    renderJitteredLightPasses(passes, scene, params, s, g, groups[g]);
    for (size_t k = 0; k < groups[g].size(); ++k) {
      const int c = groups[g][k].channel;
      passes.capture(
          "1", "light-pass{part}-{channel}-channel",
          [&] { return channel(bs::readShadowMap(*s.maps[g], params.shadowMapTexels), c); }, part,
          {{"channel", bs::channelName(c)},
           {"sample", std::to_string(g * kSamplesPerGroup + k + 1)}});
    }
    passes.capture(
        "1", "packed-shadow-map{part}-rgb",
        [&] { return toRgb(bs::readShadowMap(*s.maps[g], params.shadowMapTexels)); }, part);
    passes.capture(
        "1", "jittered-samples-minus-mean{part}",
        [&] {
          return bs::channelsMinusCentre(bs::readShadowMap(*s.maps[g], params.shadowMapTexels), -1,
                                         kDifferenceDisplayGain);
        },
        part);
  }
  const std::string again = groups.size() > 1
                                ? " (the same for each of the " + std::to_string(groups.size()) +
                                      " groups: copied once, restored before groups 2-" +
                                      std::to_string(groups.size()) + ")"
                                : "";
  for (size_t g = 0; g < groups.size(); ++g) {
    const PassPart part = groupPart(g, groups.size());
    const int samples = int(groups[g].size());
    // The camera pass is the same for every group (only passes 1, 3 and 4 depend on it): drawn
    // for the first, copied, and restored from the copy for the others; one file.
    if (g == 0) {
      renderReplicatedCameraDepth(passes, camera, params, s);
      passes.capture("2", "camera-pass-z-replicated",
                     [&] { return toRgb(bs::readWindowRgba(params)); }, {}, {{"again", again}});
      if (groups.size() > 1) saveCameraPassForGroups(passes, params, s);
    } else {
      restoreCameraPassForGroup(passes, params, s, part);
    }
    subtractPackedMap(passes, camera, params, s, g, part);
    passes.capture(
        "3", "mask-before-colour-table{part}-rgba-x32",
        [&] {
          return bs::channelPanels(
              bs::amplified(bs::readWindowRgba(params), kDifferenceDisplayGain));
        },
        part);
    passes.capture(
        "4", "mask-after-colour-table{part}-rgba",
        [&] { return bs::channelPanels(bs::readThroughColorTable(params, s.enc, samples)); }, part);
    countShadowedSamples(passes, params, s, samples, part);
    passes.capture(
        "4", "alpha-after-colour-matrix{part}",
        [&] { return bs::alphaOf(bs::readWindowRgba(params)); }, part);
    if (groups.size() > 1)
      accumulateGroup(passes, double(samples) / footprintSamples, g == 0, part);
  }
  if (groups.size() > 1) {
    returnAccumulatedGroups(passes);
    passes.capture("5b", "accumulation-result-alpha",
                   [&] { return bs::alphaOf(bs::readWindowRgba(params)); });
  }
  shade(passes, camera, params);
  frame.color = readRgb(params.width, params.height);
  frame.visibility = bs::readVisibilityFromAlpha(params);
  passes.capture("6", "shaded", [&] { return frame.color; });
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
  t.edge = Technique::Edge::kFiltered;                        // PCF over the --filter footprint
  t.plan.samples = PlanTraits::SampleGrouping::kFourPerPass;  // §3: one sample per channel
  t.plan.colourTableCompare = true;                           // §3 Fig. 4
  t.plan.colourMatrixSum = true;
  t.passes = passTable();
  t.render = render;
  return t;
}

}  // namespace sl::legacy
