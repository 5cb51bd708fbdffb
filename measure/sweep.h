// measure/sweep.h — a sweep: techniques x scenes x window sizes x shadow-map sides x filter
// footprints x precisions x --param values x camera orbits, each row measured as `shadowlab
// bench` measures a variant (measure/bench.h measureBenchRow) against the ray-traced references
// of its view. The spec is one JSON object (docs/python.md "Sweeps"); the Python module's
// sweep() takes it as a dict and runs its rows in this process or as Dask tasks.
#pragma once

#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "measure/bench.h"

namespace sl::figures {

// The window of a spec without "sizes": the quick bench's.
constexpr int kSweepDefaultWidth = 256, kSweepDefaultHeight = 192;
// Frames of a row without "warmup" / "repeat": the quick bench's.
constexpr int kSweepDefaultWarmup = 1, kSweepDefaultRepeat = 3;
constexpr int kSweepMaxFrames = 1000;  // per row, warm-up and timed each
// Rows one spec may expand to: far more than a day of llvmpipe time, so a typo that multiplies
// the axes is refused before anything runs.
constexpr size_t kSweepMaxRows = 100000;

// One view: the references are rendered once per view.
struct SweepView {
  std::string scene;  // the spec's name or file, as loadScene reads it
  int width = 0, height = 0;
  std::optional<std::string> orbit;  // "AZ,EL,DIST" (render --orbit); none: the scene's camera
};

// One row: a technique and its options on one view.
struct SweepRow {
  size_t view = 0;
  const Technique* technique = nullptr;
  std::string
      variant;        // the swept options that apply to it ("shadow-map=256 order=8"), or "default"
  cli::Args options;  // as render's command line would give them (registry/cli.h renderParams)
};

struct SweepPlan {
  std::vector<SweepView> views;
  std::vector<SweepRow> rows;  // views in spec order; per view, techniques then option axes
  Backend backend = Backend::kOsmesa;
  int warmup = kSweepDefaultWarmup, repeat = kSweepDefaultRepeat;
  bool softReference = true;  // render reference.soft (the truth of smoothies; soft_* columns)
  bool temporal = true;       // temporal_change (one more frame with the light moved)
};

// Checks the whole spec and expands it; InputError (one line, naming the key) for anything the
// rows could not run with: an unknown key, technique or scene, a malformed value, a --param key
// no technique of the sweep declares, an orbit a scene refuses. A value one technique refuses
// (fast PCF's --filter 3) is no error: that row's status says why, as in the bench.
SweepPlan planSweep(const nlohmann::json& spec);

// A view's scene (viewed) and its references, rendered once.
struct SweepViewData {
  Scene scene;
  std::shared_ptr<const BenchReferences> references;
};
// The views a process has rendered (a Dask worker keeps them between tasks): the key is the
// scene, window, orbit, back end and which references, so a cached view is the one asked for.
class SweepReferenceCache {
 public:
  std::shared_ptr<const SweepViewData> get(const SweepPlan& plan, size_t view);
  size_t size() const { return byKey_.size(); }  // views held

 private:
  static constexpr size_t kMaxViews = 32;  // each holds its references' frames and truths
  std::map<std::string, std::shared_ptr<const SweepViewData>> byKey_;
  std::vector<std::string> order_;  // oldest first
};

// Measures the rows of `plan` at `indices`, in that order (out-of-range index: InputError).
// Their paretoRank stays 0: ranks are over a whole sweep (assignSweepParetoRanks).
std::vector<BenchRow> measureSweepRows(const SweepPlan& plan, const std::vector<size_t>& indices,
                                       SweepReferenceCache& cache);

// Pareto ranks (measure/bench.h assignParetoRanks) within each group of rows: `groups[i]` names
// row i's view (its scene, window and orbit), so that rows of different windows or cameras are
// never ranked against each other.
void assignSweepParetoRanks(std::vector<BenchRow>& rows, const std::vector<std::string>& groups);

}  // namespace sl::figures
