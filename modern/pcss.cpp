// modern.pcss — percentage-closer soft shadows: ours, after Fernando 2005 (not in
// shared/papers): R. Fernando, "Percentage-Closer Soft Shadows", SIGGRAPH 2005 sketch. The paper
// is not in shared/papers, so nothing here quotes it; the method as implemented: a shadow map
// from the light's centre, then per camera pixel a blocker search, a penumbra width from similar
// triangles, and percentage-closer filtering (Reeves et al. 1987, as modern.pcf) over that width.
// The light is the scene's sphere of SpotLight::radius, the light reference.soft ray-traces and
// Chan 2004 Fig. 4-9 sweeps, so that PCSS, smoothies and the ray tracer see the same light.
//
// Passes:
//   1. renderLinearDepthFromLight — the casters' linear light depth z (distance along the light's
//                                   axis) into an R32F map (pcss_light_depth.frag)
//   2. shadeWithPcss              — camera pass (pcss.frag): (a) findBlockers averages the depth
//                                   of the texels in front of the receiver over the region
//                                   through which the light is seen; (b) penumbraWidth,
//                                   w_p = (d_r - d_b) w_light / d_b; (c) filterPenumbra, PCF over
//                                   a region of width w_p (--param pattern: Poisson disk or grid)
// The passes are declared once in pcssPasses().
#include "modern/pcss.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "core/base/errors.h"
#include "core/technique/pass_capture.h"
#include "core/technique/passes.h"
#include "modern/camera_pass.h"
#include "modern/hardware_shadow_map.h"

namespace sl::modern {
using namespace sl::gl;

namespace {
// The taps' arrays in pcss.frag hold this many each.
constexpr int kMaxTaps = 64;
constexpr const char* kTapCounts[] = {"4", "9", "16", "25", "36", "49", "64"};  // squares: grid too
constexpr const char* kDefaultSearchTaps = "16";
constexpr const char* kDefaultFilterTaps = "36";
// Linear light depth where no caster was drawn: no blocker for any receiver.
constexpr float kNoSurfaceDepth = 1.0e30f;
// The receiver bias, in texel footprints along the light axis (a footprint at depth z is
// z * 2 tan(cone / 2) / size). With the receiver's plane evaluated at each texel's centre, the
// bias only covers the rasteriser's depth interpolation and curvature: one footprint left no
// acne on brabec's spheres and torus at 256^2..1024^2 (looked at); --param bias-texels.
constexpr double kDefaultBiasTexels = 1.0;
constexpr double kMaxBiasTexels = 16.0;
// The largest search and filter radius, in map units (map side = 1): an eighth of the map. A
// receiver close to the light with a small fitted near plane would otherwise search the whole
// map (the search radius grows as 1 / near).
constexpr float kMaxRadius = 0.125f;
// The steepest receiver plane the taps follow: dz per lateral world unit, tan(85 degrees).
// Steeper (grazing) receivers are clamped, so that a plane extrapolated over a wide filter cannot
// send depths to +-infinity at a sphere's terminator.
constexpr float kMaxReceiverSlope = 11.43f;
// --param light-radius: world units, at most a light as wide as any scene here.
constexpr double kMinLightRadius = 0.0;
constexpr double kMaxLightRadius = 10.0;
// Mitchell's best-candidate sampling: candidates per tap already placed.
constexpr int kCandidatesPerTap = 24;
constexpr std::uint32_t kTapSeed = 20050731u;  // fixed: the same taps everywhere

constexpr const char* kReceiverPlaneDeviation =
    "DEVIATION (ours, after Fernando 2005, not in shared/papers): each tap compares the texel's "
    "depth with the receiver's plane at that texel's centre (the depth's gradient over the map "
    "from the screen derivatives), not with the receiver's own depth. A filter region as wide as "
    "a penumbra spans many texels, and on a slanted receiver a constant bias either leaves acne "
    "or detaches the shadow at contact; the plane is exact for planar receivers. Slopes beyond "
    "85 degrees are clamped.";
constexpr const char* kSearchRegionDeviation =
    "DEVIATION (ours, after Fernando 2005, not in shared/papers): the blocker search covers the "
    "region through which the light disk is seen from the receiver, down to the light's fitted "
    "near plane (the nearest geometry), radius R (z_r - near) / (z_r 2 near tan(cone / 2)); "
    "search and filter radii are clamped to an eighth of the map.";
constexpr const char* kShaderPlaneDeviation =  // pcss.frag blockerAt
    "DEVIATION (ours, after Fernando 2005, not in shared/papers): the tap compares the texel's "
    "depth with the receiver's plane at the texel's centre (pcss.cpp says why).";
constexpr const char* kShaderSearchDeviation =  // pcss.frag findBlockers
    "DEVIATION (ours, after Fernando 2005, not in shared/papers): the search reaches down to the "
    "light's fitted near plane and is clamped to uMaxRadius (pcss.cpp says why).";

// A deterministic uniform number in [0, 1) from a 32-bit xorshift: std:: distributions differ
// between standard libraries.
struct TapRandom {
  std::uint32_t state = kTapSeed;
  float next() {
    state ^= state << 13;
    state ^= state >> 17;
    state ^= state << 5;
    return float(state >> 8) * (1.0f / 16777216.0f);
  }
};

// Poisson-disk taps in the unit disk by Mitchell's best candidate: each new tap is, of
// kCandidatesPerTap * (taps so far) uniform candidates, the one farthest from the taps so far.
std::vector<glm::vec2> poissonTaps(int count) {
  TapRandom random;
  const auto candidate = [&] {
    for (;;) {
      const glm::vec2 p(2.0f * random.next() - 1.0f, 2.0f * random.next() - 1.0f);
      if (glm::dot(p, p) <= 1.0f) return p;
    }
  };
  std::vector<glm::vec2> taps;
  while (int(taps.size()) < count) {
    glm::vec2 best = candidate();
    float bestDistance = -1.0f;
    const int tries = std::max(1, kCandidatesPerTap * int(taps.size()));
    for (int i = 0; i < tries; ++i) {
      const glm::vec2 c = i == 0 ? best : candidate();
      float nearest = std::numeric_limits<float>::max();
      for (const glm::vec2& t : taps) nearest = std::min(nearest, glm::distance(c, t));
      if (nearest > bestDistance) {
        bestDistance = nearest;
        best = c;
      }
    }
    taps.push_back(best);
  }
  return taps;
}

// The centres of a side x side grid over [-1, 1]^2.
std::vector<glm::vec2> gridTaps(int count) {
  const int side = int(std::lround(std::sqrt(double(count))));
  std::vector<glm::vec2> taps;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x)
      taps.push_back({(2.0f * x + 1.0f) / side - 1.0f, (2.0f * y + 1.0f) / side - 1.0f});
  return taps;
}

// Passes 1 and 2, declared once: names, the method's steps, the buffers a dump shows, shaders
// and deviations.
PassTable pcssPasses() {
  return {
      {.id = "1",
       .name = "linear depth from light",
       .reference = "ours, after Fernando 2005 (not in shared/papers): PCSS's shadow map, here "
                    "the casters' linear light depth (distance along the light axis), in which "
                    "the penumbra formula holds",
       .writes = {{.name = "linear-depth", .caption = "pass 1: linear light depth{range}"}},
       .shaders = {"pcss-linear-depth"}},
      {.id = "2",
       .name = "camera pass: blocker search, penumbra width, PCF",
       .reference = "ours, after Fernando 2005 (not in shared/papers): (a) blocker search, (b) "
                    "penumbra width w_p = (d_receiver - d_blocker) w_light / d_blocker, (c) "
                    "percentage-closer filtering over w_p",
       .writes = cameraPassBuffers("2",
                                   "pcss.frag: blocker search, w_p = (d_r - d_b) w_light / d_b, "
                                   "PCF over w_p (ours, after Fernando 2005)"),
       .shaders = {"pcss-blocker-search", "pcss-penumbra", "pcss-filter"},
       .deviations = {kReceiverPlaneDeviation, kSearchRegionDeviation, kShaderPlaneDeviation,
                      kShaderSearchDeviation}},
  };
}

const PassTable& passTable() {
  static const PassTable table = pcssPasses();
  return table;
}

// Pass 1 (ours, after Fernando 2005: PCSS's shadow map): the casters' linear light depth.
RenderTarget renderLinearDepthFromLight(Passes& passes, const GpuScene& gpu, int texels) {
  RenderTarget map;
  passes.run("1", [&] {
    const Scene& scene = gpu.scene();
    map = makeRenderTarget(texels, texels, {GL_R32F}, true, GL_DEPTH_COMPONENT24);
    map.bind();
    const float none[4] = {kNoSurfaceDepth, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, none);
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    Program program("scene.vert.glsl", "pcss_light_depth.frag.glsl");
    program.use();
    program.set("uViewProjection", lightProjection(scene) * lightView(scene.light));
    program.set("uLightView", lightView(scene.light));
    gpu.draw([](const Object& o) { return o.castsShadow; },
             [&](const Object& o) { program.set("uModel", o.model); });
    glDisable(GL_DEPTH_TEST);
  });
  return map;
}

// The shader's tap arrays.
void setTaps(const Program& program, const char* count, const char* array,
             const std::vector<glm::vec2>& taps) {
  program.set(count, int(taps.size()));
  glUniform2fv(program.uniform(array), GLsizei(taps.size()), &taps[0].x);
}

struct PcssSettings {
  float lightRadius = 0.0f;
  float biasTexels = 0.0f;
  std::vector<glm::vec2> searchTaps;
  std::vector<glm::vec2> filterTaps;
};

// Pass 2 (ours, after Fernando 2005: blocker search, penumbra estimate, filtering): the camera
// view through pcss.frag.
void shadeWithPcss(Passes& passes, const GpuScene& gpu, const RenderParams& params,
                   const RenderTarget& map, const PcssSettings& s) {
  passes.run("2", [&] {
    const Scene& scene = gpu.scene();
    RenderTarget target = makeCameraTarget(params, true);
    clearCameraTarget(target);
    glEnable(GL_DEPTH_TEST);
    Program program("scene.vert.glsl", "pcss.frag.glsl");
    program.use();
    program.set("uViewProjection", cameraViewProjection(scene, params));
    program.set("uWorldToShadowMap", worldToShadowMap(scene));
    program.set("uTanHalfCone", std::tan(glm::radians(scene.light.coneDegrees) * 0.5f));
    program.set("uLightNear", lightDepthRange(scene).nearPlane);
    program.set("uLightRadius", s.lightRadius);
    program.set("uBiasTexels", s.biasTexels);
    program.set("uMaxRadius", kMaxRadius);
    program.set("uMaxSlope", kMaxReceiverSlope);
    setTaps(program, "uSearchCount", "uSearchTaps", s.searchTaps);
    setTaps(program, "uFilterCount", "uFilterTaps", s.filterTaps);
    setLightingUniforms(program, scene);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, map.color[0].id());
    program.set("uLightDepth", 0);
    gpu.draw([](const Object&) { return true; },
             [&](const Object& o) { setObjectUniforms(program, o); });
    glBindTexture(GL_TEXTURE_2D, 0);
    readCameraTarget(target, passes.frame());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  });
}

// --dump-passes: the linear depth of pass 1 as grey over the drawn range (white: no caster), and
// the camera pass.
void captureDepthAndCameraPass(Passes& passes, const RenderTarget& map) {
  if (passes.capturing()) {
    Image depth = channel(readAttachment(map, 0), 0);
    float lo = std::numeric_limits<float>::max(), hi = 0.0f;
    for (float z : depth.data)
      if (z < kNoSurfaceDepth) lo = std::min(lo, z), hi = std::max(hi, z);
    for (float& z : depth.data)
      z = z >= kNoSurfaceDepth ? 1.0f : (hi > lo ? (z - lo) / (hi - lo) : 0.0f);
    const std::string range = hi >= lo
                                  ? "; z " + std::to_string(lo) + " (black) .. " +
                                        std::to_string(hi) + " (white), white also where no caster"
                                  : "; no caster";
    passes.capture("1", "linear-depth", [&] { return depth; }, {}, {{"range", range}});
  }
  captureCameraPass(passes, "2");
}

// --param light-radius: auto = the scene's SpotLight::radius (reference.soft's light).
ParamSpec lightRadiusParam() {
  return autoNumberParam("light-radius", kMinLightRadius, kMaxLightRadius,
                         "the spherical light's radius, world units; auto: the scene's "
                         "SpotLight::radius, the light reference.soft ray-traces (w_light = 2 r)");
}
ParamSpec searchTapsParam() {
  return choiceParam("search-taps", kDefaultSearchTaps,
                     {std::begin(kTapCounts), std::end(kTapCounts)},
                     "blocker-search taps (ours, after Fernando 2005: blocker search)");
}
ParamSpec filterTapsParam() {
  return choiceParam("filter-taps", kDefaultFilterTaps,
                     {std::begin(kTapCounts), std::end(kTapCounts)},
                     "PCF taps over the penumbra width (ours, after Fernando 2005: filtering)");
}
constexpr const char* kPoisson = "poisson";
constexpr const char* kGrid = "grid";
ParamSpec patternParam() {
  return choiceParam("pattern", kPoisson, {kPoisson, kGrid},
                     "where the taps lie: Poisson disk (best candidate) or a square grid");
}
ParamSpec biasTexelsParam() {
  return numberParam("bias-texels", kDefaultBiasTexels, 0.0, kMaxBiasTexels,
                     "depth bias below the receiver's plane, in texel footprints along the light "
                     "axis");
}

Frame render(GlContext&, const Scene& scene, const RenderParams& params) {
  PcssSettings s;
  const std::optional<double> radius = params.numberOrAuto(lightRadiusParam());
  s.lightRadius = radius ? float(*radius) : scene.light.radius;
  s.biasTexels = float(params.number(biasTexelsParam()));
  const PcssPattern pattern = params.text(patternParam()) == std::string(kGrid)
                                  ? PcssPattern::kGrid
                                  : PcssPattern::kPoisson;
  s.searchTaps = pcssTaps(std::stoi(params.text(searchTapsParam())), pattern);
  s.filterTaps = pcssTaps(std::stoi(params.text(filterTapsParam())), pattern);
  Frame frame;
  Passes passes(frame, params, passTable());
  GpuScene gpu(scene);
  const RenderTarget map = renderLinearDepthFromLight(passes, gpu, params.shadowMapTexels);
  shadeWithPcss(passes, gpu, params, map, s);
  frame.counters["search_taps"] = double(s.searchTaps.size());
  frame.counters["filter_taps"] = double(s.filterTaps.size());
  frame.counters["light_radius"] = s.lightRadius;
  captureDepthAndCameraPass(passes, map);
  return frame;
}
}  // namespace

std::vector<glm::vec2> pcssTaps(int count, PcssPattern pattern) {
  if (count < 1 || count > kMaxTaps)
    throw InputError("modern.pcss: " + std::to_string(count) + " taps; 1 to " +
                     std::to_string(kMaxTaps) + " fit the shader");
  if (pattern == PcssPattern::kGrid) {
    const int side = int(std::lround(std::sqrt(double(count))));
    if (side * side != count)
      throw InputError("modern.pcss: a grid needs a square number of taps, not " +
                       std::to_string(count));
    return gridTaps(count);
  }
  return poissonTaps(count);
}

float pcssPenumbraWidth(float receiverDepth, float blockerDepth, float lightWidth) {
  // As penumbraWidth in pcss.frag.
  return std::max(receiverDepth - blockerDepth, 0.0f) * lightWidth / blockerDepth;
}

Technique pcssTechnique() {
  Technique t;
  t.name = "modern.pcss";
  t.light = Technique::Light::kArea;  // the spherical light of SpotLight::radius
  t.paper = "ours, after Fernando 2005 (not in shared/papers): percentage-closer soft shadows";
  t.summary = "blocker search, penumbra width (d_r - d_b) w_light / d_b, PCF over that width";
  t.status = "complete";
  t.needs.profile = Profile::kCore;
  t.params = {lightRadiusParam(), searchTapsParam(), filterTapsParam(), patternParam(),
              biasTexelsParam()};
  t.reads = {.shadowMap = true};
  t.edge = Technique::Edge::kFiltered;  // PCF over the penumbra width
  t.passes = passTable();
  t.render = render;
  return t;
}

}  // namespace sl::modern
