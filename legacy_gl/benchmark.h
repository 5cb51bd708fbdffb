// legacy_gl/benchmark.h — Brabec & Seidel 2001 §5 timings: every variant in the paper's
// configuration (800x600 window, the ~7000-triangle brabec scene, 512x512 map, one light),
// median per pass over several frames after warm-up, beside the paper's SGI Octane VPro/8
// frame rates. Called by the `legacy_bench` executable (apps/legacy_bench.cpp).
#pragma once

#include <string>
#include <vector>

#include "core/scene.h"
#include "core/technique.h"

namespace sl::legacy {

struct BenchmarkVariant {
  std::string label;      // "fast PCF 2x2"
  std::string technique;  // "legacy.fast-pcf"
  int filter = 2;
  std::string paperFps;  // the paper's Octane VPro/8 figure (§5), "" when not reported
};

// The variants of Figure 7 (+ PCF 4x4, which §3 calls impractical and reports no rate for).
std::vector<BenchmarkVariant> paperVariants();

struct BenchmarkOptions {
  int width = 800;  // §5
  int height = 600;
  int shadowMapTexels = 512;
  int warmupFrames = 2;
  int timedFrames = 7;
  Backend backend = Backend::kOsmesa;
};

struct BenchmarkResult {
  BenchmarkVariant variant;
  Backend backend = Backend::kOsmesa;
  double medianFrameMs = 0;  // wall time of a whole render() call (includes the readbacks)
  double medianPassSumMs = 0;
  std::vector<PassTime> medianPasses;  // per pass, in pass order
};

// Renders each variant warmupFrames + timedFrames times in one context per variant.
std::vector<BenchmarkResult> benchmarkBrabecSeidel(const Scene& scene,
                                                   const BenchmarkOptions& options,
                                                   const std::vector<BenchmarkVariant>& variants);

// The README table: variant | paper fps | ours fps (ms) | speed-up over the paper's upper
// figure; then one per-pass table per variant.
std::string benchmarkMarkdown(const std::vector<BenchmarkResult>& results);

}  // namespace sl::legacy
