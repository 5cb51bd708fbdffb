// figures/figures.h — the reproduced paper figures and tables, the report, the benchmark and
// the pass planner entry points of the shadowlab command.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/base/image.h"
#include "figures/figure_composite.h"
#include "figures/report.h"
#include "registry/cli.h"

namespace sl::figures {

struct FigureInfo {
  std::string id;
  std::string title;
};

std::vector<FigureInfo> listFigures();
struct FigureOverrides;  // figures/overrides.h

// Renders every figure (or only the ids in `only`) into outDir, a lesson per technique into
// outDir/lessons/ (teach/lesson.h; with `only`, the techniques those figures show) and writes
// outDir/report.html, which links them. With overrides (figures --set, with exactly one --only):
// the figure re-made with them, into outDir/ID--<overrides>/ (figures/overrides.h).
int runFigures(const std::string& outDir, const std::vector<std::string>& only, bool progress,
               const FigureOverrides& overrides);
int runBench(const cli::Args& args);

// figure.png: the figure laid out as the paper lays it out, in rows of spec.columns tiles, then
// the close-ups: one row per row of tiles and close-up number, each close-up under the left edge
// of the tile it magnifies (pushed right only where the close-up before it is wider than its
// tile). Every panel gives its tiles in order: each image it
// made (a buffer panel every buffer it shows, a chart its chart), or one dark red block of the
// panel's size when it could not be made. Every tile sits under its label drawn as text: the
// panel's letter and label (letters (a), (b), ... added when the figure's labels have none) and
// technique, a buffer's caption (its channel names), a close-up's caption, a missing panel's
// reason (figures/figure_composite.h: layout, shrinking, the font). Images are read from outDir
// (the files PanelResult names). A figure without panels: empty. `layout` (optional) receives
// where each tile and label went.
Image composeFigure(const FigureResult& fig, const std::string& outDir,
                    CompositeLayout* layout = nullptr);
int runPlan(const cli::Args& args);

}  // namespace sl::figures
