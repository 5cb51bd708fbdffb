// figures/figures.h — the reproduced paper figures and tables, the report, the benchmark and
// the pass planner entry points of the shadowlab command.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "registry/cli.h"
#include "core/image.h"
#include "figures/report.h"

namespace sl::figures {

struct FigureInfo {
  std::string id;
  std::string title;
};

std::vector<FigureInfo> listFigures();
struct FigureOverrides;  // figures/overrides.h

// Renders every figure (or only `only`) into outDir and writes outDir/report.html. With
// overrides (figures --set, only with `only`): the figure re-made with them, into
// outDir/ID--<overrides>/ (figures/overrides.h applyOverrides).
int runFigures(const std::string& outDir, const std::optional<std::string>& only, bool progress,
               const FigureOverrides& overrides);
int runBench(const cli::Args& args);

// figure.png: the figure laid out as the paper lays it out, in rows of spec.columns tiles, then
// the close-ups in rows of spec.columns. Every panel gives its tiles in order: each image it
// made (a buffer panel every buffer it shows, a chart its chart), or one dark red block of the
// panel's size when it could not be made. Tiles are top-aligned, 6 pixels apart; a composite
// wider than 1600 pixels is shrunk by the smallest integer factor that fits (box filter).
// Images are read from outDir (the files PanelResult names). A figure without panels: empty.
Image composeFigure(const FigureResult& fig, const std::string& outDir);
int runPlan(const cli::Args& args);

}  // namespace sl::figures
