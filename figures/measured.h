// figures/measured.h — what a figure's run measured, in words: the sentences
// and tables report.html sets under a caption. Every number in them is computed here from the
// FigureResult (frame times, their interleaved rounds, counters, errors); the captions in
// figure_list.cpp carry configuration and the papers' quoted numbers only.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "figures/report.h"

namespace sl::figures {

// A paper's time for a panel ("25-30 fps on an SGI Octane", "about 10 fps", "16 ms"), as
// milliseconds per frame: the first number (a range's midpoint) and the unit after it.
// Empty when the text quotes no time.
std::optional<double> paperMilliseconds(const std::string& paperNumbers);

// One timed cell set beside the paper: ours against the cell it is compared with (the figure's
// first timed panel with the same scene and map size: the unfiltered map in Brabec Fig. 7, PCF
// in CSM Table 1, the plain map in each row of Chan Fig. 4-8), and whether the paper's
// direction (slower / faster / the same within kSameTimeShare) holds for ours.
struct TrendCell {
  std::string label, baseline;
  double ours = 0, oursBaseline = 0;    // ms, medians
  double paper = 0, paperBaseline = 0;  // ms
  int roundsAgreeing = 0, rounds = 0;   // rounds in which ours goes the paper's way
  std::string verdict;                  // "holds", "does not hold", ...
};
// Two times differing by less than this share count as the same.
constexpr double kSameTimeShare = 0.05;
std::vector<TrendCell> timingTrend(const FigureResult& fig);

// Brabec Fig. 8's depth-bias counters (PanelSpec::countDepthErrors, figures.cpp): pixels a
// panel draws lit where both the ray tracer and 24-bit legacy.hw put them in shadow (the leak
// under the teapot's base), and drawn in shadow where the ray tracer puts them in light (acne).
constexpr const char* kLeakPixelsCounter = "leak_pixels";
constexpr const char* kAcnePixelsCounter = "acne_pixels";

// The HTML block under the figure's caption ("" when it measured nothing to say).
std::string measuredHtml(const FigureResult& fig);

}  // namespace sl::figures
