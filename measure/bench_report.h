// measure/bench_report.h — the quick bench as a section of report.html: a table in the report,
// a plot of error against time, and the claims' verdicts.
#pragma once

#include <string>

namespace sl::figures {

// Runs `shadowlab bench --quick` into outDir/bench (CSV, JSON lines, gnuplot plots) and
// returns the report's HTML section: the default variant of every technique per scene, the
// plots, and each paper claim with its measured numbers and verdict.
std::string runQuickBenchForReport(const std::string& outDir, bool progress);

}  // namespace sl::figures
