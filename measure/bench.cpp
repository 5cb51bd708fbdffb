// measure/bench.cpp — `shadowlab bench`: error against run time (issue 8 items 1 and 2).
//
// For each benchmark scene (and the claim scenes derived in code, benchSceneSpecs):
//   1. renderReferences  — reference.hard and reference.soft at the bench's window size in
//                          both forms (pixel=area, the primary truth, and pixel=centre), the
//                          shadow-boundary band of each (core/base/metrics.h boundaryBand), and the
//                          area references again with the light moved (temporal stability)
//   2. measureVariant    — per technique and parameter variant: one context, warm-up frames,
//                          then timed frames (median of the pass-time sums and of each pass),
//                          the errors of the last frame's visibility mask against the four
//                          references (RMSE, max, share above 0.5, the same in the band, leak),
//                          and one more frame with the light moved by a fifth of a texel
//                          (mean |change| of the mask: temporal stability)
//   3. outputs           — a JSON object per row on stdout, CSV (--csv), one gnuplot plot per
//                          scene (error against time, log axes, Pareto front), claim checks
#include "measure/bench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <iomanip>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <tuple>

#include "core/base/decimal.h"
#include "core/base/errors.h"
#include "core/base/output_files.h"
#include "core/base/png_text.h"
#include "core/base/provenance.h"
#include "core/gl/gl.h"
#include "core/scene/scene_library.h"
#include "core/technique/frame_timing.h"
#include "core/technique/plan.h"
#include "imaging/imaging.h"
#include "measure/sweep.h"
#include "reference/reference.h"
#include "registry/commands.h"  // optionsJson: the common options a technique reads
#include "registry/registry.h"
#include "registry/twins.h"

namespace sl::figures {
namespace fs = std::filesystem;

namespace {

// Window sizes: quick keeps the whole run under 2 minutes on two cores; full is the papers'
// 800x600 halved in each direction (llvmpipe fill bounds the run time, docs/design.md).
constexpr int kQuickWidth = 256, kQuickHeight = 192;
constexpr int kFullWidth = 400, kFullHeight = 300;
constexpr int kQuickWarmup = 1, kQuickTimed = 3;
// The fill-bound claim scene's two techniques run at 20-30 ms a frame: its verdict is a time
// ratio near 1, so it gets more frames than a quick variant (still about a second each).
constexpr int kFillBoundWarmup = 2, kFillBoundTimed = 11;
constexpr int kFullWarmup = 2, kFullTimed = 7;
// The shadow-boundary band: pixels within 2 pixels of a reference edge (where aliasing and
// filtering errors live; everything else is either all right or a gross failure).
// (kBandRadiusPixels and kLeakThreshold: registry/shadow_error.h, the one error definition.)
// --quick: a variant whose first timed frame takes longer than this is timed over that frame
// alone, not 3 (CSM on llvmpipe takes 0.3-2 s per frame; its median of 3 would take the whole
// budget).
constexpr double kSlowFrameMs = 250.0;
constexpr int kPlannerShadowMapTexels = 2048;  // the planner scene's map (what a skip saves)

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

// What the sweep asks of a technique, from its declaration (core/technique/technique.h), never its
// name.
bool isReference(const Technique& t) {  // ray traced: the truth
  return t.plan.shadowWork == PlanTraits::ShadowWork::kRays;
}
bool usesShadowMap(const Technique& t) { return t.reads.shadowMap; }
bool usesFilterFootprint(const Technique& t) {  // Brabec–Seidel §3-4 and their GLSL twins
  return t.reads.filter;
}
// Techniques whose result approximates an area light (the soft reference is their truth).
bool approximatesSoftShadows(const Technique& t) { return t.light == Technique::Light::kArea; }

// The values swept for each --param key a technique may declare (only declared keys are
// swept; a value a technique rejects becomes a row with its InputError as the status).
struct ParamAxis {
  std::string key;
  std::vector<std::string> quick, full;
};
const std::vector<ParamAxis>& paramAxes() {
  static const std::vector<ParamAxis> kAxes = {
      {"order", {"4"}, {"4", "8", "32", "64"}},       // CSM truncation order M
      {"blur", {"0"}, {"0", "5", "7"}},               // CSM/VSM Gaussian taps
      {"storage", {"float"}, {"8", "16", "float"}},   // CSM/VSM basis precision
      {"samples", {"1"}, {"1", "4"}},                 // GPU Gems PCF samples
      {"compare", {"nearest"}, {"nearest"}},          // hardware 2x2 compare off
      {"width", {"0.01"}, {"0.01", "0.04", "0.08"}},  // smoothie width t
      {"smoothie-width", {}, {"0.01", "0.04", "0.08"}},
      {"t", {}, {"0.01", "0.04", "0.08"}},
      {"bleed-reduction", {}, {"0", "0.4"}},       // VSM light-bleeding reduction
      {"alpha", {}, {"0", "4"}},                   // CSM attenuation
      {"filtering", {}, {"bilinear", "nearest"}},  // CSM/VSM mip-mapping
      {"plan", {"off"}, {"off"}},                  // the pass planner's omissions
  };
  return kAxes;
}

// Footprints a technique does not accept (fast PCF packs 2x2 neighbours, and 4x4 in four
// phases, only: CommonOptions::filterSides) are not swept.
bool acceptsFootprint(const Technique& t, int footprint) {
  const std::vector<int>& sides = t.reads.filterSides;
  return sides.empty() || std::find(sides.begin(), sides.end(), footprint) != sides.end();
}
// A swept --param value the technique's declaration refuses (modern.vsm's storage has no "8"):
// such a variant is not swept.
bool isRejectedValue(const Technique& t, const std::string& key, const std::string& value) {
  const ParamSpec* spec = findParam(t, key);
  if (!spec) return true;
  if (spec->kind == ParamSpec::Kind::kChoice)
    return std::find(spec->choices.begin(), spec->choices.end(), value) == spec->choices.end();
  return false;
}
// `p` without the --param entries that equal the technique's declared defaults (what the
// render sees): a variant that only restates a default repeats the default variant.
RenderParams withoutDefaults(const Technique& t, RenderParams p) {
  for (auto it = p.extra.begin(); it != p.extra.end();) {
    const ParamSpec* spec = findParam(t, it->first);
    if (spec && spec->isDefault(it->second))
      it = p.extra.erase(it);
    else
      ++it;
  }
  return p;
}

std::string describe(const RenderParams& p) {
  std::ostringstream s;
  s << "size=" << p.width << "x" << p.height << " shadow-map=" << p.shadowMapTexels
    << " filter=" << p.filter << " precision=" << precisionName(p.precision);
  for (const auto& [k, v] : p.extra) s << " " << k << "=" << v;
  return s.str();
}

std::string key(const std::string& scene, const std::string& technique,
                const std::string& variant) {
  return scene + "|" + technique + "|" + variant;
}

// Pass 1: the truths of both metrics (registry/shadow_error.h: the references in both forms,
// their scored pixels and edge bands), and the area references with the light moved.
struct References {
  ShadowTruth hard, soft;            // pixel=area: the area metric's truths (primary)
  ShadowTruth hardPoint, softPoint;  // pixel=centre: the point metric's truths
  bool withSoft = true;
  // Temporal stability: each reference's mean |change| under lightShiftWorld (< 0: not made).
  double hardTemporal = -1, softTemporal = -1, hardPointTemporal = -1;
  // The scored pixels (the same for every truth of a frame: the pixel centres' categories).
  const Image& scored() const { return hardPoint.scored; }
  // The back end's GL strings (a small probe context), for rows that made no context.
  std::string glVendor, glRenderer, glVersion;
};

// GL_VENDOR, GL_RENDERER and GL_VERSION of a context.
void readGlStrings(GlContext& context, std::string& vendor, std::string& renderer,
                   std::string& version) {
  const GLubyte* v = context.dispatch().GetString(GL_VENDOR);
  vendor = v ? reinterpret_cast<const char*>(v) : "";
  renderer = context.caps().renderer;
  version = context.caps().version;
}

// The back end's strings from a context of its own (the size of a few texels: nothing is drawn).
void probeGlStrings(Backend backend, References& r) {
  constexpr int kProbeSide = 16;
  try {
    ContextSpec spec;
    spec.backend = backend;
    spec.width = spec.height = kProbeSide;
    spec.accumulation = false;
    auto context = GlContext::create(spec);
    readGlStrings(*context, r.glVendor, r.glRenderer, r.glVersion);
  } catch (const std::exception& e) {
    r.glVendor = r.glRenderer = r.glVersion = std::string("unknown: ") + e.what();
  }
}

// The quartile q (0.25, 0.75) of `sorted` by linear interpolation between order statistics.
double quartile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0.0;
  const double at = q * double(sorted.size() - 1);
  const size_t lo = size_t(std::floor(at)), hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (at - double(lo)) * (sorted[hi] - sorted[lo]);
}
void setSpread(BenchRow& row, std::vector<double> samples) {
  std::sort(samples.begin(), samples.end());
  row.framesTimed = int(samples.size());
  row.q1Ms = quartile(samples, 0.25);
  row.q3Ms = quartile(samples, 0.75);
  row.minFrameMs = samples.empty() ? 0.0 : samples.front();
}
RenderParams areaParams(const RenderParams& p) {
  RenderParams a = p;
  a.extra[reference::kPixelParam] = reference::kPixelArea;
  return a;
}
References renderReferences(const Scene& scene, const RenderParams& base, bool withSoft,
                            bool temporal) {
  References r;
  r.withSoft = withSoft;
  probeGlStrings(base.backend, r);
  r.hardPoint = renderShadowTruth(scene, base, ErrorMetric::kPoint, false);
  r.hard = renderShadowTruth(scene, base, ErrorMetric::kArea, false);
  if (withSoft) {
    r.softPoint = renderShadowTruth(scene, base, ErrorMetric::kPoint, true);
    r.soft = renderShadowTruth(scene, base, ErrorMetric::kArea, true);
  }
  if (temporal) {
    const Scene moved = shiftLight(scene, lightShiftWorld(scene));
    RenderParams p = base;
    p.extra.clear();
    p.capturePasses = false;
    const Technique& hard = findTechnique("reference.hard");
    const Technique& soft = findTechnique("reference.soft");
    r.hardPointTemporal = meanAbsChange(r.hardPoint.visibility,
                                        renderTechnique(hard, moved, p).visibility, r.scored());
    r.hardTemporal = meanAbsChange(
        r.hard.visibility, renderTechnique(hard, moved, areaParams(p)).visibility, r.scored());
    if (withSoft)
      r.softTemporal = meanAbsChange(
          r.soft.visibility, renderTechnique(soft, moved, areaParams(p)).visibility, r.scored());
  }
  return r;
}

void measureAgainstReferences(BenchRow& row, const Image& mask, const References& refs) {
  row.hard = scoreShadow(mask, refs.hard);
  row.hardPoint = scoreShadow(mask, refs.hardPoint);
  row.softMeasured = refs.withSoft;
  if (refs.withSoft) {
    row.soft = scoreShadow(mask, refs.soft);
    row.softPoint = scoreShadow(mask, refs.softPoint);
  }
  row.referenceTemporalChange = row.primaryIsSoft() ? refs.softTemporal : refs.hardTemporal;
}

// Pass 2: one variant, timed on one context.
BenchRow measureVariant(const Technique& t, const Scene& scene, const BenchVariant& v,
                        const References& refs, int warmup, int timed, bool quick, bool temporal,
                        Image& maskOut) {
  BenchRow row;
  row.scene = scene.name;
  row.technique = t.name;
  row.variant = v.label;
  row.params = v.params;
  row.backend = backendName(v.params.backend);
  row.glVendor = refs.glVendor;
  row.glRenderer = refs.glRenderer;
  row.glVersion = refs.glVersion;
  row.loadBefore = readLoadAverage();
  row.primaryReference =
      approximatesSoftShadows(t) && refs.withSoft ? kPrimarySoftReference : kPrimaryHardReference;
  const auto pixel = v.params.extra.find(reference::kPixelParam);
  const bool areaForm = pixel != v.params.extra.end() && pixel->second == reference::kPixelArea;
  if (refs.hard.visibility.width > 0 && isReference(t) &&
      v.params.extra.size() == (areaForm ? 1u : 0u) &&
      (t.light == Technique::Light::kPoint || refs.withSoft)) {
    // The references were rendered once for this scene (pass 1): their row is that frame.
    const bool soft = t.light == Technique::Light::kArea;
    const Frame& f = soft ? (areaForm ? refs.soft : refs.softPoint).frame
                          : (areaForm ? refs.hard : refs.hardPoint).frame;
    row.frameMs = row.wallMs = f.totalMilliseconds();
    setSpread(row, {row.frameMs});
    row.loadAfter = readLoadAverage();
    row.date = utcIsoNow();
    row.passes = f.passes;
    row.counters = f.counters;
    measureAgainstReferences(row, f.visibility, refs);
    // The reference's own change under the light motion (reference.soft pixel=centre is not
    // re-rendered: it costs seconds and is not a primary reference).
    row.temporalChange = soft ? (areaForm ? refs.softTemporal : -1.0)
                              : (areaForm ? refs.hardTemporal : refs.hardPointTemporal);
    maskOut = f.visibility;
    return row;
  }
  try {
    checkParams(t, v.params, 0);
    auto context = GlContext::create(contextFor(t, v.params));
    checkParams(t, v.params, context->caps().maxTextureSize);
    readGlStrings(*context, row.glVendor, row.glRenderer, row.glVersion);
    if (t.needs.profile == Profile::kCompatibility) imaging::install(*context);
    // The steady-state median (core/technique/frame_timing.h) on this context, which the temporal
    // frame below reuses; quick mode's budget times a slow variant over one frame.
    Frame last;
    const FrameCounts counts{warmup, timed,
                             quick ? kSlowFrameMs : std::numeric_limits<double>::infinity(), 1};
    const SteadyTiming timing =
        timeSteadyState([&] { return t.render(*context, scene, v.params); }, counts, &last);
    row.loadAfter = readLoadAverage();
    row.frameMs = timing.frameMs;
    row.wallMs = timing.wallMs;
    setSpread(row, timing.frameSamples);
    row.passes = timing.passes;
    row.counters = last.counters;
    if (!allFinite(last.visibility)) throw GlError("visibility mask has NaN or Inf");
    measureAgainstReferences(row, last.visibility, refs);
    if (temporal) {
      // One more frame with the light moved by a fifth of a texel (kLightShiftTexels).
      const Frame moved = t.render(*context, shiftLight(scene, lightShiftWorld(scene)), v.params);
      if (!allFinite(moved.visibility)) throw GlError("visibility mask has NaN or Inf");
      row.temporalChange = meanAbsChange(last.visibility, moved.visibility, refs.scored());
    }
    maskOut = std::move(last.visibility);
  } catch (const InputError& e) {
    row.status = std::string("invalid: ") + e.what();
  } catch (const GlError& e) {
    row.status = std::string("GL error: ") + e.what();
  }
  if (row.loadAfter < 0) row.loadAfter = readLoadAverage();
  row.date = utcIsoNow();
  return row;
}

nlohmann::json errorJson(const ErrorSet& e) { return toJson(e); }

nlohmann::json rowJson(const BenchRow& r, bool withSoft) {
  using Json = nlohmann::json;
  const Json params = effectiveParamsJson(r);
  Json j = {{"scene", r.scene},
            {"technique", r.technique},
            {"variant", r.variant},
            {"status", r.status},
            {"reference", r.primaryReference},
            {"width", r.params.width},
            {"height", r.params.height},
            {"orbit", r.orbit.empty() ? Json(nullptr) : Json(r.orbit)}};
  // The common options: the value used, or null where the technique does not read it.
  for (const char* option : {"shadow_map", "filter", "precision"})
    j[option] = params.contains(option) ? params.at(option) : Json(nullptr);
  j["params"] = params;
  // null: a reference (the truth, not ranked) or a row that did not run.
  j["pareto_rank"] = r.paretoRank > 0 ? Json(r.paretoRank) : Json(nullptr);
  // What made the row (core/base/provenance.h), as render's and compare's JSON lines say it, and
  // where and when it ran.
  j["commit"] = buildCommit();
  j["command"] = commandLine();
  j["backend"] = r.backend;
  j["gl_vendor"] = r.glVendor;
  j["gl_renderer"] = r.glRenderer;
  j["gl_version"] = r.glVersion;
  j["date"] = r.date;
  j["load_before"] = r.loadBefore >= 0 ? Json(r.loadBefore) : Json(nullptr);
  j["load_after"] = r.loadAfter >= 0 ? Json(r.loadAfter) : Json(nullptr);
  if (r.status != "ok") return j;
  j["frame_ms"] = r.frameMs;
  j["frames_timed"] = r.framesTimed;
  j["frame_iqr_ms"] = r.iqrMs();
  j["frame_min_ms"] = r.minFrameMs;
  j["spread_large"] = r.spreadLarge();
  j["wall_ms"] = r.wallMs;
  j["error"] = errorJson(r.primary());
  j["vs_reference_hard_area"] = errorJson(r.hard);
  j["vs_reference_hard_centre"] = errorJson(r.hardPoint);
  if (withSoft) {
    j["vs_reference_soft_area"] = errorJson(r.soft);
    j["vs_reference_soft_centre"] = errorJson(r.softPoint);
  }
  if (r.temporalChange >= 0) j["temporal_change"] = r.temporalChange;
  if (r.referenceTemporalChange >= 0) j["reference_temporal_change"] = r.referenceTemporalChange;
  for (const PassTime& p : r.passes) j["passes"][p.name] = p.milliseconds;
  for (const auto& [k, v] : r.counters) j["counters"][k] = v;
  return j;
}

}  // namespace

std::vector<std::string> benchScenes(bool quick) {
  if (quick) return {"brabec", "fence"};
  return builtinSceneNames();
}

std::vector<BenchVariant> sweepVariants(const Technique& t, const RenderParams& base, bool quick) {
  std::vector<BenchVariant> out = {{"default", base}};
  // Identical variants: the same parameters once the technique's defaults are left out.
  std::set<std::string> seen = {describe(withoutDefaults(t, base))};
  auto add = [&](const std::string& label, const RenderParams& p) {
    for (const auto& [k, v] : p.extra)
      if (isRejectedValue(t, k, v)) return;
    if (!acceptsFootprint(t, p.filter)) return;
    if (seen.insert(describe(withoutDefaults(t, p))).second) out.push_back({label, p});
  };
  if (isReference(t)) return out;  // the references are the truth; their cost is measured once
  if (usesShadowMap(t)) {
    const std::vector<int> sides =
        quick ? std::vector<int>{256, 1024} : std::vector<int>{128, 256, 512, 1024, 2048};
    for (int n : sides) {
      RenderParams p = base;
      p.shadowMapTexels = n;
      add("shadow-map=" + std::to_string(n), p);
    }
  }
  if (usesFilterFootprint(t)) {
    for (int k : quick ? std::vector<int>{1, 4} : std::vector<int>{1, 2, 3, 4}) {
      RenderParams p = base;
      p.filter = k;
      add("filter=" + std::to_string(k), p);
    }
  }
  if (t.needs.colorFromPrecision) {
    for (Precision q :
         quick ? std::vector<Precision>{Precision::kFloat}
               : std::vector<Precision>{Precision::k8, Precision::k12, Precision::kFloat}) {
      RenderParams p = base;
      p.precision = q;
      add(std::string("precision=") + precisionName(q), p);
    }
  }
  for (const ParamAxis& axis : paramAxes()) {
    if (!findParam(t, axis.key)) continue;
    for (const std::string& value : quick ? axis.quick : axis.full) {
      RenderParams p = base;
      p.extra[axis.key] = value;
      add(axis.key + "=" + value, p);
    }
  }
  // Annen et al. Table 1: shadow map side x order M x blur (full mode only).
  if (!quick && findParam(t, "order") && findParam(t, "blur")) {
    for (int n : {256, 512, 1024, 2048})
      for (const char* m : {"4", "8", "16"})
        for (const char* blur : {"0", "3", "7"}) {
          RenderParams p = base;
          p.shadowMapTexels = n;
          p.extra["order"] = m;
          p.extra["blur"] = blur;
          add("table1 shadow-map=" + std::to_string(n) + " order=" + m + " blur=" + blur, p);
        }
  }
  return out;
}

ErrorSet measureErrors(const Image& mask, const Image& reference, const Image& region,
                       const Image& band) {
  ShadowTruth truth;
  truth.visibility = reference;
  truth.scored = region;
  truth.band = band;
  truth.counts.total = (long long)region.width * region.height;
  for (float v : region.data) truth.counts.scored += v > 0.5f ? 1 : 0;
  truth.counts.noReceiver = truth.counts.total - truth.counts.scored;
  return scoreShadow(mask, truth);
}

double lightShiftWorld(const Scene& scene) {
  const SpotLight& l = scene.light;
  const double distance = glm::length(l.target - l.position);
  const double texel = 2.0 * distance * std::tan(glm::radians(0.5 * double(l.coneDegrees))) /
                       double(kLightShiftMapTexels);
  return kLightShiftTexels * texel;
}

Scene shiftLight(const Scene& scene, double world) {
  Scene moved = scene;
  // The light's x axis in world space: the first row of the view matrix's rotation.
  const glm::mat4 view = lightView(scene.light);
  const glm::vec3 right(view[0][0], view[1][0], view[2][0]);
  const glm::vec3 step = float(world) * glm::normalize(right);
  moved.light.position += step;
  moved.light.target += step;
  return moved;
}

Scene farScene(const Scene& scene) {
  Scene far = scene;
  far.name = scene.name + kFarSceneSuffix;
  far.camera.position =
      scene.camera.target + kFarCameraFactor * (scene.camera.position - scene.camera.target);
  far.camera.farPlane = std::max(far.camera.farPlane, kFarCameraFactor * scene.camera.farPlane);
  return far;
}

// Chan 2004 §4.2: a smoothie edge extends a silhouette edge by t in the light's screen space
// (map side = 1, i.e. 2 tan(cone / 2) in tangent units); Eq. 4.1 remaps its alpha by
// 1 / (1 - b / r), so on a receiver at depth r behind a blocker edge at depth b the ramp from
// 0 to 1 spans t (1 - b / r) outside the hard edge. The spherical light of radius R lights a
// receiver point fully once the blocker edge, seen from it, clears the light's disk: the true
// penumbra ends R (r - b) / b beyond the hard edge in world units at depth r, i.e.
// (R / b) (1 - b / r) in tangent units. Equal for every r when t 2 tan(cone / 2) = R / b:
//   t = R / (2 b tan(cone / 2)),
// the light's radius seen from the blocker, in shadow-map sides. b: the casters' depth along
// the light axis (the centre of each caster's bounding box), averaged over the casters.
double smoothieWidthFromLight(const Scene& scene) {
  const SpotLight& l = scene.light;
  const glm::vec3 axis = glm::normalize(l.target - l.position);
  double depthSum = 0.0;
  int casters = 0;
  for (const Object& o : scene.objects) {
    if (!o.castsShadow || !o.mesh) continue;
    const Bounds b = worldBounds(o);
    if (b.empty()) continue;
    const double depth = glm::dot(0.5f * (b.lo + b.hi) - l.position, axis);
    if (!(depth > 0.0)) continue;  // behind the light: casts nothing into the frustum
    depthSum += depth;
    ++casters;
  }
  if (casters == 0) return 0.0;
  const double b = depthSum / casters;
  return double(l.radius) / (2.0 * b * std::tan(glm::radians(0.5 * double(l.coneDegrees))));
}

namespace {

// One scene of the run and what is measured on it.
struct SceneRun {
  Scene scene;
  std::vector<std::string> techniques;  // empty: every technique (and its sweep)
  bool soft = true;                     // render reference.soft (smoothies' truth)
  bool temporal = true;                 // temporal stability (a frame with the light moved)
  bool planner = false;                 // the planner scene: plan=on/off only
  int shadowMapTexels = 0;              // 0: the bench's map; else every variant's map
  int width = 0, height = 0;            // 0: the bench's window; else this scene's window
};

std::vector<SceneRun> benchSceneRuns(const BenchOptions& options) {
  std::vector<SceneRun> runs;
  const std::vector<std::string> scenes =
      options.scenes.empty() ? benchScenes(options.quick) : options.scenes;
  // The light-bleeding claim scene: VSM against CSM only (kBleedingScene).
  const auto bleedingRun = [] {
    Scene s = loadScene(kBleedingScene);
    s.name = kBleedingScene;  // the claim looks for this name
    return SceneRun{s, {"modern.vsm", "modern.csm"}, false, false, false};
  };
  for (const std::string& name : scenes)
    runs.push_back(name == kBleedingScene ? bleedingRun()
                                          : SceneRun{loadScene(name), {}, true, true, false});
  if (options.scenes.empty() || contains(options.scenes, kDefaultScene)) {
    // What the planner's omissions save (issue 8 item 4): a purpose-built scene where no
    // caster reaches the light frustum, measured with the planner on and off for every
    // technique that consults it (declares --param plan).
    Scene away = loadScene(kDefaultScene);
    away.name = std::string(kDefaultScene) + "-light-away";
    away.light.target = away.light.position + glm::vec3(0, 5, 0);  // the light looks up
    away.light.up = {0, 0, -1};
    runs.push_back({away, {}, false, false, true});
    // Annen et al. Fig. 10: the trees (thin branches) moved far away, so that many
    // shadow-map texels fall in one pixel; CSM against the PCF techniques (and the
    // unfiltered map), all with the kMinificationMapTexels map.
    runs.push_back({farScene(loadScene(kMinificationScene)),
                    {"modern.hw", "modern.pcf", "modern.gems16", "modern.csm"},
                    false,
                    true,
                    false,
                    kMinificationMapTexels});
  }
  if (options.scenes.empty() && contains(sceneFileNames(), kBleedingScene))
    runs.push_back(bleedingRun());
  if (options.scenes.empty()) {
    // Chan §3.3: the hybrid pays off where shadow volumes are fill bound. The scene file is
    // another part of issue 14; without it the claim says so.
    const std::vector<std::string> files = sceneFileNames();
    if (contains(files, kFillBoundScene)) {
      Scene fill = loadScene(kFillBoundScene);
      fill.name = kFillBoundScene;  // the claim looks for this name, whatever the file calls it
      // Chan §3.1 step 1 and Fig. 3-11's setting: a low-resolution shadow map and a window
      // large enough for the volumes' fill to dominate (the quick bench's 256x192 is not).
      runs.push_back({fill,
                      {"modern.volumes", "modern.hybrid"},
                      false,
                      false,
                      false,
                      kFillBoundMapTexels,
                      kFillBoundWidth,
                      kFillBoundHeight});
    }
  }
  return runs;
}

}  // namespace

BenchResult runBenchmark(const BenchOptions& options, std::ostream& json) {
  BenchResult result;
  RenderParams base;
  base.width = options.width > 0 ? options.width : (options.quick ? kQuickWidth : kFullWidth);
  base.height = options.height > 0 ? options.height : (options.quick ? kQuickHeight : kFullHeight);
  base.backend = options.backend;
  const int warmup = options.warmupFrames > 0 ? options.warmupFrames
                                              : (options.quick ? kQuickWarmup : kFullWarmup);
  const int timed =
      options.timedFrames > 0 ? options.timedFrames : (options.quick ? kQuickTimed : kFullTimed);
  std::vector<const Technique*> techniques;
  for (const Technique& t : allTechniques())
    if (options.techniques.empty() || contains(options.techniques, t.name))
      techniques.push_back(&t);
  for (const std::string& name : options.techniques) findTechnique(name);  // throws if unknown
  const std::vector<SceneRun> runs = benchSceneRuns(options);
  if (options.scenes.empty() && !contains(sceneFileNames(), kFillBoundScene))
    result.sceneNotes[kFillBoundScene] =
        "scene not present (assets/scenes/" + std::string(kFillBoundScene) + ".json)";
  for (const SceneRun& run : runs)
    if (run.scene.name == std::string(kDefaultScene) + "-light-away")
      result.sceneNotes[run.scene.name] =
          "the light looks straight up: no caster reaches its frustum and no pixel is lit, so "
          "every mask equals the reference (RMSE 0) and an error-against-time plot has nothing "
          "to show; the scene measures what the planner's omissions save: compare the "
          "plan=on/off variants' frame times in bench/bench.csv";
  const RenderParams benchBase = base;
  for (const SceneRun& run : runs) {
    const Scene& scene = run.scene;
    RenderParams base = benchBase;  // this scene's window (a claim scene may set its own)
    if (run.width > 0) {
      base.width = run.width;
      base.height = run.height;
    }
    std::vector<const Technique*> here;
    for (const Technique* t : techniques)
      if ((run.techniques.empty() || contains(run.techniques, t->name)) &&
          (!run.planner || findParam(*t, "plan")))
        here.push_back(t);
    if (here.empty()) continue;
    if (options.progress) std::cerr << "bench: " << scene.name << ": references\n";
    const References refs = renderReferences(scene, base, run.soft, run.temporal);
    result.texelsPerPixel[scene.name] = 0.0;
    for (const Technique* t : here) {
      std::vector<BenchVariant> variants;
      if (run.planner) {
        // A 2048 map: the full pass clears and fills it, the planned frame does neither.
        RenderParams on = base;
        on.shadowMapTexels = kPlannerShadowMapTexels;
        RenderParams off = on;
        off.extra["plan"] = "off";
        variants = {{"plan=on", on}, {"plan=off", off}};
      } else if (!run.techniques.empty()) {
        // A claim scene: the default variants (modern.csm on the minification scene: Fig. 10's
        // 5x5 kernel).
        RenderParams p = base;
        if (run.shadowMapTexels > 0) p.shadowMapTexels = run.shadowMapTexels;
        if (run.shadowMapTexels > 0 && t->name == "modern.csm") {
          p.extra["blur"] = kCsmFig10Blur;
          variants = {{kCsmFig10Variant, p}};
        } else {
          variants = {{"default", p}};
        }
      } else {
        variants = sweepVariants(*t, base, options.quick);
        if (isReference(*t)) {
          if (t->name == "reference.soft" && !run.soft) continue;
          variants.push_back({std::string(reference::kPixelParam) + "=" + reference::kPixelArea,
                              areaParams(base)});
        }
        if (t->name == "modern.smoothies" && findParam(*t, "width")) {
          // Chan §4.2's width t derived from the light's radius (smoothieWidthFromLight).
          std::ostringstream width;
          width << std::setprecision(4) << smoothieWidthFromLight(scene);
          RenderParams p = base;
          p.extra["width"] = width.str();
          variants.push_back({kSmoothieWidthFromLightVariant, p});
        }
      }
      for (const BenchVariant& v : variants) {
        Image mask;
        // The references are measured once, without warm-up: they are the truth, not a
        // contender, and reference.soft costs seconds per frame.
        const bool truth = isReference(*t);
        const bool fillBound = scene.name == kFillBoundScene && options.timedFrames == 0;
        const int sceneWarmup = fillBound ? std::max(warmup, kFillBoundWarmup) : warmup;
        const int sceneTimed = fillBound ? std::max(timed, kFillBoundTimed) : timed;
        BenchRow row = measureVariant(*t, scene, v, refs, truth ? 0 : sceneWarmup,
                                      truth ? 1 : sceneTimed, options.quick, run.temporal, mask);
        if (row.status == "ok") {
          result.masks[key(scene.name, t->name, v.label)] = std::move(mask);
          const double texelsPerPixel = planFrame(scene, *t, v.params).maxShadowTexelsPerPixel;
          row.counters["plan_max_shadow_texels_per_pixel"] = texelsPerPixel;
          result.texelsPerPixel[scene.name] =
              std::max(result.texelsPerPixel[scene.name], texelsPerPixel);
        }
        if (options.progress)
          std::cerr << "bench: " << scene.name << " " << t->name << " " << v.label << ": "
                    << (row.status == "ok" ? std::to_string(row.frameMs) + " ms, rmse " +
                                                 std::to_string(row.primary().all.rmse)
                                           : row.status)
                    << "\n";
        result.rows.push_back(std::move(row));
      }
    }
  }
  // The outputs are sorted and ranked once every row is measured.
  sortRowsBySceneThenTime(result.rows);
  assignParetoRanks(result.rows);
  for (const BenchRow& row : result.rows) json << benchRowJsonLine(row) << "\n";
  json << std::flush;
  return result;
}

std::string benchRowJsonLine(const BenchRow& row) {
  // Invalid UTF-8 (a scene file named in other bytes) becomes U+FFFD, never a throw.
  return rowJson(row, row.softMeasured)
      .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::vector<size_t> paretoFront(const std::vector<BenchRow>& rows, const std::string& scene) {
  std::vector<size_t> candidates;
  for (size_t i = 0; i < rows.size(); ++i)
    if (rows[i].scene == scene && rows[i].status == "ok" &&
        rows[i].technique.rfind("reference.", 0) != 0)
      candidates.push_back(i);
  std::sort(candidates.begin(), candidates.end(), [&](size_t a, size_t b) {
    return rows[a].frameMs != rows[b].frameMs
               ? rows[a].frameMs < rows[b].frameMs
               : rows[a].primary().all.rmse < rows[b].primary().all.rmse;
  });
  std::vector<size_t> front;
  double best = 1e300;
  for (size_t i : candidates)
    if (rows[i].primary().all.rmse < best) {
      best = rows[i].primary().all.rmse;
      front.push_back(i);
    }
  return front;
}

namespace {
bool isRankedRow(const BenchRow& r) {  // a competitor: ran, and not a reference (the truth)
  return r.status == "ok" && r.technique.rfind("reference.", 0) != 0;
}
// a no slower and no worse than b, and strictly better in one of the two.
bool dominates(const BenchRow& a, const BenchRow& b) {
  const double ea = a.primary().all.rmse, eb = b.primary().all.rmse;
  return a.frameMs <= b.frameMs && ea <= eb && (a.frameMs < b.frameMs || ea < eb);
}
}  // namespace

void assignParetoRanks(std::vector<BenchRow>& rows) {
  std::map<std::string, std::vector<size_t>> unranked;  // scene -> its competitors
  for (size_t i = 0; i < rows.size(); ++i) {
    rows[i].paretoRank = 0;
    if (isRankedRow(rows[i])) unranked[rows[i].scene].push_back(i);
  }
  for (auto& [scene, left] : unranked) {
    // Peel the fronts: rank k = the rows no remaining row dominates.
    for (int rank = 1; !left.empty(); ++rank) {
      std::vector<size_t> front, rest;
      for (size_t i : left) {
        const bool dominated = std::any_of(left.begin(), left.end(),
                                           [&](size_t j) { return dominates(rows[j], rows[i]); });
        (dominated ? rest : front).push_back(i);
      }
      for (size_t i : front) rows[i].paretoRank = rank;
      left = std::move(rest);
    }
  }
}

void sortRowsBySceneThenTime(std::vector<BenchRow>& rows) {
  std::stable_sort(rows.begin(), rows.end(), [](const BenchRow& a, const BenchRow& b) {
    const bool aRan = a.status == "ok", bRan = b.status == "ok";
    return std::tie(a.scene, bRan, a.frameMs, a.technique, a.variant) <
           std::tie(b.scene, aRan, b.frameMs, b.technique, b.variant);
  });
}

double parseBudgetMs(const std::string& text) {
  const std::optional<double> v = parseDecimal(text);  // strict: no hex, inf, nan or spaces
  if (!v || !(*v > 0.0))
    throw InputError("--budget-ms must be a positive number of milliseconds, got '" + text + "'");
  return *v;
}

std::vector<BudgetRanking> rankWithinBudget(const std::vector<BenchRow>& rows, double budgetMs) {
  std::vector<BudgetRanking> out;
  auto sceneRanking = [&](const std::string& scene) -> BudgetRanking& {
    for (BudgetRanking& r : out)
      if (r.scene == scene) return r;
    out.push_back({scene, {}, 0, 0});
    return out.back();
  };
  for (size_t i = 0; i < rows.size(); ++i) {
    const BenchRow& r = rows[i];
    if (r.technique.rfind("reference.", 0) == 0) continue;  // the truth, not a competitor
    BudgetRanking& s = sceneRanking(r.scene);
    if (r.status != "ok")
      ++s.notRun;
    else if (r.frameMs <= budgetMs)
      s.within.push_back(i);
    else
      ++s.overBudget;
  }
  for (BudgetRanking& s : out)
    std::stable_sort(s.within.begin(), s.within.end(), [&](size_t a, size_t b) {
      const double ea = rows[a].primary().all.rmse, eb = rows[b].primary().all.rmse;
      return ea != eb ? ea < eb : rows[a].frameMs < rows[b].frameMs;
    });
  return out;
}

void printBudgetRanking(std::ostream& out, const std::vector<BenchRow>& rows, double budgetMs) {
  auto fixed = [](double v, int digits) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(digits) << v;
    return s.str();
  };
  auto variants = [](size_t n) { return std::to_string(n) + (n == 1 ? " variant" : " variants"); };
  for (const BudgetRanking& s : rankWithinBudget(rows, budgetMs)) {
    out << "budget " << fixed(budgetMs, 1) << " ms, scene " << s.scene << ": "
        << variants(s.within.size())
        << " within budget, ranked by RMSE against the pixel-integrated reference\n";
    if (!s.within.empty())
      out << "  " << std::left << std::setw(4) << "#" << std::setw(20) << "technique"
          << std::setw(44) << "variant" << std::right << std::setw(9) << "ms" << std::setw(9)
          << "RMSE" << std::setw(9) << "band" << std::setw(20) << "temporal (ref)" << std::setw(8)
          << "pareto"
          << "\n";
    int place = 0;
    for (size_t i : s.within) {
      const BenchRow& r = rows[i];
      const std::string temporal =
          (r.temporalChange >= 0 ? fixed(r.temporalChange, 5) : std::string("-")) + " (" +
          (r.referenceTemporalChange >= 0 ? fixed(r.referenceTemporalChange, 5)
                                          : std::string("-")) +
          ")";
      out << "  " << std::left << std::setw(4) << std::to_string(++place) + "." << std::setw(20)
          << r.technique << std::setw(44) << r.variant << std::right << std::setw(9)
          << fixed(r.frameMs, 2) << std::setw(9) << fixed(r.primary().all.rmse, 4) << std::setw(9)
          << fixed(r.primary().band.rmse, 4) << std::setw(20) << temporal << std::setw(8)
          << r.paretoRank << "\n";
    }
    out << "  " << variants(size_t(s.overBudget)) << " over budget";
    if (s.notRun > 0)
      out << ", " << variants(size_t(s.notRun)) << " did not run (see their status)";
    out << "\n";
  }
}

void writeCsvRows(std::ostream& out, const std::vector<BenchRow>& rows) {
  // The JSON line's fields as columns: the common options empty where the technique does not
  // read them, "params" the same JSON object as the line's (CSV-quoted, quotes doubled).
  out << "scene,technique,variant,status,reference,width,height,orbit,shadow_map,filter,"
         "precision,params,frame_ms,frames_timed,frame_iqr_ms,frame_min_ms,spread_large,wall_ms,"
         "pareto_rank";
  // hard_*, soft_*: against the pixel-integrated references (pixel=area, the primary truth);
  // hard_point_*, soft_point_*: against the pixel-centre references.
  for (const char* ref : {"hard", "soft", "hard_point", "soft_point"})
    for (const char* m : {"rmse", "max_abs", "share_above_half", "band_rmse", "band_max_abs",
                          "band_share_above_half", "leak_share"})
      out << "," << ref << "_" << m;
  // The one error definition's scored pixels (docs/error.md): how many, and the share left out.
  out << ",metric,scored_pixels,left_out_share,temporal_change,reference_temporal_change,passes,"
         "load_before,load_after,backend,gl_vendor,gl_renderer,gl_version,date,commit,command\n";
  auto csvField = [](const std::string& s) {  // RFC 4180: in quotes, inner quotes doubled
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
  };
  auto quoted = [](std::string s) {
    for (char& c : s)
      if (c == '"') c = '\'';
    return "\"" + s + "\"";
  };
  for (const BenchRow& r : rows) {
    const nlohmann::json params = effectiveParamsJson(r);
    auto common = [&](const char* key) -> std::string {  // empty: not read by the technique
      if (!params.contains(key)) return "";
      return params.at(key).is_string() ? params.at(key).get<std::string>() : params.at(key).dump();
    };
    const bool ran = r.status == "ok";
    auto timing = [&](double v) { return ran ? formatNumber(v) : std::string(); };
    out << r.scene << "," << r.technique << "," << quoted(r.variant) << "," << quoted(r.status)
        << "," << r.primaryReference << "," << r.params.width << "," << r.params.height << ","
        << quoted(r.orbit) << "," << common("shadow_map") << "," << common("filter") << ","
        << common("precision") << ","
        << csvField(params.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace)) << ","
        << r.frameMs << "," << (ran ? std::to_string(r.framesTimed) : "") << ","
        << timing(r.iqrMs()) << "," << timing(r.minFrameMs) << ","
        << (ran ? (r.spreadLarge() ? "1" : "0") : "") << "," << r.wallMs << ",";
    if (r.paretoRank > 0) out << r.paretoRank;  // empty: a reference, or a row that did not run
    for (const ErrorSet* e : {&r.hard, &r.soft, &r.hardPoint, &r.softPoint})
      out << "," << e->all.rmse << "," << e->all.maxAbs << "," << e->all.shareAboveHalf << ","
          << e->band.rmse << "," << e->band.maxAbs << "," << e->band.shareAboveHalf << ","
          << e->leakShare;
    out << "," << r.primary().metric << "," << r.primary().counts.scored << ","
        << r.primary().counts.leftOutShare();
    // Empty where not measured.
    for (double v : {r.temporalChange, r.referenceTemporalChange}) {
      out << ",";
      if (v >= 0) out << v;
    }
    std::string passes;
    for (const PassTime& p : r.passes)
      passes += (passes.empty() ? "" : "; ") + p.name + "=" + std::to_string(p.milliseconds);
    out << "," << quoted(passes);
    for (double load : {r.loadBefore, r.loadAfter}) {
      out << ",";
      if (load >= 0) out << load;
    }
    out << "," << quoted(r.backend) << "," << quoted(r.glVendor) << "," << quoted(r.glRenderer)
        << "," << quoted(r.glVersion) << "," << r.date << "," << quoted(buildCommit()) << ","
        << csvField(commandLine()) << "\n";
  }
}

void writeCsv(const std::string& path, const std::vector<BenchRow>& rows) {
  writeFileAtomically(path, [&](std::ostream& out) { writeCsvRows(out, rows); });
}

namespace {
bool gnuplotHasTerminal(const std::string& terminal) {
  const std::string command =
      "gnuplot -e 'set terminal " + terminal + "' > /dev/null 2>&1 < /dev/null";
  return std::system(command.c_str()) == 0;
}
}  // namespace

namespace {
// The Pareto front's numbers on an error-against-time plot, placed so that none overlaps
// another or a plotted point: each label tries below its point, then above, right, left and
// farther out, and takes the first place that is free. Positions are in data coordinates on
// the log axes [xLo, xHi] x [yLo, yHi] of a plot area of about kPlotAreaPixels (the 1000x640
// terminal less its margins and the key outside) with kLabelCharPixels characters.
struct PlotPoint {
  double x, y;
};
constexpr double kPlotAreaWidthPixels = 720, kPlotAreaHeightPixels = 540;
constexpr double kLabelCharWidthPixels = 7, kLabelCharHeightPixels = 13;
constexpr double kMarkerRadiusPixels = 7;  // point size 1.6 of the terminal
std::vector<PlotPoint> placeFrontLabels(const std::vector<PlotPoint>& front,
                                        const std::vector<std::string>& labels,
                                        const std::vector<PlotPoint>& points, double xLo,
                                        double xHi, double yLo, double yHi) {
  const double lx = std::log10(xHi / xLo), ly = std::log10(yHi / yLo);
  auto toPixels = [&](const PlotPoint& p) {
    return PlotPoint{std::log10(p.x / xLo) / lx * kPlotAreaWidthPixels,
                     std::log10(p.y / yLo) / ly * kPlotAreaHeightPixels};
  };
  auto toData = [&](const PlotPoint& p) {
    return PlotPoint{xLo * std::pow(10.0, p.x / kPlotAreaWidthPixels * lx),
                     yLo * std::pow(10.0, p.y / kPlotAreaHeightPixels * ly)};
  };
  struct Box {
    double x0, y0, x1, y1;
  };
  auto overlaps = [](const Box& a, const Box& b) {
    return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
  };
  std::vector<Box> taken;
  for (const PlotPoint& p : points) {
    const PlotPoint c = toPixels(p);
    taken.push_back({c.x - kMarkerRadiusPixels, c.y - kMarkerRadiusPixels,
                     c.x + kMarkerRadiusPixels, c.y + kMarkerRadiusPixels});
  }
  // Offsets of the label's centre from its point, in character heights.
  const std::vector<PlotPoint> candidates = {{0, -1.2},   {0, 1.2},    {1.6, 0},  {-1.6, 0},
                                             {1.4, -1.2}, {-1.4, 1.2}, {0, -2.3}, {0, 2.3}};
  std::vector<PlotPoint> placed;
  for (size_t i = 0; i < front.size(); ++i) {
    const PlotPoint c = toPixels(front[i]);
    const double halfW = 0.5 * kLabelCharWidthPixels * double(labels[i].size()) + 1;
    const double halfH = 0.5 * kLabelCharHeightPixels;
    PlotPoint chosen{c.x, c.y - 1.2 * kLabelCharHeightPixels};
    for (const PlotPoint& o : candidates) {
      const PlotPoint at{c.x + o.x * kLabelCharHeightPixels, c.y + o.y * kLabelCharHeightPixels};
      const Box box{at.x - halfW, at.y - halfH, at.x + halfW, at.y + halfH};
      if (std::none_of(taken.begin(), taken.end(),
                       [&](const Box& t) { return overlaps(box, t); })) {
        chosen = at;
        break;
      }
    }
    taken.push_back({chosen.x - halfW, chosen.y - halfH, chosen.x + halfW, chosen.y + halfH});
    placed.push_back(toData(chosen));
  }
  return placed;
}
}  // namespace

std::string plotFamily(const std::string& technique) {
  if (technique.rfind("reference.", 0) == 0) return "";
  if (technique.rfind("legacy.", 0) == 0) return "legacy";
  for (const twins::TwinPair& pair : twins::twinPairs())
    if (pair.modern == technique) return "modern twins";
  return "later papers";
}

BenchPlots writePlots(const std::string& outDir, const BenchResult& result) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0)
    throw InputError("gnuplot is not installed (apt-get install gnuplot-nox): no plots written");
  std::error_code ec;
  fs::create_directories(outDir, ec);
  if (ec) throw InputError("cannot create " + outDir + ": " + ec.message());
  const std::string terminal =
      gnuplotHasTerminal("pngcairo") ? "pngcairo size 1000,640 font ',10'" : "png size 1000,640";
  // Margins around the data on the log axes: a factor of kPlotMargin each way.
  constexpr double kPlotMargin = 1.25;
  const std::vector<std::string> families = {"legacy", "modern twins", "later papers"};
  std::set<std::string> scenes;
  for (const BenchRow& r : result.rows) scenes.insert(r.scene);
  BenchPlots out;
  for (const std::string& scene : scenes) {
    std::vector<const BenchRow*> drawn;
    std::vector<std::string> zero;
    for (const BenchRow& r : result.rows) {
      if (r.scene != scene || r.status != "ok" || plotFamily(r.technique).empty()) continue;
      if (r.primary().all.rmse > 0 && r.frameMs > 0)
        drawn.push_back(&r);
      else
        zero.push_back(r.technique + (r.variant == "default" ? "" : " " + r.variant));
    }
    if (drawn.empty()) {
      out.notes[scene] = "no plot: every technique's RMSE is 0 here (" +
                         std::to_string(zero.size()) +
                         " variants), and a log axis cannot show 0; frame times are in the table";
      continue;
    }
    if (!zero.empty()) {
      std::string list;
      for (const std::string& z : zero) list += (list.empty() ? "" : ", ") + z;
      out.notes[scene] = "RMSE 0, not on the log axis: " + list;
    }
    std::vector<size_t> front;
    for (size_t i : paretoFront(result.rows, scene))
      if (result.rows[i].primary().all.rmse > 0) front.push_back(i);
    for (size_t k = 0; k < front.size(); ++k) {
      const BenchRow& r = result.rows[front[k]];
      std::ostringstream line;
      line << k + 1 << ": " << r.technique << " " << r.variant << " (" << std::fixed
           << std::setprecision(1) << r.frameMs << " ms, RMSE " << std::setprecision(4)
           << r.primary().all.rmse << ")";
      // The front is ordered by time: say where this run cannot order two neighbours.
      if (k > 0 && timesWithinSpread(result.rows[front[k - 1]], r))
        line << " [time within the spread of " << k << ": interquartile ranges overlap]";
      out.pareto[scene].push_back(line.str());
    }
    for (const std::string& family : families) {
      std::vector<std::string> techniques;
      for (const BenchRow* r : drawn)
        if (plotFamily(r->technique) == family && !contains(techniques, r->technique))
          techniques.push_back(r->technique);
      if (techniques.empty()) continue;
      // The axes fit this plot's points and the scene's front (the front is drawn on each).
      double xLo = 1e300, xHi = 0, yLo = 1e300, yHi = 0;
      auto fit = [&](const BenchRow& r) {
        xLo = std::min(xLo, r.frameMs);
        xHi = std::max(xHi, r.frameMs);
        yLo = std::min(yLo, r.primary().all.rmse);
        yHi = std::max(yHi, r.primary().all.rmse);
      };
      for (const BenchRow* r : drawn)
        if (plotFamily(r->technique) == family) fit(*r);
      for (size_t i : front) fit(result.rows[i]);
      std::string tag = family;
      std::replace(tag.begin(), tag.end(), ' ', '-');
      const fs::path base = fs::path(outDir) / ("bench-" + scene + "-" + tag);
      // One data block per technique (gnuplot index), then the Pareto front.
      writeFileAtomically(base.string() + ".dat", [&](std::ostream& data) {
        for (const std::string& t : techniques) {
          data << "# " << t << "\n";
          for (const BenchRow* r : drawn)
            if (r->technique == t)
              data << r->frameMs << " " << r->primary().all.rmse << " \"" << r->variant << "\"\n";
          data << "\n\n";
        }
        // The front, numbered, with each number's place (placeFrontLabels) in columns 4-5.
        std::vector<PlotPoint> frontPoints, drawnPoints;
        std::vector<std::string> numbers;
        for (size_t k = 0; k < front.size(); ++k) {
          frontPoints.push_back(
              {result.rows[front[k]].frameMs, result.rows[front[k]].primary().all.rmse});
          numbers.push_back(std::to_string(k + 1));
        }
        for (const BenchRow* r : drawn)
          if (plotFamily(r->technique) == family)
            drawnPoints.push_back({r->frameMs, r->primary().all.rmse});
        for (const PlotPoint& p : frontPoints) drawnPoints.push_back(p);
        const std::vector<PlotPoint> labelAt =
            placeFrontLabels(frontPoints, numbers, drawnPoints, xLo / kPlotMargin,
                             xHi * kPlotMargin, yLo / kPlotMargin, yHi * kPlotMargin);
        data << "# pareto front of the scene (every family), numbered; label x y\n";
        for (size_t k = 0; k < front.size(); ++k)
          data << frontPoints[k].x << " " << frontPoints[k].y << " \"" << numbers[k] << "\" "
               << labelAt[k].x << " " << labelAt[k].y << "\n";
      });
      // The script names its PNG unless told another name (`out`): the run below draws into a
      // temporary and renames it, so that a failed gnuplot leaves no half-written PNG.
      const std::string dat = base.string() + ".dat";
      writeFileAtomically(base.string() + ".gp", [&](std::ostream& script) {
        script << "set terminal " << terminal << "\n"
               << "if (!exists('out')) out = '" << base.string() << ".png'\n"
               << "set output out\n"
               << "set title 'scene " << scene << ", " << family
               << ": visibility error against frame time (grey: Pareto front of the scene, "
                  "numbered)'\n"
               << "set logscale xy\nset grid\nset key outside right top\n"
               << "set xrange [" << xLo / kPlotMargin << ":" << xHi * kPlotMargin << "]\n"
               << "set yrange [" << yLo / kPlotMargin << ":" << yHi * kPlotMargin << "]\n"
               << "set xlabel 'median frame time [ms] (sum of pass times)'\n"
               << "set ylabel 'RMSE, area metric (scored pixels; docs/error.md)'\n"
               << "plot '" << dat << "' index " << techniques.size()
               << " using 1:2 with steps lw 2 lc rgb '#aaaaaa' title 'Pareto front', '' index "
               << techniques.size()
               << " using 4:5:3 with labels font ',9' tc rgb '#444444' notitle";
        for (size_t i = 0; i < techniques.size(); ++i)
          script << ", '' index " << i << " using 1:2 with points pt " << (i % 13) + 1
                 << " ps 1.6 lw 2 title '" << techniques[i] << "'";
        script << "\n";
      });
      const std::string png = base.string() + ".png";
      const std::string temporaryPng = temporaryName(png).string();
      const std::string command =
          // Its warnings go to stderr: stdout carries only JSON lines.
          "gnuplot -e \"out='" + temporaryPng + "'\" '" + base.string() + ".gp' 1>&2";
      if (std::system(command.c_str()) != 0 ||
          std::rename(temporaryPng.c_str(), png.c_str()) != 0) {
        std::remove(temporaryPng.c_str());
        std::cerr << "bench: no plot for " << scene << " " << family << " (gnuplot failed)\n";
        continue;
      }
      // The same tEXt chunks as our own PNGs (core/base/png_text.h), added after gnuplot drew it.
      const nlohmann::json parameters = {{"plot", "visibility error against frame time"},
                                         {"scene", scene},
                                         {"family", family},
                                         {"techniques", techniques},
                                         {"data", dat},
                                         {"script", base.string() + ".gp"},
                                         {"commit", buildCommit()}};
      try {
        addPngProvenance(
            png, {commandLine(),
                  parameters.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace)});
      } catch (const InputError& e) {
        std::cerr << "bench: " << png << ": no provenance chunks (" << e.what() << ")\n";
      }
      out.plots.push_back({scene, family, png});
    }
  }
  return out;
}

BenchOptions parseBenchOptions(const cli::Args& args) {
  BenchOptions options;
  options.quick = args.has("quick");
  // --scene and --technique: repeatable, each value also a comma-separated list; every name
  // given is kept (in order, once).
  auto listed = [&](const char* key) {
    std::vector<std::string> names;
    if (auto it = args.options.find(key); it != args.options.end())
      for (const std::string& value : it->second) {
        size_t start = 0;
        for (size_t comma; start <= value.size(); start = comma + 1) {
          comma = value.find(',', start);
          if (comma == std::string::npos) comma = value.size();
          const std::string name = value.substr(start, comma - start);
          if (name.empty())
            throw InputError(std::string("--") + key + " '" + value + "': an empty name");
          if (!contains(names, name)) names.push_back(name);
        }
      }
    return names;
  };
  options.scenes = listed("scene");
  options.techniques = listed("technique");
  options.csvPath = args.value("csv");
  if (auto out = args.value("out")) options.outDir = *out;
  if (auto size = args.value("size")) cli::parseSize(*size, options.width, options.height);
  if (auto b = args.value("backend")) options.backend = parseBackend(*b);
  if (auto r = args.value("repeat"))
    options.timedFrames = cli::parsePositiveInt("--repeat", *r, 1000);
  if (auto b = args.value("budget-ms")) options.budgetMs = parseBudgetMs(*b);
  // Bad names fail before any work.
  for (const std::string& s : options.scenes) loadScene(s);
  for (const std::string& t : options.techniques) findTechnique(t);
  return options;
}

namespace {
// The options --sweep and --merge take from elsewhere (the spec, the merged files).
void rejectWith(const cli::Args& args, const std::string& mode,
                const std::vector<std::string>& options) {
  for (const std::string& o : options)
    if (args.has(o))
      throw InputError(mode + " does not take --" + o +
                       (mode == "--sweep" ? " (the sweep file says what to run)"
                                          : " (the merged rows are printed as they were run)"));
}

// `bench --merge A.jsonl B.jsonl ...`: the rows on stdout with their Pareto ranks recomputed.
int runBenchMerge(const cli::Args& args) {
  rejectWith(args, "--merge",
             {"sweep", "quick", "scene", "technique", "csv", "size", "backend", "repeat", "out",
              "budget-ms"});
  const std::vector<nlohmann::json> rows = mergeBenchRows(args.options.at("merge"));
  for (const nlohmann::json& row : rows)
    std::cout << row.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  std::cerr << "bench: merged " << rows.size() << " rows from " << args.options.at("merge").size()
            << " files; Pareto ranks recomputed per scene, window and orbit\n";
  return 0;
}

// `bench --sweep FILE.json`: the rows of a sweep spec (measure/sweep.h), one JSON line each
// in the spec's order, with Pareto ranks within each view; --csv as the bench's.
int runBenchSweep(const cli::Args& args) {
  rejectWith(args, "--sweep",
             {"quick", "scene", "technique", "size", "backend", "repeat", "budget-ms", "out"});
  const std::string path = *args.value("sweep");
  std::ifstream in(path);
  if (!in) throw InputError("--sweep " + path + ": cannot open it");
  const nlohmann::json spec = nlohmann::json::parse(in, nullptr, false);
  if (spec.is_discarded()) throw InputError("--sweep " + path + ": not valid JSON");
  const SweepPlan plan = planSweep(spec);
  OutputSet outputs;
  outputs.addInput(path);
  std::optional<std::string> csv;
  if (auto file = args.value("csv")) csv = outputs.addFile("--csv", *file);
  SweepReferenceCache cache;
  std::vector<BenchRow> rows;
  std::vector<std::string> groups;
  for (size_t i = 0; i < plan.rows.size(); ++i) {
    BenchRow row = measureSweepRows(plan, {i}, cache).front();
    const SweepView& view = plan.views[plan.rows[i].view];
    groups.push_back(rankGroup(view.scene, view.width, view.height, view.orbit.value_or("")));
    std::cerr << "bench: sweep row " << i + 1 << "/" << plan.rows.size() << " " << row.scene << " "
              << row.technique << " " << row.variant << ": "
              << (row.status == "ok" ? std::to_string(row.frameMs) + " ms" : row.status) << "\n";
    rows.push_back(std::move(row));
  }
  assignSweepParetoRanks(rows, groups);
  for (const BenchRow& row : rows) std::cout << benchRowJsonLine(row) << "\n";
  std::cout << std::flush;
  if (csv) {
    writeCsv(*csv, rows);
    outputs.commit();
    std::cerr << "bench: wrote " << *args.value("csv") << "\n";
  }
  return 0;
}
}  // namespace

int runBenchCommand(const cli::Args& args) {
  if (args.options.count("merge")) return runBenchMerge(args);
  if (args.value("sweep")) return runBenchSweep(args);
  const BenchOptions options = parseBenchOptions(args);
  // Unwritable destinations fail before any work (core/base/output_files.h): the CSV is written to
  // a temporary and renamed at the end; the plots' folder must be writable.
  OutputSet outputs;
  for (const std::string& s : options.scenes) outputs.addInput(s);
  std::optional<std::string> csv;
  if (options.csvPath) csv = outputs.addFile("--csv", *options.csvPath);
  checkDirectoryCreatable("--out", options.outDir);
  const BenchResult result = runBenchmark(options, std::cout);
  if (csv) {
    writeCsv(*csv, result.rows);
    outputs.commit();
    std::cerr << "bench: wrote " << *options.csvPath << "\n";
  }
  try {
    const BenchPlots plots = writePlots(options.outDir, result);
    for (const BenchPlot& p : plots.plots) std::cerr << "bench: wrote " << p.path << "\n";
    for (const auto& [scene, note] : plots.notes)
      std::cerr << "bench: " << scene << ": " << note << "\n";
  } catch (const InputError& e) {
    std::cerr << "bench: " << e.what() << "\n";
  }
  for (const ClaimCheck& c : checkClaims(result)) {
    std::cout << nlohmann::json{{"claim", c.id},          {"source", c.source},
                                {"statement", c.claim},   {"scene", c.scene},
                                {"measured", c.measured}, {"verdict", c.verdict},
                                {"setup", c.setup}}
                     .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)
              << "\n";
    std::cerr << "claim " << c.id << " (" << c.source << ") on " << c.scene << ": " << c.verdict
              << "\n    " << c.claim << "\n    setup: " << c.setup
              << "\n    measured: " << c.measured << "\n";
  }
  // The answer to "which technique at this budget", last so that it ends the run's output
  // (stderr, with the other human-readable lines; stdout stays JSON lines).
  if (options.budgetMs) printBudgetRanking(std::cerr, result.rows, *options.budgetMs);
  return 0;
}

struct BenchReferences {
  References refs;
  bool temporal = true;
};

std::shared_ptr<const BenchReferences> renderBenchReferences(const Scene& scene,
                                                             const RenderParams& base,
                                                             bool withSoft, bool temporal) {
  auto out = std::make_shared<BenchReferences>();
  out->refs = renderReferences(scene, base, withSoft, temporal);
  out->temporal = temporal;
  return out;
}

BenchRow measureBenchRow(const Technique& t, const Scene& scene, const BenchVariant& v,
                         const BenchReferences& refs, int warmup, int timed, bool quick) {
  Image mask;
  const bool truth = isReference(t);
  BenchRow row = measureVariant(t, scene, v, refs.refs, truth ? 0 : warmup, truth ? 1 : timed,
                                quick, refs.temporal, mask);
  if (row.status == "ok")
    row.counters["plan_max_shadow_texels_per_pixel"] =
        planFrame(scene, t, v.params).maxShadowTexelsPerPixel;
  return row;
}

double readLoadAverage() {
  std::ifstream in("/proc/loadavg");
  double oneMinute = -1.0;
  if (!(in >> oneMinute)) return -1.0;
  return oneMinute;
}

std::string utcIsoNow() {
  const std::time_t t = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&t, &utc);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

nlohmann::json effectiveParamsJson(const BenchRow& row) {
  nlohmann::json out = nlohmann::json::object();
  const Technique* t = nullptr;
  for (const Technique& candidate : allTechniques())
    if (candidate.name == row.technique) t = &candidate;
  if (t == nullptr) return out;  // not a technique of this build (a merged row's)
  const nlohmann::json common = optionsJson({t}, row.params);
  for (const char* option : {"shadow_map", "filter", "precision", "imaging"})
    if (!common.at(option).is_null()) out[option] = common.at(option);
  for (const ParamSpec& spec : t->params) {
    const auto given = row.params.extra.find(spec.key);
    out[spec.key] = given != row.params.extra.end() ? given->second : spec.defaultText();
  }
  for (const auto& [key, value] : row.params.extra)
    if (!out.contains(key)) out[key] = value;
  return out;
}

bool timesWithinSpread(const BenchRow& a, const BenchRow& b) {
  if (a.framesTimed == 0 || b.framesTimed == 0) return false;  // no timing statistics to judge
  return a.q1Ms <= b.q3Ms && b.q1Ms <= a.q3Ms;
}

std::string rankGroup(const std::string& scene, int width, int height, const std::string& orbit) {
  return scene + "|" + std::to_string(width) + "x" + std::to_string(height) + "|" + orbit;
}

std::vector<nlohmann::json> mergeBenchRows(const std::vector<std::string>& paths) {
  using Json = nlohmann::json;
  std::vector<Json> lines;
  std::vector<BenchRow> rows;  // what the ranking reads of each line
  for (const std::string& path : paths) {
    std::ifstream in(path);
    if (!in) throw InputError("--merge " + path + ": cannot open it");
    std::string text;
    for (int number = 1; std::getline(in, text); ++number) {
      if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
      const std::string where = "--merge " + path + " line " + std::to_string(number);
      Json j = Json::parse(text, nullptr, false);
      if (j.is_discarded() || !j.is_object()) throw InputError(where + ": not a JSON object");
      if (j.contains("claim")) continue;  // a claim's verdict, not a row
      for (const char* key : {"scene", "technique", "status", "reference", "width", "height"})
        if (!j.contains(key))
          throw InputError(where + ": not a bench row (no \"" + key +
                           "\"; rows of this version's bench carry it)");
      BenchRow r;
      try {
        const std::string orbit = j.value("orbit", Json(nullptr)).is_string()
                                      ? j.at("orbit").get<std::string>()
                                      : std::string();
        r.scene = rankGroup(j.at("scene").get<std::string>(), j.at("width").get<int>(),
                            j.at("height").get<int>(), orbit);
        r.technique = j.at("technique").get<std::string>();
        r.status = j.at("status").get<std::string>();
        r.primaryReference = j.at("reference").get<std::string>();
        if (r.status == "ok") {
          r.frameMs = j.at("frame_ms").get<double>();
          const double rmse = j.at("error").at("rmse").get<double>();
          (r.primaryIsSoft() ? r.soft : r.hard).all.rmse = rmse;
        }
      } catch (const Json::exception& e) {
        throw InputError(where + ": a field of the wrong type (" + e.what() + ")");
      }
      lines.push_back(std::move(j));
      rows.push_back(std::move(r));
    }
  }
  assignParetoRanks(rows);
  for (size_t i = 0; i < rows.size(); ++i)
    lines[i]["pareto_rank"] = rows[i].paretoRank > 0 ? Json(rows[i].paretoRank) : Json(nullptr);
  return lines;
}

}  // namespace sl::figures
