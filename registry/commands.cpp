#include "registry/commands.h"

#include "core/base/content_hash.h"
#include "core/base/errors.h"
#include "core/base/metrics.h"
#include "core/base/provenance.h"
#include "core/scene/scene_library.h"
#include "reference/reference.h"  // the references' pixel= param
#include "registry/registry.h"

namespace sl {
namespace {

// The imaging subset a legacy technique's context got (--imaging; registry/registry.cpp).
const char* imagingName(const RenderParams& p) {
  switch (p.imaging) {
    case ImagingChoice::kNative: return "native";
    case ImagingChoice::kEmulated: return "emulated";
    case ImagingChoice::kBackendDefault: break;
  }
  switch (p.backend) {
    case Backend::kReference: return "native";
    case Backend::kOsmesa: return "emulated";
    case Backend::kEgl: break;
  }
  return "native where the driver has it, else emulated";
}

// The named scene with --camera-distance, --light-radius, --light-position and --orbit applied.
Scene viewedScene(const cli::Args& args, const std::string& sceneName) {
  Scene scene = loadScene(sceneName);
  cli::viewScene(args, scene);
  return scene;
}

// Where the scene came from when a file: its path and the SHA-256 of its bytes (the file may
// change after the run; the hash says which content made the output). Built-in: both null.
void addSceneFile(nlohmann::json& made, const std::string& sceneName) {
  const std::string path = sceneFilePath(sceneName);
  made["scene_file"] = path.empty() ? nlohmann::json(nullptr) : nlohmann::json(path);
  made["scene_sha256"] =
      path.empty() ? nlohmann::json(nullptr) : nlohmann::json(sha256OfFile(path));
}

// The scene knobs given, in the JSON line and the PNGs' provenance.
void addAdjustments(nlohmann::json& made, const SceneAdjustments& a) {
  if (a.cameraDistance) made["camera_distance"] = *a.cameraDistance;
  if (a.lightRadius) made["light_radius"] = *a.lightRadius;
  if (a.lightPosition)
    made["light_position"] = {a.lightPosition->x, a.lightPosition->y, a.lightPosition->z};
}

// --a-param / --b-param KEY=VALUE: one side's --params (over --param, which goes to both). A key
// the side's technique does not declare is an InputError naming its keys, as --param's is.
void addSideParams(const cli::Args& args, const char* option, const Technique& t, RenderParams& p) {
  const auto it = args.options.find(option);
  if (it == args.options.end()) return;
  for (const std::string& kv : it->second) {
    const auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError(std::string("--") + option + " must look like key=value, got '" + kv + "'");
    const std::string key = kv.substr(0, eq);
    if (!findParam(t, key)) {
      std::string keys;
      for (const std::string& k : paramKeys(t)) keys += (keys.empty() ? "" : ", ") + k;
      throw InputError(
          std::string("--") + option + " " + key + ": technique " + t.name + " has no parameter '" +
          key + "'" +
          (keys.empty() ? std::string(" (it takes none)") : " (it takes " + keys + ")"));
    }
    p.extra[key] = kv.substr(eq + 1);
  }
}

// compare's score (registry/shadow_error.h, docs/error.md): when one side is a ray-traced
// reference, the other side's error against it as that truth (pixel=centre: the point metric,
// pixel=area: the area metric), exactly as bench scores it; otherwise the two masks' difference
// over the same scored pixels (B as the baseline), the categories from reference.hard.
struct CompareScore {
  ShadowError error;
  std::string truthSide;  // "a", "b" or "" (neither is a reference)
};
CompareScore scorePair(const Scene& scene, const Technique& a, const Frame& fa,
                       const RenderParams& paramsA, const Technique& b, const Frame& fb,
                       const RenderParams& paramsB, double threshold) {
  CompareScore out;
  const bool bIsTruth = isRayTracedReference(b), aIsTruth = !bIsTruth && isRayTracedReference(a);
  if (aIsTruth || bIsTruth) {
    const Technique& truthTechnique = bIsTruth ? b : a;
    const RenderParams& truthParams = bIsTruth ? paramsB : paramsA;
    const bool area =
        truthParams.text(reference::kPixelParam, reference::kPixelCentre,
                         {reference::kPixelCentre, reference::kPixelArea}) == reference::kPixelArea;
    const ErrorMetric metric = area ? ErrorMetric::kArea : ErrorMetric::kPoint;
    const bool soft = truthTechnique.light == Technique::Light::kArea;
    std::string name = truthName(soft, metric);
    for (const auto& [k, v] : truthParams.extra)
      if (k != reference::kPixelParam) name += " " + k + "=" + v;
    const ShadowTruth truth =
        truthFromReferenceFrame(bIsTruth ? fb : fa, metric, soft, std::move(name));
    out.error = scoreShadow(bIsTruth ? fa.visibility : fb.visibility, truth, threshold);
    out.truthSide = bIsTruth ? "b" : "a";
    return out;
  }
  ShadowTruth baseline;
  if (haveRayTracedReferences()) {
    baseline = renderShadowTruth(scene, paramsB, ErrorMetric::kPoint, false);
  } else {  // no ray tracer in this build: every pixel is scored
    baseline.scored = Image(fb.visibility.width, fb.visibility.height, 1, 1.0f);
    baseline.counts.total = baseline.counts.scored =
        (long long)fb.visibility.width * fb.visibility.height;
  }
  baseline.visibility = fb.visibility;
  baseline.band = scoredBand(baseline.visibility, baseline.scored);
  baseline.name = b.name;
  out.error = scoreShadow(fa.visibility, baseline, threshold);
  out.error.metric = "mask difference";
  return out;
}

}  // namespace

nlohmann::json optionsJson(const std::vector<const Technique*>& techniques, const RenderParams& p) {
  auto anyReads = [&](CommonOption o) {
    for (const Technique* t : techniques)
      if (readsOption(*t, o)) return true;
    return false;
  };
  nlohmann::json out;
  out["size"] = std::to_string(p.width) + "x" + std::to_string(p.height);
  out["shadow_map"] =
      anyReads(CommonOption::kShadowMap) ? nlohmann::json(p.shadowMapTexels) : nlohmann::json();
  out["filter"] = anyReads(CommonOption::kFilter) ? nlohmann::json(p.filter) : nlohmann::json();
  out["precision"] = anyReads(CommonOption::kPrecision) ? nlohmann::json(precisionName(p.precision))
                                                        : nlohmann::json();
  out["backend"] = backendName(p.backend);
  out["imaging"] =
      anyReads(CommonOption::kImaging) ? nlohmann::json(imagingName(p)) : nlohmann::json();
  return out;
}

nlohmann::json paramsJson(const RenderParams& p) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [key, value] : effectiveParams(p)) out[key] = value;
  return out;
}

RenderParams withReadLog(RenderParams p) {
  p.readLog = std::make_shared<ParamReadLog>();
  return p;
}

RenderRequest prepareRender(const cli::Args& args) {
  RenderRequest r;
  r.sceneName = args.value("scene").value_or(kDefaultScene);
  r.adjustments = cli::sceneAdjustments(args);
  r.scene = viewedScene(args, r.sceneName);
  r.technique = &findTechnique(args.required("technique"));
  r.params = withReadLog(cli::renderParams(args));
  rejectIgnoredOptions(*r.technique, cli::givenCommonOptions(args));
  return r;
}

RenderRun runRender(const RenderRequest& request) {
  RenderRun run;
  const Technique& technique = *request.technique;
  run.frame = renderTechnique(technique, request.scene, request.params);
  run.made = optionsJson({&technique}, request.params);
  run.made["technique"] = technique.name;
  run.made["scene"] = request.scene.name;
  addSceneFile(run.made, request.sceneName);
  addAdjustments(run.made, request.adjustments);
  run.made["params"] = paramsJson(request.params);
  run.line = run.made;
  run.line["command"] = commandLine();
  run.line["commit"] = buildCommit();
  run.line["frame_ms"] = run.frame.totalMilliseconds();
  for (const PassTime& p : run.frame.passes) run.line["passes"][p.name] = p.milliseconds;
  for (const auto& [k, v] : run.frame.counters) run.line["counters"][k] = v;
  return run;
}

CompareRequest prepareCompare(const cli::Args& args) {
  CompareRequest r;
  r.sceneName = args.value("scene").value_or(kDefaultScene);
  r.adjustments = cli::sceneAdjustments(args);
  r.scene = viewedScene(args, r.sceneName);
  r.a = &findTechnique(args.required("a"));
  r.b = &findTechnique(args.required("b"));
  r.params = cli::renderParams(args);
  r.warnings = checkOptionsOfPair(*r.a, *r.b, cli::givenCommonOptions(args));
  if (auto t = args.value("threshold")) {
    r.threshold = cli::parseNumber("--threshold", *t);
    if (!(r.threshold >= 0.0 && r.threshold <= 1.0))
      throw InputError("--threshold must lie in [0, 1]");
  }
  r.paramsA = withReadLog(r.params);
  r.paramsB = withReadLog(r.params);
  addSideParams(args, "a-param", *r.a, r.paramsA);
  addSideParams(args, "b-param", *r.b, r.paramsB);
  // A reference side keeps its passes: its pixel categories decide the scored pixels.
  r.paramsA.capturePasses = isRayTracedReference(*r.a);
  r.paramsB.capturePasses = isRayTracedReference(*r.b);
  return r;
}

CompareRun runCompare(const CompareRequest& request) {
  CompareRun run;
  const Technique &a = *request.a, &b = *request.b;
  run.a = renderTechnique(a, request.scene, request.paramsA);
  run.b = renderTechnique(b, request.scene, request.paramsB);
  const CompareScore score = scorePair(request.scene, a, run.a, request.paramsA, b, run.b,
                                       request.paramsB, request.threshold);
  run.made = optionsJson({&a, &b}, request.params);
  run.made["scene"] = request.scene.name;
  addSceneFile(run.made, request.sceneName);
  addAdjustments(run.made, request.adjustments);
  run.made["a"] = a.name;
  run.made["b"] = b.name;
  run.made["a_params"] = paramsJson(request.paramsA);
  run.made["b_params"] = paramsJson(request.paramsB);
  run.made["threshold"] = request.threshold;
  nlohmann::json& out = run.line;
  out = toJson(score.error);
  out["truth"] =
      score.truthSide.empty() ? nlohmann::json(nullptr) : nlohmann::json(score.error.truth);
  out["truth_side"] =
      score.truthSide.empty() ? nlohmann::json(nullptr) : nlohmann::json(score.truthSide);
  out["all_pixels"] = toJson(compareMasks(run.a.visibility, run.b.visibility, request.threshold));
  out.update(run.made);
  out["command"] = commandLine();
  out["commit"] = buildCommit();
  out["a_frame_ms"] = run.a.totalMilliseconds();
  out["b_frame_ms"] = run.b.totalMilliseconds();
  return run;
}

}  // namespace sl
