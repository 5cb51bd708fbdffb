// figures/figures.h — the reproduced paper figures and tables, the report, the benchmark and
// the pass planner entry points of the shadowlab command.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "apps/cli.h"

namespace sl::figures {

struct FigureInfo {
  std::string id;
  std::string title;
};

std::vector<FigureInfo> listFigures();
// Renders every figure (or only `only`) into outDir and writes outDir/report.html.
int runFigures(const std::string& outDir, const std::optional<std::string>& only, bool progress);
int runBench(const cli::Args& args);
int runPlan(const cli::Args& args);

}  // namespace sl::figures
