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
//   4. subtractPackedMap           — the packed map projected with texture coordinates offset
//                                  by (ds/2, dt/2) (Fig. 6) and subtracted
//   5. countShadowedSamples        — glCopyPixels through the colour table and the colour matrix
//                                  (as §3, Fig. 4): 5 levels per phase
//   6. bs::accumulateGroup         — 4x4 (in render(): once per phase, then
//                                  bs::returnAccumulation): the upper-left, upper-right,
//                                  lower-left and lower-right 2x2 regions summed in the
//                                  accumulation buffer, weight 1/4 each (§4 counts 4 x 5 = 20 levels; the sums take 17)
//   7. shade                       — OpenGL lighting, direct light x (1 - alpha) + ambient (§5)
// Visibility = 1 - alpha (brabec_seidel.h).
#include <memory>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/gl.h"
#include "core/gl_trace.h"
#include "legacy_gl/brabec_seidel.h"
#include "legacy_gl/brabec_seidel_passes.h"
#include "legacy_gl/spotlight_tessellation.h"

namespace sl::legacy {
using namespace sl::gl;

namespace {

constexpr int kPackedSamples = 4;                // one 2x2 region per packed texel
constexpr float kDifferenceDisplayGain = 32.0f;  // a few depth steps made visible in dumps
constexpr float kHalfTexel = 0.5f;
constexpr int kTexelItselfChannel = 3;  // A: the upper right of the 2x2 region (Eq. (1) centre)

// One shadow-mapping phase: which 2x2 region the kernel packs and the texture-coordinate
// offset (in texels) that makes the lookup land on it.
struct Phase {
  std::string name;
  glm::ivec2 blockOffset;  // packingKernel(): the block's upper-right texel is (x+ox, y+oy)
  glm::vec2 offsetTexels;
};

// For a point at u texels, x0 = floor(u + 1/2) is the texel corner nearest to it.
//   2x2 (Fig. 5, 6): Eq. (1)'s block {x-1, x} looked up at x = x0: offset +ds/2.
//   4x4 (§4 last paragraph): the footprint {x0-2 .. x0+1} as four 2x2 regions; the left
//   regions use Eq. (1)'s kernel at x = x0 - 1 (offset -ds/2), the right ones the kernel
//   moved one texel right ({x, x+1}) at x = x0 (offset +ds/2); likewise in t.
std::vector<Phase> phasesFor(int side) {
  if (side == 2) return {{"", {0, 0}, {kHalfTexel, kHalfTexel}}};
  return {{"upper-left", {0, 1}, {-kHalfTexel, kHalfTexel}},
          {"upper-right", {1, 1}, {kHalfTexel, kHalfTexel}},
          {"lower-left", {0, 0}, {-kHalfTexel, -kHalfTexel}},
          {"lower-right", {1, 0}, {kHalfTexel, -kHalfTexel}}};
}

struct FastPcfState {
  bs::DepthEncoding enc;
  bs::RampTexture ramp;
  std::vector<std::unique_ptr<bs::ShadowMapTexture>> maps;  // one packed map per phase
};

std::string phaseTag(const Phase& p) {
  return p.name.empty() ? "" : " (" + p.name + ")";
}
std::string phaseFileTag(const Phase& p) {
  return p.name.empty() ? "" : "-" + p.name;
}

// Pass 1 (§4): "we store the encoded depth values in all four channels".
void renderDepthIntoAllChannels(const Scene& scene, const RenderParams& params, FastPcfState& s,
                                Frame& frame) {
  PassTimer timer(frame, "1 light pass: depth ramp in RGBA",
                  "Brabec & Seidel 2001 §4: the map rendered as in §2 (Fig. 1), the encoded depth "
                  "in all four channels");
  bs::renderLightDepth(scene, s.enc, s.ramp, params.shadowMapTexels, glm::vec2(0.0f),
                       bs::kAllChannels, true);
}

// Pass 2 (Eq. (1), Fig. 5): the copy to the texture with the packing convolution enabled.
void packNeighboursByConvolution(const RenderParams& params, FastPcfState& s, size_t phase,
                                 const Phase& p, Frame& frame) {
  PassTimer timer(frame, "2 copy to texture through the 3x3 packing convolution" + phaseTag(p),
                  "Brabec & Seidel 2001 §4, Eq. (1), Fig. 5");
  bs::copyLightPassToMapPacked(*s.maps[phase], params.shadowMapTexels, p.blockOffset);
}

// Pass 3 (§3/§4): the light depth of every visible point in all four channels.
void renderReplicatedCameraDepth(const Scene& scene, const RenderParams& params, FastPcfState& s,
                                 Frame& frame, const std::string& tag) {
  PassTimer timer(frame, "3 camera pass: light depth in RGBA" + tag,
                  "Brabec & Seidel 2001 §4 (\"very similar to ... Section 3\"): §3's camera pass, "
                  "the light depth replicated over the four channels");
  bs::renderCameraDepth(scene, params, s.enc, s.ramp, bs::depthBias(params, s.enc),
                        bs::kAllChannels);
}

// Pass 4 (Fig. 6): projective packed map, coordinates offset by (ds/2, dt/2), subtracted.
void subtractPackedMap(const Scene& scene, const RenderParams& params, FastPcfState& s,
                       size_t phase, const Phase& p, Frame& frame) {
  PassTimer timer(frame,
                  "4 projective pass: subtract packed map, offset texture coordinates" + phaseTag(p),
                  "Brabec & Seidel 2001 §4, Fig. 6: the packed map projected with its texture "
                  "coordinates offset by (ds/2, dt/2), subtracted as in §3");
  bs::subtractProjectedMap(scene, params, *s.maps[phase], p.offsetTexels, bs::kAllChannels);
}

// Pass 5 (Fig. 4): colour table + colour matrix -> alpha.
void countShadowedSamples(const RenderParams& params, FastPcfState& s, Frame& frame,
                          const std::string& tag) {
  PassTimer timer(frame, "5 copy: colour table + colour matrix -> alpha" + tag,
                  "Brabec & Seidel 2001 §3, Fig. 4 (as §4 says): colour table 0 / 64 (63 in "
                  "alpha), the colour matrix sums the channels into alpha");
  bs::countShadowSamplesByCopy(params, s.enc, kPackedSamples);
}

// Pass 7 (§5 "normal OpenGL lighting").
void shade(const Scene& scene, const RenderParams& params, Frame& frame) {
  PassTimer timer(frame, "7 lighting x shadow term",
                  "Brabec & Seidel 2001 §5 (\"normal OpenGL lighting\"): direct light x "
                  "(1 - shadow), ambient kept");
  bs::shadeWithShadowTerm(scene, params);
}

Frame render(GlContext& context, const Scene& scene, const RenderParams& params) {
  (void)context;
  const int side = bs::footprintSide(params, "legacy.fast-pcf");
  if (side != 2 && side != 4)
    throw InputError("legacy.fast-pcf: --filter must be 2 or 4 (the footprints of §4), got " +
                     std::to_string(side));
  const std::vector<Phase> phases = phasesFor(side);
  Frame frame;
  // The camera passes draw the scene split for per-vertex spotlight lighting (same geometry).
  const Scene camera = cameraPassScene(scene, params, frame);
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
    renderDepthIntoAllChannels(scene, params, s, frame);
    if (params.capturePasses) {
      const GlTracePause dumpOnly;  // a readback for the dump, not state of a pass
      bs::capture(frame, params, "1-light-pass-depth-rgba",
                  "Pass 1: one light pass, encoded depth in all four channels (one shown)",
                  channel(readColorBuffer(0, 0, n, n), 0));
    }
    // The light image stays in the framebuffer while every phase copies its packed map.
    for (size_t i = 0; i < phases.size(); ++i)
      packNeighboursByConvolution(params, s, i, phases[i], frame);
    target.unbind();
  }
  if (params.capturePasses)
    for (size_t i = 0; i < phases.size(); ++i) {
      PassImage packed("2-packed-shadow-map" + phaseFileTag(phases[i]) + "-rgba",
                       "Pass 2: the packed map, R | G | B | A = lower left, lower right, upper "
                       "left, upper right of each texel's 2x2 region (Fig. 5)",
                       bs::readShadowMap(*s.maps[i], n));
      packed.centreChannel = kTexelItselfChannel;
      packed.channelMeaning = {"lower left", "lower right", "upper left",
                               phases.size() == 1 ? "upper right = the texel itself" : "upper right"};
      frame.intermediates.push_back(std::move(packed));
    }
  // Fig. 5's one-texel shift made visible: G, B and A minus R, the lower-left neighbour (the
  // texel's own depth is A, kTexelItselfChannel), non-grey along every depth edge, one texel to
  // the side the other channel's texel lies on.
  if (params.capturePasses)
    for (size_t i = 0; i < phases.size(); ++i)
      bs::capture(
          frame, params, "2-packed-neighbours-minus-lower-left" + phaseFileTag(phases[i]),
          "Pass 2's packed map, lower right | upper left | upper right minus lower left "
          "(G | B | A minus R), amplified " +
              std::to_string(int(kDifferenceDisplayGain)) +
              "x, grey = equal: the one-texel shift of Fig. 5",
          bs::channelsMinusCentre(bs::readShadowMap(*s.maps[i], n), 0, kDifferenceDisplayGain));

  for (size_t i = 0; i < phases.size(); ++i) {
    const Phase& p = phases[i];
    const std::string tag = phaseTag(p), file = phaseFileTag(p);
    renderReplicatedCameraDepth(camera, params, s, frame, tag);
    // The camera pass is the same in every phase (only passes 2, 4 and 5 depend on it): one file.
    if (params.capturePasses && i == 0)
      bs::capture(frame, params, "3-camera-pass-z-replicated",
                  "Pass 3: light depth of each visible point in all four channels" +
                      std::string(phases.size() > 1 ? " (drawn again, identical, in each of the " +
                                                          std::to_string(phases.size()) +
                                                          " phases)"
                                                    : ""),
                  toRgb(bs::readWindowRgba(params)));
    subtractPackedMap(camera, params, s, i, p, frame);
    if (params.capturePasses) {
      bs::capture(
          frame, params, "4-mask-before-colour-table" + file + "-rgba-x32",
          "Pass 4: camera depth minus the four packed neighbours (R | G | B | A), "
          "amplified 32x: > 0 = that neighbour shadows the point",
          bs::channelPanels(bs::amplified(bs::readWindowRgba(params), kDifferenceDisplayGain)));
      bs::capture(frame, params, "5-mask-after-colour-table" + file + "-rgba",
                  "The same read through the colour table only: 0 or 64 (63 in alpha)",
                  bs::channelPanels(bs::readThroughColorTable(params, s.enc, kPackedSamples)));
    }
    countShadowedSamples(params, s, frame, tag);
    if (params.capturePasses)
      bs::capture(frame, params, "5-alpha-after-colour-matrix" + file,
                  "Pass 5: alpha = share of the four neighbours that shadow the point",
                  bs::alphaOf(bs::readWindowRgba(params)));
    if (phases.size() > 1) {
      PassTimer timer(frame, "6 accumulate" + tag, "Brabec & Seidel 2001 §4 (4x4 footprints)");
      bs::accumulateGroup(1.0 / double(phases.size()), i == 0);
    }
  }
  if (phases.size() > 1) {
    {
      PassTimer timer(frame, "6 accumulation return", "Brabec & Seidel 2001 §4 (4x4 footprints)");
      bs::returnAccumulation();
    }
    if (params.capturePasses)
      bs::capture(frame, params, "6-accumulation-result-alpha",
                  "Pass 6: the four phases summed in the accumulation buffer (4 x 5 levels)",
                  bs::alphaOf(bs::readWindowRgba(params)));
  }
  shade(camera, params, frame);
  frame.color = readRgb(params.width, params.height);
  frame.visibility = bs::readVisibilityFromAlpha(params);
  if (params.capturePasses)
    bs::capture(frame, params, "7-shaded", "Pass 7: OpenGL lighting x (1 - shadow) + ambient",
                frame.color);
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
  t.reads = {.shadowMap = true, .filter = true, .precision = true};
  t.plan.samples = PlanTraits::SampleGrouping::kPackedPhases;  // §4: packed 2x2 phases
  t.plan.colourTableCompare = true;                            // §3 Fig. 4
  t.plan.colourMatrixSum = true;
  t.plan.packingConvolution = true;  // §4 Eq. (1)
  t.render = render;
  return t;
}

}  // namespace sl::legacy
