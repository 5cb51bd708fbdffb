// modern.woo — Woo's midpoint shadow map (Everitt, Rege & Cebenoyan 2001, "Advantages and
// Limitations": average of the nearest and second-nearest depth layers from the light, made by
// depth peeling) as shaders. Twin of legacy_gl/woo_shadow_map.cpp.
//
// Passes:
//   1. renderFirstDepthLayer — casters from the light into depth texture z1 (no offset)
//   2. peelSecondDepthLayer  — casters again; woo_peel.frag discards what is not behind z1,
//                              the depth test keeps the second layer z2
//   3. storeMidpointDepth    — woo_midpoint.frag writes gl_FragDepth = (z1 + z2) / 2
//   4. shadeWithShadowMap    — modern.hw's camera pass on the midpoint map
#include "core/errors.h"
#include "core/pass_capture.h"
#include "modern/camera_pass.h"
#include "modern/depth_layer_shadow_maps.h"
#include "modern/hardware_shadow_map.h"

namespace sl::modern {
using namespace sl::gl;

namespace {

// Same tolerance as legacy.woo (see legacy_gl/woo_shadow_map.cpp): 2^-20 in window depth, times
// lightDepthRoundoffScale (core/scene.h) where the light's depth range is narrow.
constexpr float kPeelEpsilon = 1.0f / float(1 << 20);

RenderTarget makeDepthMap(int n) {
  RenderTarget map = makeRenderTarget(n, n, {}, true, GL_DEPTH_COMPONENT24);
  map.bind();
  glClear(GL_DEPTH_BUFFER_BIT);
  return map;
}

// Pass 1 (Everitt, Woo paragraph): nearest depth layer from the light, without polygon offset.
RenderTarget renderFirstDepthLayer(const GpuScene& gpu, int n, Frame& frame) {
  PassTimer timer(frame, "1 first depth layer",
                  "Everitt, Rege & Cebenoyan 2001, Advantages and Limitations (Woo [9]): the "
                  "nearest layer from the light, no polygon offset");
  timer.shaderPasses({"depth-only"});
  RenderTarget map = makeDepthMap(n);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  const Program& program = cachedProgram("scene.vert.glsl", "depth_only.frag.glsl");
  program.use();
  program.set("uViewProjection", lightProjection(gpu.scene()) * lightView(gpu.scene().light));
  gpu.draw([](const Object& o) { return o.castsShadow; },
           [&](const Object& o) { program.set("uModel", o.model); });
  return map;
}

// Pass 2 (Everitt, depth peeling [2]): keep only fragments behind the first layer.
RenderTarget peelSecondDepthLayer(const GpuScene& gpu, int n, const RenderTarget& first,
                                  Frame& frame) {
  PassTimer timer(frame, "2 peel to second depth layer",
                  "Everitt, Rege & Cebenoyan 2001, Advantages and Limitations (Woo [9]), by "
                  "depth peeling [2]: the second-nearest layer");
  timer.shaderPasses({"peel"});
  glBindTexture(GL_TEXTURE_2D, first.depth.id());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_GEQUAL);
  RenderTarget map = makeDepthMap(n);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  const Program& program = cachedProgram("scene.vert.glsl", "woo_peel.frag.glsl");
  program.use();
  program.set("uViewProjection", lightProjection(gpu.scene()) * lightView(gpu.scene().light));
  program.set("uWorldToShadowMap", worldToShadowMap(gpu.scene()));
  program.set("uPeelEpsilon", kPeelEpsilon * lightDepthRoundoffScale(gpu.scene()));
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, first.depth.id());
  program.set("uFirstLayer", 0);
  gpu.draw([](const Object& o) { return o.castsShadow; },
           [&](const Object& o) { program.set("uModel", o.model); });
  return map;
}

// Pass 3 (Woo's midpoint): (z1 + z2) / 2 as the depth of a full-screen triangle.
RenderTarget storeMidpointDepth(int n, const RenderTarget& first, const RenderTarget& second,
                                bool linear, Frame& frame) {
  PassTimer timer(frame, "3 midpoint of the layers",
                  "Everitt, Rege & Cebenoyan 2001, Advantages and Limitations (Woo [9]): the map "
                  "is the average of the two layers, written as gl_FragDepth");
  timer.shaderPasses({"midpoint"});
  for (GLuint t : {first.depth.id(), second.depth.id()}) {
    glBindTexture(GL_TEXTURE_2D, t);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  }
  RenderTarget map = makeDepthMap(n);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_ALWAYS);
  const Program& program = cachedProgram("fullscreen.vert.glsl", "woo_midpoint.frag.glsl");
  program.use();
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, first.depth.id());
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, second.depth.id());
  glActiveTexture(GL_TEXTURE0);
  program.set("uFirstLayer", 0);
  program.set("uSecondLayer", 1);
  FullScreenTriangle().draw();
  glDepthFunc(GL_LESS);
  setDepthCompareParameters(map.depth.id(), linear);
  return map;
}

// --dump-passes: z1, z2 and the midpoint on one grey scale (nearest z1 black, the clear depth
// 1 white: one affine map, as legacy.woo shows them), then the camera pass.
void captureLayersAndCameraPass(const RenderTarget& first, const RenderTarget& second,
                                const RenderTarget& midpoint, Frame& frame) {
  const Image z1 = readDepthTexture(first.depth.id(), first.width, first.height);
  const Image z2 = readDepthTexture(second.depth.id(), second.width, second.height);
  const Image mid = readDepthTexture(midpoint.depth.id(), midpoint.width, midpoint.height);
  const WindowDepthSpan range{drawnDepthRange({&z1}).lo, kClearDepth};
  frame.intermediates.push_back(
      greyDepth("1-first-depth-layer",
                "pass 1: nearest depth from the light z1 (Everitt, Woo paragraph)", z1, range));
  frame.intermediates.push_back(greyDepth(
      "2-second-depth-layer",
      "pass 2: woo_peel.frag discards what is not behind z1, the depth test keeps z2", z2, range));
  frame.intermediates.push_back(greyDepth("3-midpoint-shadow-map",
                                          "pass 3: woo_midpoint.frag, gl_FragDepth = (z1 + z2) / 2",
                                          mid, range));
  captureCameraPass(frame, 4, "hw_shadow.frag on the midpoint map, Everitt Eq. 5");
}

Frame render(GlContext&, const Scene& scene, const RenderParams& params) {
  const bool linear = params.text(compareParam()) == "linear";
  const int n = params.shadowMapTexels;
  Frame frame;
  GpuScene gpu(scene);
  RenderTarget first = renderFirstDepthLayer(gpu, n, frame);
  RenderTarget second = peelSecondDepthLayer(gpu, n, first, frame);
  RenderTarget midpoint = storeMidpointDepth(n, first, second, linear, frame);
  shadeWithShadowMap(gpu, params, midpoint.depth.id(), "4 camera pass with shadow test", frame);
  if (params.capturePasses) captureLayersAndCameraPass(first, second, midpoint, frame);
  return frame;
}

}  // namespace

Technique wooShadowMapTechnique() {
  Technique t;
  t.name = "modern.woo";
  t.paper = "Woo's midpoint shadow map (Everitt, Rege & Cebenoyan 2001), as GLSL";
  t.summary = "depth peeling in a shader, midpoint written as gl_FragDepth, no polygon offset";
  t.status = "complete";
  t.needs.profile = Profile::kCore;
  t.params = {compareParam()};
  t.reads = {.shadowMap = true};
  t.render = render;
  return t;
}

}  // namespace sl::modern
