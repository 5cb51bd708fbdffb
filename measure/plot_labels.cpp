// measure/plot_labels.cpp — label placement for gnuplot scatter plots (measure/plot_labels.h).
#include "measure/plot_labels.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sl::plots {
namespace {

// Offsets of a label's centre from its point, in character heights: the nearest ring first
// (below, above, right, left, the diagonals), then rings 2 and 3 times as far, so that labels of
// points that coincide (a legacy technique and its GLSL twin) still find free places.
constexpr double kRingSteps[] = {1.2, 2.4, 3.6};
constexpr double kSideStep = 1.4;  // right/left: beyond the marker, from the label's edge
const PlotPoint kDirections[] = {{0, -1}, {0, 1},  {1, 0}, {-1, 0},
                                 {1, -1}, {-1, 1}, {1, 1}, {-1, -1}};

double axisFraction(double v, double lo, double hi, bool log) {
  return log ? std::log10(v / lo) / std::log10(hi / lo) : (v - lo) / (hi - lo);
}
double axisValue(double f, double lo, double hi, bool log) {
  return log ? lo * std::pow(10.0, f * std::log10(hi / lo)) : lo + f * (hi - lo);
}

PlotPoint toPixels(const PlotPoint& p, const LabelCanvas& c) {
  return {axisFraction(p.x, c.xLo, c.xHi, c.logX) * c.widthPixels,
          axisFraction(p.y, c.yLo, c.yHi, c.logY) * c.heightPixels};
}
PlotPoint toData(const PlotPoint& p, const LabelCanvas& c) {
  return {axisValue(p.x / c.widthPixels, c.xLo, c.xHi, c.logX),
          axisValue(p.y / c.heightPixels, c.yLo, c.yHi, c.logY)};
}

LabelBox boxAround(const PlotPoint& centre, const std::string& text, const LabelCanvas& c) {
  const double halfW = 0.5 * c.charWidthPixels * double(text.size()) + 1;
  const double halfH = 0.5 * c.charHeightPixels;
  return {centre.x - halfW, centre.y - halfH, centre.x + halfW, centre.y + halfH};
}

}  // namespace

bool boxesOverlap(const LabelBox& a, const LabelBox& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

LabelBox labelBox(const PlotPoint& centre, const std::string& text, const LabelCanvas& canvas) {
  return boxAround(toPixels(centre, canvas), text, canvas);
}

std::vector<PlotPoint> placeLabels(const std::vector<PlotPoint>& at,
                                   const std::vector<std::string>& labels,
                                   const std::vector<PlotPoint>& points, const LabelCanvas& canvas,
                                   std::vector<size_t>* crowded) {
  std::vector<LabelBox> taken;
  const double r = canvas.markerRadiusPixels;
  for (const PlotPoint& p : points) {
    const PlotPoint c = toPixels(p, canvas);
    taken.push_back({c.x - r, c.y - r, c.x + r, c.y + r});
  }
  std::vector<PlotPoint> placed;
  for (size_t i = 0; i < at.size() && i < labels.size(); ++i) {
    const PlotPoint c = toPixels(at[i], canvas);
    const double h = canvas.charHeightPixels;
    const double halfW = 0.5 * canvas.charWidthPixels * double(labels[i].size()) + 1;
    LabelBox best{};
    PlotPoint bestAt{c.x, c.y - kRingSteps[0] * h};
    int bestOverlaps = std::numeric_limits<int>::max();
    for (const double ring : kRingSteps) {
      for (const PlotPoint& d : kDirections) {
        // Sideways the label's edge, not its centre, keeps the ring's distance from the point.
        const PlotPoint o{d.x == 0 ? 0 : d.x * (halfW + (kSideStep + ring - kRingSteps[0]) * h),
                          d.y * ring * h};
        const PlotPoint centre{c.x + o.x, c.y + o.y};
        const LabelBox box = boxAround(centre, labels[i], canvas);
        if (box.x0 < 0 || box.y0 < 0 || box.x1 > canvas.widthPixels || box.y1 > canvas.heightPixels)
          continue;
        const int overlaps = int(std::count_if(
            taken.begin(), taken.end(), [&](const LabelBox& t) { return boxesOverlap(box, t); }));
        if (overlaps < bestOverlaps) {
          bestOverlaps = overlaps;
          best = box;
          bestAt = centre;
        }
        if (overlaps == 0) break;
      }
      if (bestOverlaps == 0) break;
    }
    if (bestOverlaps == std::numeric_limits<int>::max())
      best = boxAround(bestAt, labels[i], canvas);
    if (bestOverlaps > 0 && crowded != nullptr) crowded->push_back(i);
    taken.push_back(best);
    placed.push_back(toData(bestAt, canvas));
  }
  return placed;
}

}  // namespace sl::plots
