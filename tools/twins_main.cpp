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
#include "measure/twin_tables.h"
#include "registry/cli.h"
#include "registry/registry.h"
#include "registry/twins.h"

namespace sl {
namespace {
using measure::twin_tables::agreementTable;
using measure::twin_tables::benchTable;
using measure::twin_tables::Options;

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
