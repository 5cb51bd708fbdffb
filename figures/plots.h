// figures/plots.h — charts for the report, drawn by gnuplot (a subprocess running a generated
// script; no hand-written plotter), and the data of Annen et al. Fig. 3 computed from Eq. 10-14.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace sl::figures {

struct Series {
  std::string title;
  std::vector<std::pair<double, double>> points;
};

struct LineChart {
  std::string title, xLabel, yLabel;
  double xMin = 0, xMax = 1, yMin = 0, yMax = 1;
  std::vector<Series> series;
};

// True when a gnuplot executable with a PNG terminal runs; `why` says what is missing.
bool gnuplotAvailable(std::string* why);

// Line charts in a grid of `columns` (gnuplot multiplot) into a PNG. Throws GlError naming
// gnuplot's complaint when it fails. `scriptPath` keeps the generated script beside the PNG.
void plotLines(const std::vector<LineChart>& charts, int columns, const std::string& pngPath,
               int width, int height);
// Labelled points (x, y, label), e.g. error against time; log-scale x when `logX`.
void plotLabelledPoints(
    const std::string& title, const std::string& xLabel, const std::string& yLabel,
    const std::vector<std::pair<std::pair<double, double>, std::string>>& points, bool logX,
    const std::string& pngPath, int width, int height);
// A scatter plot's groups: each its own point type and colour and a line in the key.
struct LabelledPoint {
  double x = 0, y = 0;
  std::string label;
};
struct PointGroup {
  std::string title;
  std::vector<LabelledPoint> points;
};
// Labelled points on log-log axes, one point style per group with a key; every label placed
// where it overlaps no other label and no point (measure/plot_labels.h, the plot area's margins
// fixed so that the placement's pixels are gnuplot's). Returns the labels that found no free
// place (none on the report's error-vs-time chart so far; the caller may say so).
std::vector<std::string> plotGroupedPoints(const std::string& title, const std::string& xLabel,
                                           const std::string& yLabel,
                                           const std::vector<PointGroup>& groups,
                                           const std::string& pngPath, int width, int height);
// Colours of `count` stack segments, "#rrggbb", all different (one per pass in Chan Fig. 3-11).
std::vector<std::string> segmentColours(size_t count);
// Stacked bars: one bar per row label, one stack segment per column name, each its own colour
// (segmentColours).
void plotStackedBars(const std::string& title, const std::string& yLabel,
                     const std::vector<std::string>& rows, const std::vector<std::string>& columns,
                     const std::vector<std::vector<double>>& values, const std::string& pngPath,
                     int width, int height);

// Annen et al. 2007, Eq. 11 with the attenuation of §3.2.1 and the offset and scaling of
// §3.2.2, as the visibility the shadow test reconstructs (1 = lit) for t = d - z:
//   V(t) = clamp(scale * (1/2 - 2 sum_k exp(-alpha (k/M)^2) sin(c_k (t - offset)) / c_k), 0, 1)
// with c_k = pi (2k - 1). Without clamping when `clampResult` is false (to show ringing).
double csmVisibility(double t, int M, double alpha, double offset, double scale, bool clampResult);
// The offset of §3.2.2: the smallest shift that makes the reconstruction reach its maximum at
// t = 0 (found numerically on a fine grid, since it only depends on M and alpha).
double csmOffsetFor(int M, double alpha);
// The four panels of Fig. 3 (a: truncation, b: attenuation, c: offset, d: scaling).
std::vector<LineChart> csmFigure3Charts();

}  // namespace sl::figures
