// legacy.fast-pcf — Stefan Brabec and Hans-Peter Seidel, "Hardware-accelerated Rendering of
// Antialiased Shadows with Shadow Maps", CGI 2001, §4 "Fast PCF for Real-Time Applications":
// one light pass at full resolution; the imaging subset's convolution packs each texel's 2x2
// neighbourhood into its four channels while the framebuffer is copied to the texture.
//
// Passes:
//   1. renderDepthIntoAllChannels — one light pass, the encoded depth in R, G, B and A (§4)
//   2. packNeighboursByConvolution — glCopyTexSubImage2D with GL_CONVOLUTION_2D and the 3x3
//                                  kernel of Eq. (1): R = lower left, G = lower mid, B = mid
//                                  left, A = centre, i.e. the texel itself (Fig. 5); at 4x4
//                                  once per phase with the kernel moved to the phase's 2x2
//                                  region
//   3. renderReplicatedCameraDepth — the camera pass with the light depth in all four channels
//   3s. saveCameraPassForPhases   — 4x4 only: the camera pass copied to a texture once
//   3r. restoreCameraPassForPhase — 4x4 phases 2-4: the copy drawn back (the subtraction of
//                                  pass 4 overwrites the camera pass; DEVIATION in the table)
//   4. subtractPackedMap           — the packed map projected with texture coordinates offset
//                                  by (ds/2, dt/2) (Fig. 6) and subtracted
//   5. countShadowedSamples        — glCopyPixels through the colour table and the colour matrix
//                                  (as §3, Fig. 4): 5 levels per phase
//   6a. accumulatePhase            — 4x4 only, once per phase: the upper-left, upper-right,
//                                  lower-left and lower-right 2x2 regions summed in the
//                                  accumulation buffer, weight 1/4 each (§4 counts 4 x 5 = 20
//                                  levels; the sums take 17)
//   6b. returnAccumulatedPhases    — 4x4 only: the sum back into the colour buffer
//   7. shade                       — OpenGL lighting, direct light x (1 - alpha) + ambient (§5)
// Visibility = 1 - alpha (brabec_seidel.h). The passes are declared once in fastPcfPasses().
#include <memory>
#include <string>
#include <vector>

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

constexpr int kPackedSamples = 4;                // one 2x2 region per packed texel
constexpr float kDifferenceDisplayGain = 32.0f;  // a few depth steps made visible in dumps
constexpr float kHalfTexel = 0.5f;
constexpr int kTexelItselfChannel = 3;  // A: the upper right of the 2x2 region (Eq. (1) centre)

// The passes of §4, declared once: names, the paper's text, the buffers a dump shows, floors.
PassTable fastPcfPasses() {
  using F = PassFloor;
  const std::string gain = std::to_string(int(kDifferenceDisplayGain));
  return {
      meshFeedingPass(),
      {.id = "1",
       .name = "light pass: depth ramp in RGBA",
       .reference = "Brabec & Seidel 2001 §4: the map rendered as in §2 (Fig. 1), the encoded "
                    "depth in all four channels",
       .writes = {{.name = "light-pass-depth-rgba",
                   .caption = "Pass 1: one light pass, encoded depth in all four channels (one "
                              "shown)"}},
       .floor = F::kLightDepth,
       .role = PassRole::kLight,
       .deviations = {kOffscreenLightPassDeviation, bs::kFloatChannelsDeviation},
       .keyState = {"rising in 256 steps", "texture matrix (unit 0): load", "GL_EYE_PLANE"}},
      {.id = "2",
       .name = "copy to texture through the 3x3 packing convolution",
       .reference = "Brabec & Seidel 2001 §4, Eq. (1), Fig. 5",
       .writes = {{.name = "packed-shadow-map{part}-rgba",
                   .caption = "Pass 2: the packed map, R | G | B | A = lower left, lower right, "
                              "upper left, upper right of each texel's 2x2 region (Fig. 5)",
                   .centreChannel = kTexelItselfChannel,
                   .channelMeaning = {"lower left", "lower right", "upper left",
                                      "upper right{itself}"}},
                  // Fig. 5's one-texel shift made visible: G, B and A minus R, the lower-left
                  // neighbour, non-grey along every depth edge, one texel to the side the other
                  // channel's texel lies on.
                  {.name = "packed-neighbours-minus-lower-left{part}",
                   .caption = "Pass 2's packed map, lower right | upper left | upper right minus "
                              "lower left (G | B | A minus R), amplified " +
                              gain + "x, grey = equal: the one-texel shift of Fig. 5"}},
       .floor = F::kCopyToTexture,
       .role = PassRole::kCopyToTexture,
       .keyState = {"GL_CONVOLUTION_2D [", "GL_CONVOLUTION_BORDER", "glCopyTexSubImage2D"}},
      {.id = "3",
       .name = "camera pass: light depth in RGBA",
       .reference = "Brabec & Seidel 2001 §4 (\"very similar to ... Section 3\"): §3's camera "
                    "pass, the light depth replicated over the four channels",
       .writes = {{.name = "camera-pass-z-replicated",
                   .caption = "Pass 3: light depth of each visible point in all four "
                              "channels{again}"}},
       .floor = F::kCameraDepth,
       .role = PassRole::kCamera,
       .deviations = {bs::kDepthBiasDeviation},
       .keyState = {"texture matrix (unit 0): load", "GL_TEXTURE_1D = texture"}},
      {.id = "3s",
       .name = "camera pass saved: copy to texture",
       .reference = "ours, 4x4 only: the camera pass copied once (glCopyTexSubImage2D) for "
                    "phases 2-4, instead of drawing it again in each (Brabec & Seidel 2001 §3 "
                    "counts the redraws, §4 does not require them)",
       .floor = F::kCopyWindowToTexture,
       .role = PassRole::kCopyToTexture,
       .deviations = {bs::kCameraPassCopyDeviation}},
      {.id = "3r",
       .name = "camera pass restored from its copy",
       .reference = "ours, 4x4 phases 2-4: the saved camera pass drawn back as one textured "
                    "full-window quad, where §3/§4 draw the camera pass again",
       .floor = F::kTexturedWindowQuad,
       .role = PassRole::kCamera,
       .deviations = {bs::kCameraPassCopyDeviation}},
      {.id = "4",
       .name = "projective pass: subtract packed map, offset texture coordinates",
       .reference = "Brabec & Seidel 2001 §4, Fig. 6: the packed map projected with its texture "
                    "coordinates offset by (ds/2, dt/2), subtracted as in §3",
       .writes = {{.name = "mask-before-colour-table{part}-rgba-x" + gain,
                   .caption = "Pass 4: camera depth minus the four packed neighbours (R | G | B | "
                              "A), amplified " +
                              gain +
                              "x: > 0 = that neighbour shadows the "
                              "point"}},
       .floor = F::kProjectiveSubtract,
       .role = PassRole::kProjective,
       .keyState = {"GL_FUNC_REVERSE_SUBTRACT", "glBlendFunc(GL_ONE, GL_ONE)",
                    "GL_TEXTURE_2D = texture", "glDepthFunc(GL_LEQUAL)",
                    "texture matrix (unit 0): load"}},
      {.id = "5",
       .name = "copy: colour table + colour matrix -> alpha",
       .reference = "Brabec & Seidel 2001 §3, Fig. 4 (as §4 says): colour table 0 / 64 (63 in "
                    "alpha), the colour matrix sums the channels into alpha",
       .writes = {{.name = "mask-after-colour-table{part}-rgba",
                   .caption = "The same read through the colour table only: 0 or 64 (63 in "
                              "alpha)"},
                  {.name = "alpha-after-colour-matrix{part}",
                   .caption = "Pass 5: alpha = share of the four neighbours that shadow the "
                              "point"}},
       .floor = F::kCopyPixels,
       .role = PassRole::kCopy,
       .keyState = {"GL_COLOR_TABLE [", "colour matrix: load [0 0 0 0", "glCopyPixels"}},
      {.id = "6a",
       .name = "accumulate",
       .reference = "Brabec & Seidel 2001 §4 (4x4 footprints)",
       .floor = F::kAccumulate,
       .role = PassRole::kAccumulate,
       .keyState = {"glAccum"}},
      {.id = "6b",
       .name = "accumulation return",
       .reference = "Brabec & Seidel 2001 §4 (4x4 footprints)",
       .writes = {{.name = "accumulation-result-alpha",
                   .caption = "Pass 6: the four phases summed in the accumulation buffer, weight "
                              "1/4 each: 17 levels, 0/16 .. 16/16 of the 16 samples shadowed "
                              "(the paper counts 4 x 5 = 20; sums of four 5-level phases "
                              "coincide)"}},
       .floor = F::kAccumulationReturn,
       .role = PassRole::kAccumulationReturn,
       .keyState = {"glAccum(GL_RETURN"}},
      {.id = "7",
       .name = "lighting x shadow term",
       .reference = "Brabec & Seidel 2001 §5 (\"normal OpenGL lighting\"): direct light x "
                    "(1 - shadow), ambient kept",
       .writes = {{.name = "shaded",
                   .caption = "Pass 7: OpenGL lighting x (1 - shadow) + ambient"}},
       .floor = F::kLighting,
       .role = PassRole::kLighting,
       .deviations = {kProjectedConeDeviation},
       .keyState = {"GL_ONE_MINUS_DST_ALPHA", "GL_LIGHT_MODEL_AMBIENT", "GL_LIGHT0 GL_DIFFUSE"}},
  };
}

const PassTable& passTable() {
  static const PassTable table = fastPcfPasses();
  return table;
}

// One shadow-mapping phase: which 2x2 region the kernel packs and the texture-coordinate
// offset (in texels) that makes the lookup land on it; `part` names its runs of passes 2-6.
struct Phase {
  PassPart part;
  glm::ivec2 blockOffset;  // packingKernel(): the block's upper-right texel is (x+ox, y+oy)
  glm::vec2 offsetTexels;
};

// For a point at u texels, x0 = floor(u + 1/2) is the texel corner nearest to it.
//   2x2 (Fig. 5, 6): Eq. (1)'s block {x-1, x} looked up at x = x0: offset +ds/2.
//   4x4 (§4 last paragraph): the footprint {x0-2 .. x0+1} as four 2x2 regions; the left
//   regions use Eq. (1)'s kernel at x = x0 - 1 (offset -ds/2), the right ones the kernel
//   moved one texel right ({x, x+1}) at x = x0 (offset +ds/2); likewise in t.
std::vector<Phase> phasesFor(int side) {
  if (side == 2) return {{{}, {0, 0}, {kHalfTexel, kHalfTexel}}};
  return {{{"(upper-left)", "-upper-left", 0}, {0, 1}, {-kHalfTexel, kHalfTexel}},
          {{"(upper-right)", "-upper-right", 1}, {1, 1}, {kHalfTexel, kHalfTexel}},
          {{"(lower-left)", "-lower-left", 2}, {0, 0}, {-kHalfTexel, -kHalfTexel}},
          {{"(lower-right)", "-lower-right", 3}, {1, 0}, {kHalfTexel, -kHalfTexel}}};
}

struct FastPcfState {
  bs::DepthEncoding enc;
  bs::RampTexture ramp;
  std::vector<std::unique_ptr<bs::ShadowMapTexture>> maps;  // one packed map per phase
  bs::SavedCameraPass savedCamera;                          // 4x4: pass 3 for phases 2-4
};

// Pass 1 (§4): "we store the encoded depth values in all four channels".
void renderDepthIntoAllChannels(Passes& passes, const Scene& scene, const RenderParams& params,
                                FastPcfState& s) {
  passes.run("1", [&] {
    bs::renderLightDepth(scene, s.enc, s.ramp, params.shadowMapTexels, glm::vec2(0.0f),
                         bs::kAllChannels, true);
  });
}

// Pass 2 (Eq. (1), Fig. 5): the copy to the texture with the packing convolution enabled.
void packNeighboursByConvolution(Passes& passes, const RenderParams& params, FastPcfState& s,
                                 size_t phase, const Phase& p) {
  passes.run(
      "2",
      [&] { bs::copyLightPassToMapPacked(*s.maps[phase], params.shadowMapTexels, p.blockOffset); },
      p.part);
}

// Pass 3 (§3/§4): the light depth of every visible point in all four channels. One pass for
// all phases (it does not depend on the phase), so it names no phase.
void renderReplicatedCameraDepth(Passes& passes, const Scene& scene, const RenderParams& params,
                                 FastPcfState& s) {
  passes.run("3", [&] {
    bs::renderCameraDepth(scene, params, s.enc, s.ramp, bs::depthBias(params, s.enc),
                          bs::kAllChannels);
  });
}

// Pass 3s (4x4, phase 1): the camera pass kept in a texture for phases 2-4.
void saveCameraPassForPhases(Passes& passes, const RenderParams& params, FastPcfState& s) {
  passes.run("3s", [&] {
    bs::allocateSavedCameraPass(s.savedCamera, params, s.enc);
    bs::saveCameraPass(s.savedCamera, params);
  });
}

// Pass 3r (4x4, phases 2-4): the camera pass back from its copy (the subtraction overwrote it).
void restoreCameraPassForPhase(Passes& passes, const RenderParams& params, FastPcfState& s,
                               const Phase& p) {
  passes.run(
      "3r", [&] { bs::restoreCameraPass(s.savedCamera, params); }, p.part);
}

// Pass 4 (Fig. 6): projective packed map, coordinates offset by (ds/2, dt/2), subtracted.
void subtractPackedMap(Passes& passes, const Scene& scene, const RenderParams& params,
                       FastPcfState& s, size_t phase, const Phase& p) {
  passes.run(
      "4",
      [&] {
        bs::subtractProjectedMap(scene, params, *s.maps[phase], p.offsetTexels, bs::kAllChannels);
      },
      p.part);
}

// Pass 5 (Fig. 4): colour table + colour matrix -> alpha.
void countShadowedSamples(Passes& passes, const RenderParams& params, FastPcfState& s,
                          const Phase& p) {
  passes.run(
      "5", [&] { bs::countShadowSamplesByCopy(params, s.enc, kPackedSamples); }, p.part);
}

// Pass 6a (§4, 4x4): one phase's share into the accumulation buffer, weight 1/4.
void accumulatePhase(Passes& passes, size_t phase, size_t phases, const Phase& p) {
  passes.run(
      "6a", [&] { bs::accumulateGroup(1.0 / double(phases), phase == 0); }, p.part);
}

// Pass 6b (§4, 4x4): the sum of the four phases back into the colour buffer.
void returnAccumulatedPhases(Passes& passes) {
  passes.run("6b", [&] { bs::returnAccumulation(); });
}

// Pass 7 (§5 "normal OpenGL lighting").
void shade(Passes& passes, const Scene& scene, const RenderParams& params) {
  const SpotlightConeTexture cone;  // untimed: the same texture for every light and scene
  passes.run("7", [&] { bs::shadeWithShadowTerm(scene, params, cone); });
}

Frame render(GlContext& context, const Scene& scene, const RenderParams& params) {
  (void)context;
  const int side = bs::footprintSide(params, "legacy.fast-pcf");
  if (side != 2 && side != 4)
    throw InputError("legacy.fast-pcf: --filter must be 2 or 4 (the footprints of §4), got " +
                     std::to_string(side));
  const std::vector<Phase> phases = phasesFor(side);
  Frame frame;
  Passes passes(frame, params, passTable());
  // The camera passes draw the scene split for per-vertex spotlight lighting (same geometry).
  const Scene camera = cameraPassScene(scene, params, passes);
  FastPcfState s;
  s.enc = bs::depthEncoding(params.precision);
  bs::createRampTexture(s.ramp, s.enc);
  for (size_t i = 0; i < phases.size(); ++i) {
    s.maps.push_back(std::make_unique<bs::ShadowMapTexture>());
    bs::allocateShadowMap(*s.maps.back(), s.enc, params.shadowMapTexels);
  }

  const int n = params.shadowMapTexels;
  {
    LightTarget target(n, n <= params.width && n <= params.height, true, s.enc.mapFormat);
    target.bind();
    renderDepthIntoAllChannels(passes, scene, params, s);
    passes.capture("1", "light-pass-depth-rgba",
                   [&] { return channel(readColorBuffer(0, 0, n, n), 0); });
    // The light image stays in the framebuffer while every phase copies its packed map.
    for (size_t i = 0; i < phases.size(); ++i)
      packNeighboursByConvolution(passes, params, s, i, phases[i]);
    target.unbind();
  }
  const std::string itself = phases.size() == 1 ? " = the texel itself" : "";
  for (size_t i = 0; i < phases.size(); ++i)
    passes.capture("2", "packed-shadow-map{part}-rgba",
                   [&] { return bs::readShadowMap(*s.maps[i], n); }, phases[i].part,
                   {{"itself", itself}});
  for (size_t i = 0; i < phases.size(); ++i)
    passes.capture(
        "2", "packed-neighbours-minus-lower-left{part}",
        [&] {
          return bs::channelsMinusCentre(bs::readShadowMap(*s.maps[i], n), 0,
                                         kDifferenceDisplayGain);
        },
        phases[i].part);

  const std::string again = phases.size() > 1
                                ? " (the same in each of the " + std::to_string(phases.size()) +
                                      " phases: copied once, restored before "
                                      "phases 2-" +
                                      std::to_string(phases.size()) + ")"
                                : "";
  for (size_t i = 0; i < phases.size(); ++i) {
    const Phase& p = phases[i];
    // The camera pass is the same in every phase (only passes 2, 4 and 5 depend on it): drawn
    // in the first, copied, and restored from the copy in the others; one file.
    if (i == 0) {
      renderReplicatedCameraDepth(passes, camera, params, s);
      passes.capture("3", "camera-pass-z-replicated",
                     [&] { return toRgb(bs::readWindowRgba(params)); }, {}, {{"again", again}});
      if (phases.size() > 1) saveCameraPassForPhases(passes, params, s);
    } else {
      restoreCameraPassForPhase(passes, params, s, p);
    }
    subtractPackedMap(passes, camera, params, s, i, p);
    passes.capture(
        "4", "mask-before-colour-table{part}-rgba-x32",
        [&] {
          return bs::channelPanels(
              bs::amplified(bs::readWindowRgba(params), kDifferenceDisplayGain));
        },
        p.part);
    passes.capture(
        "5", "mask-after-colour-table{part}-rgba",
        [&] { return bs::channelPanels(bs::readThroughColorTable(params, s.enc, kPackedSamples)); },
        p.part);
    countShadowedSamples(passes, params, s, p);
    passes.capture(
        "5", "alpha-after-colour-matrix{part}",
        [&] { return bs::alphaOf(bs::readWindowRgba(params)); }, p.part);
    if (phases.size() > 1) accumulatePhase(passes, i, phases.size(), p);
  }
  if (phases.size() > 1) {
    returnAccumulatedPhases(passes);
    passes.capture("6b", "accumulation-result-alpha",
                   [&] { return bs::alphaOf(bs::readWindowRgba(params)); });
  }
  shade(passes, camera, params);
  frame.color = readRgb(params.width, params.height);
  frame.visibility = bs::readVisibilityFromAlpha(params);
  passes.capture("7", "shaded", [&] { return frame.color; });
  frame.counters["footprint samples"] = side * side;
  frame.counters["light passes"] = 1;
  checkGl("legacy.fast-pcf");
  return frame;
}

}  // namespace

Technique fastPcfTechnique() {
  Technique t;
  t.name = "legacy.fast-pcf";
  t.paper = "Brabec & Seidel 2001, §4";
  t.summary = "fast PCF: convolution packs 2x2 neighbours on the copy; 4x4 in four phases";
  t.status = "complete";
  t.needs.profile = Profile::kCompatibility;
  t.needs.accumulation = true;
  t.needs.colorFromPrecision = true;
  t.params = {bs::depthBiasParam()};
  t.reads = {.shadowMap = true, .filter = true, .filterSides = {2, 4}, .precision = true};
  t.edge = Technique::Edge::kFiltered;                         // PCF over the --filter footprint
  t.plan.samples = PlanTraits::SampleGrouping::kPackedPhases;  // §4: packed 2x2 phases
  t.plan.colourTableCompare = true;                            // §3 Fig. 4
  t.plan.colourMatrixSum = true;
  t.plan.packingConvolution = true;  // §4 Eq. (1)
  t.passes = passTable();
  t.render = render;
  return t;
}

}  // namespace sl::legacy
