// measure/bench.cpp — `shadowlab bench`: error against run time.
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
//   3. outputs           — a JSON object per row on stdout (here); the Pareto ranks and the
//                          output order (bench_ranking.cpp), CSV (--csv, bench_csv.cpp), the
//                          gnuplot plots per scene and family (error against time, log axes,
//                          Pareto front; bench_plots.cpp), claim checks (bench_claims.cpp)
// The command itself (options, --sweep, --merge): bench_command.cpp.
#include "measure/bench.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <glm/glm.hpp>
#include <iomanip>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/base/errors.h"
#include "core/base/provenance.h"
#include "core/gl/gl.h"
#include "core/scene/scene_library.h"
#include "core/technique/frame_timing.h"
#include "core/technique/plan.h"
#include "imaging/imaging.h"
#include "reference/reference.h"
#include "registry/commands.h"  // optionsJson: the common options a technique reads
#include "registry/registry.h"

namespace sl::figures {

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
  // The light-bleeding claim scene: VSM against CSM, and the filtered-map baselines after them
  // (kBleedingScene).
  const auto bleedingRun = [] {
    Scene s = loadScene(kBleedingScene);
    s.name = kBleedingScene;  // the claim looks for this name
    return SceneRun{
        s,
        {"modern.vsm", "modern.csm", "modern.esm", "modern.evsm2", "modern.evsm4", "modern.msm"},
        false,
        false,
        false};
  };
  for (const std::string& name : scenes)
    runs.push_back(name == kBleedingScene ? bleedingRun()
                                          : SceneRun{loadScene(name), {}, true, true, false});
  if (options.scenes.empty() || contains(options.scenes, kDefaultScene)) {
    // What the planner's omissions save: a purpose-built scene where no
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
    // another part of the bench; without it the claim says so.
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

}  // namespace sl::figures
