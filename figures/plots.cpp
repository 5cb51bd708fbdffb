// figures/plots.cpp — gnuplot scripts for the report's charts, and Annen et al. Fig. 3's data.
#include "figures/plots.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/base/errors.h"
#include "core/base/output_files.h"
#include "measure/plot_labels.h"

namespace sl::figures {
namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kCurveSamples = 801;         // points per reconstruction curve
constexpr double kPlotHalfRange = 0.5;     // Fig. 3 shows d - z in [-0.5, 0.5] ("range scaled")
constexpr double kAttenuationAlpha = 4.0;  // a strong attenuation for Fig. 3 (b)

// Stack segments' colours: the ten saturated colours of Tableau 20 first, then their ten light
// partners, so that up to ten segments differ in hue and up to twenty differ at all.
constexpr const char* kSegmentPalette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                           "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf",
                                           "#aec7e8", "#ffbb78", "#98df8a", "#ff9896", "#c5b0d5",
                                           "#c49c94", "#f7b6d2", "#c7c7c7", "#dbdb8d", "#9edae5"};
constexpr size_t kSegmentPaletteSize = sizeof(kSegmentPalette) / sizeof(kSegmentPalette[0]);
constexpr double kSegmentSaturation = 0.65;  // hues spread evenly beyond the palette
constexpr double kSegmentValue = 0.85;

std::string quote(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// The PNG terminal: cairo when present (anti-aliased), libgd's otherwise.
std::string terminalLine(int width, int height) {
  static const bool cairo = std::system("gnuplot -e 'set terminal pngcairo' >/dev/null 2>&1") == 0;
  std::ostringstream s;
  if (cairo)
    s << "set terminal pngcairo size " << width << "," << height << " font 'sans,10'\n";
  else
    s << "set terminal png size " << width << "," << height << "\n";
  // Titles and labels are plain text: a counter's or a pass's name keeps its underscores.
  s << "set termoption noenhanced\n";
  return s.str();
}

// Runs a script whose `set output` names `pngPath`: gnuplot draws into a temporary beside it,
// renamed over `pngPath` only when gnuplot succeeded, so a failed plot never replaces the
// previous one with a half-drawn file.
void runScript(const std::string& script, const std::string& pngPath) {
  const fs::path png(pngPath);
  const fs::path drawing = temporaryName(png, "plot");
  const fs::path gp = fs::path(pngPath).replace_extension(".gp");
  const fs::path log = fs::path(pngPath).replace_extension(".gnuplot.log");
  const std::string finalOutput = "set output " + quote(pngPath) + "\n";
  std::string toRun = script;
  if (const auto at = toRun.find(finalOutput); at != std::string::npos)
    toRun.replace(at, finalOutput.size(), "set output " + quote(drawing.string()) + "\n");
  writeFileAtomically(gp.string(), [&](std::ostream& out) { out << script; });
  const fs::path run = temporaryName(gp, "run");
  writeFileAtomically(run.string(), [&](std::ostream& out) { out << toRun; });
  std::error_code ec;
  const std::string command =
      "gnuplot " + quote(run.string()) + " >" + quote(log.string()) + " 2>&1";
  const int status = std::system(command.c_str());
  fs::remove(run, ec);
  if (status != 0 || !fs::exists(drawing)) {
    fs::remove(drawing, ec);
    std::ifstream in(log);
    std::string first;
    std::getline(in, first);
    throw GlError("gnuplot failed on " + gp.string() + ": " + first);
  }
  fs::rename(drawing, png, ec);
  if (ec) {
    fs::remove(drawing, ec);
    throw InputError("cannot write " + pngPath);
  }
  fs::remove(log, ec);
}

// gnuplot's `set tics (...)` for a log axis over [lo, hi]: its own ticks sit at powers of ten
// only, so a range within one decade would show one label or none. The first of 1; 1, 2, 5;
// 1, 2, ..., 9 (x 10^k) that puts at least kMinLogTicks inside the range.
constexpr size_t kMinLogTicks = 3;
std::string logTicks(double lo, double hi) {
  const std::vector<std::vector<int>> mantissaSets = {{1}, {1, 2, 5}, {1, 2, 3, 4, 5, 6, 7, 8, 9}};
  std::vector<double> ticks;
  for (const std::vector<int>& mantissas : mantissaSets) {
    ticks.clear();
    for (int decade = int(std::floor(std::log10(lo))); decade <= int(std::ceil(std::log10(hi)));
         ++decade)
      for (int m : mantissas) {
        const double v = m * std::pow(10.0, decade);
        if (v >= lo && v <= hi) ticks.push_back(v);
      }
    if (ticks.size() >= kMinLogTicks) break;
  }
  std::ostringstream s;
  s << "(";
  for (size_t i = 0; i < ticks.size(); ++i) s << (i ? ", " : "") << ticks[i];
  s << ")";
  return s.str();
}

}  // namespace

bool gnuplotAvailable(std::string* why) {
  const bool ok = std::system("gnuplot -e 'set terminal png' >/dev/null 2>&1") == 0;
  if (!ok && why) *why = "gnuplot with a PNG terminal is not installed (Debian: gnuplot-nox)";
  return ok;
}

void plotLines(const std::vector<LineChart>& charts, int columns, const std::string& pngPath,
               int width, int height) {
  const int rows = (int(charts.size()) + columns - 1) / columns;
  std::ostringstream s;
  s << terminalLine(width, height) << "set output " << quote(pngPath) << "\n";
  s << "set grid\nset key bottom left\n";
  int block = 0;
  for (const LineChart& c : charts)
    for (const Series& series : c.series) {
      s << "$d" << block++ << " << EOD\n";
      for (const auto& [x, y] : series.points) s << x << " " << y << "\n";
      s << "EOD\n";
    }
  s << "set multiplot layout " << rows << "," << columns << "\n";
  block = 0;
  for (const LineChart& c : charts) {
    s << "set title " << quote(c.title) << "\nset xlabel " << quote(c.xLabel) << "\nset ylabel "
      << quote(c.yLabel) << "\nset xrange [" << c.xMin << ":" << c.xMax << "]\nset yrange ["
      << c.yMin << ":" << c.yMax << "]\nplot ";
    for (size_t i = 0; i < c.series.size(); ++i)
      s << (i ? ", " : "") << "$d" << block++ << " with lines lw 2 title "
        << quote(c.series[i].title);
    s << "\n";
  }
  s << "unset multiplot\n";
  runScript(s.str(), pngPath);
}

void plotLabelledPoints(
    const std::string& title, const std::string& xLabel, const std::string& yLabel,
    const std::vector<std::pair<std::pair<double, double>, std::string>>& points, bool logX,
    const std::string& pngPath, int width, int height) {
  std::ostringstream s;
  s << terminalLine(width, height) << "set output " << quote(pngPath) << "\n";
  s << "set grid\nset title " << quote(title) << "\nset xlabel " << quote(xLabel) << "\nset ylabel "
    << quote(yLabel) << "\nunset key\n";
  if (logX) s << "set logscale x\n";
  s << "set offsets graph 0.02, graph 0.15, graph 0.05, graph 0.05\n";  // room for labels
  s << "$d << EOD\n";
  for (const auto& [xy, label] : points)
    s << xy.first << " " << xy.second << " " << quote(label) << "\n";
  s << "EOD\n";
  s << "plot $d using 1:2 with points pt 7 ps 1.5, $d using 1:2:3 with labels offset char 1,0.6 "
       "left font ',8'\n";
  runScript(s.str(), pngPath);
}

std::vector<std::string> plotGroupedPoints(const std::string& title, const std::string& xLabel,
                                           const std::string& yLabel,
                                           const std::vector<PointGroup>& groups,
                                           const std::string& pngPath, int width, int height) {
  // The plot area in screen fractions (gnuplot's margins set "at screen"), the key right of it.
  constexpr double kLeft = 0.09, kRight = 0.72, kBottom = 0.10, kTop = 0.92;
  constexpr double kRangeMargin = 1.35;        // a factor each way around the data, for labels
  constexpr double kLabelFontPoints = 8;       // the labels' font
  constexpr double kCharWidthPerPoint = 0.75;  // pngcairo sans: a wide character, pixels/point
  constexpr double kCharHeightPerPoint = 1.6;  // line height, pixels per point
  constexpr double kMarkerRadiusPixels = 7;    // point size 1.5
  plots::LabelCanvas canvas;
  canvas.xLo = canvas.yLo = 1e300;
  canvas.xHi = canvas.yHi = 0;
  std::vector<plots::PlotPoint> points;
  std::vector<std::string> labels;
  for (const PointGroup& g : groups)
    for (const LabelledPoint& p : g.points) {
      canvas.xLo = std::min(canvas.xLo, p.x);
      canvas.xHi = std::max(canvas.xHi, p.x);
      canvas.yLo = std::min(canvas.yLo, p.y);
      canvas.yHi = std::max(canvas.yHi, p.y);
      points.push_back({p.x, p.y});
      labels.push_back(p.label);
    }
  if (points.empty()) throw InputError("no points to plot");
  canvas.xLo /= kRangeMargin;
  canvas.xHi *= kRangeMargin;
  canvas.yLo /= kRangeMargin;
  canvas.yHi *= kRangeMargin;
  canvas.widthPixels = (kRight - kLeft) * width;
  canvas.heightPixels = (kTop - kBottom) * height;
  canvas.charWidthPixels = kCharWidthPerPoint * kLabelFontPoints;
  canvas.charHeightPixels = kCharHeightPerPoint * kLabelFontPoints;
  canvas.markerRadiusPixels = kMarkerRadiusPixels;
  std::vector<size_t> crowded;
  const std::vector<plots::PlotPoint> at =
      plots::placeLabels(points, labels, points, canvas, &crowded);
  std::ostringstream s;
  s << terminalLine(width, height) << "set output " << quote(pngPath) << "\n";
  s << "set grid\nset title " << quote(title) << "\nset xlabel " << quote(xLabel) << "\nset ylabel "
    << quote(yLabel) << "\nset logscale xy\nset format xy '%g'\n"
    << "set lmargin at screen " << kLeft << "\nset rmargin at screen " << kRight
    << "\nset bmargin at screen " << kBottom << "\nset tmargin at screen " << kTop << "\n"
    << "set xrange [" << canvas.xLo << ":" << canvas.xHi << "]\nset yrange [" << canvas.yLo << ":"
    << canvas.yHi << "]\n"
    << "set xtics " << logTicks(canvas.xLo, canvas.xHi) << "\nset ytics "
    << logTicks(canvas.yLo, canvas.yHi) << "\n"
    << "set key at screen " << kRight + 0.01 << ", " << kTop << " left top Left reverse\n";
  size_t block = 0;
  for (const PointGroup& g : groups) {
    s << "$g" << block++ << " << EOD\n";
    for (const LabelledPoint& p : g.points) s << p.x << " " << p.y << "\n";
    s << "EOD\n";
  }
  s << "$labels << EOD\n";
  for (size_t i = 0; i < at.size(); ++i)
    s << at[i].x << " " << at[i].y << " " << quote(labels[i]) << "\n";
  s << "EOD\n";
  const std::vector<std::string> colours = segmentColours(groups.size());
  s << "plot $labels using 1:2:3 with labels font '," << kLabelFontPoints << "' notitle";
  constexpr int kPointTypes[] = {7, 5, 9, 11, 13};  // filled circle, square, triangle, ...
  for (size_t i = 0; i < groups.size(); ++i)
    s << ", $g" << i << " using 1:2 with points pt " << kPointTypes[i % 5] << " ps 1.5 lc rgb "
      << quote(colours[i]) << " title " << quote(groups[i].title);
  s << "\n";
  runScript(s.str(), pngPath);
  std::vector<std::string> out;
  for (size_t i : crowded) out.push_back(labels[i]);
  return out;
}

std::vector<std::string> segmentColours(size_t count) {
  std::vector<std::string> out;
  for (size_t i = 0; i < count; ++i) {
    if (count <= kSegmentPaletteSize) {
      out.push_back(kSegmentPalette[i]);
      continue;
    }
    // More segments than the palette: hues i / count of the circle (HSV to RGB).
    const double h = 6.0 * double(i) / double(count);
    const double c = kSegmentValue * kSegmentSaturation;
    const double x = c * (1.0 - std::abs(std::fmod(h, 2.0) - 1.0));
    const double m = kSegmentValue - c;
    const int sector = int(h);
    const double r = sector == 0 || sector == 5 ? c : sector == 1 || sector == 4 ? x : 0.0;
    const double g = sector == 1 || sector == 2 ? c : sector == 0 || sector == 3 ? x : 0.0;
    const double b = sector == 3 || sector == 4 ? c : sector == 2 || sector == 5 ? x : 0.0;
    char hex[8];
    std::snprintf(hex, sizeof(hex), "#%02x%02x%02x", int(std::lround(255.0 * (r + m))),
                  int(std::lround(255.0 * (g + m))), int(std::lround(255.0 * (b + m))));
    out.push_back(hex);
  }
  return out;
}

void plotStackedBars(const std::string& title, const std::string& yLabel,
                     const std::vector<std::string>& rows, const std::vector<std::string>& columns,
                     const std::vector<std::vector<double>>& values, const std::string& pngPath,
                     int width, int height) {
  std::ostringstream s;
  s << terminalLine(width, height) << "set output " << quote(pngPath) << "\n";
  s << "set title " << quote(title) << "\nset ylabel " << quote(yLabel) << "\n"
    << "set style data histograms\nset style histogram rowstacked\nset style fill solid 0.8 border "
       "-1\n"
    << "set boxwidth 0.7\nset xtics rotate by -35 font ',8'\nset key outside right top font ',8'\n"
    << "set grid ytics\nset yrange [0:*]\n";
  s << "$d << EOD\n";
  for (size_t r = 0; r < rows.size(); ++r) {
    s << quote(rows[r]);
    for (size_t c = 0; c < columns.size(); ++c) s << " " << values[r][c];
    s << "\n";
  }
  s << "EOD\nplot ";
  const std::vector<std::string> colours = segmentColours(columns.size());
  for (size_t c = 0; c < columns.size(); ++c)
    s << (c ? ", " : "") << "$d using " << c + 2 << (c == 0 ? ":xtic(1)" : "") << " title "
      << quote(columns[c]) << " lc rgb " << quote(colours[c]);
  s << "\n";
  runScript(s.str(), pngPath);
}

double csmVisibility(double t, int M, double alpha, double offset, double scale, bool clampResult) {
  // Eq. 10-11: 1/2 S(t) = 2 sum_k sin(c_k t) / c_k approximates H(t) - 1/2; visibility is
  // 1 - H(d - z) (lit when the receiver is not behind the blocker).
  double sum = 0.0;
  for (int k = 1; k <= M; ++k) {
    const double ck = kPi * (2 * k - 1);
    const double attenuation = std::exp(-alpha * (double(k) / M) * (double(k) / M));  // §3.2.1
    sum += attenuation * std::sin(ck * (t - offset)) / ck;
  }
  const double v = scale * (0.5 - 2.0 * sum);
  return clampResult ? std::clamp(v, 0.0, 1.0) : v;
}

double csmOffsetFor(int M, double alpha) {
  // The reconstruction's first maximum left of the step: shifting by its distance from 0
  // makes f go through its maximum (about 1) at d - z = 0 (§3.2.2).
  constexpr int kSteps = 20000;
  double best = 0.0, bestValue = -1e9;
  for (int i = 0; i <= kSteps; ++i) {
    const double t = -0.5 * double(i) / kSteps;
    const double v = csmVisibility(t, M, alpha, 0.0, 1.0, false);
    if (v > bestValue + 1e-12) {
      bestValue = v;
      best = t;
    }
    if (v < bestValue - 0.05) break;  // past the first lobe
  }
  return -best;
}

std::vector<LineChart> csmFigure3Charts() {
  auto curve = [](const std::string& title, auto f) {
    Series s{title, {}};
    for (int i = 0; i < kCurveSamples; ++i) {
      const double t = -kPlotHalfRange + 2 * kPlotHalfRange * i / (kCurveSamples - 1);
      s.points.push_back({t, f(t)});
    }
    return s;
  };
  auto step = curve("exact step", [](double t) { return t <= 0 ? 1.0 : 0.0; });
  auto base = [](const std::string& title) {
    LineChart c;
    c.title = title;
    c.xLabel = "d - z";
    c.yLabel = "reconstructed f";
    c.xMin = -kPlotHalfRange;
    c.xMax = kPlotHalfRange;
    c.yMin = -0.2;
    c.yMax = 1.3;
    return c;
  };
  std::vector<LineChart> out;
  LineChart a = base("(a) truncation order M");
  a.series.push_back(step);
  for (int M : {4, 8, 16})
    a.series.push_back(curve("M = " + std::to_string(M),
                             [M](double t) { return csmVisibility(t, M, 0, 0, 1, false); }));
  out.push_back(a);
  LineChart b = base("(b) attenuation, M = 16");
  b.series.push_back(step);
  b.series.push_back(
      curve("alpha = 0", [](double t) { return csmVisibility(t, 16, 0, 0, 1, false); }));
  b.series.push_back(curve(
      "alpha = 4", [](double t) { return csmVisibility(t, 16, kAttenuationAlpha, 0, 1, false); }));
  out.push_back(b);
  LineChart c = base("(c) offset on d, M = 4");
  const double offset = csmOffsetFor(4, 0.0);
  c.series.push_back(step);
  c.series.push_back(
      curve("no offset", [](double t) { return csmVisibility(t, 4, 0, 0, 1, true); }));
  c.series.push_back(curve("offset " + std::to_string(offset).substr(0, 5),
                           [offset](double t) { return csmVisibility(t, 4, 0, offset, 1, true); }));
  out.push_back(c);
  LineChart d = base("(d) scaling f, M = 4");
  d.series.push_back(step);
  d.series.push_back(curve("scale 1", [](double t) { return csmVisibility(t, 4, 0, 0, 1, true); }));
  d.series.push_back(curve("scale 2", [](double t) { return csmVisibility(t, 4, 0, 0, 2, true); }));
  out.push_back(d);
  return out;
}

}  // namespace sl::figures
