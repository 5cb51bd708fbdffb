// measure/volumes_bench.h — the speed side of Chan 2004 ch. 3 (Figure 3-11) and ch. 4 (Figure
// 4-8): per-technique frame times of the shadow map, hybrid and shadow-volume algorithms (and
// smoothies) in a fill-heavy scene, with the overdraw counters of Figure 3-10. Speed is measured
// here, never asserted in tests. `tools/volumes_bench.cpp` is the command-line driver.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/technique/frame_timing.h"
#include "core/technique/technique.h"

namespace sl::modern {

// The fill-heavy scene after Chan's "Cubes" (Figure 3-6) is a scene file: loadScene("cubes")
// (assets/scenes/cubes.json: three layers of floating cubes over a ground plane, a light above,
// the camera looking across the columns of shadow volumes).

struct VolumesBenchRow {
  std::string technique;
  std::string scene;
  std::string device;  // GL renderer string
  int width = 0, height = 0, shadowMapTexels = 0, frames = 0;
  double medianMs = 0, minMs = 0;  // sum of the technique's timed passes per frame
  std::map<std::string, double> passMedianMs;
  std::map<std::string, double> counters;  // of the last frame
};

// Renders each technique `warmup + frames` times in one context (the warm-up frames let the
// driver compile its shader variants) and reports the median of the timed frames
// (core/technique/frame_timing.h timeSteadyState).
std::vector<VolumesBenchRow> benchmarkShadowVolumes(const Scene& scene, const RenderParams& params,
                                                    const std::vector<std::string>& techniques,
                                                    int frames, int warmup = kWarmupFrames);

nlohmann::json toJson(const VolumesBenchRow& row);

// The images of docs/volumes.md in `dir` (volumes_bench --doc-images): close-ups of the brabec
// sphere's shadow (hw 256^2, hybrid 256^2, volumes, smoothies), and the cubes and fill-bound
// scenes with their volume overdraw (Chan Fig. 3-9a) and the hybrid's classification (Fig.
// 3-5b). All three files or none (core/base/output_files.h); InputError for a bad destination.
void writeVolumesDocImages(const std::string& dir);

}  // namespace sl::modern
