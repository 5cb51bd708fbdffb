// legacy.hw — Cass Everitt, Ashu Rege, Cem Cebenoyan, "Hardware Shadow Mapping", NVIDIA 2001,
// with ARB_depth_texture and ARB_shadow (the SGIX_shadow/SGIX_depth_texture of the paper).
//
// Passes:
//   1. renderDepthFromLight      — the scene from the light, polygon offset, depth copied
//                                  into a DEPTH_COMPONENT texture (Fig. 2, "Polygon offset");
//                                  left out when the pass planner (core/technique/plan.h) finds no
//                                  caster in the light frustum (--param plan=off keeps it)
//   2. loadEyeLinearTexgenPlanes — EYE_LINEAR planes E_po = S·P_light·L^-1 specified while the
//                                  modelview holds the view matrix (Eq. 1-5, Appendix A)
//   3. renderAmbientPass         — lighting with the ambient term only (Kilgard's note)
//   4. addShadowedDirectLight    — diffuse + specular modulated by the shadow comparison
//                                  (ARB_shadow, NEAREST or LINEAR compare, Fig. 5), added with
//                                  blending; fragments behind the light are forced to shadow
//                                  ("negative projection", §"Advantages and Limitations")
//   5. renderVisibilityMask      — the comparison result alone, for the --mask output
// The passes are declared once in hardwareShadowMapPasses(); passes 2-5 (shadowMapCameraPasses)
// are shared with legacy.woo and legacy.second-depth.
#include "legacy_gl/hardware_shadow_map.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <string>

#include "core/base/errors.h"
#include "core/gl/gl.h"
#include "core/gl/gl_objects.h"
#include "core/technique/pass_capture.h"
#include "core/technique/passes.h"
#include "core/technique/plan.h"
#include "legacy_gl/fixed_function.h"
#include "legacy_gl/projected_spotlight.h"
#include "legacy_gl/spotlight_tessellation.h"

namespace sl::legacy {
using namespace sl::gl;

namespace {

constexpr float kDefaultOffsetFactor = 2.0f;  // glPolygonOffset slope factor (Everitt Fig. 3)
constexpr float kDefaultOffsetUnits = 4.0f;   // glPolygonOffset constant, in depth units
constexpr double kLargestOffsetUnits = 1e6;   // depth steps; far beyond any useful offset
// Texgen scale of the negative-projection test, per light far distance: s = 0.5 + q / far
// (q: light eye-space depth). Any q > 0 lands past the half-texel threshold of the 2-texel step
// texture, and in-frustum fragments get s in (0.5, 1.5] at every scene scale.
// It was once 1e4 per world unit: at a scene scale of 1e5 (q ~ 4e5) s*2 reached 8e9, beyond
// the 32-bit integer texel coordinate llvmpipe converts s to, so the texel index wrapped to
// the "behind" texel and every receiver came out in umbra.
constexpr float kBehindLightSharpness = 1.0f;

struct HwState {
  Texture shadowMap = makeTexture();
};

// Pass 1 (Everitt Fig. 2, "Polygon offset"): render the casters from the light with slope-scaled
// polygon offset and copy the depth buffer into the depth texture (glCopyTexSubImage2D reads
// the depth buffer for a DEPTH_COMPONENT texture, ARB_depth_texture).
void renderDepthFromLight(Passes& passes, const Scene& scene, const RenderParams& params,
                          HwState& s, float factor, float units, bool linearCompare,
                          bool casterInFrustum) {
  passes.run(
      "1",
      [&] {
        // The planner (core/technique/plan.h) found no caster in the light frustum: a 1x1 map at
        // the far depth (every comparison passes) replaces the pass.
        const int n = casterInFrustum ? params.shadowMapTexels : 1;
        LightTarget target(n, n <= params.width && n <= params.height, false);
        target.bind();
        glClear(GL_DEPTH_BUFFER_BIT);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        {
          const ScopedEnable offset(GL_POLYGON_OFFSET_FILL);
          glPolygonOffset(factor, units * lightDepthRoundoffScale(scene));
          loadMatrix(GL_PROJECTION, lightProjection(scene));
          loadMatrix(GL_MODELVIEW, lightView(scene.light));
          if (casterInFrustum) drawScene(scene, Draw::kCasters);
        }
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);

        glBindTexture(GL_TEXTURE_2D, s.shadowMap.id());
        glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, n, n, 0, GL_DEPTH_COMPONENT,
                     GL_UNSIGNED_INT, nullptr);
        glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, n, n);
        setDepthCompareParameters(linearCompare);
        target.unbind();
      },
      {}, casterInFrustum ? "" : " left out (planner: no caster in frustum)");
}

// Pass 2 (Everitt Eq. 5 and Appendix A): with modelview_po = V^-1 (the camera's view matrix,
// Everitt's notation), the planes E_po = S·P_light·L^-1 are given in world space and GL maps
// eye coordinates back through (modelview_po)^-1. Texture unit 0 gets (s,t,r,q) for the map;
// unit 1 gets q alone, scaled, for the behind-the-light step texture.
void loadEyeLinearTexgenPlanes(const Scene& scene, const RenderParams& params, GLuint shadowMap,
                               const Texture& behindLightStep, ScopedTexgen& mapTexgen,
                               ScopedTexgen& stepTexgen) {
  setCameraMatrices(scene, params.width, params.height);  // modelview = V^-1 (Everitt)
  const glm::mat4 planes = glm::transpose(worldToShadowMapTexture(scene));  // rows as columns
  const GLenum coords[4] = {GL_S, GL_T, GL_R, GL_Q};
  const GLenum enables[4] = {GL_TEXTURE_GEN_S, GL_TEXTURE_GEN_T, GL_TEXTURE_GEN_R,
                             GL_TEXTURE_GEN_Q};
  glActiveTexture(GL_TEXTURE0);
  for (int i = 0; i < 4; ++i) {
    glTexGeni(coords[i], GL_TEXTURE_GEN_MODE, GL_EYE_LINEAR);
    glTexGenfv(coords[i], GL_EYE_PLANE, glm::value_ptr(planes[i]));
    mapTexgen.enable(enables[i]);
  }
  loadMatrix(GL_TEXTURE, glm::mat4(1.0f));
  glMatrixMode(GL_MODELVIEW);
  glBindTexture(GL_TEXTURE_2D, shadowMap);

  // Unit 1: s = kBehindLightSharpness * q / far + 0.5 through a 2-texel step (0 behind, 1 in
  // front).
  glActiveTexture(GL_TEXTURE1);
  const glm::mat4 light = lightView(scene.light);
  const glm::vec4 depthRow(-light[0][2], -light[1][2], -light[2][2], -light[3][2]);
  glm::vec4 stepPlane = (kBehindLightSharpness / lightDepthRange(scene).farPlane) * depthRow;
  stepPlane.w += 0.5f;
  glTexGeni(GL_S, GL_TEXTURE_GEN_MODE, GL_EYE_LINEAR);
  glTexGenfv(GL_S, GL_EYE_PLANE, glm::value_ptr(stepPlane));
  stepTexgen.enable(GL_TEXTURE_GEN_S);
  glBindTexture(GL_TEXTURE_1D, behindLightStep.id());
  const GLubyte step[2] = {0, 255};
  glTexImage1D(GL_TEXTURE_1D, 0, GL_LUMINANCE8, 2, 0, GL_LUMINANCE, GL_UNSIGNED_BYTE, step);
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glActiveTexture(GL_TEXTURE0);
}

void enableShadowTexturing(bool on) {
  glActiveTexture(GL_TEXTURE0);
  if (on)
    glEnable(GL_TEXTURE_2D);
  else
    glDisable(GL_TEXTURE_2D);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
  glActiveTexture(GL_TEXTURE1);
  if (on)
    glEnable(GL_TEXTURE_1D);
  else
    glDisable(GL_TEXTURE_1D);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
  glActiveTexture(GL_TEXTURE0);
}

// Pass 3 (Kilgard's note in Everitt): the ambient term, everywhere, unshadowed.
void renderAmbientPass(Passes& passes, const Scene& scene, const RenderParams& params,
                       const std::string& id) {
  passes.run(id, [&] {
    setCameraMatrices(scene, params.width, params.height);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    enableSpotlight(scene, LightTerms::kAmbientOnly);
    drawScene(scene, Draw::kAll);
  });
}

// Pass 4 (Everitt "the shadowing result directly modulates the diffuse and specular"): direct
// light times the comparison result, added on the ambient pass (depth func EQUAL).
void addShadowedDirectLight(Passes& passes, const Scene& scene, const RenderParams& params,
                            const SpotlightConeTexture& coneTexture, const std::string& id) {
  passes.run(id, [&] {
    setCameraMatrices(scene, params.width, params.height);
    enableSpotlight(scene, LightTerms::kDiffuseSpecularOnly);
    glLightModeli(GL_LIGHT_MODEL_COLOR_CONTROL, GL_SINGLE_COLOR);
    glDepthFunc(GL_EQUAL);
    {
      const ScopedEnable blend(GL_BLEND);
      glBlendFunc(GL_ONE, GL_ONE);
      // The cone per pixel (Segal et al. 1992) on the unit after the shadow map's two.
      const ProjectedSpotlightCone cone(scene, coneTexture, GL_TEXTURE2);
      enableShadowTexturing(true);
      drawScene(scene, Draw::kReceivers);
      enableShadowTexturing(false);
      // Objects that do not receive shadows get their direct light unmodulated.
      drawScene(scene, Draw::kNonReceivers);
    }
    glDepthFunc(GL_LESS);
    disableLighting();
  });
}

// Pass 5: the comparison result alone (white surfaces, lighting off) read back as the mask.
Image renderVisibilityMask(Passes& passes, const Scene& scene, const RenderParams& params,
                           const std::string& id) {
  Image mask;
  passes.run(id, [&] {
    setCameraMatrices(scene, params.width, params.height);
    glClearColor(1, 1, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    disableLighting();
    glColor4f(1, 1, 1, 1);
    // Non-receivers untextured (visibility 1); receivers through the shadow test.
    enableShadowTexturing(false);
    drawScene(scene, Draw::kNonReceivers, Colors::kWhite);
    enableShadowTexturing(true);
    drawScene(scene, Draw::kReceivers, Colors::kWhite);
    enableShadowTexturing(false);
    mask = readRedChannel(params.width, params.height);
  });
  return mask;
}

// The passes of Everitt et al., declared once: pass 1 here, passes 2-5 shared.
PassTable hardwareShadowMapPasses() {
  PassTable table = {
      meshFeedingPass(),
      {.id = "1",
       .name = "depth from light",
       .reference = "Everitt, Rege & Cebenoyan 2001, First Pass (Depth Map Generation), Fig. 2; "
                    "polygon offset: Why Is Polygon Offset Needed?, Fig. 3",
       .writes = {{.name = "light-depth",
                   .caption = "pass 1 (Everitt Fig. 2): depth from the light with polygon "
                              "offset"}},
       .floor = PassFloor::kDepthFromLight,
       .role = PassRole::kLight,
       .deviations = {kOffscreenLightPassDeviation, kDepthRoundoffScaleDeviation},
       .keyState = {"GL_POLYGON_OFFSET_FILL", "glPolygonOffset", "glColorMask"}},
  };
  for (PassSpec& spec : shadowMapCameraPasses(2)) table.push_back(std::move(spec));
  return table;
}

const PassTable& passTable() {
  static const PassTable table = hardwareShadowMapPasses();
  return table;
}

Frame render(GlContext& context, const Scene& scene, const RenderParams& params) {
  (void)context;
  const float factor = float(params.number(offsetFactorParam(kDefaultOffsetFactor)));
  const float units =
      float(params.number(offsetUnitsParam(kDefaultOffsetUnits, kLargestOffsetUnits)));
  const bool linear = params.text(compareParam()) == "linear";
  Frame frame;
  Passes passes(frame, params, passTable());
  HwState state;
  const bool casterInFrustum = !params.flag(planParam()) || casterReachesLightFrustum(scene);
  renderDepthFromLight(passes, scene, params, state, factor, units, linear, casterInFrustum);
  const int texels = casterInFrustum ? params.shadowMapTexels : 1;
  passes.captureDepth("1", "light-depth",
                      [&] { return readDepthTexture(state.shadowMap.id(), texels, texels); });
  shadeWithShadowMap(passes, scene, params, state.shadowMap.id(), 2);
  checkGl("legacy.hw");
  return frame;
}

}  // namespace

void setDepthCompareParameters(bool linearCompare) {
  const GLint filter = linearCompare ? GL_LINEAR : GL_NEAREST;
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
  // Outside the map: the border is the far plane, so nothing there is shadowed.
  const float farDepth[4] = {1, 1, 1, 1};
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
  glTexParameterfv(GL_TEXTURE_2D, GL_TEXTURE_BORDER_COLOR, farDepth);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_R_TO_TEXTURE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  glTexParameteri(GL_TEXTURE_2D, GL_DEPTH_TEXTURE_MODE, GL_LUMINANCE);
}

PassTable shadowMapCameraPasses(int firstPass) {
  const std::string texgen = std::to_string(firstPass), ambient = std::to_string(firstPass + 1),
                    direct = std::to_string(firstPass + 2), mask = std::to_string(firstPass + 3);
  return {
      {.id = texgen,
       .name = "eye-linear texgen planes",
       .reference = "Everitt, Rege & Cebenoyan 2001, Setting Up the Transformations, Eq. 5; "
                    "Second Pass (Depth Map Comparison); Appendix A",
       .floor = PassFloor::kStateOnly,
       .keyState = {"GL_EYE_PLANE"}},
      {.id = ambient,
       .name = "ambient",
       .reference = "Everitt, Rege & Cebenoyan 2001, the shading step after Fig. 4 (Kilgard [3]: "
                    "keep some light in the shadow); the ambient term unshadowed",
       .writes = {{.name = "ambient",
                   .caption = "pass " + ambient +
                              ": the ambient term alone, unshadowed (Everitt, Kilgard's note)"}},
       .floor = PassFloor::kAmbientCamera,
       .role = PassRole::kCamera},
      {.id = direct,
       .name = "direct light x shadow test",
       .reference = "Everitt, Rege & Cebenoyan 2001, How It Works (r/q <= texture2D(s/q, t/q)), "
                    "Figs. 4-5; behind the light: Advantages and Limitations (negative "
                    "projection)",
       .writes = {{.name = "shaded",
                   .caption = "pass " + direct +
                              ": + diffuse and specular x the ARB_shadow comparison (Everitt "
                              "Eq. 5, Fig. 5): the final image"}},
       .floor = PassFloor::kShadowedDirectLight,
       .role = PassRole::kLighting,
       .deviations = {kProjectedConeDeviation}},
      {.id = mask,
       .name = "visibility mask",
       .reference = "ours, not a paper's pass: the comparison alone on white surfaces, for --mask "
                    "and the twin comparison",
       .writes = {{.name = "visibility",
                   .caption = "pass " + mask +
                              ": the comparison alone on white surfaces, white = lit, black = "
                              "shadow (what --mask writes)"}},
       .floor = PassFloor::kVisibilityMask},
  };
}

void shadeWithShadowMap(Passes& passes, const Scene& lightScene, const RenderParams& params,
                        GLuint shadowMap, int firstPass) {
  const std::string texgen = std::to_string(firstPass), ambient = std::to_string(firstPass + 1),
                    direct = std::to_string(firstPass + 2), mask = std::to_string(firstPass + 3);
  Frame& frame = passes.frame();
  // The camera passes draw the scene split for per-vertex spotlight lighting (same geometry).
  const Scene scene = cameraPassScene(lightScene, params, passes);
  const Texture behindLightStep = makeTexture();
  // The texgen pass 2 turns on (unit 0: s, t, r, q; unit 1: s), off again when the camera
  // passes end, however they end: the caller gets the texturing state it had.
  ScopedTexgen mapTexgen(GL_TEXTURE0), stepTexgen(GL_TEXTURE1);
  // Pass 2 (Everitt Eq. 5, Appendix A): timed here, loadEyeLinearTexgenPlanes does it.
  passes.run(texgen, [&] {
    loadEyeLinearTexgenPlanes(scene, params, shadowMap, behindLightStep, mapTexgen, stepTexgen);
  });
  renderAmbientPass(passes, scene, params, ambient);
  passes.capture(ambient, "ambient", [&] { return readRgb(params.width, params.height); });
  // Untimed, before the pass: the cone's texture is the same for every light and scene.
  const SpotlightConeTexture coneTexture;
  addShadowedDirectLight(passes, scene, params, coneTexture, direct);
  frame.color = readRgb(params.width, params.height);
  frame.visibility = renderVisibilityMask(passes, scene, params, mask);
  passes.capture(direct, "shaded", [&] { return frame.color; });
  passes.capture(mask, "visibility", [&] { return frame.visibility; });
}

glm::mat4 worldToShadowMapTexture(const Scene& scene) {
  // S: [-1,1] clip coordinates to [0,1] texture coordinates (Everitt Eq. 2).
  const glm::mat4 S = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) *
                      glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
  return S * lightProjection(scene) * lightView(scene.light);
}

Technique hardwareShadowMapTechnique() {
  Technique t;
  t.name = "legacy.hw";
  t.paper = "Everitt, Rege & Cebenoyan 2001 (ARB_depth_texture + ARB_shadow)";
  t.summary = "depth texture with hardware comparison, EYE_LINEAR texgen, polygon offset";
  t.status = "complete";
  t.needs.profile = Profile::kCompatibility;
  t.params = {offsetFactorParam(kDefaultOffsetFactor),
              offsetUnitsParam(kDefaultOffsetUnits, kLargestOffsetUnits), compareParam(),
              planParam()};
  t.reads = {.shadowMap = true};
  t.edge = Technique::Edge::kFiltered;  // compare=linear (default): the driver's 2x2 PCF
  t.passes = passTable();
  t.render = render;
  return t;
}

}  // namespace sl::legacy
