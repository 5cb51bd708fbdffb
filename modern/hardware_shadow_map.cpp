// modern.hw — Everitt, Rege & Cebenoyan 2001 as shaders: the depth texture with compare mode
// (hardware 2x2 filtering with GL_LINEAR), polygon offset, and the texgen planes as one
// uniform matrix. Twin of legacy_gl/hardware_shadow_map.cpp.
//
// Passes:
//   1. renderDepthFromLight — light view into a DEPTH_COMPONENT24 texture, polygon offset;
//                             left out when the pass planner (core/technique/plan.h) finds no
//                             caster in the light frustum (--param plan=off keeps it)
//   2. shadeWithShadowMap   — camera view; hw_shadow.frag does textureProj on sampler2DShadow
// The passes are declared once in hardwareShadowMapPasses().
#include "modern/hardware_shadow_map.h"

#include "core/base/errors.h"
#include "core/technique/pass_capture.h"
#include "core/technique/plan.h"
#include "modern/camera_pass.h"

namespace sl::modern {
using namespace sl::gl;

namespace {
constexpr float kDefaultOffsetFactor = 2.0f;  // same as legacy.hw (Everitt Fig. 3)
constexpr float kDefaultOffsetUnits = 4.0f;
constexpr double kLargestOffsetUnits = 1e6;  // depth steps; far beyond any useful offset

// The passes, declared once: names, the paper's text, the buffers a dump shows, the GLSL they
// run and the passes of legacy.hw (legacy_gl/hardware_shadow_map.cpp) they replace.
PassTable hardwareShadowMapPasses() {
  return {
      {.id = "1",
       .name = "depth from light",
       .reference = "Everitt, Rege & Cebenoyan 2001, First Pass (Depth Map Generation), Fig. 2; "
                    "polygon offset: Why Is Polygon Offset Needed?, Fig. 3",
       .writes = {{.name = "light-depth",
                   .caption = "pass 1 (Everitt Fig. 2): depth from the light with polygon "
                              "offset"}},
       .shaders = {"depth-only"},
       .replaces = {"1"},
       .deviations = {kDepthRoundoffScaleDeviation},
       .keyState = {"GL_POLYGON_OFFSET_FILL", "glPolygonOffset"}},
      cameraPassWithShadowTest("2", "hw_shadow.frag, Everitt Eq. 5: textureProj on sampler2DShadow",
                               {"2", "3", "4", "5"}),
  };
}

const PassTable& passTable() {
  static const PassTable table = hardwareShadowMapPasses();
  return table;
}

// Pass 1 (Everitt Fig. 2): depth from the light with slope-scaled polygon offset.
RenderTarget renderDepthFromLight(Passes& passes, const GpuScene& gpu, const RenderParams& params,
                                  float factor, float units, bool linear, bool casterInFrustum) {
  RenderTarget map;
  passes.run(
      "1",
      [&] {
        // The planner (core/technique/plan.h) found no caster in the light frustum: a 1x1 map at
        // the far depth (every comparison passes) replaces the pass.
        const int n = casterInFrustum ? params.shadowMapTexels : 1;
        map = makeRenderTarget(n, n, {}, true, GL_DEPTH_COMPONENT24);
        map.bind();
        glClear(GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        {
          const ScopedEnable polygonOffset(GL_POLYGON_OFFSET_FILL);
          glPolygonOffset(factor, units * lightDepthRoundoffScale(gpu.scene()));
          const Program& program = cachedProgram("scene.vert.glsl", "depth_only.frag.glsl");
          program.use();
          program.set("uViewProjection",
                      lightProjection(gpu.scene()) * lightView(gpu.scene().light));
          gpu.draw([&](const Object& o) { return casterInFrustum && o.castsShadow; },
                   [&](const Object& o) { program.set("uModel", o.model); });
        }
        setDepthCompareParameters(map.depth.id(), linear);
      },
      {}, casterInFrustum ? "" : " left out (planner: no caster in frustum)");
  return map;
}

}  // namespace

void setDepthCompareParameters(GLuint depthTexture, bool linear) {
  glBindTexture(GL_TEXTURE_2D, depthTexture);
  const GLint filter = linear ? GL_LINEAR : GL_NEAREST;
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
  const float farDepth[4] = {1, 1, 1, 1};
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
  glTexParameterfv(GL_TEXTURE_2D, GL_TEXTURE_BORDER_COLOR, farDepth);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
}

glm::mat4 worldToShadowMap(const Scene& scene) {
  // S: [-1,1] clip coordinates to [0,1] texture coordinates (Everitt Eq. 2).
  const glm::mat4 S = glm::mat4(0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 0.5f, 0, 0.5f, 0.5f, 0.5f, 1);
  return S * lightProjection(scene) * lightView(scene.light);
}

PassSpec cameraPassWithShadowTest(const std::string& id, const std::string& source,
                                  std::vector<std::string> replaces) {
  return {.id = id,
          .name = "camera pass with shadow test",
          .reference =
              "Everitt, Rege & Cebenoyan 2001, Second Pass (Depth Map Comparison): the "
              "planes of Eq. 5 as one matrix, the comparison of How It Works (Fig. 5) by "
              "sampler2DShadow, direct light x result + ambient",
          .writes = cameraPassBuffers(id, source),
          .shaders = {"texgen-planes", "shadow-test", "hw-shade", "hw-visibility"},
          .replaces = std::move(replaces),
          .keyState = {"uWorldToShadowMap"}};
}

// Everitt Eq. 5: shading with the comparison result modulating direct light.
void shadeWithShadowMap(Passes& passes, const std::string& id, const GpuScene& gpu,
                        const RenderParams& params, GLuint shadowMap) {
  passes.run(id, [&] {
    const Scene& scene = gpu.scene();
    RenderTarget target = makeCameraTarget(params, false);
    clearCameraTarget(target);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    const Program& program = cachedProgram("scene.vert.glsl", "hw_shadow.frag.glsl");
    program.use();
    program.set("uViewProjection", cameraViewProjection(scene, params));
    program.set("uWorldToShadowMap", worldToShadowMap(scene));
    setLightingUniforms(program, scene);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, shadowMap);
    program.set("uShadowMap", 0);
    gpu.draw([](const Object&) { return true; },
             [&](const Object& o) { setObjectUniforms(program, o); });
    readCameraTarget(target, passes.frame());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  });
}

namespace {

Frame render(GlContext&, const Scene& scene, const RenderParams& params) {
  const float factor = float(params.number(offsetFactorParam(kDefaultOffsetFactor)));
  const float units =
      float(params.number(offsetUnitsParam(kDefaultOffsetUnits, kLargestOffsetUnits)));
  const bool linear = params.text(compareParam()) == "linear";
  const bool casterInFrustum = !params.flag(planParam()) || casterReachesLightFrustum(scene);
  Frame frame;
  Passes passes(frame, params, passTable());
  GpuScene gpu(scene);
  RenderTarget map =
      renderDepthFromLight(passes, gpu, params, factor, units, linear, casterInFrustum);
  shadeWithShadowMap(passes, "2", gpu, params, map.depth.id());
  // --dump-passes: the depth texture of pass 1 as grey and the camera pass.
  passes.captureDepth("1", "light-depth",
                      [&] { return readDepthTexture(map.depth.id(), map.width, map.height); });
  captureCameraPass(passes, "2");
  return frame;
}
}  // namespace

Technique hardwareShadowMapTechnique() {
  Technique t;
  t.name = "modern.hw";
  t.paper = "Everitt, Rege & Cebenoyan 2001 (as GLSL)";
  t.summary = "sampler2DShadow with compare mode, hardware 2x2 filtering, polygon offset";
  t.status = "complete";
  t.needs.profile = Profile::kCore;
  t.params = {offsetFactorParam(kDefaultOffsetFactor),
              offsetUnitsParam(kDefaultOffsetUnits, kLargestOffsetUnits), compareParam(),
              planParam()};
  t.reads = {.shadowMap = true};
  t.edge = Technique::Edge::kFiltered;  // compare=linear (default): the driver's 2x2 PCF
  t.passes = passTable();
  t.render = render;
  return t;
}

}  // namespace sl::modern
