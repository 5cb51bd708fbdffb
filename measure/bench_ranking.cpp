// measure/bench_ranking.cpp — the bench rows ordered and ranked: the Pareto front and ranks on
// (frame time, primary RMSE), the output order, the --budget-ms ranking, and `bench --merge`'s
// rows of several runs re-ranked (measure/bench.h).
#include <algorithm>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tuple>

#include "core/base/decimal.h"
#include "core/base/errors.h"
#include "measure/bench.h"
#include "registry/registry.h"

namespace sl::figures {

namespace {
// A row of the ray-traced truth, not a competitor (Technique::family). A row that names a
// technique this build lacks (merged from another build's bench) is a competitor.
bool isReferenceRow(const BenchRow& r) {
  const Technique* t = techniqueNamed(r.technique);
  return t != nullptr && t->family == TechniqueFamily::kReference;
}
}  // namespace

std::vector<size_t> paretoFront(const std::vector<BenchRow>& rows, const std::string& scene) {
  std::vector<size_t> candidates;
  for (size_t i = 0; i < rows.size(); ++i)
    if (rows[i].scene == scene && rows[i].status == "ok" && !isReferenceRow(rows[i]))
      candidates.push_back(i);
  std::sort(candidates.begin(), candidates.end(), [&](size_t a, size_t b) {
    return rows[a].frameMs != rows[b].frameMs
               ? rows[a].frameMs < rows[b].frameMs
               : rows[a].primary().all.rmse < rows[b].primary().all.rmse;
  });
  std::vector<size_t> front;
  double best = 1e300;
  for (size_t i : candidates)
    if (rows[i].primary().all.rmse < best) {
      best = rows[i].primary().all.rmse;
      front.push_back(i);
    }
  return front;
}

namespace {
bool isRankedRow(const BenchRow& r) {  // a competitor: ran, and not a reference (the truth)
  return r.status == "ok" && !isReferenceRow(r);
}
// a no slower and no worse than b, and strictly better in one of the two.
bool dominates(const BenchRow& a, const BenchRow& b) {
  const double ea = a.primary().all.rmse, eb = b.primary().all.rmse;
  return a.frameMs <= b.frameMs && ea <= eb && (a.frameMs < b.frameMs || ea < eb);
}
}  // namespace

void assignParetoRanks(std::vector<BenchRow>& rows) {
  std::map<std::string, std::vector<size_t>> unranked;  // scene -> its competitors
  for (size_t i = 0; i < rows.size(); ++i) {
    rows[i].paretoRank = 0;
    if (isRankedRow(rows[i])) unranked[rows[i].scene].push_back(i);
  }
  for (auto& [scene, left] : unranked) {
    // Peel the fronts: rank k = the rows no remaining row dominates.
    for (int rank = 1; !left.empty(); ++rank) {
      std::vector<size_t> front, rest;
      for (size_t i : left) {
        const bool dominated = std::any_of(left.begin(), left.end(),
                                           [&](size_t j) { return dominates(rows[j], rows[i]); });
        (dominated ? rest : front).push_back(i);
      }
      for (size_t i : front) rows[i].paretoRank = rank;
      left = std::move(rest);
    }
  }
}

void sortRowsBySceneThenTime(std::vector<BenchRow>& rows) {
  std::stable_sort(rows.begin(), rows.end(), [](const BenchRow& a, const BenchRow& b) {
    const bool aRan = a.status == "ok", bRan = b.status == "ok";
    return std::tie(a.scene, bRan, a.frameMs, a.technique, a.variant) <
           std::tie(b.scene, aRan, b.frameMs, b.technique, b.variant);
  });
}

double parseBudgetMs(const std::string& text) {
  const std::optional<double> v = parseDecimal(text);  // strict: no hex, inf, nan or spaces
  if (!v || !(*v > 0.0))
    throw InputError("--budget-ms must be a positive number of milliseconds, got '" + text + "'");
  return *v;
}

std::vector<BudgetRanking> rankWithinBudget(const std::vector<BenchRow>& rows, double budgetMs) {
  std::vector<BudgetRanking> out;
  auto sceneRanking = [&](const std::string& scene) -> BudgetRanking& {
    for (BudgetRanking& r : out)
      if (r.scene == scene) return r;
    out.push_back({scene, {}, 0, 0});
    return out.back();
  };
  for (size_t i = 0; i < rows.size(); ++i) {
    const BenchRow& r = rows[i];
    if (isReferenceRow(r)) continue;  // the truth, not a competitor
    BudgetRanking& s = sceneRanking(r.scene);
    if (r.status != "ok")
      ++s.notRun;
    else if (r.frameMs <= budgetMs)
      s.within.push_back(i);
    else
      ++s.overBudget;
  }
  for (BudgetRanking& s : out)
    std::stable_sort(s.within.begin(), s.within.end(), [&](size_t a, size_t b) {
      const double ea = rows[a].primary().all.rmse, eb = rows[b].primary().all.rmse;
      return ea != eb ? ea < eb : rows[a].frameMs < rows[b].frameMs;
    });
  return out;
}

void printBudgetRanking(std::ostream& out, const std::vector<BenchRow>& rows, double budgetMs) {
  auto variants = [](size_t n) { return std::to_string(n) + (n == 1 ? " variant" : " variants"); };
  for (const BudgetRanking& s : rankWithinBudget(rows, budgetMs)) {
    out << "budget " << fixedDecimals(budgetMs, 1) << " ms, scene " << s.scene << ": "
        << variants(s.within.size())
        << " within budget, ranked by RMSE against the pixel-integrated reference\n";
    if (!s.within.empty())
      out << "  " << std::left << std::setw(4) << "#" << std::setw(20) << "technique"
          << std::setw(44) << "variant" << std::right << std::setw(9) << "ms" << std::setw(9)
          << "RMSE" << std::setw(9) << "band" << std::setw(20) << "temporal (ref)" << std::setw(8)
          << "pareto"
          << "\n";
    int place = 0;
    for (size_t i : s.within) {
      const BenchRow& r = rows[i];
      const std::string temporal =
          (r.temporalChange >= 0 ? fixedDecimals(r.temporalChange, 5) : std::string("-")) + " (" +
          (r.referenceTemporalChange >= 0 ? fixedDecimals(r.referenceTemporalChange, 5)
                                          : std::string("-")) +
          ")";
      out << "  " << std::left << std::setw(4) << std::to_string(++place) + "." << std::setw(20)
          << r.technique << std::setw(44) << r.variant << std::right << std::setw(9)
          << fixedDecimals(r.frameMs, 2) << std::setw(9) << fixedDecimals(r.primary().all.rmse, 4)
          << std::setw(9) << fixedDecimals(r.primary().band.rmse, 4) << std::setw(20) << temporal
          << std::setw(8) << r.paretoRank << "\n";
    }
    out << "  " << variants(size_t(s.overBudget)) << " over budget";
    if (s.notRun > 0)
      out << ", " << variants(size_t(s.notRun)) << " did not run (see their status)";
    out << "\n";
  }
}

bool timesWithinSpread(const BenchRow& a, const BenchRow& b) {
  if (a.framesTimed == 0 || b.framesTimed == 0) return false;  // no timing statistics to judge
  return a.q1Ms <= b.q3Ms && b.q1Ms <= a.q3Ms;
}

std::string rankGroup(const std::string& scene, int width, int height, const std::string& orbit) {
  return scene + "|" + std::to_string(width) + "x" + std::to_string(height) + "|" + orbit;
}

std::vector<nlohmann::json> mergeBenchRows(const std::vector<std::string>& paths) {
  using Json = nlohmann::json;
  std::vector<Json> lines;
  std::vector<BenchRow> rows;  // what the ranking reads of each line
  for (const std::string& path : paths) {
    std::ifstream in(path);
    if (!in) throw InputError("--merge " + path + ": cannot open it");
    std::string text;
    for (int number = 1; std::getline(in, text); ++number) {
      if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
      const std::string where = "--merge " + path + " line " + std::to_string(number);
      Json j = Json::parse(text, nullptr, false);
      if (j.is_discarded() || !j.is_object()) throw InputError(where + ": not a JSON object");
      if (j.contains("claim")) continue;  // a claim's verdict, not a row
      for (const char* key : {"scene", "technique", "status", "reference", "width", "height"})
        if (!j.contains(key))
          throw InputError(where + ": not a bench row (no \"" + key +
                           "\"; rows of this version's bench carry it)");
      BenchRow r;
      try {
        const std::string orbit = j.value("orbit", Json(nullptr)).is_string()
                                      ? j.at("orbit").get<std::string>()
                                      : std::string();
        r.scene = rankGroup(j.at("scene").get<std::string>(), j.at("width").get<int>(),
                            j.at("height").get<int>(), orbit);
        r.technique = j.at("technique").get<std::string>();
        r.status = j.at("status").get<std::string>();
        r.primaryReference = j.at("reference").get<std::string>();
        if (r.status == "ok") {
          r.frameMs = j.at("frame_ms").get<double>();
          const double rmse = j.at("error").at("rmse").get<double>();
          (r.primaryIsSoft() ? r.soft : r.hard).all.rmse = rmse;
        }
      } catch (const Json::exception& e) {
        throw InputError(where + ": a field of the wrong type (" + e.what() + ")");
      }
      lines.push_back(std::move(j));
      rows.push_back(std::move(r));
    }
  }
  assignParetoRanks(rows);
  for (size_t i = 0; i < rows.size(); ++i)
    lines[i]["pareto_rank"] = rows[i].paretoRank > 0 ? Json(rows[i].paretoRank) : Json(nullptr);
  return lines;
}

}  // namespace sl::figures
