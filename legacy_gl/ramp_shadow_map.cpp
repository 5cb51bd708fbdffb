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
// Visibility = 1 - alpha (brabec_seidel.h).
#include "core/errors.h"
#include "core/gl.h"
#include "legacy_gl/brabec_seidel.h"
#include "legacy_gl/brabec_seidel_passes.h"
#include "legacy_gl/spotlight_tessellation.h"

namespace sl::legacy {
using namespace sl::gl;

namespace {

constexpr float kDifferenceDisplayGain = 32.0f;  // a few depth steps made visible in dumps

struct RampState {
  bs::DepthEncoding enc;
  bs::RampTexture ramp;
  bs::ShadowMapTexture map;
};

// Pass 1 (§2, Fig. 1): light eye z -> ramp -> alpha; framebuffer copy into the shadow map.
void renderDepthRampFromLight(const Scene& scene, const RenderParams& params, RampState& s,
                              Frame& frame) {
  PassTimer timer(frame, "1 light pass: depth ramp into alpha + copy to texture",
                  "Brabec & Seidel 2001 §2, Fig. 1 (after Heidrich [4]): texgen r through a 1D "
                  "ramp into alpha, copied into a 2D texture");
  const int n = params.shadowMapTexels;
  LightTarget target(n, n <= params.width && n <= params.height, true, s.enc.mapFormat);
  target.bind();
  bs::renderLightDepth(scene, s.enc, s.ramp, n, glm::vec2(0.0f), bs::kAlphaOnly, true);
  bs::copyLightPassToMap(s.map, n);
  target.unbind();
}

// Pass 2 (§2): the same ramp on the light depth of every visible point, through the texture
// matrix from camera to light space.
void renderDepthRampFromCamera(const Scene& scene, const RenderParams& params, RampState& s,
                               Frame& frame) {
  PassTimer timer(frame, "2 camera pass: light depth ramp into alpha",
                  "Brabec & Seidel 2001 §2: the same ramp from the camera, a 4x4 texture "
                  "matrix from camera to light space");
  bs::renderCameraDepth(scene, params, s.enc, s.ramp, bs::depthBias(params, s.enc), bs::kAlphaOnly);
}

// Pass 3 (§2): projective shadow map subtracted from pass 2 (EXT_blend_subtract).
void subtractShadowMap(const Scene& scene, const RenderParams& params, RampState& s, Frame& frame) {
  PassTimer timer(frame, "3 projective pass: subtract shadow map",
                  "Brabec & Seidel 2001 §2: the map as a projective texture, subtracted by the "
                  "blending unit; > 0 = shadowed");
  bs::subtractProjectedMap(scene, params, s.map, glm::vec2(0.0f), bs::kAlphaOnly);
}

// Pass 4 (§2 footnote 1): "an additional frame buffer copy ... to bring values > 0 to 1".
void saturateShadowMask(const RenderParams& params, RampState& s, Frame& frame) {
  PassTimer timer(frame, "4 copy: shadow mask to 0 / 1",
                  "Brabec & Seidel 2001 §2, footnote 1: an additional frame buffer copy brings "
                  "values > 0 to 1");
  bs::saturateAlphaByCopy(params, s.enc);
}

// Pass 5 (§5 "normal OpenGL lighting"): direct light darkened by the mask, ambient kept.
void shade(const Scene& scene, const RenderParams& params, Frame& frame) {
  PassTimer timer(frame, "5 lighting x shadow mask",
                  "Brabec & Seidel 2001 §5 (\"normal OpenGL lighting\"): direct light x "
                  "(1 - mask), ambient kept");
  bs::shadeWithShadowTerm(scene, params);
}

Frame render(GlContext& context, const Scene& scene, const RenderParams& params) {
  (void)context;
  Frame frame;
  // The camera passes draw the scene split for per-vertex spotlight lighting (same geometry).
  const Scene camera = cameraPassScene(scene, params, frame);
  RampState s;
  s.enc = bs::depthEncoding(params.precision);
  bs::createRampTexture(s.ramp, s.enc);
  bs::allocateShadowMap(s.map, s.enc, params.shadowMapTexels);

  renderDepthRampFromLight(scene, params, s, frame);
  if (params.capturePasses) {
    bs::capture(frame, params, "1-light-pass-ramp-depth-alpha",
                "Pass 1: light-space depth through the 1D ramp, alpha channel of the shadow map "
                "(black = near, white = far or empty)",
                bs::alphaOf(bs::readShadowMap(s.map, params.shadowMapTexels)));
    bs::renderProjectedMapOnly(camera, params, s.map, glm::vec2(0.0f));
    bs::capture(frame, params, "3a-projected-shadow-map-alpha",
                "The shadow map projected onto the scene from the light (what pass 3 subtracts)",
                bs::alphaOf(bs::readWindowRgba(params)));
  }
  renderDepthRampFromCamera(camera, params, s, frame);
  if (params.capturePasses)
    bs::capture(frame, params, "2-camera-pass-ramp-depth-alpha",
                "Pass 2: each visible point's own depth from the light, same ramp (minus bias)",
                bs::alphaOf(bs::readWindowRgba(params)));
  subtractShadowMap(camera, params, s, frame);
  if (params.capturePasses) {
    const Image diff = bs::alphaOf(bs::readWindowRgba(params));
    bs::capture(frame, params, "3-difference-alpha",
                "Pass 3: pass 2 minus the projected map, clamped at 0: > 0 in shadow (raw)", diff);
    bs::capture(frame, params, "3-difference-alpha-x32",
                "Pass 3 difference amplified 32x for display",
                bs::amplified(diff, kDifferenceDisplayGain));
  }
  saturateShadowMask(params, s, frame);
  if (params.capturePasses)
    bs::capture(frame, params, "4-shadow-mask-alpha",
                "Pass 4 (footnote 1): the mask after the extra copy, 1 = shadow",
                bs::alphaOf(bs::readWindowRgba(params)));
  shade(camera, params, frame);
  frame.color = readRgb(params.width, params.height);
  frame.visibility = bs::readVisibilityFromAlpha(params);
  if (params.capturePasses)
    bs::capture(frame, params, "5-shaded", "Pass 5: OpenGL lighting x (1 - mask) + ambient",
                frame.color);
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
  t.render = render;
  return t;
}

}  // namespace sl::legacy
