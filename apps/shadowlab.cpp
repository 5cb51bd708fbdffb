// apps/shadowlab.cpp — the shadowlab command: list, render, compare, bench, plan, figures,
// lesson, gallery, course, exercise, serve, run-legacy. This file holds the usage text and the
// dispatch; the handlers are beside it (apps/commands.h, apps/run_legacy.h) or in their rooms.
// Contract: docs/design.md "Command-line contract". Bad input -> one line on stderr, exit status 2.
#include <iostream>
#include <string>

#include "apps/commands.h"
#include "apps/run_legacy.h"
#include "core/base/errors.h"
#include "core/base/provenance.h"
#include "figures/course.h"
#include "figures/figures.h"
#include "figures/gallery.h"
#include "figures/overrides.h"
#include "figures/report.h"
#include "lab/lab_server.h"
#include "registry/cli.h"
#include "registry/registry.h"
#include "teach/lesson.h"

namespace sl {
namespace {

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
  shadowlab exercise list | show ID | start ID --out FILE | grade ID ANSWER
                                                   graded exercises: render and measure an answer
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
  if (argc >= 2 && std::string(argv[1]) == "exercise") return exercise(argc - 1, argv + 1);
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
  if (args.command == "lesson") return figures::runLessonCommand(args, figures::figureRefs());
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
