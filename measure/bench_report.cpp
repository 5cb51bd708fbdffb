#include "measure/bench_report.h"

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/base/decimal.h"
#include "core/base/errors.h"
#include "core/base/html.h"
#include "core/base/output_files.h"
#include "core/scene/scene_library.h"
#include "measure/bench.h"

namespace sl::figures {
namespace fs = std::filesystem;

namespace {

// The quick bench's claim verdicts as the last run before the one error definition
// (docs/error.md) printed them: assets/bench/claims-before-error-definition.json, the claim
// lines of that run's stdout with the commit and command that made them. Key: "id|scene".
struct PreviousVerdicts {
  std::string madeBy;
  std::map<std::string, std::string> verdicts;
};
PreviousVerdicts previousVerdicts() {
  PreviousVerdicts p;
  std::ifstream in(fs::path(assetDirectory()) / "bench" / "claims-before-error-definition.json");
  if (!in) return p;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    p.madeBy = j.at("made_by").get<std::string>();
    for (const nlohmann::json& c : j.at("claims"))
      p.verdicts[c.at("claim").get<std::string>() + "|" + c.at("scene").get<std::string>()] =
          c.at("verdict").get<std::string>();
  } catch (const nlohmann::json::exception& e) {
    std::cerr << "bench report: claims-before-error-definition.json unreadable: " << e.what()
              << "\n";
    return {};
  }
  return p;
}

// "agrees" / "disagrees" / ...: a verdict's first word, what a change of verdict is judged on.
std::string verdictWord(const std::string& verdict) {
  return verdict.substr(0, verdict.find_first_of(" ("));
}

}  // namespace

std::string runQuickBenchForReport(const std::string& outDir, bool progress) {
  BenchOptions options;
  options.quick = true;
  options.outDir = (fs::path(outDir) / "bench").string();
  options.csvPath = (fs::path(options.outDir) / "bench.csv").string();
  options.progress = progress;
  fs::create_directories(options.outDir);
  std::ostringstream json;  // bench.jsonl appears whole, after the bench
  const BenchResult result = runBenchmark(options, json);
  writeFileAtomically((fs::path(options.outDir) / "bench.jsonl").string(),
                      [&](std::ostream& out) { out << json.str(); });
  writeCsv(*options.csvPath, result.rows);
  BenchPlots plots;
  std::string plotsMissing;
  try {
    plots = writePlots(options.outDir, result);
  } catch (const InputError& e) {
    plotsMissing = e.what();
    if (progress) std::cerr << "bench: " << e.what() << "\n";
  }
  const std::vector<ClaimCheck> claims = checkClaims(result);

  std::ostringstream h;
  h << "<h2 id=bench>Error against run time (<code>shadowlab bench --quick</code>)</h2>\n"
    << "<p>Every technique's default variant on the benchmark scenes: the median frame time "
       "of the timed frames and the error of its visibility mask against the ray-traced "
       "reference, integrated over each pixel's area (<code>--param pixel=area</code>: 8x8 "
       "sub-pixel shadow rays for reference.hard; rays from 4x4 sub-pixel points for "
       "reference.soft, the truth of smoothies; reference.hard for every other technique), "
       "counted where the light can reach; <em>centre</em> = the same RMSE against the "
       "pixel-centre reference (one ray per pixel, itself aliased); <em>band</em> = within 2 "
       "pixels of a reference shadow edge; <em>leak</em> = share of umbra pixels shown more "
       "than 20% lit; <em>temporal</em> = mean |change| of the mask when the light moves "
       "sideways by a fifth of a 512-map texel, beside the reference's own change (what the "
       "true shadow moves). Every variant is in <a href=\"bench/bench.csv\">bench/bench.csv</a>; "
       "regenerate with <code>shadowlab bench --quick --csv bench.csv</code>.</p>\n";
  // Per scene: one plot per technique family, the numbered Pareto front, and what is not drawn.
  if (!plotsMissing.empty()) h << "<p class=bad>No plots: " << htmlEscape(plotsMissing) << "</p>\n";
  std::set<std::string> scenes;
  for (const BenchRow& r : result.rows) scenes.insert(r.scene);
  for (const std::string& scene : scenes) {
    h << "<h3>Scene <code>" << htmlEscape(scene) << "</code></h3>\n<div class=plots>";
    for (const BenchPlot& plot : plots.plots)
      if (plot.scene == scene)
        h << "<figure><img src=\"bench/" << htmlEscape(fs::path(plot.path).filename().string())
          << "\" alt=\"error against time, " << htmlEscape(scene) << ", " << htmlEscape(plot.family)
          << "\"><figcaption>" << htmlEscape(plot.family)
          << ": RMSE against median frame time, log axes fitted to the scene's techniques "
             "(references are the truth, not plotted)</figcaption></figure>";
    h << "</div>\n";
    if (const auto front = plots.pareto.find(scene); front != plots.pareto.end()) {
      h << "<p><small>Pareto front (grey, numbered):";
      for (const std::string& point : front->second) h << "<br>" << htmlEscape(point);
      h << "</small></p>\n";
    }
    if (const auto why = result.sceneNotes.find(scene); why != result.sceneNotes.end())
      h << "<p class=note><small>" << htmlEscape(why->second) << "</small></p>\n";
    if (const auto note = plots.notes.find(scene); note != plots.notes.end())
      h << "<p class=note><small>" << htmlEscape(note->second) << "</small></p>\n";
  }
  h << "<table><tr><th>scene</th><th>technique</th><th>frame ms</th><th>RMSE</th>"
       "<th>RMSE (centre)</th><th>max</th><th>&gt; 0.5</th><th>band RMSE</th><th>leak</th>"
       "<th>temporal (reference)</th></tr>\n";
  for (const BenchRow& r : result.rows) {
    if (r.variant != "default") continue;
    const ErrorSet& e = r.primary();
    const ErrorSet& point = r.primaryIsSoft() ? r.softPoint : r.hardPoint;
    h << "<tr><td>" << htmlEscape(r.scene) << "</td><td><code>" << htmlEscape(r.technique)
      << "</code></td>";
    if (r.status != "ok") {
      h << "<td colspan=8 class=bad>" << htmlEscape(r.status) << "</td></tr>\n";
      continue;
    }
    h << "<td>" << fixedDecimals(r.frameMs, 1) << "</td><td>" << fixedDecimals(e.all.rmse, 4)
      << "</td><td>" << fixedDecimals(point.all.rmse, 4) << "</td><td>"
      << fixedDecimals(e.all.maxAbs, 2) << "</td><td>" << fixedDecimals(e.all.shareAboveHalf, 4)
      << "</td><td>" << fixedDecimals(e.band.rmse, 3) << "</td><td>"
      << fixedDecimals(e.leakShare, 4) << "</td><td>"
      << (r.temporalChange >= 0 ? fixedDecimals(r.temporalChange, 5) : std::string("-")) << " ("
      << (r.referenceTemporalChange >= 0 ? fixedDecimals(r.referenceTemporalChange, 5)
                                         : std::string("-"))
      << ")</td></tr>\n";
  }
  const PreviousVerdicts before = previousVerdicts();
  h << "</table>\n<h3>The papers' comparative claims, checked on these measurements</h3>\n";
  if (!before.madeBy.empty())
    h << "<p>Errors are scored by the one definition of <code>docs/error.md</code> (area "
         "metric, scored pixels only). The column <em>before</em> is the verdict of the last "
         "run before it ("
      << htmlEscape(before.madeBy)
      << "); <b>changed</b> marks the "
         "verdicts it changed. The error halves of a verdict repeat exactly from run to run; "
         "its time half (\"not cheaper\") moves with the load of a shared machine, so a time "
         "verdict that changed here may change back in the next run.</p>\n";
  h << "<table><tr><th>claim</th><th>source</th><th>scene</th><th>verdict</th>"
    << (before.madeBy.empty() ? "" : "<th>before</th>") << "<th>setup</th><th>measured</th></tr>\n";
  for (const ClaimCheck& c : claims) {
    h << "<tr><td>" << htmlEscape(c.claim) << "</td><td>" << htmlEscape(c.source) << "</td><td>"
      << htmlEscape(c.scene)
      << "</td><td class=" << (c.verdict.rfind("agrees", 0) == 0 ? "ok" : "bad") << ">"
      << htmlEscape(c.verdict) << "</td>";
    if (!before.madeBy.empty()) {
      const auto it = before.verdicts.find(c.id + "|" + c.scene);
      if (it == before.verdicts.end())
        h << "<td>(not checked then)</td>";
      else
        h << "<td>" << (verdictWord(it->second) != verdictWord(c.verdict) ? "<b>changed</b>: " : "")
          << htmlEscape(it->second) << "</td>";
    }
    h << "<td>" << htmlEscape(c.setup) << "</td><td>" << htmlEscape(c.measured) << "</td></tr>\n";
  }
  h << "</table>\n<p>Timings are llvmpipe on this machine; compare them within this "
       "table.</p>\n";
  return h.str();
}

}  // namespace sl::figures
