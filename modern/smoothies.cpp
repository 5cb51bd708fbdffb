// modern.smoothies — Eric Chan, "Hardware-Accelerated Rendering of Hard and Soft Shadows", MIT
// 2004, chapter 4: "Rendering Fake Soft Shadows Using Smoothies" (Chan & Durand, EGSR 2003).
// Smoothies are screen-space fins of width t (in the light's screen space) attached to the
// blockers' silhouette edges; rendered from the light into a smoothie buffer of depth and
// alpha, they turn the hard shadow-map edge into a penumbra-like ramp whose width follows the
// ratio b/r of light-blocker and light-receiver distances (Eq. 4.1).
//
// Steps of §4.2 and the four passes of §4.3:
//   (steps 2-3) findSilhouettesAndBuildSmoothies — CPU: silhouette edges of the blockers
//        w.r.t. the light (edge adjacency), a smoothie edge per silhouette edge and a smoothie
//        corner per silhouette vertex, in light clip space
//   1. renderShadowMapWithLinearDepth — blockers' depth (hardware depth texture) and the linear
//        depth of the nearest surface (R32F) for b/r
//   2. renderSmoothieDepth            — smoothies only, standard depth buffer
//   3. renderSmoothieAlpha            — alpha a, remapped a/(1 - b/r), minimum blending
//   4. shadeWithSmoothies             — camera pass: four nearest texels, umbra / smoothie alpha /
//        lit, bilinear, sinusoidal falloff texture
//
// --param width=t: smoothie width in light-screen-space units, where the shadow map's side is 1
// (so t = 0.1 is a tenth of the light's view). --param remap=off keeps Chan's original,
// linearly interpolated alpha (§4.2.1 before Eq. 4.1; Figures 4-4b and 4-10 left): a penumbra
// of fixed width t that does not shrink towards a contact. §4.1 assumes closed blockers; open
// casters get smoothies on the silhouette of their two-sided solid (boundary edges and folds, see
// the DEVIATION in modern/silhouettes.h), counted in Frame::counters["open_casters_two_sided"].
// The passes are declared once in smoothiesPasses().
#include "modern/smoothies.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <glm/gtc/constants.hpp>
#include <map>
#include <utility>

#include "core/base/errors.h"
#include "core/gl/winding.h"
#include "core/technique/passes.h"
#include "modern/camera_pass.h"
#include "modern/silhouettes.h"

namespace sl::modern {
using namespace sl::gl;

float remapSmoothieAlpha(float a, float bOverR) {
  const float room = 1.0f - bOverR;
  return a >= room ? 1.0f : a / room;
}

float smoothieAlpha(float a, float bOverR, bool remap) {
  if (remap) return remapSmoothieAlpha(a, bOverR);
  return bOverR >= 1.0f ? 1.0f : a;
}

float smoothieFalloff(float v) { return 0.5f - 0.5f * std::cos(glm::pi<float>() * v); }

namespace {
constexpr double kMinWidth = 1e-4;            // light screen space: narrower than any map texel
constexpr double kMaxWidth = 1.0;             // the whole map side
constexpr double kDefaultWidth = 0.03;        // t, light screen space (map side = 1)
constexpr float kDefaultOffsetFactor = 2.0f;  // as modern.hw (Everitt et al. Fig. 3)
constexpr float kDefaultOffsetUnits = 4.0f;
constexpr double kLargestOffsetUnits = 1e6;          // depth steps; far beyond any useful offset
constexpr int kFalloffTexels = 256;                  // 1D falloff texture (§4.2.1)
constexpr float kNoSurfaceDepth = 1.0e30f;           // linear depth where nothing is seen: b/r ~ 0
constexpr float kMinClipW = 1.0e-6f;                 // vertices at or behind the light: no smoothie
constexpr float kMinEdgeLength = 1.0e-7f;            // light NDC; shorter edges have no direction
constexpr float kMaxCornerSegmentRadians = 0.7854f;  // 45 degrees per corner fan triangle

// The DEVIATION comments of the passes below, for the pass table.
constexpr const char* kSquareCornersDeviation =
    "DEVIATION (Chan §4.2 step 3, \"more than two adjacent silhouette edges\"): Chan averages the "
    "adjacent face normals into one vertex normal n' and connects it to each adjacent smoothie "
    "edge. We draw the square of half-side t around such a vertex with the same corner alpha "
    "|v - p| / t instead: it covers every gap around the vertex whatever its configuration, and "
    "where it overlaps an edge smoothie, minimum blending keeps the edge's alpha, which is never "
    "larger (the distance to a line through v is at most the distance to v); inside the blocker "
    "the shadow map decides (umbra). The same square serves vertices whose two edges do not "
    "chain (both arriving or both leaving).";
constexpr const char* kFloatAlphaDeviation =
    "DEVIATION (Chan §4.3 pass 3): the alpha buffer is R32F, not fixed point, so the profile "
    "tests see the remapped alpha without 8-bit steps.";

// Steps 2-3 of §4.2 and the four passes of §4.3, declared once: names, the thesis's text, the
// buffers a dump shows, shaders and deviations.
PassTable smoothiesPasses() {
  return {
      {.id = "0",
       .name = "silhouettes and smoothies (CPU)",
       .reference = "Chan 2004 §4.2 steps 2-3 (Fig. 4-2): silhouette edges, a smoothie edge per "
                    "edge and a corner per vertex (square corners: DEVIATION)",
       .deviations = {kOpenMeshTwoSidedDeviation, kSquareCornersDeviation}},
      {.id = "1",
       .name = "shadow map + linear depth",
       .reference = "Chan 2004 §4.2 step 1 (\"Create a shadow map\"), §4.3; the receivers' linear "
                    "depth r of Eq. 4.1",
       .writes = {{.name = "linear-depth",
                   .caption = "pass 1 linear depth from the light, scaled to its maximum"}},
       .shaders = {"blocker-linear-depth"}},
      {.id = "2",
       .name = "smoothie depth",
       .reference = "Chan 2004 §4.2 step 4 (\"Render smoothies\"), §4.3: the nearest smoothie's "
                    "depth",
       .writes = {{.name = "smoothie-depth",
                   .caption = "smoothie buffer depth, linear from the light's near (black) to far "
                              "plane (white; white also where no smoothie lies) (Fig. 4-1b)"}},
       .shaders = {"smoothie-vertex", "depth-only"}},
      {.id = "3",
       .name = "smoothie alpha (min blending)",
       .reference = "Chan 2004 §4.2.1, Eq. 4.1, Fig. 4-4; §4.3: smoothie alpha, minimum blending",
       // {alpha}: " after Eq. 4.1 and min blending (Fig. 4-1c)", or with --param remap=off
       // ", linear (not remapped), min blending (Fig. 4-10 left)".
       .writes = {{.name = "smoothie-alpha", .caption = "smoothie buffer alpha{alpha}"}},
       .shaders = {"smoothie-vertex", "smoothie-alpha"},
       // Its buffer is allocated by pass 2 (renderSmoothieDepth), where the comment stands.
       .deviations = {kFloatAlphaDeviation}},
      {.id = "4",
       .name = "camera pass with smoothies",
       .reference = "Chan 2004 §4.2 step 5 (\"Compute shadows with depth comparisons\"), Fig. "
                    "4-3, §4.3 (bilinear filtering, falloff)",
       .shaders = {"smoothie-test"}},
  };
}

const PassTable& passTable() {
  static const PassTable table = smoothiesPasses();
  return table;
}

// One smoothie vertex: position in light clip space, root and normal in shadow-map pixels.
struct SmoothieVertex {
  glm::vec4 clip;
  glm::vec2 root;
  glm::vec2 normal;
  float kind;  // 0 = edge, 1 = corner
};
constexpr float kEdge = 0.0f;
constexpr float kCorner = 1.0f;

struct SmoothieGeometry {
  std::vector<SmoothieVertex> vertices;  // triangle list
  long long edges = 0;
  long long corners = 0;
  long long cornersWithManyEdges = 0;  // silhouette vertices with more than two edges
  long long cornerSquares = 0;         // corners drawn as squares (see the DEVIATION below)
  int openTwoSided = 0;
};

// Steps 2-3 (§4.2): silhouette edges, then a smoothie edge (a rectangle extended by t away from
// the blocker in light screen space, at the edge's own depth) per edge and a smoothie corner
// per silhouette vertex.
//
// Corners (Figure 4-6): at a vertex where one silhouette edge arrives and one leaves, the gap
// between their smoothie edges is the wedge from the incoming edge's outward normal to the
// outgoing one's (counter-clockwise: the silhouette runs counter-clockwise around the blocker);
// it is covered by a fan whose outer edges are tangent to the circle of radius t, shaded with
// Chan's corner alpha |v - p| / t. Concave or straight vertices have no gap and get no corner.
//
// DEVIATION (Chan §4.2 step 3, "more than two adjacent silhouette edges"): Chan averages the
// adjacent face normals into one vertex normal n' and connects it to each adjacent smoothie
// edge. We draw the square of half-side t around such a vertex with the same corner alpha
// |v - p| / t instead: it covers every gap around the vertex whatever its configuration, and
// where it overlaps an edge smoothie, minimum blending keeps the edge's alpha, which is never
// larger (the distance to a line through v is at most the distance to v); inside the blocker
// the shadow map decides (umbra). The same square serves vertices whose two edges do not chain
// (both arriving or both leaving).
SmoothieGeometry findSilhouettesAndBuildSmoothies(Passes& passes, const Scene& scene,
                                                  const SceneCasters& casters, double width,
                                                  int texels) {
  SmoothieGeometry g;
  passes.run("0", [&] {
    const glm::mat4 lightClip = lightProjection(scene) * lightView(scene.light);
    const float t = float(2.0 * width);  // NDC spans 2 per map side
    const auto toPixels = [&](glm::vec2 ndc) { return (0.5f * ndc + 0.5f) * float(texels); };
    g.openTwoSided = casters.open;
    for (const ShadowCaster& caster : casters.casters) {
      const Object& o = *caster.object;
      const EdgeAdjacency& mesh = caster.adjacency;
      const glm::vec3 light = glm::vec3(glm::inverse(o.model) * glm::vec4(scene.light.position, 1));
      const Silhouette silhouette = findSilhouette(mesh, light);
      const glm::mat4 toClip = lightClip * o.model;
      std::vector<glm::vec4> clip(mesh.positions.size());
      for (size_t i = 0; i < clip.size(); ++i) clip[i] = toClip * glm::vec4(mesh.positions[i], 1);
      // A point displaced by `offset` (NDC) in light screen space at the depth of clip point c.
      const auto displaced = [](const glm::vec4& c, glm::vec2 offset) {
        return glm::vec4(c.x + offset.x * c.w, c.y + offset.y * c.w, c.z, c.w);
      };
      // Per silhouette vertex: the outward normals of the edges arriving at it and leaving it.
      struct VertexEdges {
        std::vector<glm::vec2> arriving, leaving;
      };
      std::map<unsigned, VertexEdges> around;
      // A mirroring model matrix turns the light-facing triangles clockwise in light space: walk
      // its silhouette edges the other way round, so the blocker stays on their left.
      const bool mirrored = mirrors(o.model);
      for (auto [a, b] : silhouette.edges) {
        if (mirrored) std::swap(a, b);
        const glm::vec4 ca = clip[a], cb = clip[b];
        if (ca.w <= kMinClipW || cb.w <= kMinClipW) continue;
        const glm::vec2 na = glm::vec2(ca) / ca.w, nb = glm::vec2(cb) / cb.w;
        const glm::vec2 d = nb - na;
        if (glm::length(d) < kMinEdgeLength) continue;
        // The blocker lies to the left of a -> b (light-facing triangles are counter-clockwise
        // from the light), so "away from the blocker" is the right-hand normal.
        const glm::vec2 out = glm::normalize(glm::vec2(d.y, -d.x));
        const SmoothieVertex quad[4] = {{ca, toPixels(na), out, kEdge},
                                        {cb, toPixels(na), out, kEdge},
                                        {displaced(cb, t * out), toPixels(na), out, kEdge},
                                        {displaced(ca, t * out), toPixels(na), out, kEdge}};
        for (int k : {0, 1, 2, 0, 2, 3}) g.vertices.push_back(quad[k]);
        ++g.edges;
        around[a].leaving.push_back(out);
        around[b].arriving.push_back(out);
      }
      for (const auto& [v, edges] : around) {
        const glm::vec4 c = clip[v];
        const glm::vec2 root = toPixels(glm::vec2(c) / c.w);
        const size_t degree = edges.arriving.size() + edges.leaving.size();
        if (degree > 2) ++g.cornersWithManyEdges;
        if (edges.arriving.size() == 1 && edges.leaving.size() == 1) {
          // Figure 4-6: the wedge from the arriving edge's normal to the leaving edge's.
          const glm::vec2 from = edges.arriving[0], to = edges.leaving[0];
          const float angle = std::atan2(from.x * to.y - from.y * to.x, glm::dot(from, to));
          if (angle <= 0.0f) continue;  // concave or straight: the edge smoothies overlap
          const int segments = int(std::ceil(angle / kMaxCornerSegmentRadians));
          const float step = angle / float(segments);
          const float radius = t / std::cos(0.5f * step);  // chords tangent to the circle of t
          const float start = std::atan2(from.y, from.x);
          for (int k = 0; k < segments; ++k) {
            const float a0 = start + k * step, a1 = a0 + step;
            const glm::vec2 p0 = radius * glm::vec2(std::cos(a0), std::sin(a0));
            const glm::vec2 p1 = radius * glm::vec2(std::cos(a1), std::sin(a1));
            for (const glm::vec4& q : {c, displaced(c, p0), displaced(c, p1)})
              g.vertices.push_back({q, root, {0, 0}, kCorner});
          }
          ++g.corners;
          continue;
        }
        const SmoothieVertex square[4] = {{displaced(c, {-t, -t}), root, {0, 0}, kCorner},
                                          {displaced(c, {t, -t}), root, {0, 0}, kCorner},
                                          {displaced(c, {t, t}), root, {0, 0}, kCorner},
                                          {displaced(c, {-t, t}), root, {0, 0}, kCorner}};
        for (int k : {0, 1, 2, 0, 2, 3}) g.vertices.push_back(square[k]);
        ++g.corners;
        ++g.cornerSquares;
      }
    }
  });
  return g;
}

// Pass 1 (§4.3): the blockers' depth with polygon offset (for the umbra test), and the linear
// depth of the nearest surface of any object, caster or not (r of Eq. 4.1: "the distance from
// the light source to the receiver using the shadow map").
RenderTarget renderShadowMapWithLinearDepth(Passes& passes, const GpuScene& gpu,
                                            const Program& program, int texels, float factor,
                                            float units) {
  RenderTarget map;
  passes.run("1", [&] {
    const Scene& scene = gpu.scene();
    map = makeRenderTarget(texels, texels, {GL_R32F}, true, GL_DEPTH_COMPONENT24);
    map.bind();
    const float none[4] = {kNoSurfaceDepth, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, none);
    glClear(GL_DEPTH_BUFFER_BIT);
    program.use();
    program.set("uViewProjection", lightProjection(scene) * lightView(scene.light));
    program.set("uLightView", lightView(scene.light));
    glEnable(GL_BLEND);
    glBlendEquation(GL_MIN);  // nearest linear depth, whatever the draw order
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(factor, units * lightDepthRoundoffScale(gpu.scene()));
    const auto setModel = [&](const Object& o) { program.set("uModel", o.model); };
    gpu.draw([](const Object& o) { return o.castsShadow; }, setModel);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    gpu.draw([](const Object& o) { return !o.castsShadow; }, setModel);
    glDepthMask(GL_TRUE);
    glBlendEquation(GL_FUNC_ADD);
    glDisable(GL_BLEND);
  });
  return map;
}

// A vertex array for the smoothie geometry (attributes of smoothie.vert).
struct GpuSmoothies {
  VertexArray vao;
  Buffer buffer;
  GLsizei count = 0;
};
GpuSmoothies uploadSmoothies(const SmoothieGeometry& g) {
  GpuSmoothies s;
  s.vao = makeVertexArray();
  s.buffer = makeBuffer();
  glBindVertexArray(s.vao.id());
  glBindBuffer(GL_ARRAY_BUFFER, s.buffer.id());
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(g.vertices.size() * sizeof(SmoothieVertex)),
               g.vertices.data(), GL_STREAM_DRAW);
  const GLsizei stride = sizeof(SmoothieVertex);
  glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, stride, (void*)offsetof(SmoothieVertex, clip));
  glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, stride, (void*)offsetof(SmoothieVertex, root));
  glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, stride, (void*)offsetof(SmoothieVertex, normal));
  glVertexAttribPointer(3, 1, GL_FLOAT, GL_FALSE, stride, (void*)offsetof(SmoothieVertex, kind));
  for (GLuint i = 0; i < 4; ++i) glEnableVertexAttribArray(i);
  glBindVertexArray(0);
  s.count = GLsizei(g.vertices.size());
  return s;
}

void drawSmoothies(const GpuSmoothies& s) {
  glBindVertexArray(s.vao.id());
  glDrawArrays(GL_TRIANGLES, 0, s.count);
  glBindVertexArray(0);
}

// Pass 2 (§4.3): the smoothies' depth into a standard depth buffer (nearest smoothie).
RenderTarget renderSmoothieDepth(Passes& passes, const GpuSmoothies& smoothies,
                                 const Program& program, int texels) {
  RenderTarget buffer;
  passes.run("2", [&] {
    // DEVIATION (Chan §4.3 pass 3): the alpha buffer is R32F, not fixed point, so the profile
    // tests see the remapped alpha without 8-bit steps.
    buffer = makeRenderTarget(texels, texels, {GL_R32F}, true, GL_DEPTH_COMPONENT24);
    buffer.bind();
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    program.use();
    drawSmoothies(smoothies);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  });
  return buffer;
}

// Pass 3 (§4.2.1, §4.3): alpha per smoothie pixel, Eq. 4.1, minimum blending into a = 1.
void renderSmoothieAlpha(Passes& passes, const GpuSmoothies& smoothies, const RenderTarget& buffer,
                         const RenderTarget& map, const Program& program, double width,
                         bool remap) {
  passes.run("3", [&] {
    buffer.bind();
    const float one[4] = {1, 1, 1, 1};
    glClearBufferfv(GL_COLOR, 0, one);
    glDisable(GL_DEPTH_TEST);  // every smoothie at a texel meets the minimum
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_MIN);
    program.use();
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, map.color[0].id());
    program.set("uLinearDepth", 0);
    program.set("uWidthPixels", float(width * buffer.width));
    program.set("uRemap", remap ? 1 : 0);
    drawSmoothies(smoothies);
    glBlendEquation(GL_FUNC_ADD);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
  });
}

// Capture (Figure 4-1b): the smoothie buffer's depth, linearised between the light's near and
// far planes (0 = near, 1 = far or no smoothie), on the grey scale of the figures' shadow map.
Image linearSmoothieDepth(const RenderTarget& buffer, const Scene& scene) {
  Image depth(buffer.width, buffer.height, 1);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, buffer.fbo.id());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, buffer.width, buffer.height, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data.data());
  checkGl("read smoothie depth");
  const DepthRange range = lightDepthRange(scene);
  const float n = range.nearPlane, f = range.farPlane;
  for (float& d : depth.data) {
    const float ndc = 2.0f * d - 1.0f;  // glm::perspective's window depth back to eye distance
    const float eye = 2.0f * n * f / (f + n - ndc * (f - n));
    d = std::clamp((eye - n) / (f - n), 0.0f, 1.0f);
  }
  return depth;
}

// Capture: pass 1's linear depth r divided by its largest value (1 where nothing is seen).
Image scaledToItsMaximum(Image linear) {
  float far = 0;
  for (float v : linear.data)
    if (v < kNoSurfaceDepth) far = std::max(far, v);
  for (float& v : linear.data) v = v < kNoSurfaceDepth && far > 0 ? v / far : 1.0f;
  return linear;
}

Texture makeFalloffTexture() {
  std::vector<float> s(kFalloffTexels);
  for (int i = 0; i < kFalloffTexels; ++i) s[i] = smoothieFalloff(float(i) / (kFalloffTexels - 1));
  Texture tex = makeTexture();
  glBindTexture(GL_TEXTURE_1D, tex.id());
  glTexImage1D(GL_TEXTURE_1D, 0, GL_R32F, kFalloffTexels, 0, GL_RED, GL_FLOAT, s.data());
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_1D, 0);
  return tex;
}

// Pass 4 (§4.2 step 5, §4.3): the camera view with the depth comparisons and filtering.
void shadeWithSmoothies(Passes& passes, const GpuScene& gpu, const RenderParams& params,
                        const Program& program, const RenderTarget& map,
                        const RenderTarget& smoothie, const Texture& falloff) {
  passes.run("4", [&] {
    const Scene& scene = gpu.scene();
    RenderTarget target = makeCameraTarget(params, true);
    clearCameraTarget(target);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    program.use();
    program.set("uViewProjection", cameraViewProjection(scene, params));
    const glm::mat4 S = glm::mat4(0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 0.5f, 0, 0.5f, 0.5f, 0.5f, 1);
    program.set("uWorldToShadowMap", S * lightProjection(scene) * lightView(scene.light));
    program.set("uMapTexels", map.width);
    program.set("uFalloffTexels", float(kFalloffTexels));
    setLightingUniforms(program, scene);
    const GLuint textures[4] = {map.depth.id(), smoothie.depth.id(), smoothie.color[0].id(),
                                falloff.id()};
    const char* names[4] = {"uBlockerDepth", "uSmoothieDepth", "uSmoothieAlpha", "uFalloff"};
    for (int i = 0; i < 4; ++i) {
      glActiveTexture(GLenum(GL_TEXTURE0 + i));
      glBindTexture(i == 3 ? GL_TEXTURE_1D : GL_TEXTURE_2D, textures[i]);
      program.set(names[i], i);
    }
    gpu.draw([](const Object&) { return true; },
             [&](const Object& o) { setObjectUniforms(program, o); });
    readCameraTarget(target, passes.frame());
    for (int i = 3; i >= 0; --i) {
      glActiveTexture(GLenum(GL_TEXTURE0 + i));
      glBindTexture(i == 3 ? GL_TEXTURE_1D : GL_TEXTURE_2D, 0);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  });
}

// --param width: the smoothie's width t (Chan ch. 4 §4.2), light screen space (map side = 1).
ParamSpec widthParam() {
  return numberParam("width", kDefaultWidth, kMinWidth, kMaxWidth,
                     "smoothie width t in light screen space, map side = 1 (Chan §4.2)");
}

// --param remap: Chan's remapped alpha (on) or the linear alpha of Fig. 4-4 (b) (off).
ParamSpec remapParam() {
  return flagParam("remap", true, "remap the smoothie alpha by the depth ratio (Chan §4.3)");
}

Frame render(GlContext&, const Scene& scene, const RenderParams& params) {
  const double width = params.number(widthParam());
  const bool remap = params.flag(remapParam());
  const float factor = float(params.number(offsetFactorParam(kDefaultOffsetFactor)));
  const float units =
      float(params.number(offsetUnitsParam(kDefaultOffsetUnits, kLargestOffsetUnits)));
  const int texels = params.shadowMapTexels;
  Frame frame;
  Passes passes(frame, params, passTable());
  GpuScene gpu(scene);
  const Texture falloff = makeFalloffTexture();
  const SceneCasters casters = collectCasters(scene);
  const SmoothieGeometry geometry =
      findSilhouettesAndBuildSmoothies(passes, scene, casters, width, texels);
  const GpuSmoothies smoothies = uploadSmoothies(geometry);
  // Programs are compiled before the timed passes.
  const Program linearDepthProgram("scene.vert.glsl", "smoothie_linear_depth.frag.glsl");
  const Program smoothieDepthProgram("smoothie.vert.glsl", "depth_only.frag.glsl");
  const Program alphaProgram("smoothie.vert.glsl", "smoothie_alpha.frag.glsl");
  const Program shadeProgram("scene.vert.glsl", "smoothie_shade.frag.glsl");
  RenderTarget map =
      renderShadowMapWithLinearDepth(passes, gpu, linearDepthProgram, texels, factor, units);
  RenderTarget smoothie = renderSmoothieDepth(passes, smoothies, smoothieDepthProgram, texels);
  renderSmoothieAlpha(passes, smoothies, smoothie, map, alphaProgram, width, remap);
  shadeWithSmoothies(passes, gpu, params, shadeProgram, map, smoothie, falloff);

  frame.counters["open_casters_two_sided"] = geometry.openTwoSided;
  frame.counters["smoothie_edges"] = double(geometry.edges);
  frame.counters["smoothie_corners"] = double(geometry.corners);
  frame.counters["corners_with_more_than_two_edges"] = double(geometry.cornersWithManyEdges);
  frame.counters["corner_squares"] = double(geometry.cornerSquares);
  passes.capture("2", "smoothie-depth", [&] { return linearSmoothieDepth(smoothie, scene); });
  passes.capture("3", "smoothie-alpha", [&] { return channel(readAttachment(smoothie, 0), 0); }, {},
                 {{"alpha", remap ? " after Eq. 4.1 and min blending (Fig. 4-1c)"
                                  : ", linear (not remapped), min blending (Fig. 4-10 left)"}});
  passes.capture("1", "linear-depth",
                 [&] { return scaledToItsMaximum(channel(readAttachment(map, 0), 0)); });
  return frame;
}
}  // namespace

Technique smoothiesTechnique() {
  Technique t;
  t.name = "modern.smoothies";
  t.light = Technique::Light::kArea;  // fake soft shadows of the spherical light (Chan §4.1)
  t.paper = "Chan 2004 thesis ch. 4 (Chan & Durand 2003, smoothies)";
  t.summary = "fake soft shadows: smoothie edges/corners, depth+alpha buffer, Eq. 4.1, falloff";
  t.status = "complete (square corners at vertices with >2 silhouette edges)";
  t.needs.profile = Profile::kCore;
  t.params = {widthParam(), remapParam(), offsetFactorParam(kDefaultOffsetFactor),
              offsetUnitsParam(kDefaultOffsetUnits, kLargestOffsetUnits)};
  t.reads = {.shadowMap = true};
  t.plan.shadowWork = PlanTraits::ShadowWork::kSmoothies;
  t.passes = passTable();
  t.render = render;
  return t;
}

}  // namespace sl::modern
