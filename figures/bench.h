// figures/bench.h — `shadowlab bench`: error against run time for every technique and a sweep
// of its parameters, on a fixed set of benchmark scenes, measured against the ray-traced
// references (issue 8 items 1 and 2).
#pragma once

#include <iosfwd>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "apps/cli.h"
#include "core/image.h"
#include "core/metrics.h"
#include "core/technique.h"

namespace sl::figures {

struct BenchOptions {
  bool quick = false;
  std::vector<std::string> scenes;       // empty: the fixed set (benchScenes)
  std::optional<std::string> technique;  // only this technique (all variants)
  std::optional<std::string> csvPath;
  std::string outDir = "out/bench";       // plots, gnuplot scripts and data
  int width = 0, height = 0;              // 0: the mode's default
  int warmupFrames = 0, timedFrames = 0;  // 0: the mode's default
  Backend backend = Backend::kOsmesa;
  bool progress = true;  // one line per variant on stderr
};

// The scenes the bench measures: quick = {brabec, fence}; full = every built-in scene.
std::vector<std::string> benchScenes(bool quick);

// One parameter setting of a technique: "default" or one axis changed ("shadow-map=256").
struct BenchVariant {
  std::string label;
  RenderParams params;
};
// The sweep of `t` around `base`: the default, then one axis at a time (shadow map side,
// filter footprint, precision, and the --param keys the technique declares), plus the CSM
// Table 1 grid (side x order x blur) in the full mode.
std::vector<BenchVariant> sweepVariants(const Technique& t, const RenderParams& base, bool quick);

// Errors of one mask against one reference, counted where the light can reach (surfaces
// facing it inside its frustum: elsewhere the direct term is 0 and visibility changes nothing).
struct ErrorSet {
  MaskDifference all;   // every pixel of the direct-light region
  MaskDifference band;  // the region's pixels within 2 pixels of a reference shadow edge
  // Light leaking: share of the reference's umbra pixels (visibility 0, outside the band)
  // that the technique shows more than kLeakThreshold lit.
  double leakShare = 0.0;
};
ErrorSet measureErrors(const Image& mask, const Image& reference, const Image& region,
                       const Image& band);

struct BenchRow {
  std::string scene, technique, variant;
  std::string status = "ok";  // "ok", or why the variant could not run
  RenderParams params;
  std::string primaryReference;  // the reference the technique approximates
  ErrorSet hard, soft;           // against reference.hard and reference.soft
  double frameMs = 0.0;          // median over timed frames of the sum of the pass times
  double wallMs = 0.0;           // median wall time of render() (includes set-up)
  std::vector<PassTime> passes;  // median per pass
  std::map<std::string, double> counters;
  const ErrorSet& primary() const { return primaryReference == "reference.soft" ? soft : hard; }
};

struct BenchResult {
  std::vector<BenchRow> rows;
  std::map<std::string, Image> masks;            // "scene|technique|variant" -> visibility
  std::map<std::string, double> texelsPerPixel;  // scene -> largest shadow-map minification
};

// Runs the sweep; each row is also printed as one JSON object per line on `json`.
BenchResult runBenchmark(const BenchOptions& options, std::ostream& json);

// The papers' comparative claims (issue 8 item 2) as checks on the measurements.
struct ClaimCheck {
  std::string id;
  std::string source;  // paper and section
  std::string claim;
  std::string scene;
  std::string measured;  // the numbers
  std::string verdict;   // "agrees", "disagrees", "not measured"
};
std::vector<ClaimCheck> checkClaims(const BenchResult& result);

// Indices (into rows) of the Pareto front of one scene, fastest first: rows with status ok
// for which no faster (or equally fast) row has a lower or equal primary RMSE. The references
// are left out: their error is zero by construction.
std::vector<size_t> paretoFront(const std::vector<BenchRow>& rows, const std::string& scene);

void writeCsv(const std::string& path, const std::vector<BenchRow>& rows);
// error-against-time plots, one PNG per scene (gnuplot run as a subprocess); returns the
// written paths. Throws GlError-free InputError when gnuplot is missing.
std::vector<std::string> writePlots(const std::string& outDir, const BenchResult& result);

int runBenchCommand(const cli::Args& args);

}  // namespace sl::figures
