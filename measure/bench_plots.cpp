// measure/bench_plots.cpp — the bench's error-against-time plots: per scene and technique family
// a gnuplot data file, script and PNG, the scene's Pareto front numbered (measure/bench.h
// writePlots).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/base/errors.h"
#include "core/base/output_files.h"
#include "core/base/png_text.h"
#include "core/base/provenance.h"
#include "measure/bench.h"
#include "measure/plot_labels.h"
#include "registry/registry.h"
#include "registry/twins.h"

namespace sl::figures {
namespace fs = std::filesystem;

namespace {
bool gnuplotHasTerminal(const std::string& terminal) {
  const std::string command =
      "gnuplot -e 'set terminal " + terminal + "' > /dev/null 2>&1 < /dev/null";
  return std::system(command.c_str()) == 0;
}
}  // namespace

namespace {
// The Pareto front's numbers on an error-against-time plot, placed so that none overlaps
// another or a plotted point (measure/plot_labels.h), in a plot area of about
// kPlotAreaPixels (the 1000x640 terminal less its margins and the key outside).
using plots::PlotPoint;
constexpr double kPlotAreaWidthPixels = 720, kPlotAreaHeightPixels = 540;
constexpr double kLabelCharWidthPixels = 7, kLabelCharHeightPixels = 13;
constexpr double kMarkerRadiusPixels = 7;  // point size 1.6 of the terminal
std::vector<PlotPoint> placeFrontLabels(const std::vector<PlotPoint>& front,
                                        const std::vector<std::string>& labels,
                                        const std::vector<PlotPoint>& points, double xLo,
                                        double xHi, double yLo, double yHi) {
  plots::LabelCanvas canvas;
  canvas.xLo = xLo;
  canvas.xHi = xHi;
  canvas.yLo = yLo;
  canvas.yHi = yHi;
  canvas.widthPixels = kPlotAreaWidthPixels;
  canvas.heightPixels = kPlotAreaHeightPixels;
  canvas.charWidthPixels = kLabelCharWidthPixels;
  canvas.charHeightPixels = kLabelCharHeightPixels;
  canvas.markerRadiusPixels = kMarkerRadiusPixels;
  return plots::placeLabels(front, labels, points, canvas);
}
}  // namespace

namespace {
// The labelled ticks of a log axis over [lo, hi]. gnuplot's own ticks on a log axis sit at powers
// of ten only, so a range within one decade (a scene's RMSEs often are) would show one label or
// none. The first of these with at least kMinAxisTicks values inside the range: 10^k; 1, 2,
// 5 x 10^k; 1, 2, ..., 9 x 10^k; then evenly spaced values 1, 2 or 5 x 10^k apart.
constexpr size_t kMinAxisTicks = 3;
std::vector<double> logAxisTicks(double lo, double hi) {
  const int firstDecade = int(std::floor(std::log10(lo)));
  const int lastDecade = int(std::ceil(std::log10(hi)));
  const std::vector<std::vector<int>> mantissaSets = {{1}, {1, 2, 5}, {1, 2, 3, 4, 5, 6, 7, 8, 9}};
  for (const std::vector<int>& mantissas : mantissaSets) {
    std::vector<double> ticks;
    for (int decade = firstDecade; decade <= lastDecade; ++decade)
      for (int m : mantissas) {
        const double v = m * std::pow(10.0, decade);
        if (v >= lo && v <= hi) ticks.push_back(v);
      }
    if (ticks.size() >= kMinAxisTicks) return ticks;
  }
  // A step of at most a third of the range puts at least three of its multiples inside it.
  const double most = (hi - lo) / double(kMinAxisTicks);
  const double power = std::pow(10.0, std::floor(std::log10(most)));
  double step = power;
  for (int m : {5, 2, 1})
    if (m * power <= most) {
      step = m * power;
      break;
    }
  std::vector<double> ticks;
  for (double k = std::ceil(lo / step); k * step <= hi; ++k) ticks.push_back(k * step);
  return ticks;
}
// gnuplot's `set xtics (...)`: the ticks listed, each labelled by `set format` (%g).
std::string ticsList(const std::vector<double>& ticks) {
  std::ostringstream s;
  s << "(";
  for (size_t i = 0; i < ticks.size(); ++i) s << (i ? ", " : "") << ticks[i];
  s << ")";
  return s.str();
}
}  // namespace

std::string plotFamily(const std::string& technique) {
  // Technique::family; a technique this build lacks (a merged row) is one of the later papers.
  const Technique* t = techniqueNamed(technique);
  if (t != nullptr && t->family == TechniqueFamily::kReference) return "";
  if (t != nullptr && t->family == TechniqueFamily::kLegacy) return "legacy";
  for (const twins::TwinPair& pair : twins::twinPairs())
    if (pair.modern == technique) return "modern twins";
  return "later papers";
}

BenchPlots writePlots(const std::string& outDir, const BenchResult& result) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0)
    throw InputError("gnuplot is not installed (apt-get install gnuplot-nox): no plots written");
  std::error_code ec;
  fs::create_directories(outDir, ec);
  if (ec) throw InputError("cannot create " + outDir + ": " + ec.message());
  const std::string terminal =
      gnuplotHasTerminal("pngcairo") ? "pngcairo size 1000,640 font ',10'" : "png size 1000,640";
  // Margins around the data on the log axes: a factor of kPlotMargin each way.
  constexpr double kPlotMargin = 1.25;
  const std::vector<std::string> families = {"legacy", "modern twins", "later papers"};
  std::set<std::string> scenes;
  for (const BenchRow& r : result.rows) scenes.insert(r.scene);
  BenchPlots out;
  for (const std::string& scene : scenes) {
    std::vector<const BenchRow*> drawn;
    std::vector<std::string> zero;
    for (const BenchRow& r : result.rows) {
      if (r.scene != scene || r.status != "ok" || plotFamily(r.technique).empty()) continue;
      if (r.primary().all.rmse > 0 && r.frameMs > 0)
        drawn.push_back(&r);
      else
        zero.push_back(r.technique + (r.variant == "default" ? "" : " " + r.variant));
    }
    if (drawn.empty()) {
      out.notes[scene] = "no plot: every technique's RMSE is 0 here (" +
                         std::to_string(zero.size()) +
                         " variants), and a log axis cannot show 0; frame times are in the table";
      continue;
    }
    if (!zero.empty()) {
      std::string list;
      for (const std::string& z : zero) list += (list.empty() ? "" : ", ") + z;
      out.notes[scene] = "RMSE 0, not on the log axis: " + list;
    }
    std::vector<size_t> front;
    for (size_t i : paretoFront(result.rows, scene))
      if (result.rows[i].primary().all.rmse > 0) front.push_back(i);
    for (size_t k = 0; k < front.size(); ++k) {
      const BenchRow& r = result.rows[front[k]];
      std::ostringstream line;
      line << k + 1 << ": " << r.technique << " " << r.variant << " (" << std::fixed
           << std::setprecision(1) << r.frameMs << " ms, RMSE " << std::setprecision(4)
           << r.primary().all.rmse << ")";
      // The front is ordered by time: say where this run cannot order two neighbours.
      if (k > 0 && timesWithinSpread(result.rows[front[k - 1]], r))
        line << " [time within the spread of " << k << ": interquartile ranges overlap]";
      out.pareto[scene].push_back(line.str());
    }
    for (const std::string& family : families) {
      std::vector<std::string> techniques;
      for (const BenchRow* r : drawn)
        if (plotFamily(r->technique) == family &&
            std::find(techniques.begin(), techniques.end(), r->technique) == techniques.end())
          techniques.push_back(r->technique);
      if (techniques.empty()) continue;
      // The axes fit this plot's points and the scene's front (the front is drawn on each).
      double xLo = 1e300, xHi = 0, yLo = 1e300, yHi = 0;
      auto fit = [&](const BenchRow& r) {
        xLo = std::min(xLo, r.frameMs);
        xHi = std::max(xHi, r.frameMs);
        yLo = std::min(yLo, r.primary().all.rmse);
        yHi = std::max(yHi, r.primary().all.rmse);
      };
      for (const BenchRow* r : drawn)
        if (plotFamily(r->technique) == family) fit(*r);
      for (size_t i : front) fit(result.rows[i]);
      std::string tag = family;
      std::replace(tag.begin(), tag.end(), ' ', '-');
      const fs::path base = fs::path(outDir) / ("bench-" + scene + "-" + tag);
      // One data block per technique (gnuplot index), then the Pareto front.
      writeFileAtomically(base.string() + ".dat", [&](std::ostream& data) {
        for (const std::string& t : techniques) {
          data << "# " << t << "\n";
          for (const BenchRow* r : drawn)
            if (r->technique == t)
              data << r->frameMs << " " << r->primary().all.rmse << " \"" << r->variant << "\"\n";
          data << "\n\n";
        }
        // The front, numbered, with each number's place (placeFrontLabels) in columns 4-5.
        std::vector<PlotPoint> frontPoints, drawnPoints;
        std::vector<std::string> numbers;
        for (size_t k = 0; k < front.size(); ++k) {
          frontPoints.push_back(
              {result.rows[front[k]].frameMs, result.rows[front[k]].primary().all.rmse});
          numbers.push_back(std::to_string(k + 1));
        }
        for (const BenchRow* r : drawn)
          if (plotFamily(r->technique) == family)
            drawnPoints.push_back({r->frameMs, r->primary().all.rmse});
        for (const PlotPoint& p : frontPoints) drawnPoints.push_back(p);
        const std::vector<PlotPoint> labelAt =
            placeFrontLabels(frontPoints, numbers, drawnPoints, xLo / kPlotMargin,
                             xHi * kPlotMargin, yLo / kPlotMargin, yHi * kPlotMargin);
        data << "# pareto front of the scene (every family), numbered; label x y\n";
        for (size_t k = 0; k < front.size(); ++k)
          data << frontPoints[k].x << " " << frontPoints[k].y << " \"" << numbers[k] << "\" "
               << labelAt[k].x << " " << labelAt[k].y << "\n";
      });
      // The script names its PNG unless told another name (`out`): the run below draws into a
      // temporary and renames it, so that a failed gnuplot leaves no half-written PNG.
      const std::string dat = base.string() + ".dat";
      writeFileAtomically(base.string() + ".gp", [&](std::ostream& script) {
        script << "set terminal " << terminal << "\n"
               << "if (!exists('out')) out = '" << base.string() << ".png'\n"
               << "set output out\n"
               << "set title 'scene " << scene << ", " << family
               << ": visibility error against frame time (grey: Pareto front of the scene, "
                  "numbered)'\n"
               << "set logscale xy\nset grid\nset key outside right top\n"
               << "set xrange [" << xLo / kPlotMargin << ":" << xHi * kPlotMargin << "]\n"
               << "set yrange [" << yLo / kPlotMargin << ":" << yHi * kPlotMargin << "]\n"
               << "set format xy '%g'\n"
               << "set xtics " << ticsList(logAxisTicks(xLo / kPlotMargin, xHi * kPlotMargin))
               << "\n"
               << "set ytics " << ticsList(logAxisTicks(yLo / kPlotMargin, yHi * kPlotMargin))
               << "\n"
               << "set xlabel 'median frame time [ms] (sum of pass times)'\n"
               << "set ylabel 'RMSE, area metric (scored pixels; docs/error.md)'\n"
               << "plot '" << dat << "' index " << techniques.size()
               << " using 1:2 with steps lw 2 lc rgb '#aaaaaa' title 'Pareto front', '' index "
               << techniques.size()
               << " using 4:5:3 with labels font ',9' tc rgb '#444444' notitle";
        for (size_t i = 0; i < techniques.size(); ++i)
          script << ", '' index " << i << " using 1:2 with points pt " << (i % 13) + 1
                 << " ps 1.6 lw 2 title '" << techniques[i] << "'";
        script << "\n";
      });
      const std::string png = base.string() + ".png";
      const std::string temporaryPng = temporaryName(png).string();
      const std::string command =
          // Its warnings go to stderr: stdout carries only JSON lines.
          "gnuplot -e \"out='" + temporaryPng + "'\" '" + base.string() + ".gp' 1>&2";
      if (std::system(command.c_str()) != 0 ||
          std::rename(temporaryPng.c_str(), png.c_str()) != 0) {
        std::remove(temporaryPng.c_str());
        std::cerr << "bench: no plot for " << scene << " " << family << " (gnuplot failed)\n";
        continue;
      }
      // The same tEXt chunks as our own PNGs (core/base/png_text.h), added after gnuplot drew it.
      const nlohmann::json parameters = {{"plot", "visibility error against frame time"},
                                         {"scene", scene},
                                         {"family", family},
                                         {"techniques", techniques},
                                         {"data", dat},
                                         {"script", base.string() + ".gp"},
                                         {"commit", buildCommit()}};
      try {
        addPngProvenance(
            png, {commandLine(),
                  parameters.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace)});
      } catch (const InputError& e) {
        std::cerr << "bench: " << png << ": no provenance chunks (" << e.what() << ")\n";
      }
      out.plots.push_back({scene, family, png});
    }
  }
  return out;
}

}  // namespace sl::figures
