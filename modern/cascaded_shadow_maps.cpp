// modern.cascades — parallel-split (cascaded) shadow maps: ours, after Zhang et al. 2006 (not in
// shared/papers): F. Zhang, H. Sun, L. Xu, L. K. Lun, "Parallel-Split Shadow Maps for Large-scale
// Virtual Environments", VRCIA 2006. The paper is not in shared/papers, so nothing here quotes
// it; the method as implemented: the view frustum is split along the view axis at distances that
// blend a logarithmic and a uniform split, each slice gets its own shadow map, cropped in the
// light's post-projective space to the slice, and the camera pass takes each pixel's shadow from
// the map of the slice its view depth falls in.
//
// Passes:
//   1. splitViewFrustum        — CPU: split distances C_i = lambda C_log + (1 - lambda) C_uni
//                                (--param lambda, --param cascades), each slice's corners in the
//                                light's clip space and its crop matrix (--param stabilize: a
//                                bounding sphere and whole-texel offsets)
//   2. renderCascadeDepths     — one light pass per cascade, crop * P_light * V_light, into a
//                                depth texture each, polygon offset as modern.hw
//   3. shadeWithCascades       — camera pass (cascades.frag): the cascade by view depth, then the
//                                hardware compare (GL_LINEAR: 2x2 PCF) in that cascade's map; with
//                                --dump-passes also the cascade index as colour
// The passes are declared once in cascadedShadowMapPasses().
#include "modern/cascaded_shadow_maps.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/base/errors.h"
#include "core/technique/pass_capture.h"
#include "core/technique/passes.h"
#include "modern/camera_pass.h"
#include "modern/hardware_shadow_map.h"

namespace sl::modern {
using namespace sl::gl;

namespace {
constexpr int kDefaultCascades = 4;
// lambda = 0.75: mostly logarithmic, so that the slice nearest the camera stays short on a long
// view (on the long scene, C_1 = 4.5 of 58 units; lambda = 0.5 gives 7.9).
constexpr double kDefaultLambda = 0.75;
constexpr float kDefaultOffsetFactor = 2.0f;  // as modern.hw (Everitt Fig. 3)
constexpr float kDefaultOffsetUnits = 4.0f;
constexpr double kLargestOffsetUnits = 1e6;  // depth steps; far beyond any useful offset
// A slice corner with clip w at or below this lies behind (or on) the light's plane: its NDC is
// meaningless, and the cascade falls back to the whole light frustum.
constexpr float kBehindLightW = 1e-6f;
// A crop narrower than this (NDC half extent) would blow the crop matrix up; such a slice sees
// no scene, and it falls back to the whole light frustum.
constexpr float kSmallestHalfSize = 1e-6f;
// The far split never comes closer to the near one than this ratio (a scene that ends in front
// of the camera's near plane).
constexpr float kSmallestFarOverNear = 1.001f;
// The colours of the cascade-index buffer (--dump-passes), cascade 0 first.
constexpr const char* kCascadeColours = "red, green, blue, yellow";

constexpr const char* kSpotLightDeviation =
    "DEVIATION (ours, after Zhang et al. 2006): the papers' light is directional, ours is the "
    "scene's spot light (a wide cone far away): the crop is built in the spot light's "
    "post-projective space, where the slices' corners are projected and bounded.";
constexpr const char* kStabilizeDeviation =
    "DEVIATION (ours, after Zhang et al. 2006): with stabilize=on each slice is bounded by a "
    "sphere, whose projected size (bounded with the scene's nearest light depth) does not change "
    "with the camera, and the crop's centre is snapped to whole texels, so that shadow edges do "
    "not swim as the camera moves; the crop is then larger than the slice.";
constexpr const char* kFitDeviation =
    "DEVIATION (ours, after Zhang et al. 2006): the split range is the camera's near plane to "
    "its far plane, the far plane drawn in to the farthest corner of the scene's bounds.";

// Passes 1 to 3, declared once: names, the method's steps, the buffers a dump shows, shaders
// and deviations.
PassTable cascadedShadowMapPasses() {
  return {
      {.id = "1",
       .name = "split the view frustum",
       .reference = "ours, after Zhang et al. 2006 (not in shared/papers): split distances "
                    "C_i = lambda C_log + (1 - lambda) C_uni, each slice cropped in the light's "
                    "post-projective space",
       .floor = PassFloor::kCpuOnly,
       .deviations = {kSpotLightDeviation, kStabilizeDeviation, kFitDeviation}},
      {.id = "2",
       .name = "depth from light per cascade",
       .reference = "ours, after Zhang et al. 2006 (not in shared/papers): one shadow map per "
                    "split, rendered with crop * P_light * V_light; polygon offset as Everitt, "
                    "Rege & Cebenoyan 2001, Fig. 3",
       .writes = {{.name = "cascade-depth{part}",
                   .caption = "pass 2: depth from the light, cascade {cascade}, view depth "
                              "{slice}"}},
       .shaders = {"depth-only"},
       .deviations = {kDepthRoundoffScaleDeviation},
       .keyState = {"GL_POLYGON_OFFSET_FILL", "glPolygonOffset"}},
      {.id = "3",
       .name = "camera pass: cascade by view depth, shadow test",
       .reference = "ours, after Zhang et al. 2006 (not in shared/papers): the split the pixel's "
                    "view depth falls in, then the shadow test in that split's map (Everitt, "
                    "Rege & Cebenoyan 2001, Fig. 5, by sampler2DShadow)",
       .writes =
           [] {
             std::vector<PassBuffer> b =
                 cameraPassBuffers("3", "cascades.frag: cascade by view depth, 2x2 compare");
             b.push_back({.name = "cascade-index",
                          .caption = std::string("pass 3: the cascade each pixel reads (") +
                                     kCascadeColours + " from near to far), shaded"});
             return b;
           }(),
       .shaders = {"cascade-select", "cascade-shadow-test"},
       .keyState = {"uWorldToCascade"}},
  };
}

const PassTable& passTable() {
  static const PassTable table = cascadedShadowMapPasses();
  return table;
}

// The light-space NDC rectangle [lo, hi] of a set of world points; false when one of them lies
// behind the light.
bool ndcRectangle(const glm::mat4& lightViewProjection, const glm::vec3* points, int count,
                  glm::vec2& lo, glm::vec2& hi) {
  lo = glm::vec2(1e30f);
  hi = glm::vec2(-1e30f);
  for (int i = 0; i < count; ++i) {
    const glm::vec4 c = lightViewProjection * glm::vec4(points[i], 1.0f);
    if (!(c.w > kBehindLightW)) return false;
    const glm::vec2 ndc = glm::vec2(c) / c.w;
    lo = glm::min(lo, ndc);
    hi = glm::max(hi, ndc);
  }
  return true;
}

// The crop matrix of Zhang et al.'s scale/offset: light clip [centre - half, centre + half] in
// x and y to [-1, 1]; z and w unchanged.
glm::mat4 cropMatrix(glm::vec2 centre, glm::vec2 half) {
  glm::mat4 m(1.0f);
  m[0][0] = 1.0f / half.x;
  m[1][1] = 1.0f / half.y;
  m[3][0] = -centre.x / half.x;
  m[3][1] = -centre.y / half.y;
  return m;
}

// The tight crop: the slice's corners' rectangle, intersected with the scene's bounds' rectangle
// and with the light frustum.
void tightCrop(const glm::mat4& lightVP, const std::array<glm::vec3, 8>& corners,
               const Bounds& bounds, CascadeCrop& c) {
  glm::vec2 lo, hi;
  if (!ndcRectangle(lightVP, corners.data(), 8, lo, hi)) return;  // whole light frustum
  glm::vec3 box[8];
  for (int i = 0; i < 8; ++i)
    box[i] = {(i & 1) ? bounds.hi.x : bounds.lo.x, (i & 2) ? bounds.hi.y : bounds.lo.y,
              (i & 4) ? bounds.hi.z : bounds.lo.z};
  glm::vec2 sceneLo, sceneHi;
  if (ndcRectangle(lightVP, box, 8, sceneLo, sceneHi)) {
    lo = glm::max(lo, sceneLo);
    hi = glm::min(hi, sceneHi);
  }
  lo = glm::max(lo, glm::vec2(-1.0f));
  hi = glm::min(hi, glm::vec2(1.0f));
  const glm::vec2 half = 0.5f * (hi - lo);
  if (!(half.x > kSmallestHalfSize && half.y > kSmallestHalfSize)) return;
  c.centre = 0.5f * (lo + hi);
  c.halfSize = half;
}

// Departs from the method as kStabilizeDeviation says (declared by pass 1). The stabilised crop:
// the slice's bounding sphere (its size depends only on the split depths and the camera's opening,
// not on where the camera is or looks), projected with a bound that holds wherever the sphere lies
// in the light's cone, and its centre snapped to whole texels.
void stableCrop(const Scene& scene, const glm::mat4& lightVP, float aspect, const CascadeCrop& in,
                int texels, CascadeCrop& c) {
  const Camera& cam = scene.camera;
  const float tanY = std::tan(glm::radians(cam.fovyDegrees) * 0.5f);
  const float s2 = tanY * tanY * (1.0f + aspect * aspect);  // |corner offset / depth|^2
  const float n = in.nearDepth, f = in.farDepth;
  // The centre on the view axis equidistant from the near and far corners, at most at f.
  float centreDepth = 0.5f * (f + n) * (1.0f + s2);
  float radius;
  if (centreDepth >= f) {
    centreDepth = f;
    radius = f * std::sqrt(s2);
  } else {
    radius = std::sqrt(n * n * s2 + (centreDepth - n) * (centreDepth - n));
  }
  const glm::vec3 forward = glm::normalize(cam.target - cam.position);
  const glm::vec4 clip = lightVP * glm::vec4(cam.position + centreDepth * forward, 1.0f);
  if (!(clip.w > kBehindLightW)) return;  // whole light frustum
  // A point P of the sphere seen from the light moves in NDC x by |dX - u dZ| / (z_P tan) <=
  // r sqrt(1 + u^2) / (z_P tan), u = X / Z of the centre; inside the cone |u| <= tan, and every
  // caster and receiver lies at z_P >= the scene's nearest light depth.
  const float tanHalfCone = std::tan(glm::radians(scene.light.coneDegrees) * 0.5f);
  const float nearest = lightDepthRange(scene).nearPlane;
  const float half = radius * std::sqrt(1.0f + tanHalfCone * tanHalfCone) / (nearest * tanHalfCone);
  if (!(half < 1.0f)) return;  // the sphere needs the whole light frustum
  // One texel of this cascade's map spans 2 half / texels of NDC: the centre on whole texels.
  const float texel = 2.0f * half / float(texels);
  const glm::vec2 centre = glm::vec2(clip) / clip.w;
  c.centre = glm::round(centre / texel) * texel;
  c.halfSize = glm::vec2(half);
}

// Pass 1 (ours, after Zhang et al. 2006: the split scheme and the crop matrix): the cascades.
std::vector<CascadeCrop> splitViewFrustum(Passes& passes, const Scene& scene, float aspect,
                                          const CascadeSettings& s) {
  std::vector<CascadeCrop> out;
  passes.run("1", [&] { out = cascadeCrops(scene, aspect, s); });
  return out;
}

// Pass 2 (ours, after Zhang et al. 2006: one map per split): each cascade's depth from the light
// through its crop, with polygon offset as modern.hw.
std::vector<RenderTarget> renderCascadeDepths(Passes& passes, const GpuScene& gpu, int texels,
                                              const std::vector<CascadeCrop>& cascades,
                                              float factor, float units, bool linear) {
  std::vector<RenderTarget> maps;
  passes.run("2", [&] {
    for (const CascadeCrop& c : cascades) {
      RenderTarget map = makeRenderTarget(texels, texels, {}, true, GL_DEPTH_COMPONENT24);
      map.bind();
      glClear(GL_DEPTH_BUFFER_BIT);
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_LESS);
      {
        const ScopedEnable polygonOffset(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(factor, units * lightDepthRoundoffScale(gpu.scene()));
        const Program& program = cachedProgram("scene.vert.glsl", "depth_only.frag.glsl");
        program.use();
        program.set("uViewProjection", c.viewProjection);
        gpu.draw([](const Object& o) { return o.castsShadow; },
                 [&](const Object& o) { program.set("uModel", o.model); });
      }
      setDepthCompareParameters(map.depth.id(), linear);
      maps.push_back(std::move(map));
    }
  });
  return maps;
}

// S: [-1, 1] clip coordinates to [0, 1] texture coordinates (Everitt Eq. 2).
glm::mat4 clipToTexture() {
  return glm::mat4(0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 0.5f, 0, 0.5f, 0.5f, 0.5f, 1);
}

// Pass 3 (ours, after Zhang et al. 2006: each pixel reads the split of its view depth): the
// camera view through cascades.frag; while dumping, the cascade index too (attachment 2).
void shadeWithCascades(Passes& passes, const GpuScene& gpu, const RenderParams& params,
                       const std::vector<CascadeCrop>& cascades,
                       const std::vector<RenderTarget>& maps, Image* cascadeIndex) {
  passes.run("3", [&] {
    const Scene& scene = gpu.scene();
    // Shaded colour, visibility (RGBA8 as modern.hw's camera target) and the cascade index.
    RenderTarget target = makeRenderTarget(
        params.width, params.height, {GL_RGBA8, GL_RGBA8, GL_RGBA8}, true, GL_DEPTH_COMPONENT24);
    clearCameraTarget(target);
    const float black[4] = {0, 0, 0, 1};
    glClearBufferfv(GL_COLOR, 2, black);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    const Program& program = cachedProgram("scene.vert.glsl", "cascades.frag.glsl");
    program.use();
    program.set("uViewProjection", cameraViewProjection(scene, params));
    program.set("uCameraView", cameraView(scene.camera));
    program.set("uCascadeCount", int(cascades.size()));
    const char* samplers[kMaxCascades] = {"uMap0", "uMap1", "uMap2", "uMap3"};
    const char* matrices[kMaxCascades] = {"uWorldToCascade[0]", "uWorldToCascade[1]",
                                          "uWorldToCascade[2]", "uWorldToCascade[3]"};
    const char* splits[kMaxCascades] = {"uSplitFar[0]", "uSplitFar[1]", "uSplitFar[2]",
                                        "uSplitFar[3]"};
    for (int i = 0; i < kMaxCascades; ++i) {
      // Unused samplers still read a valid texture: the last cascade's.
      const size_t k = std::min(size_t(i), cascades.size() - 1);
      glActiveTexture(GLenum(GL_TEXTURE0 + i));
      glBindTexture(GL_TEXTURE_2D, maps[k].depth.id());
      program.set(samplers[i], i);
      program.set(matrices[i], clipToTexture() * cascades[k].viewProjection);
      program.set(splits[i], cascades[k].farDepth);
    }
    setLightingUniforms(program, scene);
    gpu.draw([](const Object&) { return true; },
             [&](const Object& o) { setObjectUniforms(program, o); });
    for (int i = kMaxCascades - 1; i >= 0; --i) {
      glActiveTexture(GLenum(GL_TEXTURE0 + i));
      glBindTexture(GL_TEXTURE_2D, 0);
    }
    readCameraTarget(target, passes.frame());
    if (cascadeIndex) *cascadeIndex = readAttachment(target, 2);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  });
}

std::string formatDepth(float d) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", double(d));
  return buffer;
}

// --dump-passes: each cascade's depth map as grey, the camera pass and the cascade index.
void captureCascades(Passes& passes, const std::vector<CascadeCrop>& cascades,
                     const std::vector<RenderTarget>& maps, const Image& cascadeIndex) {
  if (!passes.capturing()) return;
  for (size_t i = 0; i < maps.size(); ++i) {
    const PassPart part{"(cascade " + std::to_string(i) + ")", "-" + std::to_string(i), int(i)};
    passes.captureDepth(
        "2", "cascade-depth{part}",
        [&] { return readDepthTexture(maps[i].depth.id(), maps[i].width, maps[i].height); }, part,
        {{"cascade", std::to_string(i)},
         {"slice",
          formatDepth(cascades[i].nearDepth) + " .. " + formatDepth(cascades[i].farDepth)}});
  }
  captureCameraPass(passes, "3");
  passes.capture("3", "cascade-index", [&] {
    Image rgb(cascadeIndex.width, cascadeIndex.height, 3);
    for (size_t p = 0; p < size_t(cascadeIndex.width) * cascadeIndex.height; ++p)
      for (int ch = 0; ch < 3; ++ch) rgb.data[p * 3 + ch] = cascadeIndex.data[p * 4 + ch];
    return rgb;
  });
}

ParamSpec cascadesParam() {
  return integerParam("cascades", kDefaultCascades, 1, kMaxCascades,
                      "N, the number of splits of the view frustum, one shadow map each (ours, "
                      "after Zhang et al. 2006)");
}
ParamSpec lambdaParam() {
  return numberParam("lambda", kDefaultLambda, 0.0, 1.0,
                     "the split scheme C_i = lambda C_log + (1 - lambda) C_uni: 0 uniform, 1 "
                     "logarithmic (ours, after Zhang et al. 2006)");
}
ParamSpec stabilizeParam() {
  return flagParam("stabilize", true,
                   "bound each slice by a sphere and snap the crop to whole texels, so that "
                   "shadows do not swim as the camera moves (ours)");
}

Frame render(GlContext&, const Scene& scene, const RenderParams& params) {
  CascadeSettings s;
  s.count = params.integer(cascadesParam());
  s.lambda = float(params.number(lambdaParam()));
  s.stabilize = params.flag(stabilizeParam());
  s.texels = params.shadowMapTexels;
  const float factor = float(params.number(offsetFactorParam(kDefaultOffsetFactor)));
  const float units =
      float(params.number(offsetUnitsParam(kDefaultOffsetUnits, kLargestOffsetUnits)));
  const bool linear = params.text(compareParam()) == "linear";
  Frame frame;
  Passes passes(frame, params, passTable());
  GpuScene gpu(scene);
  const float aspect = float(params.width) / float(params.height);
  const std::vector<CascadeCrop> cascades = splitViewFrustum(passes, scene, aspect, s);
  const std::vector<RenderTarget> maps =
      renderCascadeDepths(passes, gpu, s.texels, cascades, factor, units, linear);
  Image cascadeIndex;
  shadeWithCascades(passes, gpu, params, cascades, maps,
                    passes.capturing() ? &cascadeIndex : nullptr);
  for (size_t i = 0; i < cascades.size(); ++i)
    frame.counters["split_" + std::to_string(i + 1)] = cascades[i].farDepth;
  captureCascades(passes, cascades, maps, cascadeIndex);
  return frame;
}
}  // namespace

std::vector<float> cascadeSplitDistances(float nearPlane, float farPlane, int count, float lambda) {
  if (count < 1 || count > kMaxCascades)
    throw InputError("modern.cascades: " + std::to_string(count) + " cascades; 1 to " +
                     std::to_string(kMaxCascades) + " fit the shader");
  if (!(nearPlane > 0.0f && farPlane > nearPlane))
    throw InputError("modern.cascades: the split range needs 0 < near < far");
  std::vector<float> c(size_t(count) + 1);
  for (int i = 0; i <= count; ++i) {
    const double t = double(i) / count;
    const double logarithmic = nearPlane * std::pow(double(farPlane) / nearPlane, t);
    const double uniform = nearPlane + (double(farPlane) - nearPlane) * t;
    c[size_t(i)] = float(lambda * logarithmic + (1.0 - lambda) * uniform);
  }
  c.front() = nearPlane;  // exact ends despite pow's round-off
  c.back() = farPlane;
  return c;
}

std::array<glm::vec3, 8> frustumSliceCorners(const Camera& camera, float aspect, float nearDepth,
                                             float farDepth) {
  const glm::mat4 viewToWorld = glm::inverse(cameraView(camera));
  const float tanY = std::tan(glm::radians(camera.fovyDegrees) * 0.5f);
  std::array<glm::vec3, 8> out;
  const float depths[2] = {nearDepth, farDepth};
  const glm::vec2 quad[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  for (int d = 0; d < 2; ++d)
    for (int q = 0; q < 4; ++q) {
      const float z = depths[d];
      const glm::vec4 view(quad[q].x * z * tanY * aspect, quad[q].y * z * tanY, -z, 1.0f);
      out[size_t(d * 4 + q)] = glm::vec3(viewToWorld * view);
    }
  return out;
}

// Departs from the method as kSpotLightDeviation (the scene's spot light, not a directional one:
// the crop is built in its post-projective space) and kFitDeviation (the split range drawn in to
// the scene) say, both declared by pass 1.
std::vector<CascadeCrop> cascadeCrops(const Scene& scene, const float aspect,
                                      const CascadeSettings& s) {
  const Camera& cam = scene.camera;
  const Bounds bounds = sceneBounds(scene);
  // The far plane drawn in to the farthest corner of the scene (kFitDeviation).
  float farthest = 0.0f;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 p((i & 1) ? bounds.hi.x : bounds.lo.x, (i & 2) ? bounds.hi.y : bounds.lo.y,
                      (i & 4) ? bounds.hi.z : bounds.lo.z);
    farthest = std::max(farthest, glm::distance(p, cam.position));
  }
  const float farPlane =
      std::max(std::min(cam.farPlane, farthest), cam.nearPlane * kSmallestFarOverNear);
  const std::vector<float> splits =
      cascadeSplitDistances(cam.nearPlane, farPlane, s.count, s.lambda);
  const glm::mat4 lightVP = lightProjection(scene) * lightView(scene.light);
  std::vector<CascadeCrop> out;
  for (int i = 0; i < s.count; ++i) {
    CascadeCrop c;
    c.nearDepth = splits[size_t(i)];
    c.farDepth = splits[size_t(i) + 1];
    if (s.stabilize)
      stableCrop(scene, lightVP, aspect, c, s.texels, c);
    else
      tightCrop(lightVP, frustumSliceCorners(cam, aspect, c.nearDepth, c.farDepth), bounds, c);
    c.crop = cropMatrix(c.centre, c.halfSize);
    c.viewProjection = c.crop * lightVP;
    out.push_back(c);
  }
  return out;
}

Technique cascadedShadowMapTechnique() {
  Technique t;
  t.name = "modern.cascades";
  t.paper = "ours, after Zhang et al. 2006 (not in shared/papers): parallel-split shadow maps";
  t.summary =
      "view frustum split at lambda log + (1 - lambda) uniform, one cropped map per split, "
      "2x2 compare";
  t.status = "complete";
  t.needs.profile = Profile::kCore;
  t.params = {cascadesParam(),
              lambdaParam(),
              stabilizeParam(),
              offsetFactorParam(kDefaultOffsetFactor),
              offsetUnitsParam(kDefaultOffsetUnits, kLargestOffsetUnits),
              compareParam()};
  t.reads = {.shadowMap = true};
  t.edge = Technique::Edge::kFiltered;  // compare=linear (default): the driver's 2x2 PCF
  t.passes = passTable();
  t.render = render;
  return t;
}

}  // namespace sl::modern
