// legacy.second-depth — Yulan Wang & Steven Molnar, "Second-Depth Shadow Mapping", UNC TR94-019,
// 1994, as Everitt, Rege & Cebenoyan 2001 summarise it ("Advantages and Limitations"): only
// back faces (as seen from the light) go into the shadow map, so a lit front face lies a whole
// object thickness in front of the stored depth and needs no polygon offset. Back faces are
// unlit by definition, which hides their own acne. Valid for closed objects only.
//
// Passes:
//   1. renderBackFacesFromLight — closed casters from the light with front faces culled, open
//                                 casters with both faces and polygon offset (our fallback);
//                                 the depth buffer copied into the DEPTH_COMPONENT map
//   2-5. shadeWithShadowMap     — legacy.hw's camera passes (texgen planes, ambient, direct
//                                 light x shadow test, visibility mask)
// The passes are declared once in secondDepthPasses().
#include "core/base/errors.h"
#include "core/gl/gl.h"
#include "core/gl/gl_objects.h"
#include "core/technique/pass_capture.h"
#include "core/technique/passes.h"
#include "legacy_gl/depth_layer_shadow_maps.h"
#include "legacy_gl/fixed_function.h"
#include "legacy_gl/hardware_shadow_map.h"
#include "legacy_gl/spotlight_tessellation.h"

namespace sl::legacy {
using namespace sl::gl;

namespace {

// DEVIATION (Wang & Molnar 1994; Everitt et al. 2001): the method needs closed casters. An open
// caster (a quad, a ground plane, a mesh with holes) has no back face behind its front face, so
// it would cast nothing. Our fallback draws open casters with both faces and legacy.hw's
// slope-scaled polygon offset: they cast as in legacy.hw, closed casters keep the second depth.
constexpr float kOpenCasterOffsetFactor = 2.0f;  // glPolygonOffset slope factor, as legacy.hw
constexpr float kOpenCasterOffsetUnits = 4.0f;   // glPolygonOffset constant, in depth units
constexpr char kOpenCasterDeviation[] =
    "DEVIATION (Wang & Molnar 1994; Everitt et al. 2001): the method needs closed casters. An "
    "open caster (a quad, a ground plane, a mesh with holes) has no back face behind its front "
    "face, so it would cast nothing. Our fallback draws open casters with both faces and "
    "legacy.hw's slope-scaled polygon offset: they cast as in legacy.hw, closed casters keep the "
    "second depth.";

Scene castersOf(const Scene& scene, bool closed) {
  Scene subset = scene;
  std::erase_if(subset.objects,
                [&](const Object& o) { return !o.castsShadow || o.mesh->closed != closed; });
  return subset;
}

// Pass 1 (Wang & Molnar via Everitt): the second depth of closed casters = their back faces.
// Meshes wind counter-clockwise seen from outside (core/scene/primitives.h), so culling GL_FRONT in
// the light's view keeps the faces that point away from the light.
void renderBackFacesFromLight(Passes& passes, const Scene& scene, const RenderParams& params,
                              GLuint shadowMap, bool linearCompare) {
  passes.run("1", [&] {
    const int n = params.shadowMapTexels;
    LightTarget target(n, n <= params.width && n <= params.height, false);
    target.bind();
    glClear(GL_DEPTH_BUFFER_BIT);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glFrontFace(GL_CCW);
    {
      const ScopedEnable cull(GL_CULL_FACE);
      glCullFace(GL_FRONT);
      loadMatrix(GL_PROJECTION, lightProjection(scene));
      loadMatrix(GL_MODELVIEW, lightView(scene.light));
      drawScene(castersOf(scene, true), Draw::kCasters);
    }
    glCullFace(GL_BACK);
    {
      const ScopedEnable offset(GL_POLYGON_OFFSET_FILL);  // the open-caster fallback (DEVIATION)
      glPolygonOffset(kOpenCasterOffsetFactor,
                      kOpenCasterOffsetUnits * lightDepthRoundoffScale(scene));
      drawScene(castersOf(scene, false), Draw::kCasters);
    }
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBindTexture(GL_TEXTURE_2D, shadowMap);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, n, n, 0, GL_DEPTH_COMPONENT,
                 GL_UNSIGNED_INT, nullptr);
    glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, n, n);
    setDepthCompareParameters(linearCompare);
    target.unbind();
  });
}

// The passes of the second-depth map, declared once: pass 1 here, 2-5 legacy.hw's.
PassTable secondDepthPasses() {
  PassTable table = {
      meshFeedingPass(),
      {.id = "1",
       .name = "back faces from light",
       .reference = "Everitt, Rege & Cebenoyan 2001, Advantages and Limitations (Wang & Molnar "
                    "[7]): back faces only, no polygon offset; open casters with offset are ours "
                    "(DEVIATION)",
       .writes = {{.name = "second-depth-map",
                   .caption = "pass 1 (Wang & Molnar 1994, Everitt \"Advantages and "
                              "Limitations\"): back faces of closed casters from the light, open "
                              "casters with polygon offset"}},
       .role = PassRole::kLight,
       .deviations = {kOpenCasterDeviation, kOffscreenLightPassDeviation,
                      kDepthRoundoffScaleDeviation}},
  };
  for (PassSpec& spec : shadowMapCameraPasses(2)) table.push_back(std::move(spec));
  return table;
}

const PassTable& passTable() {
  static const PassTable table = secondDepthPasses();
  return table;
}

Frame render(GlContext&, const Scene& scene, const RenderParams& params) {
  const bool linear = params.text(compareParam()) == "linear";
  const int n = params.shadowMapTexels;
  Frame frame;
  Passes passes(frame, params, passTable());
  const Texture shadowMap = makeTexture();
  renderBackFacesFromLight(passes, scene, params, shadowMap.id(), linear);
  passes.captureDepth("1", "second-depth-map",
                      [&] { return readDepthTexture(shadowMap.id(), n, n); });
  shadeWithShadowMap(passes, scene, params, shadowMap.id(), 2);
  checkGl("legacy.second-depth");
  return frame;
}

}  // namespace

Technique secondDepthShadowMapTechnique() {
  Technique t;
  t.name = "legacy.second-depth";
  t.paper = "Wang & Molnar 1994 second-depth shadow map (Everitt, Rege & Cebenoyan 2001)";
  t.summary = "only back faces of closed casters in the shadow map, no polygon offset";
  t.status = "complete";
  t.needs.profile = Profile::kCompatibility;
  t.params = {compareParam()};
  t.reads = {.shadowMap = true};
  t.edge = Technique::Edge::kFiltered;  // compare=linear (default): the driver's 2x2 PCF
  t.passes = passTable();
  t.render = render;
  return t;
}

}  // namespace sl::legacy
