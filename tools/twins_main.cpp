// tools/twins_main.cpp — shadowlab-twins: the legacy/modern agreement table and the speed of
// each pair, as markdown (docs/twins.md is this program's output).
//
//   shadowlab-twins [--size WxH] [--shadow-map N] [--backend osmesa|egl] [--scenes a,b,c]
//                   [--bench-size WxH] [--bench-shadow-map N] [--bench-scene S] [--frames N]
//                   [--no-agreement] [--no-bench]
//
// Agreement: every pair of registry/twins.h on every scene, at the equivalence tests' size by
// default (320x240, 256^2 map), judged against the pair's bound. Speed: each technique's median
// frame time (sum of its timed passes after warm-up frames, core/technique/frame_timing.h) at the
// paper's configuration (Brabec–Seidel §5: 800x600, 512^2 map, the brabec scene) and legacy/modern.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>

#include "core/base/errors.h"
#include "core/base/provenance.h"
#include "core/scene/scene_library.h"
#include "registry/cli.h"
#include "registry/registry.h"
#include "registry/twins.h"

namespace sl {
namespace {

struct Options {
  int width = 320, height = 240, shadowMap = 256;  // as tests/modern/equivalence_test.cpp
  int benchWidth = 800, benchHeight = 600, benchShadowMap = 512;  // Brabec–Seidel §5
  std::string benchScene = "brabec";
  int frames = 5;
  Backend backend = Backend::kOsmesa;
  std::vector<std::string> scenes = twins::equivalenceScenes();
  bool agreement = true;
  bool bench = true;
};

std::vector<std::string> splitCommas(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

constexpr int kMaxShadowMap = 1 << 16;  // texels; the GL maximum is checked once a context exists
constexpr int kMaxFrames = 1000;        // timed frames per technique

// The command line (see the head of this file); std::nullopt after --help.
std::optional<Options> parse(int argc, char** argv) {
  Options o;
  std::string size, shadowMap, benchSize, benchShadowMap, frames, backend, scenes;
  bool noAgreement = false, noBench = false;
  CLI::App app{"the legacy/modern agreement table and the speed of each pair (markdown)",
               "shadowlab-twins"};
  app.add_option("--size", size, "agreement window WxH [320x240]")->type_name("WxH");
  app.add_option("--shadow-map", shadowMap, "agreement shadow map side [256]")->type_name("N");
  app.add_option("--backend", backend, "osmesa or egl [osmesa]")->type_name("NAME");
  CLI::Option* scenesOption =
      app.add_option("--scenes", scenes,
                     "agreement scenes, comma-separated [the equivalence scenes]")
          ->type_name("a,b,c");
  app.add_option("--bench-size", benchSize, "frame-time window WxH [800x600]")->type_name("WxH");
  app.add_option("--bench-shadow-map", benchShadowMap, "frame-time shadow map side [512]")
      ->type_name("N");
  app.add_option("--bench-scene", o.benchScene, "frame-time scene [brabec]")->type_name("S");
  app.add_option("--frames", frames, "timed frames per technique, after the warm-up [5]")
      ->type_name("N");
  app.add_flag("--no-agreement", noAgreement, "skip the agreement table");
  app.add_flag("--no-bench", noBench, "skip the frame-time table");
  if (!cli::parseTool(app, argc, argv)) return std::nullopt;
  if (!size.empty()) cli::parseSize(size, o.width, o.height);
  if (!shadowMap.empty())
    o.shadowMap = cli::parsePositiveInt("--shadow-map", shadowMap, kMaxShadowMap);
  if (!benchSize.empty()) cli::parseSize(benchSize, o.benchWidth, o.benchHeight);
  if (!benchShadowMap.empty())
    o.benchShadowMap = cli::parsePositiveInt("--bench-shadow-map", benchShadowMap, kMaxShadowMap);
  if (!frames.empty()) o.frames = cli::parsePositiveInt("--frames", frames, kMaxFrames);
  if (!backend.empty()) o.backend = parseBackend(backend);
  if (scenesOption->count() > 0) {
    o.scenes = splitCommas(scenes);
    if (o.scenes.empty())
      throw InputError("--scenes needs at least one scene name, got '" + scenes + "'");
  }
  o.agreement = !noAgreement;
  o.bench = !noBench;
  return o;
}

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

void agreementTable(const Options& o) {
  std::cout << "### Agreement (" << backendName(o.backend) << ", " << o.width << "x" << o.height
            << ", " << o.shadowMap << "^2 map)\n\n"
            << "| pair | scene | bound | max difference | differing pixels | > 1/255 | "
               "> 1/255 off band | within bound | image: > 3/255 (where masks agree) | image: "
               "bound (cone-edge band) | image: max, RMSE | image within bound |\n"
            << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const twins::TwinPair& pair : twins::twinPairs())
    for (const std::string& name : o.scenes) {
      const Scene scene = loadScene(name);
      const RenderParams pl =
          twins::paramsFor(pair, true, o.width, o.height, o.shadowMap, o.backend);
      const RenderParams pm =
          twins::paramsFor(pair, false, o.width, o.height, o.shadowMap, o.backend);
      std::cout << "| " << pair.label << " | " << name << " | "
                << (pair.faithful ? "faithful (ties only)" : "1/255, band") << " | ";
      try {
        if (const std::string why = twins::unavailablePrecision(pair, pl); !why.empty())
          throw InputError(why);
        const Frame legacy = renderTechnique(findTechnique(pair.legacy), scene, pl);
        const Frame modern = renderTechnique(findTechnique(pair.modern), scene, pm);
        const twins::Agreement a = twins::judge(pair, legacy.visibility, modern.visibility);
        std::cout << fixed(a.all.maxAbs, 4) << " (" << fixed(a.all.maxAbs * 255.0, 1) << "/255) | "
                  << a.differing << " of " << a.all.pixels << " | " << a.beyondOneStep << " | "
                  << a.beyondOutsideBand << " | " << (a.withinBound ? "yes" : "**no**") << " | ";
        const twins::ImageAgreement im =
            twins::judgeImages(legacy.color, modern.color, legacy.visibility, modern.visibility);
        std::cout << im.beyondSteps << " (" << im.beyondWhereMasksAgree << ") | " << im.boundPixels
                  << " | " << fixed(im.maxAbs, 3) << ", " << fixed(im.rmse, 4) << " | "
                  << (im.withinBound ? "yes" : "**no**") << " |\n";
      } catch (const std::exception& e) {
        std::cout << "not run: " << e.what() << " | | | | | | | | |\n";
      }
    }
  for (const std::string& m : twins::missingPairs()) std::cout << "\nnot in this build: " << m;
  std::cout << "\n";
}

void benchTable(const Options& o) {
  std::cout << "### Frame time (" << backendName(o.backend) << ", " << o.benchScene << ", "
            << o.benchWidth << "x" << o.benchHeight << ", " << o.benchShadowMap << "^2 map, "
            << o.frames << " frames each after " << kWarmupFrames << " warm-up)\n\n"
            << "| pair | legacy ms (median / min) | modern ms (median / min) | legacy / modern "
               "(medians) | legacy / modern (minima) |\n| --- | --- | --- | --- | --- |\n";
  const Scene scene = loadScene(o.benchScene);
  for (const twins::TwinPair& pair : twins::twinPairs()) {
    std::cout << "| " << pair.label << " | ";
    try {
      const RenderParams pl =
          twins::paramsFor(pair, true, o.benchWidth, o.benchHeight, o.benchShadowMap, o.backend);
      if (const std::string why = twins::unavailablePrecision(pair, pl); !why.empty())
        throw InputError(why);
      const twins::FrameTimes legacy =
          twins::frameMilliseconds(findTechnique(pair.legacy), scene, pl, o.frames);
      const twins::FrameTimes modern = twins::frameMilliseconds(
          findTechnique(pair.modern), scene,
          twins::paramsFor(pair, false, o.benchWidth, o.benchHeight, o.benchShadowMap, o.backend),
          o.frames);
      std::cout << fixed(legacy.median, 1) << " / " << fixed(legacy.minimum, 1) << " | "
                << fixed(modern.median, 1) << " / " << fixed(modern.minimum, 1) << " | "
                << fixed(legacy.median / modern.median, 2) << " | "
                << fixed(legacy.minimum / modern.minimum, 2) << " |\n";
    } catch (const std::exception& e) {
      std::cout << "not run: " << e.what() << " | | |\n";
    }
    std::cout.flush();
  }
}

int run(int argc, char** argv) {
  const std::optional<Options> parsed = parse(argc, argv);
  if (!parsed) return 0;  // --help
  const Options& o = *parsed;
  // Every scene name is checked before the first table line is printed.
  if (o.agreement)
    for (const std::string& name : o.scenes) loadScene(name);
  if (o.bench) loadScene(o.benchScene);
  if (o.agreement) agreementTable(o);
  if (o.agreement && o.bench) std::cout << "\n";
  if (o.bench) benchTable(o);
  return 0;
}

}  // namespace
}  // namespace sl

int main(int argc, char** argv) { return sl::runProgram("shadowlab-twins", argc, argv, sl::run); }
