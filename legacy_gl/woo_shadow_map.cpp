// legacy.woo — Andrew Woo's midpoint shadow map, as Everitt, Rege & Cebenoyan 2001 describe it
// ("Advantages and Limitations": the map holds the average of the nearest and second-nearest
// depth layers seen from the light, made with depth peeling), in OpenGL 1.x + ARB_shadow.
// Chan 2004 §2 explains why a bias is needed at all; Woo's midpoint removes the polygon-offset
// fudge factor: a lit surface lies half a layer in front of the stored depth.
//
// Passes:
//   1. renderFirstDepthLayer  — casters from the light, nearest depth z1 (no polygon offset)
//   2. peelSecondDepthLayer   — casters again; the z1 map as an ARB_shadow texture (GEQUAL)
//                               and the alpha test keep only fragments behind z1, so the
//                               depth buffer ends with the second layer z2 (depth peeling)
//   3. storeMidpointDepth     — (z1 + z2) / 2 into the DEPTH_COMPONENT shadow map
//   4-7. shadeWithShadowMap   — legacy.hw's camera passes (texgen planes, ambient, direct light
//                               x shadow test, visibility mask) on the midpoint map
// The passes are declared once in wooPasses().
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <string>
#include <vector>

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

// Depth peeling's own tolerance, in window depth [0,1]: a fragment counts as "behind" the
// first layer when its texgen depth r/q exceeds z1 by more than this. r/q and the rasterised
// z of the very same fragment differ only by float rounding (~1e-7) and the 24-bit storage of
// z1 (6e-8), so 2^-20 (16 depth units) separates the layer from itself and nothing else —
// for a wide depth range; a narrow one far from the light multiplies r/q's round-off, and the
// tolerance with it (core/scene/scene.h lightDepthRoundoffScale).
constexpr float kPeelEpsilon = 1.0f / float(1 << 20);
constexpr float kAlphaTestThreshold = 0.5f;  // ARB_shadow gives 0 or 1 with GL_NEAREST

// Pass 1 (Everitt, Woo paragraph): nearest depth layer from the light, without polygon offset.
std::vector<float> renderFirstDepthLayer(Passes& passes, const Scene& scene, int n,
                                         LightTarget& target, GLuint firstLayer) {
  std::vector<float> z1(size_t(n) * n);
  passes.run("1", [&] {
    target.bind();
    glClear(GL_DEPTH_BUFFER_BIT);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    loadMatrix(GL_PROJECTION, lightProjection(scene));
    loadMatrix(GL_MODELVIEW, lightView(scene.light));
    drawScene(scene, Draw::kCasters);
    glBindTexture(GL_TEXTURE_2D, firstLayer);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, n, n, 0, GL_DEPTH_COMPONENT,
                 GL_UNSIGNED_INT, nullptr);
    glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, n, n);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, n, n, GL_DEPTH_COMPONENT, GL_FLOAT, z1.data());
  });
  return z1;
}

// Pass 2 (Everitt, Woo paragraph and his depth peeling [2]): the first layer, projected from
// the light onto the casters with EYE_LINEAR texgen, peels itself away. The ARB_shadow result
// (r - kPeelEpsilon >= z1) goes to alpha (DEPTH_TEXTURE_MODE ALPHA) and the alpha test drops
// fragments that are not behind z1; the depth test then keeps the nearest of the rest = z2.
std::vector<float> peelSecondDepthLayer(Passes& passes, const Scene& scene, int n,
                                        LightTarget& target, GLuint firstLayer) {
  std::vector<float> z2(size_t(n) * n);
  passes.run("2", [&] {
    target.bind();
    glClear(GL_DEPTH_BUFFER_BIT);
    loadMatrix(GL_PROJECTION, lightProjection(scene));
    loadMatrix(GL_MODELVIEW, lightView(scene.light));  // planes given in world space (Eq. 5)
    const glm::mat4 planes = glm::transpose(worldToShadowMapTexture(scene));
    const GLenum coords[4] = {GL_S, GL_T, GL_R, GL_Q};
    const GLenum enables[4] = {GL_TEXTURE_GEN_S, GL_TEXTURE_GEN_T, GL_TEXTURE_GEN_R,
                               GL_TEXTURE_GEN_Q};
    glActiveTexture(GL_TEXTURE0);
    {  // texgen on for the peel, off again before the texture matrix is reset
      ScopedTexgen texgen(GL_TEXTURE0);
      for (int i = 0; i < 4; ++i) {
        glTexGeni(coords[i], GL_TEXTURE_GEN_MODE, GL_EYE_LINEAR);
        glTexGenfv(coords[i], GL_EYE_PLANE, glm::value_ptr(planes[i]));
        texgen.enable(enables[i]);
      }
      // r' = r - kPeelEpsilon * q: the texture matrix moves the reference depth, not the map.
      const float epsilon = kPeelEpsilon * lightDepthRoundoffScale(scene);
      loadMatrix(GL_TEXTURE, glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -epsilon)));
      glMatrixMode(GL_MODELVIEW);
      glBindTexture(GL_TEXTURE_2D, firstLayer);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_R_TO_TEXTURE);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_GEQUAL);
      glTexParameteri(GL_TEXTURE_2D, GL_DEPTH_TEXTURE_MODE, GL_ALPHA);
      glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
      {
        const ScopedEnable firstLayerTexture(GL_TEXTURE_2D);
        const ScopedEnable alphaTest(GL_ALPHA_TEST);
        glAlphaFunc(GL_GREATER, kAlphaTestThreshold);
        drawScene(scene, Draw::kCasters, Colors::kWhite);
      }
    }
    loadMatrix(GL_TEXTURE, glm::mat4(1.0f));
    glMatrixMode(GL_MODELVIEW);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, n, n, GL_DEPTH_COMPONENT, GL_FLOAT, z2.data());
    target.unbind();
  });
  return z2;
}

// Pass 3 (Woo's midpoint): the map holds (z1 + z2) / 2. Where nothing lies behind z1 the
// cleared depth 1 stands in for z2.
// DEVIATION (Everitt, Woo paragraph): the GeForce3 wrote the average as the fragment depth
// during the peel (texture-shader depth replace); OpenGL 1.x fixed function cannot write a
// computed depth, so the two layers are averaged on the host between glReadPixels and
// glTexImage2D. The nearest averaged fragment is the average of the two nearest layers, so
// the map is the same.
void storeMidpointDepth(Passes& passes, int n, const std::vector<float>& z1,
                        const std::vector<float>& z2, GLuint midpointMap, bool linearCompare) {
  passes.run("3", [&] {
    std::vector<float> mid(z1.size());
    for (size_t i = 0; i < mid.size(); ++i) mid[i] = 0.5f * (z1[i] + z2[i]);
    glBindTexture(GL_TEXTURE_2D, midpointMap);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, n, n, 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                 mid.data());
    setDepthCompareParameters(linearCompare);
  });
}

// Pass 3's DEVIATION, for the pass table.
constexpr char kHostMidpointDeviation[] =
    "DEVIATION (Everitt, Woo paragraph): the GeForce3 wrote the average as the fragment depth "
    "during the peel (texture-shader depth replace); OpenGL 1.x fixed function cannot write a "
    "computed depth, so the two layers are averaged on the host between glReadPixels and "
    "glTexImage2D. The nearest averaged fragment is the average of the two nearest layers, so "
    "the map is the same.";

// The passes of Woo's midpoint map, declared once: passes 1-3 here, 4-7 legacy.hw's.
PassTable wooPasses() {
  PassTable table = {
      meshFeedingPass(),
      {.id = "1",
       .name = "first depth layer",
       .reference = "Everitt, Rege & Cebenoyan 2001, Advantages and Limitations (Woo [9]): the "
                    "nearest layer from the light, no polygon offset",
       .writes = {{.name = "first-depth-layer",
                   .caption = "pass 1: nearest depth from the light z1 (Everitt, Woo paragraph)"}},
       .role = PassRole::kLight,
       .deviations = {kOffscreenLightPassDeviation}},
      {.id = "2",
       .name = "peel to second depth layer",
       .reference = "Everitt, Rege & Cebenoyan 2001, Advantages and Limitations (Woo [9]), by "
                    "depth peeling [2]: the second-nearest layer",
       .writes = {{.name = "second-depth-layer",
                   .caption = "pass 2: depth after peeling z1 away, z2 (depth peeling)"}},
       .role = PassRole::kLight,
       .deviations = {kOffscreenLightPassDeviation, kDepthRoundoffScaleDeviation}},
      {.id = "3",
       .name = "midpoint of the layers",
       .reference = "Everitt, Rege & Cebenoyan 2001, Advantages and Limitations (Woo [9]): the map "
                    "is the average of the two layers (averaged on the host: DEVIATION)",
       .writes = {{.name = "midpoint-shadow-map",
                   .caption = "pass 3: Woo's midpoint (z1 + z2) / 2, the shadow map"}},
       .role = PassRole::kLight,
       .deviations = {kHostMidpointDeviation}},
  };
  for (PassSpec& spec : shadowMapCameraPasses(4)) table.push_back(std::move(spec));
  return table;
}

const PassTable& passTable() {
  static const PassTable table = wooPasses();
  return table;
}

// An n x n depth map from host floats (a layer read back, or their midpoint).
Image depthImage(int n, std::vector<float> depth) {
  Image image(n, n, 1);
  image.data = std::move(depth);
  return image;
}

Frame render(GlContext&, const Scene& scene, const RenderParams& params) {
  const bool linear = params.text(compareParam()) == "linear";
  const int n = params.shadowMapTexels;
  Frame frame;
  Passes passes(frame, params, passTable());
  const Texture firstLayer = makeTexture();
  const Texture midpointMap = makeTexture();
  std::vector<float> z1, z2;
  {
    LightTarget target(n, n <= params.width && n <= params.height, false);
    z1 = renderFirstDepthLayer(passes, scene, n, target, firstLayer.id());
    z2 = peelSecondDepthLayer(passes, scene, n, target, firstLayer.id());
  }
  storeMidpointDepth(passes, n, z1, z2, midpointMap.id(), linear);
  // --dump-passes: z1, z2 and their midpoint as grey on one scale, from the nearest drawn depth
  // (black) to the clear depth 1 (white): one affine map for all three, so that each grey of
  // the midpoint is the mean of the layers' greys, also where z2 is the clear value.
  const auto oneScale = [&] {
    const Image first = depthImage(n, z1);
    return WindowDepthSpan{drawnDepthRange({&first}).lo, kClearDepth};
  };
  passes.captureDepth(
      "1", "first-depth-layer", [&] { return depthImage(n, z1); }, {}, {}, oneScale);
  passes.captureDepth(
      "2", "second-depth-layer", [&] { return depthImage(n, z2); }, {}, {}, oneScale);
  passes.captureDepth(
      "3", "midpoint-shadow-map",
      [&] {
        std::vector<float> mid(z1.size());
        for (size_t i = 0; i < mid.size(); ++i) mid[i] = 0.5f * (z1[i] + z2[i]);
        return depthImage(n, std::move(mid));
      },
      {}, {}, oneScale);
  shadeWithShadowMap(passes, scene, params, midpointMap.id(), 4);
  checkGl("legacy.woo");
  return frame;
}

}  // namespace

Technique wooShadowMapTechnique() {
  Technique t;
  t.name = "legacy.woo";
  t.paper =
      "Woo's midpoint shadow map (Everitt, Rege & Cebenoyan 2001, Advantages and Limitations)";
  t.summary = "depth peeling of two layers from the light, map = their midpoint, no polygon offset";
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
