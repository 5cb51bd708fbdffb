// measure/bench_command.cpp — `shadowlab bench`: its options, and the runs of its three modes
// (the sweep of every technique with CSV, plots and claim checks; --sweep FILE.json; --merge).
#include <algorithm>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "core/base/errors.h"
#include "core/base/output_files.h"
#include "core/gl/gl.h"
#include "core/scene/scene_library.h"
#include "measure/bench.h"
#include "measure/sweep.h"
#include "registry/registry.h"

namespace sl::figures {

BenchOptions parseBenchOptions(const cli::Args& args) {
  BenchOptions options;
  options.quick = args.has("quick");
  // --scene and --technique: repeatable, each value also a comma-separated list; every name
  // given is kept (in order, once).
  auto listed = [&](const char* key) {
    std::vector<std::string> names;
    if (auto it = args.options.find(key); it != args.options.end())
      for (const std::string& value : it->second) {
        size_t start = 0;
        for (size_t comma; start <= value.size(); start = comma + 1) {
          comma = value.find(',', start);
          if (comma == std::string::npos) comma = value.size();
          const std::string name = value.substr(start, comma - start);
          if (name.empty())
            throw InputError(std::string("--") + key + " '" + value + "': an empty name");
          if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
        }
      }
    return names;
  };
  options.scenes = listed("scene");
  options.techniques = listed("technique");
  options.csvPath = args.value("csv");
  if (auto out = args.value("out")) options.outDir = *out;
  if (auto size = args.value("size")) cli::parseSize(*size, options.width, options.height);
  if (auto b = args.value("backend")) options.backend = parseBackend(*b);
  if (auto r = args.value("repeat"))
    options.timedFrames = cli::parsePositiveInt("--repeat", *r, 1000);
  if (auto b = args.value("budget-ms")) options.budgetMs = parseBudgetMs(*b);
  // Bad names fail before any work.
  for (const std::string& s : options.scenes) loadScene(s);
  for (const std::string& t : options.techniques) findTechnique(t);
  return options;
}

namespace {
// The options --sweep and --merge take from elsewhere (the spec, the merged files).
void rejectWith(const cli::Args& args, const std::string& mode,
                const std::vector<std::string>& options) {
  for (const std::string& o : options)
    if (args.has(o))
      throw InputError(mode + " does not take --" + o +
                       (mode == "--sweep" ? " (the sweep file says what to run)"
                                          : " (the merged rows are printed as they were run)"));
}

// `bench --merge A.jsonl B.jsonl ...`: the rows on stdout with their Pareto ranks recomputed.
int runBenchMerge(const cli::Args& args) {
  rejectWith(args, "--merge",
             {"sweep", "quick", "scene", "technique", "csv", "size", "backend", "repeat", "out",
              "budget-ms"});
  const std::vector<nlohmann::json> rows = mergeBenchRows(args.options.at("merge"));
  for (const nlohmann::json& row : rows)
    std::cout << row.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  std::cerr << "bench: merged " << rows.size() << " rows from " << args.options.at("merge").size()
            << " files; Pareto ranks recomputed per scene, window and orbit\n";
  return 0;
}

// `bench --sweep FILE.json`: the rows of a sweep spec (measure/sweep.h), one JSON line each
// in the spec's order, with Pareto ranks within each view; --csv as the bench's.
int runBenchSweep(const cli::Args& args) {
  rejectWith(args, "--sweep",
             {"quick", "scene", "technique", "size", "backend", "repeat", "budget-ms", "out"});
  const std::string path = *args.value("sweep");
  std::ifstream in(path);
  if (!in) throw InputError("--sweep " + path + ": cannot open it");
  const nlohmann::json spec = nlohmann::json::parse(in, nullptr, false);
  if (spec.is_discarded()) throw InputError("--sweep " + path + ": not valid JSON");
  const SweepPlan plan = planSweep(spec);
  OutputSet outputs;
  outputs.addInput(path);
  std::optional<std::string> csv;
  if (auto file = args.value("csv")) csv = outputs.addFile("--csv", *file);
  SweepReferenceCache cache;
  std::vector<BenchRow> rows;
  std::vector<std::string> groups;
  for (size_t i = 0; i < plan.rows.size(); ++i) {
    BenchRow row = measureSweepRows(plan, {i}, cache).front();
    const SweepView& view = plan.views[plan.rows[i].view];
    groups.push_back(rankGroup(view.scene, view.width, view.height, view.orbit.value_or("")));
    std::cerr << "bench: sweep row " << i + 1 << "/" << plan.rows.size() << " " << row.scene << " "
              << row.technique << " " << row.variant << ": "
              << (row.status == "ok" ? std::to_string(row.frameMs) + " ms" : row.status) << "\n";
    rows.push_back(std::move(row));
  }
  assignSweepParetoRanks(rows, groups);
  for (const BenchRow& row : rows) std::cout << benchRowJsonLine(row) << "\n";
  std::cout << std::flush;
  if (csv) {
    writeCsv(*csv, rows);
    outputs.commit();
    std::cerr << "bench: wrote " << *args.value("csv") << "\n";
  }
  return 0;
}
}  // namespace

int runBenchCommand(const cli::Args& args) {
  if (args.options.count("merge")) return runBenchMerge(args);
  if (args.value("sweep")) return runBenchSweep(args);
  const BenchOptions options = parseBenchOptions(args);
  // Unwritable destinations fail before any work (core/base/output_files.h): the CSV is written to
  // a temporary and renamed at the end; the plots' folder must be writable.
  OutputSet outputs;
  for (const std::string& s : options.scenes) outputs.addInput(s);
  std::optional<std::string> csv;
  if (options.csvPath) csv = outputs.addFile("--csv", *options.csvPath);
  checkDirectoryCreatable("--out", options.outDir);
  const BenchResult result = runBenchmark(options, std::cout);
  if (csv) {
    writeCsv(*csv, result.rows);
    outputs.commit();
    std::cerr << "bench: wrote " << *options.csvPath << "\n";
  }
  try {
    const BenchPlots plots = writePlots(options.outDir, result);
    for (const BenchPlot& p : plots.plots) std::cerr << "bench: wrote " << p.path << "\n";
    for (const auto& [scene, note] : plots.notes)
      std::cerr << "bench: " << scene << ": " << note << "\n";
  } catch (const InputError& e) {
    std::cerr << "bench: " << e.what() << "\n";
  }
  for (const ClaimCheck& c : checkClaims(result)) {
    std::cout << nlohmann::json{{"claim", c.id},          {"source", c.source},
                                {"statement", c.claim},   {"scene", c.scene},
                                {"measured", c.measured}, {"verdict", c.verdict},
                                {"setup", c.setup}}
                     .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)
              << "\n";
    std::cerr << "claim " << c.id << " (" << c.source << ") on " << c.scene << ": " << c.verdict
              << "\n    " << c.claim << "\n    setup: " << c.setup
              << "\n    measured: " << c.measured << "\n";
  }
  // The answer to "which technique at this budget", last so that it ends the run's output
  // (stderr, with the other human-readable lines; stdout stays JSON lines).
  if (options.budgetMs) printBudgetRanking(std::cerr, result.rows, *options.budgetMs);
  return 0;
}

}  // namespace sl::figures
