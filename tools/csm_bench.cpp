// tools/csm_bench.cpp — frame times of the filtered-shadow techniques and the grid of Annen et
// al. 2007 Table 1 (shadow map 256..2048, M = 4 / 8 / 16, no blur / 3x3 / 7x7) printed beside
// the paper's GeForce 8800 GTX frame rates. Built to build/bin/csm_bench.
//
//   csm_bench [--quick] [--size WxH] [--repeat N] [--scene S] [--backend osmesa|egl]
//             [--part techniques|table1|ratio|all] [--csv FILE] [--param key=value ...]
//             [--shadow-map N]
//
// --part ratio: modern.csm against modern.hw on the bench scenes (brabec, fence; or --scene)
// at the bench sizes (256x192, 400x300; or --size), shadow map 512 (or --shadow-map, this part
// only: exit 2 with another), each technique's defaults plus --param for CSM; the two contexts
// render alternately (hw, csm, hw, csm, ...) so that both see the same load on a shared machine,
// and the ratio of medians is printed with CSM's per-pass medians. --param applies to this part
// only, and --csv to the others only (a ratio of interleaved runs is not a row of the CSV): either
// given with the wrong part is exit 2.
// --csv is checked before anything runs, written to a temporary and renamed at the end.
//
// --part table1: every cell of Table 1 as the ratio CSM / PCF (--param key=value: added to
// every CSM cell, under the cell's own order, blur and filtering), the two timed interleaved in one
// run, beside the paper's ratio (PCF fps / CSM fps of the same map size) and ours / paper.
//
// Each configuration is timed at steady state (core/technique/frame_timing.h, registry/registry.h
// timeTechnique): in one context, --warmup frames first (shader compilation, first
// allocation), then the median of --repeat frames of the sum of the pass times (default
// kSteadyFrames: 2 + 5). --quick: 512x384 and kQuickFrames (1 warm-up, median of 3; one timed
#include "measure/csm_bench.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/base/errors.h"
#include "core/base/output_files.h"
#include "core/base/provenance.h"
#include "core/scene/scene_library.h"
#include "registry/cli.h"
#include "registry/registry.h"

namespace sl {
namespace {
using measure::csm::Options;
using measure::csm::paramsFor;
using measure::csm::runRatio;
using measure::csm::runTechniquesAndTable1;
using measure::csm::Timing;

constexpr int kMaxTimedFrames = 1000;  // --repeat
constexpr int kMaxWarmupFrames = 100;  // --warmup
constexpr int kQuickWidth = 512;       // --quick window
constexpr int kQuickHeight = 384;
constexpr int kMaxRatioMap = 4096;  // --shadow-map, texels (Table 1's largest is 2048)

// The command line (see the head of this file); std::nullopt after --help.
std::optional<Options> parseOptions(int argc, char** argv) {
  Options o;
  bool quick = false;
  std::string size, repeat, warmup, backend;
  std::vector<std::string> params;
  CLI::App app{"frame times of the filtered-shadow techniques and Annen et al. 2007 Table 1",
               "csm_bench"};
  app.add_flag("--quick", quick, "512x384 and the quick frame counts (kQuickFrames)");
  app.add_option("--size", size, "window WxH [1024x768, the paper's]")->type_name("WxH");
  app.add_option("--repeat", repeat, "timed frames per configuration, after the warm-up")
      ->type_name("N");
  app.add_option("--warmup", warmup, "warm-up frames per configuration (0 allowed)")
      ->type_name("N");
  CLI::Option* sceneOption =
      app.add_option("--scene", o.scene, "built-in scene [brabec]")->type_name("S");
  app.add_option("--backend", backend, "osmesa or egl [osmesa]")->type_name("NAME");
  std::string map;
  app.add_option("--shadow-map", map, "shadow map side of --part ratio [512]")->type_name("N");
  app.add_option("--part", o.part, "techniques, table1, ratio or all [all]")->type_name("PART");
  CLI::Option* csvOption =
      app.add_option("--csv", o.csv, "also write every row as CSV (not with --part ratio)")
          ->type_name("FILE");
  app.add_option("--param", params,
                 "key=value for modern.csm in --part ratio and table1 (repeatable)")
      ->type_name("KEY=VALUE")
      ->type_size(1)
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  if (!cli::parseTool(app, argc, argv)) return std::nullopt;
  if (quick) {
    o.width = kQuickWidth;
    o.height = kQuickHeight;
    o.frames = kQuickFrames;
  }
  o.sizeGiven = !size.empty();
  o.sceneGiven = sceneOption->count() > 0;
  if (!size.empty()) cli::parseSize(size, o.width, o.height);
  if (!repeat.empty()) o.frames.timed = cli::parsePositiveInt("--repeat", repeat, kMaxTimedFrames);
  if (!warmup.empty())
    o.frames.warmup =
        warmup == "0" ? 0 : cli::parsePositiveInt("--warmup", warmup, kMaxWarmupFrames);
  if (!backend.empty()) {
    if (backend != "osmesa" && backend != "egl")  // modern.* needs GLSL: not Mesa 7.8.2
      throw InputError("--backend must be osmesa or egl, got '" + backend + "'");
    o.backend = parseBackend(backend);
  }
  if (!map.empty()) o.ratioMap = cli::parsePositiveInt("--shadow-map", map, kMaxRatioMap);
  if (!map.empty() && o.part != "ratio")
    throw InputError("--shadow-map applies to --part ratio only, got --part " + o.part);
  if (o.part != "techniques" && o.part != "table1" && o.part != "ratio" && o.part != "all")
    throw InputError("--part must be techniques, table1, ratio or all, got '" + o.part + "'");
  for (const std::string& kv : params) {
    const size_t eq = kv.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("--param needs key=value, got '" + kv + "'");
    o.csmParams[kv.substr(0, eq)] = kv.substr(eq + 1);
  }
  if (!params.empty() && o.part != "ratio" && o.part != "table1")
    throw InputError("--param applies to --part ratio and table1 only, got --part " + o.part);
  if (csvOption->count() > 0 && o.part == "ratio")
    throw InputError(
        "--csv is not written by --part ratio (it prints ratios of interleaved "
        "runs); use --part techniques, table1 or all");
  if (csvOption->count() > 0 && o.csv.empty()) throw InputError("--csv: empty file name");
  return o;
}

int run(int argc, char** argv) {
  const std::optional<Options> parsed = parseOptions(argc, argv);
  if (!parsed) return 0;  // --help
  const Options& o = *parsed;
  const Scene scene = builtinScene(o.scene);
  // The CSV's rows are kept in memory and written at the end (core/base/output_files.h): a run that
  // fails or is interrupted leaves no file, and the destination is checked before any work.
  OutputSet outputs;
  std::optional<std::string> csvTemporary;
  std::ostringstream csv;
  if (!o.csv.empty()) {
    csvTemporary = outputs.addFile("--csv", o.csv);
    csv << "part,technique,map,order,blur,width,height,median_ms,min_ms,fps,wall_ms,timed\n";
  }
  auto record = [&](const std::string& part, const std::string& technique, int map, int order,
                    int blur, const Timing& t) {
    if (csvTemporary)
      csv << part << "," << technique << "," << map << "," << order << "," << blur << "," << o.width
          << "," << o.height << "," << t.frameMs << "," << t.minimumFrameMs << "," << t.fps() << ","
          << t.wallMs << "," << t.timedFrames << "\n";
  };
  // The driver's one-time start-up (llvmpipe's LLVM initialisation) must not land in the
  // first configuration's time: one throwaway frame first.
  renderTechnique(findTechnique("modern.hw"), scene, paramsFor(o, 256, {}));
  std::printf("scene %s, %dx%d, %s, %d warm-up + median of %d timed frames (sum of the passes)",
              o.scene.c_str(), o.width, o.height, o.backend == Backend::kEgl ? "egl" : "osmesa",
              o.frames.warmup, o.frames.timed);
  for (const auto& [k, v] : o.csmParams) std::printf(", csm %s=%s", k.c_str(), v.c_str());
  std::printf("\n\n");

  if (o.part == "ratio") {
    runRatio(o);
    return 0;
  }
  runTechniquesAndTable1(o, scene, record);
  if (csvTemporary) {
    std::ofstream file(*csvTemporary, std::ios::binary);
    file << csv.str();
    file.close();
    if (!file) throw InputError("--csv " + o.csv + ": the write failed (disk full?)");
    outputs.commit();
  }
  return 0;
}

}  // namespace
}  // namespace sl

int main(int argc, char** argv) { return sl::runProgram("csm_bench", argc, argv, sl::run); }
