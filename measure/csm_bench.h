// measure/csm_bench.h — csm_bench's measurements (tools/csm_bench.cpp is its command line): the
// filtered-shadow techniques' frame times, the grid of Annen et al. 2007 Table 1 (shadow map
// 256..2048, M = 4 / 8 / 16, no blur / 3x3 / 7x7) timed as CSM / PCF beside the paper's GeForce
// 8800 GTX ratios, and modern.csm against modern.hw with their frames interleaved.
#pragma once

#include <functional>
#include <map>
#include <string>

#include "core/gl/context.h"
#include "core/scene/scene.h"
#include "core/technique/frame_timing.h"
#include "core/technique/technique.h"

namespace sl::measure::csm {

constexpr int kPaperWidth = 1024;  // Table 1: "screen resolution is 1024x768"
constexpr int kPaperHeight = 768;

struct Options {
  int width = kPaperWidth;
  int height = kPaperHeight;
  FrameCounts frames = kSteadyFrames;
  std::string scene = "brabec";
  Backend backend = Backend::kOsmesa;
  std::string part = "all";
  std::string csv;
  std::map<std::string, std::string> csmParams;  // --param key=value, for --part ratio
  bool sizeGiven = false;                        // --size: --part ratio measures this size only
  bool sceneGiven = false;                       // --scene: --part ratio measures this scene only
  int ratioMap = 512;  // --shadow-map: the map of --part ratio (RenderParams' default)
};

using Timing = SteadyTiming;

// The render parameters of one configuration: the options' window and back end, a map of
// `mapSize` texels, and the --param entries `extra`.
RenderParams paramsFor(const Options& o, int mapSize, std::map<std::string, std::string> extra);

// --part ratio: modern.csm / modern.hw on the bench scenes and sizes (or --scene, --size), the
// two contexts rendering alternately so that both see the same load; one markdown table.
void runRatio(const Options& o);

// One row of the CSV: part, technique, map, order, blur and the timing.
using Recorder = std::function<void(const std::string& part, const std::string& technique, int map,
                                    int order, int blur, const Timing& t)>;

// --part techniques, table1 or all: the techniques' frame times and the Table 1 grid (markdown
// on stdout), each timing also given to `record`.
void runTechniquesAndTable1(const Options& o, const Scene& scene, const Recorder& record);

}  // namespace sl::measure::csm
