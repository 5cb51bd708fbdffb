// modern.second-depth — Wang & Molnar's second-depth shadow map (UNC TR94-019, 1994, as
// Everitt, Rege & Cebenoyan 2001 summarise it): only back faces, seen from the light, in the
// map; no polygon offset; closed casters only. Twin of legacy_gl/second_depth_shadow_map.cpp.
//
// Passes:
//   1. renderBackFacesFromLight — closed casters from the light with front faces culled, open
//                                 casters with both faces and polygon offset (fallback)
//   2. shadeWithShadowMap       — modern.hw's camera pass on that map
// The passes are declared once in secondDepthPasses().
#include "core/base/errors.h"
#include "core/technique/pass_capture.h"
#include "modern/camera_pass.h"
#include "modern/depth_layer_shadow_maps.h"
#include "modern/hardware_shadow_map.h"

namespace sl::modern {
using namespace sl::gl;

namespace {

// DEVIATION (Wang & Molnar 1994; Everitt et al. 2001), as legacy.second-depth: open casters have
// no back face behind their front face, so they are drawn with both faces and modern.hw's
// polygon offset; closed casters keep the second depth.
constexpr float kOpenCasterOffsetFactor = 2.0f;  // glPolygonOffset slope factor, as modern.hw
constexpr float kOpenCasterOffsetUnits = 4.0f;   // glPolygonOffset constant, in depth units

// The passes, declared once: names, the paper's text, the buffers a dump shows, the GLSL they
// run, the passes of legacy.second-depth (legacy_gl/second_depth_shadow_map.cpp) they replace
// and the departure above.
PassTable secondDepthPasses() {
  return {
      {.id = "1",
       .name = "back faces from light",
       .reference = "Everitt, Rege & Cebenoyan 2001, Advantages and Limitations (Wang & Molnar "
                    "[7]): back faces only, no polygon offset; open casters with offset are ours "
                    "(DEVIATION)",
       .writes = {{.name = "second-depth-map",
                   .caption = "pass 1 (Wang & Molnar 1994, Everitt \"Advantages and "
                              "Limitations\"): back faces of closed casters from the light, open "
                              "casters with polygon offset"}},
       .shaders = {"depth-only"},
       .replaces = {"1"},
       .deviations = {"DEVIATION (Wang & Molnar 1994; Everitt et al. 2001), as "
                      "legacy.second-depth: open casters have no back face behind their front "
                      "face, so they are drawn with both faces and modern.hw's polygon offset; "
                      "closed casters keep the second depth.",
                      kDepthRoundoffScaleDeviation}},
      cameraPassWithShadowTest("2", "hw_shadow.frag on the second-depth map, Everitt Eq. 5",
                               {"2", "3", "4", "5"}),
  };
}

const PassTable& passTable() {
  static const PassTable table = secondDepthPasses();
  return table;
}

// Pass 1 (Wang & Molnar via Everitt): counter-clockwise meshes, GL_FRONT culled in the light's
// view, so the depth buffer keeps the faces that point away from the light.
RenderTarget renderBackFacesFromLight(Passes& passes, const GpuScene& gpu, int n, bool linear) {
  RenderTarget map;
  passes.run("1", [&] {
    map = makeRenderTarget(n, n, {}, true, GL_DEPTH_COMPONENT24);
    map.bind();
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glFrontFace(GL_CCW);
    const Program& program = cachedProgram("scene.vert.glsl", "depth_only.frag.glsl");
    auto setModel = [&](const Object& o) { program.set("uModel", o.model); };
    {
      const ScopedEnable cullFace(GL_CULL_FACE);
      glCullFace(GL_FRONT);
      program.use();
      program.set("uViewProjection", lightProjection(gpu.scene()) * lightView(gpu.scene().light));
      gpu.draw([](const Object& o) { return o.castsShadow && o.mesh->closed; }, setModel);
    }
    glCullFace(GL_BACK);
    {
      const ScopedEnable polygonOffset(GL_POLYGON_OFFSET_FILL);  // the open-caster fallback
      glPolygonOffset(kOpenCasterOffsetFactor,
                      kOpenCasterOffsetUnits * lightDepthRoundoffScale(gpu.scene()));
      gpu.draw([](const Object& o) { return o.castsShadow && !o.mesh->closed; }, setModel);
    }
    setDepthCompareParameters(map.depth.id(), linear);
  });
  return map;
}

Frame render(GlContext&, const Scene& scene, const RenderParams& params) {
  const bool linear = params.text(compareParam()) == "linear";
  Frame frame;
  Passes passes(frame, params, passTable());
  GpuScene gpu(scene);
  RenderTarget map = renderBackFacesFromLight(passes, gpu, params.shadowMapTexels, linear);
  shadeWithShadowMap(passes, "2", gpu, params, map.depth.id());
  // --dump-passes: the second-depth map of pass 1 as grey and the camera pass.
  passes.captureDepth("1", "second-depth-map",
                      [&] { return readDepthTexture(map.depth.id(), map.width, map.height); });
  captureCameraPass(passes, "2");
  return frame;
}

}  // namespace

Technique secondDepthShadowMapTechnique() {
  Technique t;
  t.name = "modern.second-depth";
  t.paper = "Wang & Molnar 1994 second-depth shadow map (Everitt et al. 2001), as GLSL";
  t.summary = "only back faces of closed casters in the shadow map, no polygon offset";
  t.status = "complete";
  t.needs.profile = Profile::kCore;
  t.params = {compareParam()};
  t.reads = {.shadowMap = true};
  t.edge = Technique::Edge::kFiltered;  // compare=linear (default): the driver's 2x2 PCF
  t.passes = passTable();
  t.render = render;
  return t;
}

}  // namespace sl::modern
