// measure/legacy_benchmark.h — Brabec & Seidel 2001 §5 timings: every variant in the paper's
// configuration (800x600 window, the ~7000-triangle brabec scene, 512x512 map, one light),
// timed at steady state (core/technique/frame_timing.h: warm-up frames, then the median frame time
// and the median per pass), beside the paper's SGI Octane VPro/8 frame rates, and beside each
// pass's llvmpipe floor (measure/roofline.h), measured in the same context with the frames
// and the floors interleaved. Called by the `legacy_bench` executable (tools/legacy_bench.cpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "core/technique/frame_timing.h"
#include "core/technique/technique.h"

namespace sl::legacy {

struct BenchmarkVariant {
  std::string label;      // "fast PCF 2x2"
  std::string technique;  // "legacy.fast-pcf"
  int filter = 2;
  std::string paperFps;  // the paper's Octane VPro/8 figure (§5), "" when not reported
};

// The variants of Figure 7 (+ PCF 4x4, which §3 calls impractical and reports no rate for), and
// legacy.hw (Everitt, Rege & Cebenoyan 2001, no rate reported), timed against the same kind of
// floors.
std::vector<BenchmarkVariant> paperVariants();

struct BenchmarkOptions {
  int width = 800;  // §5
  int height = 600;
  int shadowMapTexels = 512;
  FrameCounts frames = kSteadyFrames;
  Backend backend = Backend::kOsmesa;
  ImagingChoice imaging = ImagingChoice::kBackendDefault;  // --imaging
};

struct BenchmarkResult {
  BenchmarkVariant variant;
  Backend backend = Backend::kOsmesa;
  bool imagingReplaced = false;  // imaging/ installed over the back end's native imaging
  // frameMs: median of the pass-time sums (what stands beside the paper's rate); wallMs: the
  // whole render() call, which adds the read-back of the colour image and the mask; passes:
  // the median of each pass.
  SteadyTiming timing;
  // Per pass of timing.passes, in order: its floor (measure/roofline.h passFloor, each term
  // the median of its own timings), 0 for a pass without GL work, nullopt where no rule knows
  // the pass. floors: the median of each floor term measured.
  std::vector<std::optional<double>> passFloorMs;
  double frameFloorMs = 0.0;  // the sum of the passes' floors
  std::vector<PassTime> floors;
};

// Times each variant on one context per variant: its frames interleaved with frames of its
// passes' floors (core/technique/frame_timing.h timeInterleavedSteadyState), options.frames rounds.
std::vector<BenchmarkResult> benchmarkBrabecSeidel(const Scene& scene,
                                                   const BenchmarkOptions& options,
                                                   const std::vector<BenchmarkVariant>& variants);

// What the spotlight split of the camera-view scene costs a pass (docs/legacy.md "Feeding the
// passes"): in one context of legacy.ramp, interleaved round by round, the camera pass's draw
// (clear, then every object white under the 1D ramp texture with eye-linear texgen, depth test
// LESS, as §2's camera pass draws it) of the scene's own meshes, of the split meshes the camera
// passes draw (spotlight_tessellation.h), and the camera pass's floor (measure/roofline.h:
// clear + one ramp-textured full-window quad). Markdown: each draw's median ms, triangles and
// ratio to the floor.
std::string splitCostMarkdown(const Scene& scene, const BenchmarkOptions& options);

// The summary table (docs/performance.md): variant | GL | paper fps | ours fps |
// ours ms/frame | render() wall ms | floor ms/frame | time / floor; then per variant its
// per-pass table (ms, floor ms, time / floor) and the floors measured.
std::string benchmarkMarkdown(const std::vector<BenchmarkResult>& results);

// The cost of the GL trace of --dump-passes (core/gl/gl_trace.h) on each variant: frame times
// with the trace off and on, interleaved round by round on two contexts, as a markdown table
// (legacy_bench --trace-overhead).
std::string traceOverheadMarkdown(const BenchmarkOptions& options,
                                  const std::vector<BenchmarkVariant>& variants);

}  // namespace sl::legacy
