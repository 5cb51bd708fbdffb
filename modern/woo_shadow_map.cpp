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
// The passes are declared once in wooPasses().
#include "core/base/errors.h"
#include "core/technique/pass_capture.h"
#include "modern/camera_pass.h"
#include "modern/depth_layer_shadow_maps.h"
#include "modern/hardware_shadow_map.h"

namespace sl::modern {
using namespace sl::gl;

namespace {

// Same tolerance as legacy.woo (see legacy_gl/woo_shadow_map.cpp): 2^-20 in window depth, times
// lightDepthRoundoffScale (core/scene/scene.h) where the light's depth range is narrow.
constexpr float kPeelEpsilon = 1.0f / float(1 << 20);

// The passes, declared once: names, the paper's text, the buffers a dump shows, the GLSL they
// run and the passes of legacy.woo (legacy_gl/woo_shadow_map.cpp) they replace. The three maps
// are shown on one grey scale (nearest z1 black, the clear depth 1 white).
PassTable wooPasses() {
  return {
      {.id = "1",
       .name = "first depth layer",
       .reference = "Everitt, Rege & Cebenoyan 2001, Advantages and Limitations (Woo [9]): the "
                    "nearest layer from the light, no polygon offset",
       .writes = {{.name = "first-depth-layer",
                   .caption = "pass 1: nearest depth from the light z1 (Everitt, Woo paragraph)"}},
       .shaders = {"depth-only"},
       .replaces = {"1"}},
      {.id = "2",
       .name = "peel to second depth layer",
       .reference = "Everitt, Rege & Cebenoyan 2001, Advantages and Limitations (Woo [9]), by "
                    "depth peeling [2]: the second-nearest layer",
       .writes = {{.name = "second-depth-layer",
                   .caption = "pass 2: woo_peel.frag discards what is not behind z1, the depth "
                              "test keeps z2"}},
       .shaders = {"peel"},
       .replaces = {"2"},
       .deviations = {kDepthRoundoffScaleDeviation}},
      {.id = "3",
       .name = "midpoint of the layers",
       .reference = "Everitt, Rege & Cebenoyan 2001, Advantages and Limitations (Woo [9]): the map "
                    "is the average of the two layers, written as gl_FragDepth",
       .writes = {{.name = "midpoint-shadow-map",
                   .caption = "pass 3: woo_midpoint.frag, gl_FragDepth = (z1 + z2) / 2"}},
       .shaders = {"midpoint"},
       .replaces = {"3"}},
      cameraPassWithShadowTest("4", "hw_shadow.frag on the midpoint map, Everitt Eq. 5",
                               {"4", "5", "6", "7"}),
  };
}

const PassTable& passTable() {
  static const PassTable table = wooPasses();
  return table;
}

RenderTarget makeDepthMap(int n) {
  RenderTarget map = makeRenderTarget(n, n, {}, true, GL_DEPTH_COMPONENT24);
  map.bind();
  glClear(GL_DEPTH_BUFFER_BIT);
  return map;
}

// Pass 1 (Everitt, Woo paragraph): nearest depth layer from the light, without polygon offset.
RenderTarget renderFirstDepthLayer(Passes& passes, const GpuScene& gpu, int n) {
  RenderTarget map;
  passes.run("1", [&] {
    map = makeDepthMap(n);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    const Program& program = cachedProgram("scene.vert.glsl", "depth_only.frag.glsl");
    program.use();
    program.set("uViewProjection", lightProjection(gpu.scene()) * lightView(gpu.scene().light));
    gpu.draw([](const Object& o) { return o.castsShadow; },
             [&](const Object& o) { program.set("uModel", o.model); });
  });
  return map;
}

// Pass 2 (Everitt, depth peeling [2]): keep only fragments behind the first layer.
RenderTarget peelSecondDepthLayer(Passes& passes, const GpuScene& gpu, int n,
                                  const RenderTarget& first) {
  RenderTarget map;
  passes.run("2", [&] {
    glBindTexture(GL_TEXTURE_2D, first.depth.id());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_GEQUAL);
    map = makeDepthMap(n);
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
  });
  return map;
}

// Pass 3 (Woo's midpoint): (z1 + z2) / 2 as the depth of a full-screen triangle.
RenderTarget storeMidpointDepth(Passes& passes, int n, const RenderTarget& first,
                                const RenderTarget& second, bool linear) {
  RenderTarget map;
  passes.run("3", [&] {
    for (GLuint t : {first.depth.id(), second.depth.id()}) {
      glBindTexture(GL_TEXTURE_2D, t);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    }
    map = makeDepthMap(n);
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
  });
  return map;
}

Image readDepth(const RenderTarget& map) {
  return readDepthTexture(map.depth.id(), map.width, map.height);
}

Frame render(GlContext&, const Scene& scene, const RenderParams& params) {
  const bool linear = params.text(compareParam()) == "linear";
  const int n = params.shadowMapTexels;
  Frame frame;
  Passes passes(frame, params, passTable());
  GpuScene gpu(scene);
  RenderTarget first = renderFirstDepthLayer(passes, gpu, n);
  RenderTarget second = peelSecondDepthLayer(passes, gpu, n, first);
  RenderTarget midpoint = storeMidpointDepth(passes, n, first, second, linear);
  shadeWithShadowMap(passes, "4", gpu, params, midpoint.depth.id());
  // --dump-passes: z1, z2 and the midpoint on one grey scale, the nearest z1 black, the clear
  // depth 1 white (one affine map, as legacy.woo shows them).
  const auto layerScale = [&] {
    const Image z1 = readDepth(first);
    return WindowDepthSpan{drawnDepthRange({&z1}).lo, kClearDepth};
  };
  passes.captureDepth(
      "1", "first-depth-layer", [&] { return readDepth(first); }, {}, {}, layerScale);
  passes.captureDepth(
      "2", "second-depth-layer", [&] { return readDepth(second); }, {}, {}, layerScale);
  passes.captureDepth(
      "3", "midpoint-shadow-map", [&] { return readDepth(midpoint); }, {}, {}, layerScale);
  captureCameraPass(passes, "4");
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
  t.edge = Technique::Edge::kFiltered;  // compare=linear (default): the driver's 2x2 PCF
  t.passes = passTable();
  t.render = render;
  return t;
}

}  // namespace sl::modern
