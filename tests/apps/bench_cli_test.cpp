// tests/apps/bench_cli_test.cpp — `shadowlab bench` runs the techniques and scenes it is given:
// repeated options and comma-separated lists both count (a repeated --technique used to keep
// only the last one, with exit status 0).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "command_util.h"
#include "core/base/image.h"

namespace sl {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;
using test::CommandResult;

fs::path dir() { return test::testDir("bench-cli"); }

CommandResult shadowlab(const std::string& args) {
  return test::runBinary(SHADOWLAB_BINARY, args, dir());
}

// The (scene, technique) pairs of the rows bench printed for the two scenes the tests name.
std::set<std::pair<std::string, std::string>> rowsOf(const std::string& out) {
  std::set<std::pair<std::string, std::string>> rows;
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    const json row = json::parse(line);
    // The claim scenes bench derives from brabec (trees-far, brabec-light-away) are its own.
    if (row.contains("technique") && (row["scene"] == "brabec" || row["scene"] == "analytic"))
      rows.insert({row["scene"].get<std::string>(), row["technique"].get<std::string>()});
  }
  return rows;
}

// Every row names what made it (commit, command, back end, GL strings, UTC date, load), its
// timing statistics, and the technique's full effective parameters: the common options it
// does not read are null (GPU Gems PCF has no --filter and no --precision; PCF has --filter).
void expectRowsSayWhatMadeThem(const std::string& out) {
  std::istringstream lines(out);
  int rows = 0;
  for (std::string line; std::getline(lines, line);) {
    const json row = json::parse(line);
    if (row.contains("claim")) continue;
    ++rows;
    for (const char* key : {"commit", "command", "backend", "gl_vendor", "gl_renderer",
                            "gl_version", "date", "load_before", "load_after", "params"})
      EXPECT_TRUE(row.contains(key)) << key << " in " << line;
    EXPECT_EQ(row["backend"], "osmesa");
    EXPECT_NE(row["gl_renderer"].get<std::string>().find("llvmpipe"), std::string::npos) << line;
    EXPECT_FALSE(row["gl_vendor"].get<std::string>().empty()) << line;
    // UTC ISO 8601: 2026-12-03T13:05:12Z.
    const std::string date = row["date"];
    EXPECT_EQ(date.size(), 20u) << date;
    EXPECT_EQ(date.substr(10, 1), "T") << date;
    EXPECT_EQ(date.back(), 'Z') << date;
    EXPECT_TRUE(row["load_before"].is_number()) << "Linux has /proc/loadavg";
    ASSERT_TRUE(row["params"].is_object()) << line;
    const std::string technique = row["technique"];
    if (technique == "modern.gems16") {
      EXPECT_TRUE(row["filter"].is_null()) << line;
      EXPECT_TRUE(row["precision"].is_null()) << line;
      EXPECT_FALSE(row["params"].contains("filter")) << line;
      EXPECT_TRUE(row["params"].contains("samples")) << "a declared --param, given or default";
    }
    if (technique == "modern.pcf") {
      EXPECT_TRUE(row["filter"].is_number_integer()) << line;
      EXPECT_EQ(row["params"]["filter"], row["filter"]) << line;
    }
    if (row["status"] == "ok") {
      const int frames = row["frames_timed"];
      EXPECT_GE(frames, 1);
      EXPECT_GE(row["frame_iqr_ms"].get<double>(), 0.0);
      EXPECT_LE(row["frame_min_ms"].get<double>(), row["frame_ms"].get<double>());
      EXPECT_TRUE(row["spread_large"].is_boolean());
    }
  }
  EXPECT_GT(rows, 0);
}

// Within each scene, window and orbit, no ranked row is dominated by a row of a better rank,
// and rank 1 rows are dominated by no row.
void expectRanksArePareto(const std::vector<json>& rows) {
  auto group = [](const json& r) {
    return r["scene"].get<std::string>() + "|" + std::to_string(r["width"].get<int>()) + "x" +
           std::to_string(r["height"].get<int>()) + "|" +
           (r["orbit"].is_string() ? r["orbit"].get<std::string>() : "");
  };
  auto ranked = [](const json& r) { return r["pareto_rank"].is_number(); };
  int ranks = 0;
  for (const json& a : rows) {
    if (!ranked(a)) continue;
    ++ranks;
    for (const json& b : rows) {
      if (!ranked(b) || group(a) != group(b)) continue;
      const double ta = a["frame_ms"], tb = b["frame_ms"];
      const double ea = a["error"]["rmse"], eb = b["error"]["rmse"];
      const bool bDominatesA = tb <= ta && eb <= ea && (tb < ta || eb < ea);
      if (bDominatesA) {
        EXPECT_LT(b["pareto_rank"].get<int>(), a["pareto_rank"].get<int>())
            << b.dump() << " dominates " << a.dump();
      }
    }
  }
  EXPECT_GT(ranks, 0);
}

// The error-against-time plots carry the tEXt chunks of render's PNGs.
void expectPlotsCarryProvenance(const fs::path& out) {
  int plots = 0;
  for (const auto& entry : fs::directory_iterator(out)) {
    if (entry.path().extension() != ".png") continue;
    ++plots;
    const std::map<std::string, std::string> text = readPngText(entry.path().string());
    EXPECT_EQ(text.count("Software"), 1u) << entry.path();
    ASSERT_EQ(text.count("shadowlab:parameters"), 1u) << entry.path();
    EXPECT_NE(text.at("shadowlab:parameters").find("\"scene\""), std::string::npos);
    ASSERT_EQ(text.count("shadowlab:command"), 1u) << entry.path();
    EXPECT_NE(text.at("shadowlab:command").find("bench"), std::string::npos);
  }
  EXPECT_GT(plots, 0) << "gnuplot is a dependency of the project (scripts/setup.sh)";
}

// A tiny window: the references and two techniques' variants in a few seconds.
constexpr const char* kTiny = " --quick --size 48x36 --out ";

TEST(BenchCli, RepeatedAndListedTechniquesAndScenesAllRun) {
  const std::set<std::pair<std::string, std::string>> expected = {{"brabec", "modern.pcf"},
                                                                  {"brabec", "modern.gems16"},
                                                                  {"analytic", "modern.pcf"},
                                                                  {"analytic", "modern.gems16"}};
  const CommandResult repeated = shadowlab(
      "bench --scene brabec --scene analytic --technique modern.pcf --technique "
      "modern.gems16" +
      std::string(kTiny) + (dir() / "repeated").string());
  ASSERT_EQ(repeated.status, 0) << repeated.err;
  EXPECT_EQ(rowsOf(repeated.out), expected);
  expectRowsSayWhatMadeThem(repeated.out);
  expectPlotsCarryProvenance(dir() / "repeated");
  const CommandResult listed = shadowlab(
      "bench --scene brabec,analytic --technique "
      "modern.pcf,modern.gems16" +
      std::string(kTiny) + (dir() / "listed").string());
  ASSERT_EQ(listed.status, 0) << listed.err;
  EXPECT_EQ(rowsOf(listed.out), expected);

  // The two runs merged: every row of both, ranks recomputed over all of them per scene and
  // window (a row of one run can push a row of the other off the front).
  std::ofstream(dir() / "repeated.jsonl") << repeated.out;
  std::ofstream(dir() / "listed.jsonl") << listed.out;
  const CommandResult merged = shadowlab("bench --merge " + (dir() / "repeated.jsonl").string() +
                                         " --merge " + (dir() / "listed.jsonl").string());
  ASSERT_EQ(merged.status, 0) << merged.err;
  std::vector<json> rows;
  std::istringstream lines(merged.out);
  for (std::string line; std::getline(lines, line);) rows.push_back(json::parse(line));
  size_t inputRows = 0;
  for (const std::string* out : {&repeated.out, &listed.out}) {
    std::istringstream in(*out);
    for (std::string line; std::getline(in, line);)
      inputRows += json::parse(line).contains("claim") ? 0 : 1;
  }
  EXPECT_EQ(rows.size(), inputRows) << "every row of both runs, no claim lines";
  expectRanksArePareto(rows);
  // A file that is not bench rows: exit 2 naming the file and the line.
  std::ofstream(dir() / "not-rows.jsonl") << "{\"hello\": 1}\n";
  const CommandResult bad = shadowlab("bench --merge " + (dir() / "not-rows.jsonl").string());
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("not-rows.jsonl line 1"), std::string::npos) << bad.err;
  EXPECT_TRUE(bad.out.empty());
}

TEST(BenchCli, ASweepFileRunsItsRowsInOrderWithTheirViews) {
  // Two techniques x two views (the scene's camera and one orbit): gems16 sweeps its samples,
  // pcf its filter; the references of each view are rendered once.
  const fs::path spec = dir() / "sweep.json";
  std::ofstream(spec) << R"({"techniques": ["modern.gems16", "modern.pcf"], "scenes": ["fence"],
      "sizes": ["48x36"], "filters": [1, 3], "params": {"samples": [1, 16]},
      "orbits": [null, "30,25,9"], "repeat": 2, "soft_reference": false, "temporal": false})";
  const fs::path csv = dir() / "sweep.csv";
  const CommandResult r = shadowlab("bench --sweep " + spec.string() + " --csv " + csv.string());
  ASSERT_EQ(r.status, 0) << r.err;
  std::vector<json> rows;
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);) rows.push_back(json::parse(line));
  const std::vector<std::string> variants = {"samples=1", "samples=16", "filter=1", "filter=3"};
  ASSERT_EQ(rows.size(), 2 * variants.size()) << r.out;
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i]["variant"], variants[i % variants.size()]) << i;
    EXPECT_EQ(rows[i]["orbit"], i < variants.size() ? json(nullptr) : json("30,25,9")) << i;
    EXPECT_EQ(rows[i]["status"], "ok") << rows[i].dump();
    EXPECT_EQ(rows[i]["frames_timed"], 2) << rows[i].dump();
  }
  expectRowsSayWhatMadeThem(r.out);
  expectRanksArePareto(rows);
  // The CSV's params column holds the same JSON object as the line's "params".
  std::ifstream in(csv);
  std::string header, first;
  std::getline(in, header);
  std::getline(in, first);
  const size_t open = first.find("\"{"), close = first.find("}\"");
  ASSERT_NE(open, std::string::npos) << first;
  std::string text = first.substr(open + 1, close - open);
  // CSV doubles a quote inside a quoted field (RFC 4180 §2.7): undo it.
  std::string unquoted;
  for (size_t i = 0; i < text.size(); ++i) {
    unquoted += text[i];
    if (text[i] == '"' && i + 1 < text.size() && text[i + 1] == '"') ++i;
  }
  text = unquoted;
  EXPECT_EQ(json::parse(text), rows[0]["params"]) << first;
  EXPECT_NE(header.find("frame_iqr_ms"), std::string::npos);
  EXPECT_NE(header.find("gl_renderer"), std::string::npos);
  // Options the file decides are refused beside it.
  const CommandResult both = shadowlab("bench --sweep " + spec.string() + " --technique modern.hw");
  EXPECT_EQ(both.status, 2);
  EXPECT_NE(both.err.find("--sweep does not take --technique"), std::string::npos) << both.err;
}

TEST(BenchCli, AnUnknownOrEmptyNameInAListIsAnInputError) {
  const CommandResult unknown = shadowlab("bench --technique modern.pcf,modern.nope" +
                                          std::string(kTiny) + (dir() / "unknown").string());
  EXPECT_EQ(unknown.status, 2) << unknown.err;
  EXPECT_NE(unknown.err.find("modern.nope"), std::string::npos) << unknown.err;
  EXPECT_TRUE(unknown.out.empty());
  const CommandResult empty = shadowlab("bench --technique modern.pcf, --scene brabec" +
                                        std::string(kTiny) + (dir() / "empty").string());
  EXPECT_EQ(empty.status, 2) << empty.err;
  EXPECT_NE(empty.err.find("--technique 'modern.pcf,': an empty name"), std::string::npos)
      << empty.err;
}

}  // namespace
}  // namespace sl
