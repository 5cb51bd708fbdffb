// apps/shadowlab.cpp — the shadowlab command: list, render, compare, bench, plan, figures,
// lesson, gallery, serve.
// Contract: ../shared/DESIGN.md "Contracts". Bad input -> one line on stderr, exit status 2.
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "registry/cli.h"
#include "reference/reference.h"  // the references' pixel= param
#include "registry/registry.h"
#include "registry/shadow_error.h"
#include "registry/twins.h"
#include "core/errors.h"
#include "core/metrics.h"
#include "core/output_files.h"
#include "core/pass_dump.h"
#include "core/provenance.h"
#include "core/scene_library.h"
#include "figures/course.h"
#include "figures/figures.h"
#include "figures/gallery.h"
#include "figures/lesson.h"
#include "figures/overrides.h"
#include "lab/lab_server.h"

namespace sl {
namespace {
namespace fs = std::filesystem;

const char* kUsage =
    R"(shadowlab — classic shadow-map antialiasing, legacy OpenGL 1.x beside modern GLSL

usage:
  shadowlab list                                   techniques, scenes, figures
  shadowlab render --scene S --technique T [--size WxH] [--shadow-map N] [--filter K]
                   [--precision 8|12|float] [--param key=value ...] [--backend osmesa|egl|reference]
                   [--camera-distance X] [--light-radius R] [--light-position X,Y,Z]
                   --out image.png [--mask visibility.png] [--dump-passes DIR]
  shadowlab compare --scene S --a T1 --b T2 [render options] [--a-param K=V] [--b-param K=V]
                    [--diff diff.png] [--threshold X]
  shadowlab bench  [--quick] [--scene S] [--technique T] [--csv FILE]
  shadowlab plan   --scene S --technique T         passes kept and passes left out, and why
  shadowlab figures [--out DIR] [--only ID ...]    the main job: every figure + report.html
  shadowlab figures --only ID --set key=value ...  one figure re-made with parameters changed
  shadowlab lesson TECHNIQUE --out DIR             one HTML lesson: paper, passes, GL state, GLSL twin
  shadowlab gallery --out DIR                      the artefact gallery: DIR/gallery/index.html
  shadowlab course --out DIR                       the lessons in order, exercises, teacher's page
  shadowlab serve  [--host 127.0.0.1] [--port 8080] the live lab in a browser (Ctrl-C stops it)
  shadowlab --version                              the commit this binary was built from

`shadowlab COMMAND --help` lists a command's options.
--mask writes the light-visibility term (1 = lit, 0 = umbra) as a 16-bit grayscale PNG.
Image outputs (render --out and --mask, compare --diff) are PNG only: their names end in .png.
Every output is checked before rendering and appears only when the whole run succeeds.
Exit status: 0 ok, 2 bad input (names, files, numbers), 3 GL failure.
)";

int list() {
  std::cout << "techniques:\n";
  for (const Technique& t : allTechniques()) {
    std::cout << "  " << t.name << std::string(t.name.size() < 22 ? 22 - t.name.size() : 1, ' ')
              << t.paper << " — " << t.summary << " [" << t.status << "]\n";
    for (const ParamSpec& p : t.params)
      std::cout << std::string(24, ' ') << "--param " << describeParam(p) << "\n";
  }
  std::cout << "scenes:\n";
  for (const std::string& s : builtinSceneNames()) std::cout << "  " << s << " (built in)\n";
  for (const std::string& s : sceneFileNames()) std::cout << "  " << s << " (assets/scenes)\n";
  std::cout << "figures:\n";
  for (const figures::FigureInfo& f : figures::listFigures())
    std::cout << "  " << f.id << "  " << f.title << "\n";
  return 0;
}

// The files a --scene argument reads (core/scene_library.cpp loadScene): the argument itself
// when it is a file, or assets/scenes/<name>.json. No output may replace them.
void addSceneInputs(OutputSet& outputs, const std::string& scene) {
  outputs.addInput(scene);
  outputs.addInput((fs::path(assetDirectory()) / "scenes" / (scene + ".json")).string());
}

// One JSON line: built before any output is committed, so that a name that is not UTF-8 (a
// scene file's name when the file has no "name" key) cannot fail after the files are written;
// invalid bytes become U+FFFD.
std::string jsonLine(const nlohmann::json& out) {
  return out.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// What made an output (issue 21 item 2): the common options as they took effect on the
// technique(s) rendered: an option none of them reads is null (registry/registry.h refuses it
// when given).
// The imaging subset a legacy technique's context got (--imaging; registry/registry.cpp).
const char* imagingName(const RenderParams& p) {
  switch (p.imaging) {
    case ImagingChoice::kNative:
      return "native";
    case ImagingChoice::kEmulated:
      return "emulated";
    case ImagingChoice::kBackendDefault:
      break;
  }
  switch (p.backend) {
    case Backend::kReference:
      return "native";
    case Backend::kOsmesa:
      return "emulated";
    case Backend::kEgl:
      break;
  }
  return "native where the driver has it, else emulated";
}

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

// The --params of a render as it used them: given ones and the defaults it read.
nlohmann::json paramsJson(const RenderParams& p) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [key, value] : effectiveParams(p)) out[key] = value;
  return out;
}

// A render's params with a fresh log of the --param values its technique reads.
RenderParams withReadLog(RenderParams p) {
  p.readLog = std::make_shared<ParamReadLog>();
  return p;
}

// The PNG text of an output: the command line and the parameters (ASCII JSON).
Provenance pngProvenance(const nlohmann::json& parameters) {
  return {commandLine(), parameters.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace)};
}

// The destinations of `render`, checked before rendering (core/output_files.h).
struct RenderOutputs {
  OutputSet set;
  std::string image;                // temporary of --out
  std::optional<std::string> mask;  // temporary of --mask
  std::optional<std::string> dump;  // temporary directory of --dump-passes
};

// --dump-passes (core/pass_dump.h): the buffers in pipeline order, passes.json, index.html.
void writeFrameOutputs(const Frame& frame, const PassDumpHeader& dumpHeader, RenderOutputs& outputs,
                       const Provenance& provenance) {
  if (!frame.color.empty() && !allFinite(frame.color)) throw GlError("the image has NaN or Inf");
  if (!allFinite(frame.visibility)) throw GlError("the visibility mask has NaN or Inf");
  if (outputs.dump) requireSomethingToDump(frame, dumpHeader.technique);
  outputs.set.beginWriting();
  writePng(outputs.image, frame.color, 8, provenance);
  if (outputs.mask) writePng(*outputs.mask, frame.visibility, 16, provenance);
  if (outputs.dump) writePassDump(*outputs.dump, frame, dumpHeader, provenance);
}

// The named scene with --camera-distance, --light-radius, --light-position and --orbit applied.
Scene viewedScene(const cli::Args& args, const std::string& sceneName) {
  Scene scene = loadScene(sceneName);
  cli::viewScene(args, scene);
  return scene;
}

// The scene knobs given, in the JSON line and the PNGs' provenance.
void addAdjustments(nlohmann::json& made, const SceneAdjustments& a) {
  if (a.cameraDistance) made["camera_distance"] = *a.cameraDistance;
  if (a.lightRadius) made["light_radius"] = *a.lightRadius;
  if (a.lightPosition)
    made["light_position"] = {a.lightPosition->x, a.lightPosition->y, a.lightPosition->z};
}

int render(const cli::Args& args) {
  const std::string sceneName = args.value("scene").value_or(kDefaultScene);
  const SceneAdjustments adjustments = cli::sceneAdjustments(args);
  Scene scene = viewedScene(args, sceneName);
  const Technique& technique = findTechnique(args.required("technique"));
  RenderParams params = withReadLog(cli::renderParams(args));
  rejectIgnoredOptions(technique, cli::givenCommonOptions(args));
  RenderOutputs outputs;
  addSceneInputs(outputs.set, sceneName);
  outputs.image = outputs.set.addFile("--out", args.required("out"));
  if (auto mask = args.value("mask")) outputs.mask = outputs.set.addFile("--mask", *mask);
  if (auto dir = args.value("dump-passes")) {
    outputs.dump = outputs.set.addDirectory("--dump-passes", *dir);
    params.capturePasses = true;
  }
  const Frame frame = renderTechnique(technique, scene, params);
  nlohmann::json made = optionsJson({&technique}, params);
  made["technique"] = technique.name;
  made["scene"] = scene.name;
  addAdjustments(made, adjustments);
  made["params"] = paramsJson(params);
  nlohmann::json out = made;
  out["command"] = commandLine();
  out["commit"] = buildCommit();
  out["frame_ms"] = frame.totalMilliseconds();
  for (const PassTime& p : frame.passes) out["passes"][p.name] = p.milliseconds;
  for (const auto& [k, v] : frame.counters) out["counters"][k] = v;
  const std::string line = jsonLine(out);
  const PassDumpHeader dumpHeader{technique.name, technique.paper, scene.name, made,
                                  twins::legacyTwinOf(technique.name)};
  writeFrameOutputs(frame, dumpHeader, outputs, pngProvenance(made));
  outputs.set.commit();
  std::cout << line << "\n";
  return 0;
}

// --a-param / --b-param KEY=VALUE: one side's --params (over --param, which goes to both). A key
// the side's technique does not declare is an InputError naming its keys, as --param's is.
void addSideParams(const cli::Args& args, const char* option, const Technique& t,
                   RenderParams& p) {
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
      throw InputError(std::string("--") + option + " " + key + ": technique " + t.name +
                       " has no parameter '" + key + "'" +
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
    const bool area = truthParams.text(reference::kPixelParam, reference::kPixelCentre,
                                       {reference::kPixelCentre, reference::kPixelArea}) ==
                      reference::kPixelArea;
    const ErrorMetric metric = area ? ErrorMetric::kArea : ErrorMetric::kPoint;
    const bool soft = truthTechnique.name == "reference.soft";
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

int compare(const cli::Args& args) {
  const std::string sceneName = args.value("scene").value_or(kDefaultScene);
  const SceneAdjustments adjustments = cli::sceneAdjustments(args);
  Scene scene = viewedScene(args, sceneName);
  const Technique& a = findTechnique(args.required("a"));
  const Technique& b = findTechnique(args.required("b"));
  const RenderParams params = cli::renderParams(args);
  for (const std::string& warning : checkOptionsOfPair(a, b, cli::givenCommonOptions(args)))
    std::cerr << "shadowlab: warning: " << warning << "\n";
  double threshold = 0.0;
  if (auto t = args.value("threshold")) {
    threshold = cli::parseNumber("--threshold", *t);
    if (!(threshold >= 0.0 && threshold <= 1.0)) throw InputError("--threshold must lie in [0, 1]");
  }
  RenderParams paramsA = withReadLog(params), paramsB = withReadLog(params);
  addSideParams(args, "a-param", a, paramsA);
  addSideParams(args, "b-param", b, paramsB);
  // A reference side keeps its passes: its pixel categories decide the scored pixels.
  paramsA.capturePasses = isRayTracedReference(a);
  paramsB.capturePasses = isRayTracedReference(b);
  OutputSet outputs;
  addSceneInputs(outputs, sceneName);
  std::optional<std::string> diff;
  if (auto path = args.value("diff")) diff = outputs.addFile("--diff", *path);
  const Frame fa = renderTechnique(a, scene, paramsA);
  const Frame fb = renderTechnique(b, scene, paramsB);
  const CompareScore score = scorePair(scene, a, fa, paramsA, b, fb, paramsB, threshold);
  nlohmann::json made = optionsJson({&a, &b}, params);
  made["scene"] = scene.name;
  addAdjustments(made, adjustments);
  made["a"] = a.name;
  made["b"] = b.name;
  made["a_params"] = paramsJson(paramsA);
  made["b_params"] = paramsJson(paramsB);
  made["threshold"] = threshold;
  nlohmann::json out = toJson(score.error);
  out["truth"] = score.truthSide.empty() ? nlohmann::json(nullptr) : nlohmann::json(score.error.truth);
  out["truth_side"] = score.truthSide.empty() ? nlohmann::json(nullptr) : nlohmann::json(score.truthSide);
  out["all_pixels"] = toJson(compareMasks(fa.visibility, fb.visibility, threshold));
  out.update(made);
  out["command"] = commandLine();
  out["commit"] = buildCommit();
  out["a_frame_ms"] = fa.totalMilliseconds();
  out["b_frame_ms"] = fb.totalMilliseconds();
  const std::string line = jsonLine(out);
  if (diff)
    writePng(*diff, differenceHeatMap(fa.visibility, fb.visibility), 8, pngProvenance(made));
  outputs.commit();
  std::cout << line << "\n";
  return 0;
}

int run(int argc, char** argv) {
  if (argc >= 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h" ||
                    std::string(argv[1]) == "help")) {
    std::cout << kUsage;
    return 0;
  }
  if (argc >= 2 && std::string(argv[1]) == "--version") {
    if (argc > 2)
      throw InputError("--version takes no arguments, got '" + std::string(argv[2]) + "'");
    std::cout << softwareName() << "\n";  // "shadowlab <commit>" (core/provenance.h)
    return 0;
  }
  cli::Args args;
  try {
    args = cli::parse(argc, argv);
  } catch (const cli::HelpRequested& help) {
    std::cout << help.text;
    return 0;
  }
  if (args.command == "list") return list();
  if (args.command == "render") return render(args);
  if (args.command == "compare") return compare(args);
  if (args.command == "figures")
    return figures::runFigures(
        args.value("out").value_or("out/figures"),
        args.options.count("only") ? args.options.at("only") : std::vector<std::string>{},
        !args.has("no-progress"), figures::parseOverrides(args));
  if (args.command == "lesson") return figures::runLessonCommand(args);
  if (args.command == "gallery") return figures::runGalleryCommand(args);
  if (args.command == "course") return figures::runCourseCommand(args);
  if (args.command == "bench") return figures::runBench(args);
  if (args.command == "serve") return lab::runServe(args);
  if (args.command == "plan") {
    rejectIgnoredOptions(findTechnique(args.required("technique")), cli::givenCommonOptions(args));
    return figures::runPlan(args);
  }
  throw InputError("unknown command " + args.command);
}

}  // namespace
}  // namespace sl

int main(int argc, char** argv) {
  return sl::runProgram("shadowlab", argc, argv, sl::run);
}
