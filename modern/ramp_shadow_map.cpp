// modern.ramp — Stefan Brabec & Hans-Peter Seidel, "Hardware-accelerated Rendering of
// Antialiased Shadows with Shadow Maps", CGI 2001, §2 (after Heidrich 1999): shadow mapping on
// any OpenGL by encoding depth as colour, as shaders. Twin of legacy_gl's legacy.ramp.
//
// Passes:
//   1. renderDepthAsColourFromLight — the casters from the light, light-space depth through the
//                                     1D ramp into a colour map (Figure 1); render-to-texture
//                                     replaces the framebuffer copy
//   2. shadowTestAndShade           — the camera view: the fragment's depth through the same ramp
//                                     minus the projected map, clamped at 0 as subtractive
//                                     blending does, > 0 = shadowed (footnote 1); shading
// The passes are declared once in rampPasses().
#include "core/base/errors.h"
#include "core/technique/pass_capture.h"
#include "core/technique/passes.h"
#include "modern/brabec_seidel.h"
#include "modern/brabec_seidel_techniques.h"
#include "modern/camera_pass.h"

namespace sl::modern {
using namespace sl::gl;

namespace {

// The passes, declared once: names, the paper's text, the buffers a dump shows, the GLSL they
// run and the passes of legacy.ramp (legacy_gl/ramp_shadow_map.cpp) they replace.
PassTable rampPasses() {
  return {
      {.id = "1",
       .name = "light pass: depth as colour",
       .reference = "Brabec & Seidel 2001 §2, Fig. 1 (after Heidrich [4]): light depth through "
                    "the ramp as colour; render-to-texture replaces the copy",
       .writes = {{.name = "light-pass-ramp-depth",
                   .caption = "light-space depth through the ramp (Figure 1)"}},
       .shaders = {"encode-depth"},
       .replaces = {"1"}},
      {.id = "2",
       .name = "camera pass: ramp depth minus projected map",
       .reference = "Brabec & Seidel 2001 §2 (second and third passes, footnote 1) and §5: ramp "
                    "depth minus projected map, > 0 = shadowed, OpenGL lighting",
       .writes = cameraPassBuffers(
           "2", "ramp_shadow.frag: ramp depth minus the projected map, Brabec & Seidel §2"),
       .shaders = {"ramp-camera-depth", "ramp-subtract", "ramp-saturate", "ramp-float",
                   "ramp-shade"},
       .replaces = {"2", "3", "4", "5"}},
  };
}

const PassTable& passTable() {
  static const PassTable table = rampPasses();
  return table;
}

// Pass 1 (§2, Figure 1): depth -> ramp -> colour, from the light.
RenderTarget renderDepthAsColourFromLight(Passes& passes, const GpuScene& gpu,
                                          const RenderParams& params, const Texture& ramp) {
  RenderTarget map;
  passes.run("1", [&] {
    map = bs::makeEncodedDepthTarget(params);
    bs::renderEncodedDepth(gpu, params, ramp, map, glm::bvec4(true), glm::vec2(0.0f));
  });
  return map;
}

// Pass 2 (§2, second and third passes): encoded fragment depth minus projected map.
void shadowTestAndShade(Passes& passes, const GpuScene& gpu, const RenderParams& params,
                        const Texture& ramp, const RenderTarget& map) {
  passes.run("2", [&] {
    const Scene& scene = gpu.scene();
    const bool faithful = bs::arithmeticOf(params) == bs::Arithmetic::kFaithful;
    RenderTarget target = makeCameraTarget(params, true);  // visibility exactly as computed
    clearCameraTarget(target);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    const Program& program = cachedProgram("texgen.vert.glsl", "ramp_shadow.frag.glsl");
    program.use();
    const glm::mat4 view = cameraView(scene.camera);
    const glm::mat4 projection =
        cameraProjection(scene.camera, float(params.width) / float(params.height));
    program.set("uEyeToRamp", bs::cameraEyeToRamp(scene, params));
    program.set("uEyeToShadowMap[0]",
                bs::cameraEyeToShadowMap(scene, params.shadowMapTexels, glm::vec2(0.0f)));
    program.set("uDepthPlane", bs::depthPlane(scene));
    program.set("uBias", bs::depthBias(params));
    program.set("uFaithful", faithful ? 1 : 0);
    bs::setLegacyArithmeticUniforms(program, params);
    setLightingUniforms(program, scene);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_1D, ramp.id());
    program.set("uRamp", 0);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, map.color[0].id());
    program.set("uShadowMap", 1);
    glActiveTexture(GL_TEXTURE0);
    gpu.draw([](const Object&) { return true; },
             [&](const Object& o) {
               setObjectUniforms(program, o);
               bs::setTexgenObjectUniforms(program, o, view, projection);
             });
    readCameraTarget(target, passes.frame());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  });
}

Frame render(GlContext&, const Scene& scene, const RenderParams& params) {
  Frame frame;
  Passes passes(frame, params, passTable());
  GpuScene gpu(scene);
  const Texture ramp = bs::makeRampTexture(params);
  const RenderTarget map = renderDepthAsColourFromLight(passes, gpu, params, ramp);
  passes.capture("1", "light-pass-ramp-depth", [&] { return readAttachment(map, 0); });
  shadowTestAndShade(passes, gpu, params, ramp, map);
  captureCameraPass(passes, "2");
  return frame;
}

}  // namespace

Technique rampShadowMapTechnique() {
  Technique t;
  t.name = "modern.ramp";
  t.paper = "Brabec & Seidel 2001, §2 (as GLSL)";
  t.summary =
      "depth encoded through a 1D ramp, shadow test by subtraction; faithful|float arithmetic";
  t.status = "complete";
  t.needs.profile = Profile::kCore;
  t.params = bs::params();
  t.reads = {.shadowMap = true, .precision = true};
  t.passes = passTable();
  t.render = render;
  return t;
}

}  // namespace sl::modern
