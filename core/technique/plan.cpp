// core/technique/plan.cpp — the pass planner (core/technique/plan.h).
//
// Rules, each an item with its reason:
//   1. shadow passes    — left out when no caster has a triangle inside the light frustum, or
//                         no receiver does (nothing can be shadowed)
//   2. light objects    — non-casters and casters wholly outside the frustum are left out
//   3. depth range      — fitted: near to the casters inside the frustum, far to the casters
//                         and receivers inside it (a receiver nearer than every caster cannot
//                         be shadowed; a receiver beyond far would be compared wrongly)
//   4. accumulation     — only for footprints that need more than one pass of four samples
//                         (Brabec–Seidel §3: a 2x2 footprint fits the RGBA channels of one
//                         pass; §4: fast PCF packs 2x2 by convolution, 4x4 sums four phases)
//   5. imaging stages   — the colour matrix is the identity for one sample (filter 1); the
//                         convolution is the identity for filter 1
//   6. convolution taps — Eq. (1)'s 3x3 RGBA kernel has 4 non-zero taps of 36
//   7. blur taps        — no blur pass for blur=0; binomial taps below half an 8-bit step
//   8. mip chain        — left out when the view never minifies the shadow map
#include "core/technique/plan.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <sstream>

namespace sl {
namespace {

constexpr int kSamplesPerTriangleSide = 4;        // barycentric grid for the minification estimate
constexpr double kMinificationPercentile = 0.95;  // of the camera-facing receiver samples
constexpr float kHalf8BitStep = 1.0f / 510.0f;    // a weight below this rounds to 0 in 8 bits
constexpr int kChannelsPerPass = 4;               // R, G, B, A: four samples per pass (§3)

// The light-side work a technique declares (core/technique/technique.h PlanTraits), as the plan
// names it.
const char* shadowWorkName(PlanTraits::ShadowWork work) {
  switch (work) {
    case PlanTraits::ShadowWork::kRays: return "shadow rays (Embree)";
    case PlanTraits::ShadowWork::kShadowVolumes: return "shadow volume passes";
    case PlanTraits::ShadowWork::kSmoothies: return "light passes (depth + smoothies)";
    case PlanTraits::ShadowWork::kShadowMap: break;
  }
  return "light passes (shadow map)";
}

// Clip-space position of a model-space vertex.
glm::vec4 clip(const glm::mat4& m, const glm::vec3& p) { return m * glm::vec4(p, 1.0f); }

// True when the triangle is certainly outside the frustum: all three vertices beyond the same
// lateral plane or behind the near plane (w <= 0 counts as behind the light).
bool outsideLateralOrBehind(const glm::vec4 v[3]) {
  auto allOutside = [&](auto test) { return test(v[0]) && test(v[1]) && test(v[2]); };
  return allOutside([](const glm::vec4& c) { return c.x > c.w; }) ||
         allOutside([](const glm::vec4& c) { return c.x < -c.w; }) ||
         allOutside([](const glm::vec4& c) { return c.y > c.w; }) ||
         allOutside([](const glm::vec4& c) { return c.y < -c.w; }) ||
         allOutside([](const glm::vec4& c) { return c.w <= 0.0f; });
}

// The light frustum with a depth range wide enough for every object (near at 1e-6 of far):
// only the lateral planes and the light's own position decide "inside" here.
glm::mat4 lateralLightMatrix(const Scene& scene) {
  const DepthRange r = lightDepthRange(scene);
  return glm::perspective(glm::radians(scene.light.coneDegrees), 1.0f, r.farPlane * 1e-6f,
                          r.farPlane * 2.0f) *
         lightView(scene.light);
}

struct ObjectReach {
  bool inside = false;
  float zMin = 1e30f, zMax = -1e30f;  // light-view distances of its triangles inside
  float maxTangent = 0.0f;            // largest |x|/z or |y|/z of those vertices
};

ObjectReach reach(const Object& o, const glm::mat4& lightClip, const glm::mat4& view) {
  ObjectReach r;
  if (!o.mesh) return r;
  const Mesh& m = *o.mesh;
  const glm::mat4 toClip = lightClip * o.model;
  const glm::mat4 toView = view * o.model;
  for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    glm::vec4 c[3];
    for (int k = 0; k < 3; ++k) c[k] = clip(toClip, m.positions[m.indices[t + k]]);
    if (outsideLateralOrBehind(c)) continue;
    r.inside = true;
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 v = glm::vec3(toView * glm::vec4(m.positions[m.indices[t + k]], 1.0f));
      const float z = -v.z;
      r.zMin = std::min(r.zMin, z);
      r.zMax = std::max(r.zMax, z);
      r.maxTangent =
          std::max(r.maxTangent, z > 0.0f ? std::max(std::fabs(v.x), std::fabs(v.y)) / z : 1e30f);
    }
  }
  return r;
}

// GL's rho (glspec §3.8.8): the larger of the two screen-axis footprints, in shadow-map
// texels per camera pixel, sampled over the camera-facing receiver triangles inside both
// frusta; the 95th percentile by screen area (samples weighted by the pixels they cover).
double maxTexelsPerPixel(const Scene& scene, const RenderParams& params) {
  const glm::mat4 camera = cameraProjection(scene.camera, float(params.width) / params.height) *
                           cameraView(scene.camera);
  const glm::mat4 light = lightProjection(scene) * lightView(scene.light);
  const glm::vec2 window(params.width, params.height);
  const float texels = float(params.shadowMapTexels);
  std::vector<std::pair<double, double>> rhos;  // (rho, screen pixels the sample stands for)
  auto toWindow = [&](const glm::vec3& p, glm::vec2& out) {
    const glm::vec4 c = camera * glm::vec4(p, 1.0f);
    if (c.w <= 0.0f || std::fabs(c.x) > c.w || std::fabs(c.y) > c.w) return false;
    out = (glm::vec2(c) / c.w * 0.5f + 0.5f) * window;
    return true;
  };
  auto toTexels = [&](const glm::vec3& p, glm::vec2& out) {
    const glm::vec4 c = light * glm::vec4(p, 1.0f);
    if (c.w <= 0.0f || std::fabs(c.x) > c.w || std::fabs(c.y) > c.w) return false;
    out = (glm::vec2(c) / c.w * 0.5f + 0.5f) * texels;
    return true;
  };
  for (const Object& o : scene.objects) {
    if (!o.receivesShadow || !o.mesh) continue;
    const Mesh& m = *o.mesh;
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
      const glm::vec3 a = glm::vec3(o.model * glm::vec4(m.positions[m.indices[t]], 1.0f));
      const glm::vec3 b = glm::vec3(o.model * glm::vec4(m.positions[m.indices[t + 1]], 1.0f));
      const glm::vec3 c = glm::vec3(o.model * glm::vec4(m.positions[m.indices[t + 2]], 1.0f));
      const glm::vec3 e1 = b - a, e2 = c - a;
      const glm::vec3 n = glm::cross(e1, e2);
      if (glm::length(n) <= 0.0f) continue;
      const float h = 1.0f / (8.0f * kSamplesPerTriangleSide);  // finite-difference step
      for (int i = 0; i <= kSamplesPerTriangleSide; ++i)
        for (int j = 0; i + j <= kSamplesPerTriangleSide; ++j) {
          const glm::vec3 p = a + (float(i) / kSamplesPerTriangleSide) * e1 +
                              (float(j) / kSamplesPerTriangleSide) * e2;
          if (glm::dot(n, scene.camera.position - p) <= 0.0f) continue;  // faces away
          glm::vec2 w0, w1, w2, t0, t1, t2;
          if (!toWindow(p, w0) || !toWindow(p + h * e1, w1) || !toWindow(p + h * e2, w2)) continue;
          if (!toTexels(p, t0) || !toTexels(p + h * e1, t1) || !toTexels(p + h * e2, t2)) continue;
          const glm::mat2 dWindow(w1 - w0, w2 - w0), dTexel(t1 - t0, t2 - t0);
          if (std::fabs(glm::determinant(dWindow)) < 1e-12f) continue;
          const glm::mat2 J = dTexel * glm::inverse(dWindow);  // texels per window pixel
          const double rho = std::max(glm::length(J[0]), glm::length(J[1]));
          // Pixels per unit of (e1, e2) parameter area, times the parameter area per sample.
          const double pixels =
              std::fabs(glm::determinant(dWindow)) / (double(h) * h) /
              double((kSamplesPerTriangleSide + 1) * (kSamplesPerTriangleSide + 2));
          if (std::isfinite(rho) && std::isfinite(pixels)) rhos.push_back({rho, pixels});
        }
    }
  }
  if (rhos.empty()) return 0.0;
  // Near a silhouette the footprint grows without bound (the surface turns edge-on); the
  // percentile keeps those few grazing samples from deciding for the whole view.
  // Weighted by the screen area each sample stands for: "95% of the receivers' pixels".
  std::sort(rhos.begin(), rhos.end());
  double total = 0.0;
  for (const auto& r : rhos) total += r.second;
  double below = 0.0;
  for (const auto& r : rhos) {
    below += r.second;
    if (below >= kMinificationPercentile * total) return r.first;
  }
  return rhos.back().first;
}

std::string significantDigits(double v, int digits = 3) {
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}

}  // namespace

bool casterReachesLightFrustum(const Scene& scene) {
  const glm::mat4 lightClip = lateralLightMatrix(scene);
  const glm::mat4 view = lightView(scene.light);
  for (const Object& o : scene.objects)
    if (o.castsShadow && reach(o, lightClip, view).inside) return true;
  return false;
}

FramePlan planFrame(const Scene& scene, const Technique& t, const RenderParams& params) {
  FramePlan plan;
  plan.technique = t.name;
  plan.scene = scene.name;
  plan.sceneConeDegrees = scene.light.coneDegrees;
  const bool reference = t.plan.shadowWork == PlanTraits::ShadowWork::kRays;
  const glm::mat4 lightClip = lateralLightMatrix(scene);
  const glm::mat4 view = lightView(scene.light);
  float casterNear = 1e30f, farthest = -1e30f, casterTangent = 0.0f;
  for (const Object& o : scene.objects) {
    const ObjectReach r = reach(o, lightClip, view);
    if (r.inside && o.receivesShadow) ++plan.receiversInFrustum;
    if (r.inside && (o.castsShadow || o.receivesShadow)) farthest = std::max(farthest, r.zMax);
    PlanItem item{o.name, true, ""};
    if (!o.castsShadow) {
      item = {o.name, false, "casts no shadow (castsShadow off)"};
    } else if (!r.inside) {
      item = {o.name, false, "no triangle inside the light frustum"};
    } else {
      ++plan.castersInFrustum;
      casterNear = std::min(casterNear, r.zMin);
      casterTangent = std::max(casterTangent, r.maxTangent);
      item.reason = "caster inside the light frustum";
    }
    plan.lightObjects.push_back(item);
  }
  plan.shadowPassesNeeded = plan.castersInFrustum > 0 && plan.receiversInFrustum > 0;
  // The frustum fitted to the casters: the cone through their farthest-out vertex.
  const float coneTangent = std::tan(glm::radians(0.5f * scene.light.coneDegrees));
  plan.fittedConeDegrees =
      plan.castersInFrustum > 0
          ? 2.0f * glm::degrees(std::atan(std::min(casterTangent, coneTangent)))
          : scene.light.coneDegrees;
  plan.sceneRange = lightDepthRange(scene);
  plan.fittedRange = plan.sceneRange;
  if (plan.castersInFrustum > 0) {
    // The same margin rule as lightDepthRange (2% of the span), on the fitted set.
    const float span = std::max(farthest - std::max(casterNear, 0.0f), 1e-6f);
    plan.fittedRange.farPlane = farthest + 0.02f * span;
    plan.fittedRange.nearPlane =
        std::max(casterNear - 0.02f * span, plan.fittedRange.farPlane * 1e-4f);
  }

  // Passes.
  const std::string shadowWork = shadowWorkName(t.plan.shadowWork);
  if (plan.shadowPassesNeeded) {
    plan.passes.push_back({shadowWork, true,
                           std::to_string(plan.castersInFrustum) + " caster(s) and " +
                               std::to_string(plan.receiversInFrustum) +
                               " receiver(s) inside the light frustum"});
  } else {
    plan.passes.push_back({shadowWork, false,
                           plan.castersInFrustum == 0
                               ? "no caster reaches the light frustum: every pixel is lit"
                               : "no receiver inside the light frustum: nothing can be shadowed"});
  }
  plan.passes.push_back({"camera pass", true, "always: it produces the image"});

  // Resources.
  const bool fastPcf = t.plan.samples == PlanTraits::SampleGrouping::kPackedPhases;
  if (t.needs.accumulation || t.plan.samples != PlanTraits::SampleGrouping::kOnePerPixel) {
    const int largestWithoutAccumulation = fastPcf ? 3 : 2;
    const int f = params.filter;
    if (f > largestWithoutAccumulation)
      plan.resources.push_back(
          {"accumulation buffer", true,
           "footprint " + std::to_string(f) + "x" + std::to_string(f) + " needs " +
               (fastPcf ? "four 2x2 phases summed (Brabec–Seidel §4)"
                        : std::to_string((f * f + kChannelsPerPass - 1) / kChannelsPerPass) +
                              " groups of four samples summed (Brabec–Seidel §3)")});
    else
      plan.resources.push_back({"accumulation buffer", false,
                                "footprint " + std::to_string(f) + "x" + std::to_string(f) +
                                    (fastPcf ? " is packed by one convolution pass (§4)"
                                             : " fits the four channels of one pass (§3)")});
  }
  if (t.plan.colourTableCompare)
    plan.resources.push_back({"imaging: colour table (the comparison step)", true,
                              "maps each channel's difference to shadowed / lit (§3, Fig. 4)"});
  if (t.plan.colourMatrixSum) {
    if (params.filter == 1)
      plan.resources.push_back({"imaging: colour matrix", false,
                                "one sample in one channel: the channel sum is the identity"});
    else
      plan.resources.push_back(
          {"imaging: colour matrix", true, "sums the four channels' results into alpha (Fig. 4)"});
  }
  if (t.plan.packingConvolution) {
    if (params.filter == 1)
      plan.resources.push_back(
          {"imaging: convolution", false, "footprint 1x1: the packing kernel is the identity"});
    else
      plan.resources.push_back(
          {"imaging: convolution (Eq. 1, 3x3 RGBA)", true,
           "4 non-zero taps of 36 (one per channel): 32 zero taps skipped, and its top row and "
           "right column are zero in every channel, so the support is 2x2"});
  }
  if (t.plan.prefilter != PlanTraits::Prefilter::kNone) {
    // The values the technique will use: those given, else its declared defaults.
    const auto value = [&](const char* key) {
      if (auto it = params.extra.find(key); it != params.extra.end()) return it->second;
      const ParamSpec* spec = findParam(t, key);
      return spec ? spec->defaultText() : std::string();
    };
    int taps = 0;
    try {
      taps = std::stoi(value("blur"));
    } catch (const std::exception&) {
      taps = 0;  // no blur declared, or a value the technique itself will refuse
    }
    const std::string storage = value("storage");
    if (taps <= 1) {
      plan.resources.push_back({"separable blur pass", false, "blur=0: no kernel"});
    } else {
      // Binomial weights C(taps-1, i) / 2^(taps-1) (the modules' Gaussian approximation).
      int zero = 0;
      double w = 1.0;
      for (int i = 0; i < taps; ++i) {
        if (i > 0) w = w * double(taps - i) / double(i);
        if (storage == "8" && w / std::ldexp(1.0, taps - 1) < kHalf8BitStep) ++zero;
      }
      plan.resources.push_back({"separable blur pass", true,
                                std::to_string(taps) + " taps per axis, " + std::to_string(zero) +
                                    " of them below half an 8-bit step" +
                                    (zero ? " (skipped)" : " (none skipped)")});
    }
    const std::string filtering = value("filtering");
    plan.maxShadowTexelsPerPixel = maxTexelsPerPixel(scene, params);
    const std::string rho =
        significantDigits(plan.maxShadowTexelsPerPixel) + " shadow-map texels per pixel";
    // Tri-linear and anisotropic filtering read the mip chain (modern/prefiltered_maps.cpp);
    // mipmaps=always builds it whatever the view does.
    const bool readsMipChain = filtering == "trilinear" || filtering == "anisotropic";
    const bool alwaysBuilt = value("mipmaps") == "always";
    if (!readsMipChain)
      plan.resources.push_back(
          {"mip chain", false, "filtering=" + filtering + " reads level 0 only"});
    else if (alwaysBuilt)
      plan.resources.push_back({"mip chain", true, "mipmaps=always (up to " + rho + ")"});
    else if (plan.maxShadowTexelsPerPixel <= 1.0)
      plan.resources.push_back(
          {"mip chain", false, "the view never minifies the map (at most " + rho + ")"});
    else
      plan.resources.push_back(
          {"mip chain", true, "the view minifies the map (up to " + rho + ")"});
  } else if (!reference) {
    plan.maxShadowTexelsPerPixel = maxTexelsPerPixel(scene, params);
  }
  if (!plan.shadowPassesNeeded)
    for (PlanItem& r : plan.resources)
      if (r.kept) r = {r.name, false, "no shadow passes run"};
  return plan;
}

std::string formatPlan(const FramePlan& plan) {
  std::ostringstream s;
  auto list = [&](const char* title, const std::vector<PlanItem>& items) {
    if (items.empty()) return;
    s << title << ":\n";
    for (const PlanItem& i : items) {
      std::string name = i.name;
      if (name.size() < 34) name += std::string(34 - name.size(), ' ');
      s << "  " << (i.kept ? "keep  " : "leave ") << name << " " << i.reason << "\n";
    }
  };
  s << "plan for " << plan.technique << " on scene " << plan.scene << "\n";
  list("passes", plan.passes);
  list("objects in the light passes", plan.lightObjects);
  list("resources", plan.resources);
  s << "light frustum: cone " << significantDigits(plan.sceneConeDegrees, 4)
    << " deg, fitted to the casters " << significantDigits(plan.fittedConeDegrees, 4) << " deg: "
    << significantDigits(std::tan(glm::radians(0.5 * plan.sceneConeDegrees)) /
                             std::tan(glm::radians(0.5 * plan.fittedConeDegrees)),
                         3)
    << "x the shadow-map texels per unit across the casters\n";
  s << "light depth range: scene fit [" << significantDigits(plan.sceneRange.nearPlane, 4) << ", "
    << significantDigits(plan.sceneRange.farPlane, 4)
    << "], fitted to casters and receivers in the frustum ["
    << significantDigits(plan.fittedRange.nearPlane, 4) << ", "
    << significantDigits(plan.fittedRange.farPlane, 4) << "]: near/far "
    << significantDigits(plan.sceneRange.nearPlane / plan.sceneRange.farPlane, 3) << " -> "
    << significantDigits(plan.fittedRange.nearPlane / plan.fittedRange.farPlane, 3) << "\n";
  if (plan.maxShadowTexelsPerPixel > 0)
    s << "largest minification: " << significantDigits(plan.maxShadowTexelsPerPixel)
      << " shadow-map texels per camera pixel\n";
  return s.str();
}

}  // namespace sl
