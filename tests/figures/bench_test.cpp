// The bench's machinery (figures/bench.h): the sweep declares only what a technique declares,
// the Pareto front, the error metrics and a tiny end-to-end run with CSV, JSON and plot.
#include "figures/bench.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "apps/registry.h"

namespace sl::figures {
namespace {
namespace fs = std::filesystem;

TEST(BenchSweep, OnlyDeclaredParamsAreSwept) {
  Technique t;
  t.name = "modern.test";
  t.paramKeys = {"order"};
  const auto variants = sweepVariants(t, RenderParams{}, true);
  ASSERT_FALSE(variants.empty());
  EXPECT_EQ(variants[0].label, "default");
  bool sawOrder = false;
  for (const BenchVariant& v : variants) {
    for (const auto& [k, value] : v.params.extra) {
      EXPECT_EQ(k, "order") << v.label;
      sawOrder = true;
    }
    EXPECT_EQ(v.params.filter, RenderParams{}.filter) << "no filter sweep without PCF: " << v.label;
  }
  EXPECT_TRUE(sawOrder);
}

TEST(BenchSweep, ReferencesAreNotSwept) {
  EXPECT_EQ(sweepVariants(findTechnique("reference.hard"), RenderParams{}, false).size(), 1u);
}

BenchRow row(const std::string& technique, double ms, double rmse) {
  BenchRow r;
  r.scene = "s";
  r.technique = technique;
  r.frameMs = ms;
  r.primaryReference = "reference.hard";
  r.hard.all.rmse = rmse;
  return r;
}

TEST(BenchPareto, KeepsOnlyUndominatedRows) {
  // (time, error): a (1, 0.5), b (2, 0.2), c (3, 0.3) dominated by b, d (4, 0.1), and a
  // reference (0.5, 0) that is left out by construction.
  const std::vector<BenchRow> rows = {row("a", 1, 0.5), row("b", 2, 0.2), row("c", 3, 0.3),
                                      row("d", 4, 0.1), row("reference.hard", 0.5, 0.0)};
  const std::vector<size_t> front = paretoFront(rows, "s");
  EXPECT_EQ(front, (std::vector<size_t>{0, 1, 3}));
}

TEST(BenchErrors, LeakCountsLitUmbraOutsideTheBand) {
  Image reference(4, 1, 1, 0.0f), mask(4, 1, 1, 0.0f), region(4, 1, 1, 1.0f), band(4, 1, 1, 0.0f);
  mask.data = {0.0f, 0.5f, 0.1f, 1.0f};  // two of four umbra pixels more than 20% lit
  band.data = {0, 0, 0, 1};              // the last one is on the edge band: not a leak
  const ErrorSet e = measureErrors(mask, reference, region, band);
  EXPECT_DOUBLE_EQ(e.leakShare, 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(e.all.maxAbs, 1.0);
  EXPECT_EQ(e.band.pixels, 1);
}

TEST(BenchRun, TinyRunWritesCsvJsonAndPlot) {
  const fs::path dir = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "bench";
  fs::remove_all(dir);
  fs::create_directories(dir);
  BenchOptions o;
  o.quick = true;
  o.scenes = {"brabec"};  // also adds the planner scene brabec-light-away
  o.technique = "modern.hw";
  o.width = 128;
  o.height = 96;
  o.timedFrames = 1;
  o.warmupFrames = 1;
  o.progress = false;
  std::ostringstream json;
  const BenchResult r = runBenchmark(o, json);
  ASSERT_FALSE(r.rows.empty());
  for (const BenchRow& row : r.rows) {
    EXPECT_EQ(row.status, "ok") << row.variant;
    EXPECT_GT(row.frameMs, 0.0);
    EXPECT_FALSE(row.passes.empty());
  }
  size_t lines = 0;
  for (char c : json.str()) lines += c == '\n';
  EXPECT_EQ(lines, r.rows.size()) << "one JSON object per row";
  writeCsv((dir / "bench.csv").string(), r.rows);
  std::ifstream csv(dir / "bench.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_NE(header.find("hard_band_rmse"), std::string::npos);
  bool plannerRows = false;
  for (const BenchRow& row : r.rows) plannerRows |= row.scene == "brabec-light-away";
  EXPECT_TRUE(plannerRows);
  // A plot per scene with a non-zero error (the planner scene has none: no pixel is lit).
  const auto plots = writePlots(dir.string(), r);
  ASSERT_EQ(plots.size(), 1u);
  EXPECT_NE(plots[0].find("bench-brabec.png"), std::string::npos);
  EXPECT_GT(fs::file_size(plots[0]), 1000u);
}

}  // namespace
}  // namespace sl::figures
