// measure/plot_labels.h — where to write the labels of a gnuplot scatter plot so that none
// overlaps another label or a plotted point: the bench's error-against-time plots (their Pareto
// numbers, measure/bench_plots.cpp) and the report's error-vs-time chart (technique names,
// figures/plots.cpp). The placement is computed from the data, in the plot area's pixels.
#pragma once

#include <string>
#include <vector>

namespace sl::plots {

struct PlotPoint {
  double x = 0, y = 0;
};

// The plot area the labels are placed in: its data ranges (log or linear per axis), its size in
// pixels (gnuplot's margins fixed so that this is exact, or estimated), the font's character
// cell and the markers' radius in pixels.
struct LabelCanvas {
  double xLo = 1, xHi = 10, yLo = 1, yHi = 10;
  bool logX = true, logY = true;
  double widthPixels = 720, heightPixels = 540;
  double charWidthPixels = 7, charHeightPixels = 13;
  double markerRadiusPixels = 7;
};

// A label's box in the plot area's pixels (origin bottom left), as placeLabels reserves it.
struct LabelBox {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// For each labels[i] of the point at[i], the centre (in data coordinates) of a place where its
// box overlaps neither a marker of `points` nor a label placed before it: candidates on rings
// around its point, nearest first (below, above, right, left, the diagonals, then farther out),
// the first free one inside the plot area. When no candidate is free the label takes the one
// that overlaps the fewest boxes (reported by `crowded`, when given, as the label's index).
std::vector<PlotPoint> placeLabels(const std::vector<PlotPoint>& at,
                                   const std::vector<std::string>& labels,
                                   const std::vector<PlotPoint>& points, const LabelCanvas& canvas,
                                   std::vector<size_t>* crowded = nullptr);

// The box a label of `text` centred at `centre` (data coordinates) takes on the canvas.
LabelBox labelBox(const PlotPoint& centre, const std::string& text, const LabelCanvas& canvas);

// Whether two boxes overlap (touching edges do not).
bool boxesOverlap(const LabelBox& a, const LabelBox& b);

}  // namespace sl::plots
