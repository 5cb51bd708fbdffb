// apps/shadowlab.cpp — the shadowlab command: list, render, compare, bench, plan, figures,
// lesson, gallery, serve.
// Contract: docs/design.md "Command-line contract". Bad input -> one line on stderr, exit status 2.
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "apps/run_legacy.h"
#include "core/base/errors.h"
#include "core/base/metrics.h"
#include "core/base/output_files.h"
#include "core/base/provenance.h"
#include "core/scene/scene_library.h"
#include "figures/course.h"
#include "figures/figures.h"
#include "figures/gallery.h"
#include "figures/overrides.h"
#include "lab/lab_server.h"
#include "registry/cli.h"
#include "registry/commands.h"
#include "registry/registry.h"
#include "registry/twins.h"
#include "teach/lesson.h"
#include "teach/pass_dump.h"

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
  shadowlab bench  --sweep FILE.json [--csv FILE]  | --merge A.jsonl --merge B.jsonl ...
  shadowlab plan   --scene S --technique T         passes kept and passes left out, and why
  shadowlab figures [--out DIR] [--only ID ...]    the main job: every figure + report.html
  shadowlab figures --only ID --set key=value ...  one figure re-made with parameters changed
  shadowlab lesson TECHNIQUE --out DIR             one HTML lesson: paper, passes, GL state, GLSL twin
  shadowlab gallery --out DIR                      the artefact gallery: DIR/gallery/index.html
  shadowlab course --out DIR                       the lessons in order, exercises, teacher's page
  shadowlab serve  [--host 127.0.0.1] [--port 8080] the live lab in a browser (Ctrl-C stops it)
  shadowlab run-legacy --backend glx|osmesa|reference [--keys "h v l"] --frames DIR -- PROGRAM [ARGS]
                                                   an unchanged GL 1.x GLUT program, imaging preloaded
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

// The files a --scene argument reads (core/scene/scene_library.cpp loadScene): the argument itself
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

// The PNG text of an output: the command line and the parameters (ASCII JSON).
Provenance pngProvenance(const nlohmann::json& parameters) {
  return {commandLine(), parameters.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace)};
}

// The destinations of `render`, checked before rendering (core/base/output_files.h).
struct RenderOutputs {
  OutputSet set;
  std::string image;                // temporary of --out
  std::optional<std::string> mask;  // temporary of --mask
  std::optional<std::string> dump;  // temporary directory of --dump-passes
};

// --dump-passes (teach/pass_dump.h): the buffers in pipeline order, passes.json, index.html.
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

int render(const cli::Args& args) {
  RenderRequest request = prepareRender(args);
  RenderOutputs outputs;
  addSceneInputs(outputs.set, request.sceneName);
  outputs.image = outputs.set.addFile("--out", args.required("out"));
  if (auto mask = args.value("mask")) outputs.mask = outputs.set.addFile("--mask", *mask);
  if (auto dir = args.value("dump-passes")) {
    outputs.dump = outputs.set.addDirectory("--dump-passes", *dir);
    request.params.capturePasses = true;
  }
  const RenderRun run = runRender(request);
  const std::string line = jsonLine(run.line);
  const Technique& technique = *request.technique;
  const PassDumpHeader dumpHeader{technique.name,
                                  technique.paper,
                                  request.scene.name,
                                  run.made,
                                  twins::legacyTwinOf(technique.name),
                                  twins::legacyTwinPassesOf(technique.name)};
  writeFrameOutputs(run.frame, dumpHeader, outputs, pngProvenance(run.made));
  outputs.set.commit();
  std::cout << line << "\n";
  return 0;
}

int compare(const cli::Args& args) {
  const CompareRequest request = prepareCompare(args);
  for (const std::string& warning : request.warnings)
    std::cerr << "shadowlab: warning: " << warning << "\n";
  OutputSet outputs;
  addSceneInputs(outputs, request.sceneName);
  std::optional<std::string> diff;
  if (auto path = args.value("diff")) diff = outputs.addFile("--diff", *path);
  const CompareRun run = runCompare(request);
  const std::string line = jsonLine(run.line);
  if (diff)
    writePng(*diff, differenceHeatMap(run.a.visibility, run.b.visibility), 8,
             pngProvenance(run.made));
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
    std::cout << softwareName() << "\n";  // "shadowlab <commit>" (core/base/provenance.h)
    return 0;
  }
  if (argc >= 2 && std::string(argv[1]) == "run-legacy") return runLegacy(argc - 1, argv + 1);
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

int main(int argc, char** argv) { return sl::runProgram("shadowlab", argc, argv, sl::run); }
