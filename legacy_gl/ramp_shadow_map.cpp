// legacy.ramp — Stefan Brabec and Hans-Peter Seidel, "Hardware-accelerated Rendering of
// Antialiased Shadows with Shadow Maps", CGI 2001, §2 (the shadow-map algorithm of Heidrich's
// thesis [4]): depth becomes colour through texgen and a 1D linear ramp texture, and the shadow
// test is a subtraction in the blending unit. No imaging subset is needed.
//
// Passes:
//   1. renderDepthRampFromLight  — the scene from the light, light eye z through a 1D ramp into
//                                  the alpha channel, copied into a 2D texture (§2, Fig. 1)
//   2. renderDepthRampFromCamera — the scene from the camera, the texture matrix maps camera eye
//                                  coordinates to the light's ramp (§2), minus the depth bias
//   3. subtractShadowMap         — the map as a projective texture, subtracted by the blending
//                                  unit: alpha > 0 = shadowed (§2)
//   4. saturateShadowMask        — footnote 1's extra copy: every alpha > 0 becomes 1
//   5. shade                     — OpenGL lighting, direct light x (1 - alpha) + ambient (§5)
// Visibility = 1 - alpha (brabec_seidel.h). The passes are declared once in rampPasses().
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

constexpr float kDifferenceDisplayGain = 32.0f;  // a few depth steps made visible in dumps

// The passes of §2, declared once: names, the paper's text, the buffers a dump shows, floors.
PassTable rampPasses() {
  using F = PassFloor;
  const std::string gain = std::to_string(int(kDifferenceDisplayGain));
  return {
      meshFeedingPass(),
      {.id = "1",
       .name = "light pass: depth ramp into alpha + copy to texture",
       .reference = "Brabec & Seidel 2001 §2, Fig. 1 (after Heidrich [4]): texgen r through a 1D "
                    "ramp into alpha, copied into a 2D texture",
       .writes = {{.name = "light-pass-ramp-depth-alpha",
                   .caption = "Pass 1: light-space depth through the 1D ramp, alpha channel of "
                              "the shadow map (black = near, white = far or empty)"}},
       .floor = F::kLightDepthAndCopy,
       .role = PassRole::kLight,
       .deviations = {kOffscreenLightPassDeviation, bs::kFloatChannelsDeviation},
       .keyState = {"rising in 256 steps", "texture matrix (unit 0): load", "glCopyTexSubImage2D"}},
      {.id = "2",
       .name = "camera pass: light depth ramp into alpha",
       .reference = "Brabec & Seidel 2001 §2: the same ramp from the camera, a 4x4 texture "
                    "matrix from camera to light space",
       .writes = {{.name = "camera-pass-ramp-depth-alpha",
                   .caption = "Pass 2: each visible point's own depth from the light, same ramp "
                              "(minus bias)"}},
       .floor = F::kCameraDepth,
       .role = PassRole::kCamera,
       .deviations = {bs::kDepthBiasDeviation},
       .keyState = {"texture matrix (unit 0): load", "GL_TEXTURE_1D = texture"}},
      {.id = "3",
       .name = "projective pass: subtract shadow map",
       .reference = "Brabec & Seidel 2001 §2: the map as a projective texture, subtracted by the "
                    "blending unit; > 0 = shadowed",
       .writes = {{.name = "projected-shadow-map-alpha",
                   .caption = "The shadow map projected onto the scene from the light (what pass "
                              "3 subtracts)"},
                  {.name = "difference-alpha",
                   .caption = "Pass 3: pass 2 minus the projected map, clamped at 0: > 0 in "
                              "shadow (raw)"},
                  {.name = "difference-alpha-x" + gain,
                   .caption = "Pass 3 difference amplified " + gain + "x for display"}},
       .floor = F::kProjectiveSubtract,
       .role = PassRole::kProjective,
       .keyState = {"GL_FUNC_REVERSE_SUBTRACT", "glBlendFunc(GL_ONE, GL_ONE)",
                    "GL_TEXTURE_2D = texture", "glDepthFunc(GL_LEQUAL)"}},
      {.id = "4",
       .name = "copy: shadow mask to 0 / 1",
       .reference = "Brabec & Seidel 2001 §2, footnote 1: an additional frame buffer copy brings "
                    "values > 0 to 1",
       .writes = {{.name = "shadow-mask-alpha",
                   .caption = "Pass 4 (footnote 1): the mask after the extra copy, 1 = shadow"}},
       .floor = F::kCopyPixels,
       .role = PassRole::kCopy,
       .deviations = {bs::kFloatClampDeviation},
       .keyState = {"glPixelTransferf", "glCopyPixels"}},
      {.id = "5",
       .name = "lighting x shadow mask",
       .reference = "Brabec & Seidel 2001 §5 (\"normal OpenGL lighting\"): direct light x "
                    "(1 - mask), ambient kept",
       .writes = {{.name = "shaded", .caption = "Pass 5: OpenGL lighting x (1 - mask) + ambient"}},
       .floor = F::kLighting,
       .role = PassRole::kLighting,
       .deviations = {kProjectedConeDeviation},
       .keyState = {"GL_ONE_MINUS_DST_ALPHA", "GL_LIGHT_MODEL_AMBIENT", "GL_LIGHT0 GL_DIFFUSE"}},
  };
}

const PassTable& passTable() {
  static const PassTable table = rampPasses();
  return table;
}

struct RampState {
  bs::DepthEncoding enc;
  bs::RampTexture ramp;
  bs::ShadowMapTexture map;
};

// Pass 1 (§2, Fig. 1): light eye z -> ramp -> alpha; framebuffer copy into the shadow map.
void renderDepthRampFromLight(Passes& passes, const Scene& scene, const RenderParams& params,
                              RampState& s) {
  passes.run("1", [&] {
    const int n = params.shadowMapTexels;
    LightTarget target(n, n <= params.width && n <= params.height, true, s.enc.mapFormat);
    target.bind();
    bs::renderLightDepth(scene, s.enc, s.ramp, n, glm::vec2(0.0f), bs::kAlphaOnly, true);
    bs::copyLightPassToMap(s.map, n);
    target.unbind();
  });
}

// Pass 2 (§2): the same ramp on the light depth of every visible point, through the texture
// matrix from camera to light space.
void renderDepthRampFromCamera(Passes& passes, const Scene& scene, const RenderParams& params,
                               RampState& s) {
  passes.run("2", [&] {
    // All four channels: the intensity ramp writes the same depth into RGB, which no later
    // pass reads (pass 5 clears RGB); llvmpipe's colour-masked writes cost about twice the pass
    // (legacy_bench). The paper's test reads alpha only.
    bs::renderCameraDepth(scene, params, s.enc, s.ramp, bs::depthBias(params, s.enc),
                          bs::kAllChannels);
  });
}

// Pass 3 (§2): projective shadow map subtracted from pass 2 (EXT_blend_subtract).
void subtractShadowMap(Passes& passes, const Scene& scene, const RenderParams& params,
                       RampState& s) {
  passes.run("3", [&] {
    bs::subtractProjectedMap(scene, params, s.map, glm::vec2(0.0f), bs::kAllChannels);
  });
}

// Pass 4 (§2 footnote 1): "an additional frame buffer copy ... to bring values > 0 to 1".
void saturateShadowMask(Passes& passes, const RenderParams& params, RampState& s) {
  passes.run("4", [&] { bs::saturateAlphaByCopy(params, s.enc); });
}

// Pass 5 (§5 "normal OpenGL lighting"): direct light darkened by the mask, ambient kept.
void shade(Passes& passes, const Scene& scene, const RenderParams& params) {
  const SpotlightConeTexture cone;  // untimed: the same texture for every light and scene
  passes.run("5", [&] { bs::shadeWithShadowTerm(scene, params, cone); });
}

Frame render(GlContext& context, const Scene& scene, const RenderParams& params) {
  (void)context;
  Frame frame;
  Passes passes(frame, params, passTable());
  // The camera passes draw the scene split for per-vertex spotlight lighting (same geometry).
  const Scene camera = cameraPassScene(scene, params, passes);
  RampState s;
  s.enc = bs::depthEncoding(params.precision);
  bs::createRampTexture(s.ramp, s.enc);
  bs::allocateShadowMap(s.map, s.enc, params.shadowMapTexels);

  renderDepthRampFromLight(passes, scene, params, s);
  passes.capture("1", "light-pass-ramp-depth-alpha",
                 [&] { return bs::alphaOf(bs::readShadowMap(s.map, params.shadowMapTexels)); });
  passes.capture("3", "projected-shadow-map-alpha", [&] {
    bs::renderProjectedMapOnly(camera, params, s.map, glm::vec2(0.0f));
    return bs::alphaOf(bs::readWindowRgba(params));
  });
  renderDepthRampFromCamera(passes, camera, params, s);
  passes.capture("2", "camera-pass-ramp-depth-alpha",
                 [&] { return bs::alphaOf(bs::readWindowRgba(params)); });
  subtractShadowMap(passes, camera, params, s);
  passes.capture("3", "difference-alpha", [&] { return bs::alphaOf(bs::readWindowRgba(params)); });
  passes.capture("3", "difference-alpha-x32", [&] {
    return bs::amplified(bs::alphaOf(bs::readWindowRgba(params)), kDifferenceDisplayGain);
  });
  saturateShadowMask(passes, params, s);
  passes.capture("4", "shadow-mask-alpha", [&] { return bs::alphaOf(bs::readWindowRgba(params)); });
  shade(passes, camera, params);
  frame.color = readRgb(params.width, params.height);
  frame.visibility = bs::readVisibilityFromAlpha(params);
  passes.capture("5", "shaded", [&] { return frame.color; });
  checkGl("legacy.ramp");
  return frame;
}

}  // namespace

Technique rampShadowMapTechnique() {
  Technique t;
  t.name = "legacy.ramp";
  t.paper = "Brabec & Seidel 2001, §2 (after Heidrich 1999)";
  t.summary = "depth as colour via texgen + 1D ramp, shadow test by subtractive blending";
  t.status = "complete";
  t.needs.profile = Profile::kCompatibility;
  t.needs.colorFromPrecision = true;
  t.params = {bs::depthBiasParam()};
  t.reads = {.shadowMap = true, .precision = true};
  t.passes = passTable();
  t.render = render;
  return t;
}

}  // namespace sl::legacy
