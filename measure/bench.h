// measure/bench.h — `shadowlab bench`: error against run time for every technique and a sweep
// of its parameters, on a fixed set of benchmark scenes, measured against the ray-traced
// references.
#pragma once

#include <iosfwd>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/base/image.h"
#include "core/base/metrics.h"
#include "core/technique/technique.h"
#include "reference/reference.h"  // kPixelParam: the bench and figures use pixel=area
#include "registry/cli.h"
#include "registry/shadow_error.h"

namespace sl::figures {

struct BenchOptions {
  bool quick = false;
  std::vector<std::string> scenes;      // empty: the fixed set (benchScenes)
  std::vector<std::string> techniques;  // only these techniques (all variants); empty: every one
  std::optional<std::string> csvPath;
  std::string outDir = "out/bench";       // plots, gnuplot scripts and data
  int width = 0, height = 0;              // 0: the mode's default
  int warmupFrames = 0, timedFrames = 0;  // 0: the mode's default
  Backend backend = Backend::kOsmesa;
  bool progress = true;  // one line per variant on stderr
  // --budget-ms: after the sweep, per scene, the variants whose median frame time is within
  // this many milliseconds, ranked by error (printBudgetRanking). Unset: no ranking.
  std::optional<double> budgetMs;
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
// Table 1 grid (side x order x blur) in the full mode. Not swept: values the
// technique rejects (fast PCF's footprints 1 and 3, modern.vsm storage=8) and variants that
// repeat another one (a --param set to the technique's own default, e.g. modern.vsm
// storage=float, or a Table 1 cell equal to a one-axis variant).
std::vector<BenchVariant> sweepVariants(const Technique& t, const RenderParams& base, bool quick);

// Errors of one mask against one truth: the one definition of registry/shadow_error.h
// (docs/error.md), over the scored pixels, with the metric and truth named.
using ErrorSet = ShadowError;
// The same arithmetic for a truth given as images (`region`: the pixels scored; `band`: the
// scored pixels near the truth's edges), for tests and the figures' whole-image details.
ErrorSet measureErrors(const Image& mask, const Image& reference, const Image& region,
                       const Image& band);

// The references every row is measured against. Primary: the
// pixel-integrated forms (--param pixel=area), the truth of a displayed pixel, for every
// technique (one truth per scene, so that every row of a plot is measured on the same axis);
// the soft one for smoothies (they approximate an area light), the hard one otherwise. The
// pixel-centre forms stay as a second column (hardPoint, softPoint).
constexpr const char* kPrimaryHardReference = "reference.hard pixel=area";
constexpr const char* kPrimarySoftReference = "reference.soft pixel=area";
// The figures' panel errors (figures.cpp) use the same pixel-integrated form with 4 x 4
// sub-pixel samples: a quarter of the bench's hard rasterisations and rays for each of the ~35
// figure setups of the main job (at 512x384: +0.5 s per setup instead of +2 s on llvmpipe);
// at a straight edge within 1/8 + 1/64 of the covered fraction (reference.h). reference.soft
// uses 4 x 4 anyway.
constexpr int kFigureReferencePixelSamplesPerSide = 4;

// Temporal stability: the light and its target move sideways (along the
// light's view x axis) by this fraction of one shadow-map texel of the default 512 map at the
// light's target: texel = 2 d tan(cone / 2) / 512, d = |target - position|. The same motion for
// every row of a scene (so every row has the same truth to follow); it is sub-texel for every
// swept map side up to 2048 (0.8 texel there).
constexpr double kLightShiftTexels = 0.2;
constexpr int kLightShiftMapTexels = 512;
// World distance of that motion for `scene`.
double lightShiftWorld(const Scene& scene);
// `scene` with the light (position and target) moved by `world` along the light's x axis.
Scene shiftLight(const Scene& scene, double world);

// Timing spread (docs/user-guide.md "Reading the timings"): a row whose interquartile range of
// timed frames exceeds this share of its median is flagged (spread_large). A quarter: two
// back-to-back quick runs at load ~1 moved variants by up to a half of their time and swapped
// neighbours whose medians were within a quarter; beyond it one run cannot order rows whose
// medians differ by less than their own spread, which is what a reader of a ranking must know.
constexpr double kSpreadFlagRatio = 0.25;

// The 1-minute load average (/proc/loadavg, first field); < 0 when it cannot be read.
double readLoadAverage();
// Now, in UTC, as ISO 8601 ("2026-12-03T13:05:12Z").
std::string utcIsoNow();

struct BenchRow {
  std::string scene, technique, variant;
  std::string orbit;          // a sweep view's camera orbit ("AZ,EL,DIST"); "": the scene's camera
  std::string status = "ok";  // "ok", or why the variant could not run
  RenderParams params;
  std::string primaryReference;   // kPrimaryHardReference or kPrimarySoftReference
  ErrorSet hard, soft;            // against the pixel-integrated (pixel=area) references
  ErrorSet hardPoint, softPoint;  // against the pixel-centre references (the point samples)
  bool softMeasured = false;      // soft and softPoint were measured (reference.soft rendered)
  // Mean |change| of the mask over the scored pixels (docs/error.md) when the light moves by
  // lightShiftWorld (one extra frame); the primary reference's own change for the same motion
  // beside it (what the true shadow moves by). < 0: not measured.
  double temporalChange = -1.0;
  double referenceTemporalChange = -1.0;
  // Pareto rank within its scene on (frame time, primary RMSE), assignParetoRanks: 1 = on the
  // front, 2 = on the front once rank 1 is removed, ...; 0 = not ranked (a reference, which is
  // the truth and not a competitor, or a row whose status is not ok).
  int paretoRank = 0;
  double frameMs = 0.0;          // median over timed frames of the sum of the pass times
  double wallMs = 0.0;           // median wall time of render() (includes set-up)
  std::vector<PassTime> passes;  // median per pass
  std::map<std::string, double> counters;
  // The timed frames' spread: how many, their quartiles (linear interpolation between order
  // statistics) and the least; a reference row is its one frame.
  int framesTimed = 0;
  double q1Ms = 0.0, q3Ms = 0.0, minFrameMs = 0.0;
  double iqrMs() const { return q3Ms - q1Ms; }
  bool spreadLarge() const { return frameMs > 0.0 && iqrMs() / frameMs > kSpreadFlagRatio; }
  // The load average just before the first warm-up frame and just after the last timed one.
  double loadBefore = -1.0, loadAfter = -1.0;
  // What made the row: the back end and the GL strings of the context that rendered it (the
  // back end's when it made none: a ray-traced reference, a refused variant), and when.
  std::string backend, glVendor, glRenderer, glVersion, date;
  bool primaryIsSoft() const { return primaryReference.rfind("reference.soft", 0) == 0; }
  const ErrorSet& primary() const { return primaryIsSoft() ? soft : hard; }
};

struct BenchResult {
  std::vector<BenchRow> rows;
  std::map<std::string, Image> masks;             // "scene|technique|variant" -> visibility
  std::map<std::string, double> texelsPerPixel;   // scene -> largest shadow-map minification
  std::map<std::string, std::string> sceneNotes;  // scene -> why a claim scene was not measured
};

// The scenes derived in code for the claims, measured after the bench
// scenes with the few techniques each claim compares (default variants):
//   trees-far    the trees scene (thin branches) with the camera kFarCameraFactor times
//                farther from its target (same field of view), every technique with the
//                kMinificationMapTexels map: many shadow-map texels of thin geometry fall in
//                one pixel, Annen Fig. 10's setting ("when a scene is moved far away from the
//                camera"); modern.csm with Fig. 10's filtering (tri-linear, 5x5 kernel)
//   fill-bound   assets/scenes/fill-bound.json when it exists (hybrid vs volumes, Chan §3.3),
//                at kFillBoundWidth x kFillBoundHeight with a kFillBoundMapTexels map;
//                otherwise sceneNotes["fill-bound"] = "scene not present"
constexpr const char* kMinificationScene = "trees";
constexpr float kFarCameraFactor = 3.0f;
constexpr int kMinificationMapTexels = 2048;  // resolves the branches; the pixel minifies it
// modern.csm's row on the far scene: Fig. 10's "regular tri-linear filtering with a 5x5
// filter kernel" (M = 16, the default order, as Table 1's scene).
constexpr const char* kCsmFig10Blur = "5";
constexpr const char* kCsmFig10Variant = "blur=5";
constexpr const char* kFarSceneSuffix = "-far";
constexpr const char* kFillBoundScene = "fill-bound";
// Annen et al. Fig. 9's claim (CSM does not leak where VSM does) needs a scene where VSM
// bleeds: assets/scenes/bleeding.json, a picket fence near the light over the shadow of a low
// plank, so that one filter kernel holds occluders at very different depths over one receiver.
// Measured with modern.vsm and modern.csm (their defaults) and the filtered-map baselines after
// them (modern.esm, evsm2, evsm4, msm); `--scene bleeding` runs just
// that; without the file the claim keeps its other scenes' verdicts.
constexpr const char* kBleedingScene = "bleeding";
// The fill-bound scene is measured in Chan's setting (§3.1 step 1: "a low-resolution shadow
// map"; Fig. 3-11: full-window frames), not the quick bench's small window: 800x600, 256².
constexpr int kFillBoundWidth = 800, kFillBoundHeight = 600;
constexpr int kFillBoundMapTexels = 256;
Scene farScene(const Scene& scene);
// The smoothie width t that makes a smoothie's remapped ramp as wide as the true penumbra of
// the scene's spherical light (Chan 2004 §4.2, Eq. 4.1; see bench.cpp):
//   t = R / (2 b tan(cone / 2)),  R = SpotLight::radius, b = the casters' mean depth along the
//   light axis (centres of their bounding boxes), cone = SpotLight::coneDegrees.
double smoothieWidthFromLight(const Scene& scene);
// The label of modern.smoothies' row with that width (the smoothies-soft claim reads it).
constexpr const char* kSmoothieWidthFromLightVariant = "width-from-light";

// Runs the sweep; each row is also printed as one JSON object per line on `json`.
BenchResult runBenchmark(const BenchOptions& options, std::ostream& json);

// The papers' comparative claims as checks on the measurements.
struct ClaimCheck {
  std::string id;
  std::string source;  // paper and section
  std::string claim;
  std::string scene;
  std::string measured;  // the numbers
  std::string verdict;   // "agrees", "disagrees (...)", "not measured (...)"
  std::string setup;     // the fair setup the verdict rests on (reference, variants, scene)
};
std::vector<ClaimCheck> checkClaims(const BenchResult& result);

// Indices (into rows) of the Pareto front of one scene, fastest first: rows with status ok
// for which no faster (or equally fast) row has a lower or equal primary RMSE. The references
// are left out: their error is zero by construction.
std::vector<size_t> paretoFront(const std::vector<BenchRow>& rows, const std::string& scene);

// Sets every row's paretoRank: per scene, repeated non-dominated fronts of the ok,
// non-reference rows, where a row dominates another when it is no slower and no worse and
// strictly better in one of the two (equal rows share a rank).
void assignParetoRanks(std::vector<BenchRow>& rows);
// The output order (CSV, JSON lines, the budget table): by scene name, then ok rows by median
// frame time (ties: technique, variant), then the rows that did not run.
void sortRowsBySceneThenTime(std::vector<BenchRow>& rows);
// The rows' JSON line (one object; the bench's stdout and bench.jsonl).
std::string benchRowJsonLine(const BenchRow& row);
// The technique's full effective parameters on a row, as one JSON object: every --param it
// declares with the value the row used (given or its default), and the common options it reads
// (shadow_map, filter, precision); the JSON's "params" and the CSV's "params" column.
nlohmann::json effectiveParamsJson(const BenchRow& row);
// Whether two rows' median frame times cannot be ordered by this run: their interquartile
// ranges [q1, q3] overlap (a claim or a plot that ranks by time says so). False when either
// has no timed frames (a row that did not run, or one made without timing statistics).
bool timesWithinSpread(const BenchRow& a, const BenchRow& b);
// The group a row is Pareto-ranked in: scene, window and camera orbit ("brabec|256x192|").
std::string rankGroup(const std::string& scene, int width, int height, const std::string& orbit);

// `bench --merge A.jsonl B.jsonl ...`: the bench rows of several runs' JSON lines (claim lines
// and blank lines are skipped) with pareto_rank recomputed over all of them, per rankGroup, by
// assignParetoRanks; every other field as it was. InputError naming the file and line for a
// line that is not a bench row.
std::vector<nlohmann::json> mergeBenchRows(const std::vector<std::string>& paths);

// --budget-ms: one scene's answer to "which technique at this budget".
struct BudgetRanking {
  std::string scene;
  std::vector<size_t> within;  // indices into rows: frameMs <= budget, by RMSE, then time
  int overBudget = 0;          // ok non-reference rows slower than the budget
  int notRun = 0;              // non-reference rows whose status is not ok
};
// Per scene (in the rows' order of first appearance); references are never ranked.
std::vector<BudgetRanking> rankWithinBudget(const std::vector<BenchRow>& rows, double budgetMs);
// The table: per scene a heading, one line per variant within the budget (rank, technique,
// variant, ms, RMSE, band RMSE, temporal change with the reference's, Pareto rank), then the
// number over budget.
void printBudgetRanking(std::ostream& out, const std::vector<BenchRow>& rows, double budgetMs);
// --budget-ms's value: a positive decimal number of milliseconds, else InputError.
double parseBudgetMs(const std::string& text);

void writeCsv(const std::string& path, const std::vector<BenchRow>& rows);
// The same CSV on a stream (the Python module reads it at the stream's precision).
void writeCsvRows(std::ostream& out, const std::vector<BenchRow>& rows);
// Error-against-time plots (gnuplot run as a subprocess), per scene one PNG per technique
// family, so that no plot carries more than a handful of series. References
// are the truth, never plotted as competitors. Each plot's x and y ranges are fitted to the
// scene's competitors (the same on the scene's plots, so they compare); the scene's Pareto
// front is drawn on each as a grey staircase with numbered points, the numbers listed in
// `pareto`. A row with RMSE 0 cannot sit on the log axis: it is named in `notes`; a scene with no
// positive RMSE gets no plot and a note saying why. Throws InputError when gnuplot is missing.
struct BenchPlot {
  std::string scene, family, path;
};
struct BenchPlots {
  std::vector<BenchPlot> plots;
  std::map<std::string, std::vector<std::string>> pareto;  // scene -> "1: technique variant ..."
  std::map<std::string, std::string> notes;                // scene -> what is not drawn and why
};
// "legacy" (the 2001 fixed-function pipelines), "modern twins" (their GLSL twins,
// registry/twins.h) or "later papers" (GPU Gems, CSM, VSM, Chan); "" for a reference.
std::string plotFamily(const std::string& technique);
BenchPlots writePlots(const std::string& outDir, const BenchResult& result);

// `shadowlab bench`'s options from its command line (InputError for a bad name or value).
BenchOptions parseBenchOptions(const cli::Args& args);
int runBenchCommand(const cli::Args& args);

// One row at a time, as runBenchmark measures each (measure/sweep.h): the references of one
// view (scene, window, back end) rendered once, then any variant measured against them.
struct BenchReferences;
std::shared_ptr<const BenchReferences> renderBenchReferences(const Scene& scene,
                                                             const RenderParams& base,
                                                             bool withSoft, bool temporal);
// The row of `v` (a reference technique: its frame from `refs`); `quick`: a variant slower
// than the quick bench's budget per frame is timed over one frame.
BenchRow measureBenchRow(const Technique& t, const Scene& scene, const BenchVariant& v,
                         const BenchReferences& refs, int warmup, int timed, bool quick);

}  // namespace sl::figures
