// figures/measured.cpp — the measured sentences under the captions (see measured.h).
#include "figures/measured.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iomanip>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "core/base/decimal.h"
#include "core/base/html.h"
#include "figures/disagreement.h"
#include "registry/registry.h"
#include "registry/shadow_error.h"
#include "registry/twins.h"

namespace sl::figures {
namespace {

// A frame rate with enough digits to tell cells apart on a slow back end (0.42, not 0.4).
std::string fpsOf(double ms) {
  const double fps = 1000.0 / ms;
  return fixedDecimals(fps, fps < 1.0 ? 3 : fps < 10.0 ? 2 : 1);
}

std::string percent(double share) {
  return fixedDecimals(100.0 * share, share < 0.01 ? 2 : 1) + "%";
}

bool timedRender(const PanelResult& p) {
  return p.ok && p.spec.kind == PanelKind::kRender && p.milliseconds > 0 && p.timedFrames > 0;
}

// Which way a time ratio goes: +1 slower, -1 faster, 0 the same within kSameTimeShare.
int direction(double ratio) {
  if (ratio > 1.0 + kSameTimeShare) return 1;
  if (ratio < 1.0 - kSameTimeShare) return -1;
  return 0;
}

const char* directionWord(int d) { return d > 0 ? "slower" : d < 0 ? "faster" : "the same"; }

// Rounds (interleaved, so round r of two cells ran under the same load) in which a/b goes way d.
int roundsGoing(const PanelResult& a, const PanelResult& b, int d, int* rounds) {
  const size_t n = std::min(a.frameSamples.size(), b.frameSamples.size());
  *rounds = int(n);
  int agreeing = 0;
  for (size_t r = 0; r < n; ++r)
    if (b.frameSamples[r] > 0 && direction(a.frameSamples[r] / b.frameSamples[r]) == d) ++agreeing;
  return agreeing;
}

std::string sceneOf(const FigureResult& fig, const PanelResult& p) {
  return p.spec.scene.empty() ? fig.spec.scene : p.spec.scene;
}

int texelsOf(const FigureResult& fig, const PanelResult& p) {
  return p.spec.shadowMapTexels ? p.spec.shadowMapTexels : fig.spec.shadowMapTexels;
}

std::optional<double> counter(const PanelResult& p, const std::string& name) {
  const auto it = p.counters.find(name);
  if (it == p.counters.end()) return std::nullopt;
  return it->second;
}

// ---------------------------------------------------------------- every timing figure
std::string trendTable(const std::vector<TrendCell>& cells) {
  if (cells.empty()) return "";
  int holds = 0;
  for (const TrendCell& c : cells) holds += c.verdict.rfind("holds", 0) == 0 ? 1 : 0;
  std::ostringstream h;
  h << "<p><b>Measured: the paper's trend, cell by cell.</b> Each timed cell against the cell "
       "the paper compares it with (same scene and map size); a time ratio above 1 is slower. "
       "The paper's trend holds in "
    << holds << " of " << cells.size()
    << " cells. Rounds: the interleaved rounds (every cell rendered once per round, so both "
       "cells of a ratio ran under the same load) in which ours goes the paper's way.</p>\n"
       "<table><tr><th>cell</th><th>compared with</th><th>ours (ms, ratio)</th><th>paper (ms, "
       "ratio)</th><th>rounds</th><th>paper's trend</th></tr>\n";
  for (const TrendCell& c : cells)
    h << "<tr><td>" << htmlEscape(c.label) << "</td><td>" << htmlEscape(c.baseline) << "</td><td>"
      << fixedDecimals(c.ours, 1) << " / " << fixedDecimals(c.oursBaseline, 1) << " = "
      << fixedDecimals(c.ours / c.oursBaseline, 2) << "</td><td class=paper>"
      << fixedDecimals(c.paper, 1) << " / " << fixedDecimals(c.paperBaseline, 1) << " = "
      << fixedDecimals(c.paper / c.paperBaseline, 2) << "</td><td>" << c.roundsAgreeing << " of "
      << c.rounds << "</td><td class=" << (c.verdict.rfind("holds", 0) == 0 ? "ok" : "bad") << ">"
      << htmlEscape(c.verdict) << "</td></tr>\n";
  h << "</table>\n";
  return h.str();
}

// ---------------------------------------------------------------- Brabec Figs. 7 and 8
// Two passes do the same job in their pipelines when their tables give them the same role
// (PassSpec::role; Brabec & Seidel §2-§4 name such passes alike); a pass of no role
// (PassRole::kOther) pairs with none.
bool sameJob(const PassTime& a, const PassTime& b) {
  return a.role != PassRole::kOther && a.role == b.role;
}

// Where a timed cell's frame differs from the frame the paper compares it with, pass by pass:
// the passes paired by role, and those without a partner, which the cell
// adds; then the share of the cell's frame the paper's ratio needs the added work to cost,
// against the share it costs here.
// Added work costing less than this share of what the paper's ratio needs cannot make that
// ratio, whatever the load: the shared passes decide the order of the two frames.
constexpr double kDecidingShare = 0.5;

std::string passBreakdown(const FigureResult& fig) {
  std::ostringstream h;
  for (const TrendCell& c : timingTrend(fig)) {
    const PanelResult *cell = nullptr, *base = nullptr;
    for (const PanelResult& p : fig.panels) {
      if (!timedRender(p)) continue;
      if (p.spec.label == c.label) cell = &p;
      if (p.spec.label == c.baseline) base = &p;
    }
    if (cell == nullptr || base == nullptr || cell->passes.empty()) continue;
    std::vector<bool> used(base->passes.size(), false);
    std::string paired, added, mostChanged;
    double addedMs = 0, pairedDelta = 0, mostDelta = 0;
    for (const PassTime& pass : cell->passes) {
      size_t k = 0;
      while (k < base->passes.size() && (used[k] || !sameJob(pass, base->passes[k]))) ++k;
      if (k < base->passes.size()) {
        used[k] = true;
        const double delta = pass.milliseconds - base->passes[k].milliseconds;
        pairedDelta += delta;
        if (std::fabs(delta) > std::fabs(mostDelta)) {
          mostDelta = delta;
          mostChanged = pass.name;
        }
        paired += "<tr><td>" + htmlEscape(base->passes[k].name) + "</td><td>" +
                  fixedDecimals(base->passes[k].milliseconds, 1) + "</td><td>" +
                  htmlEscape(pass.name) + "</td><td>" + fixedDecimals(pass.milliseconds, 1) +
                  "</td></tr>\n";
      } else {
        addedMs += pass.milliseconds;
        added += (added.empty() ? "" : "; ") + pass.name + " " +
                 fixedDecimals(pass.milliseconds, 1) + " ms";
      }
    }
    std::string dropped;
    double droppedMs = 0;
    for (size_t k = 0; k < base->passes.size(); ++k)
      if (!used[k] && base->passes[k].milliseconds > 0) {
        droppedMs += base->passes[k].milliseconds;
        dropped += (dropped.empty() ? "" : "; ") + base->passes[k].name + " " +
                   fixedDecimals(base->passes[k].milliseconds, 1) + " ms";
      }
    const auto signedMs = [](double ms) { return (ms >= 0 ? "+" : "") + fixedDecimals(ms, 1); };
    const double paperRatio = c.paper / c.paperBaseline;
    // The paper's ratio p = cell / base: with the shared passes costing the same, the added
    // work is (p - 1) / p of the cell's frame.
    const double neededShare = paperRatio > 1 ? (paperRatio - 1) / paperRatio : 0;
    const double ownShare = cell->milliseconds > 0 ? addedMs / cell->milliseconds : 0;
    h << "<p><b>Measured: " << htmlEscape(c.label) << " against " << htmlEscape(c.baseline)
      << ", pass by pass</b> (medians of the interleaved rounds, ms; passes paired by their "
         "role, the first words of their names). Frames: "
      << fixedDecimals(cell->milliseconds, 1) << " against " << fixedDecimals(base->milliseconds, 1)
      << " ms (" << signedMs(cell->milliseconds - base->milliseconds) << "). The passes "
      << htmlEscape(c.label) << " adds: " << htmlEscape(added.empty() ? std::string("none") : added)
      << ", together " << fixedDecimals(addedMs, 1) << " ms, " << percent(ownShare)
      << " of its frame";
    if (!dropped.empty())
      h << "; the passes of " << htmlEscape(c.baseline)
        << " without a partner: " << htmlEscape(dropped) << ", together "
        << fixedDecimals(droppedMs, 1) << " ms";
    h << ". The paired passes differ by " << signedMs(pairedDelta) << " ms in total";
    if (!mostChanged.empty())
      h << ", the most " << htmlEscape(mostChanged) << " (" << signedMs(mostDelta) << " ms)";
    h << ". The paper's ratio (" << fixedDecimals(paperRatio, 2) << ") needs the work "
      << htmlEscape(c.label) << " adds to cost " << percent(neededShare)
      << " of its frame if the shared passes cost the same in both; ";
    if (added.empty())
      h << "it adds no pass: what it costs more or less is in the paired passes.";
    else if (ownShare < kDecidingShare * neededShare)
      h << "its added passes cost " << percent(ownShare)
        << ", too little to make the paper's ratio: the paired passes (their cost on llvmpipe "
           "and the machine's load) decide the order of the two frames, not the added passes.";
    else
      h << "its added passes cost " << percent(ownShare)
        << ": they decide a good part of the difference, as in the paper.";
    h << "</p>\n<table><tr><th>" << htmlEscape(c.baseline) << "</th><th>ms</th><th>"
      << htmlEscape(c.label) << "</th><th>ms</th></tr>\n"
      << paired << "</table>\n";
  }
  return h.str();
}

// "rises 328 -> 4763 pixels": a counter from panel a to panel b.
std::string change(const PanelResult& a, const PanelResult& b, const char* name) {
  const double from = *counter(a, name), to = *counter(b, name);
  return std::string(to > from   ? "rises "
                     : to < from ? "falls "
                                 : "stays ") +
         fixedDecimals(from, 0) + " -> " + fixedDecimals(to, 0) + " pixels";
}

// Brabec Fig. 8: the 8-bit method's depth bias against 12-bit depth, in pixels (the panels'
// counters, figures.cpp countDepthErrors).
std::string depthBiasCounts(const FigureResult& fig) {
  std::vector<const PanelResult*> counted;
  for (const PanelResult& p : fig.panels)
    if (p.ok && counter(p, kLeakPixelsCounter) && counter(p, kAcnePixelsCounter))
      counted.push_back(&p);
  if (counted.empty()) return "";
  std::ostringstream h;
  h << "<p><b>Measured: the depth bias's trade</b> (pixels of the frame, counted as "
       "docs/figures.md counts them; leak: drawn lit where both the ray tracer and 24-bit "
       "legacy.hw put them in shadow; acne: drawn in shadow where the ray tracer puts them in "
       "light). ";
  for (const PanelResult* p : counted)
    h << htmlEscape(p->spec.label) << ": leak "
      << fixedDecimals(*counter(*p, kLeakPixelsCounter), 0) << ", acne "
      << fixedDecimals(*counter(*p, kAcnePixelsCounter), 0) << ". ";
  if (counted.size() > 1) {
    const PanelResult &a = *counted.front(), &b = *counted.back();
    h << "From " << htmlEscape(a.spec.label) << " to " << htmlEscape(b.spec.label) << " the leak "
      << htmlEscape(change(a, b, kLeakPixelsCounter)) << " and the acne "
      << htmlEscape(change(a, b, kAcnePixelsCounter)) << ".";
  }
  h << "</p>\n";
  return h.str();
}

// ---------------------------------------------------------------- CSM Table 1
// "C=none M=4 S=256" -> {"none", "M=4", "256"}.
struct TableCell {
  std::string blur, order, size;
};
std::optional<TableCell> parseTableLabel(const std::string& label) {
  static const std::regex pattern(R"(C=(\S+) (PCF|M=\d+) S=(\d+))");
  std::smatch m;
  if (!std::regex_match(label, m, pattern)) return std::nullopt;
  return TableCell{m[1], m[2], m[3]};
}

// One of Table 1's three trends (Annen Table 1: fps falls as the kernel C grows, as the map
// size S grows and as the order M grows): the cell at the axis's last step against the cell at
// its first, for every combination of the other two (the rows of the comparison). Where ours
// is inverted, whether every interleaved round inverts it (cost structure: the per-pass column
// names the passes that differ) or the rounds disagree (noise).
struct TableAxis {
  const char* heading;             // "the convolution trend"
  std::string TableCell::*field;   // what varies
  std::vector<std::string> steps;  // its values, in the paper's column order
  const char* paperSays;           // the paper's trend, in words
  const char* lowCell;             // "the cell without convolution"
  const char* highCell;            // "the 7x7 cell"
  const char* highShort;           // "7x7"
  const char* lowShort;            // "none"
  const char* rows;                // what a row is: "(M, S) pairs"
};

std::string rowKey(const TableCell& c, std::string TableCell::*varying) {
  std::string key;
  if (varying != &TableCell::blur) key += "C=" + c.blur;
  if (varying != &TableCell::order) key += (key.empty() ? "" : " ") + c.order;
  if (varying != &TableCell::size) key += (key.empty() ? "" : " ") + std::string("S=") + c.size;
  return key;
}

std::string tableTrend(const FigureResult& fig, const TableAxis& axis) {
  std::map<std::string, std::map<std::string, const PanelResult*>> cells;
  std::vector<std::string> order;
  for (const PanelResult& p : fig.panels) {
    const auto c = parseTableLabel(p.spec.label);
    if (!c || !timedRender(p)) continue;
    const std::string& step = (*c).*axis.field;
    if (std::find(axis.steps.begin(), axis.steps.end(), step) == axis.steps.end()) continue;
    const std::string key = rowKey(*c, axis.field);
    if (!cells.count(key)) order.push_back(key);
    cells[key][step] = &p;
  }
  const std::string& low = axis.steps.front();
  const std::string& high = axis.steps.back();
  std::ostringstream rows;
  int compared = 0, inverted = 0, invertedEveryRound = 0;
  for (const auto& key : order) {
    auto& bySteps = cells[key];
    if (!bySteps.count(low) || !bySteps.count(high)) continue;
    const PanelResult& first = *bySteps[low];
    const PanelResult& last = *bySteps[high];
    ++compared;
    int rounds = 0;
    // The paper: the last step's cell is slower than the first's.
    const int slowerRounds = roundsGoing(last, first, 1, &rounds);
    const int d = direction(last.milliseconds / first.milliseconds);
    std::string verdict;
    if (d > 0) {
      verdict = std::string("holds (") + axis.highShort + " slower)";
    } else {
      ++inverted;
      if (slowerRounds == 0) {
        ++invertedEveryRound;
        verdict = std::string("inverted in every round (") + axis.highShort + " " +
                  directionWord(d) + "): cost structure, not noise";
      } else {
        verdict = "inverted in the median, the rounds disagree (" + std::to_string(slowerRounds) +
                  " of " + std::to_string(rounds) + " go the paper's way): noise";
      }
    }
    // Where the time goes: per pass, last minus first (medians).
    std::string passes;
    std::map<std::string, double> firstMs;
    for (const PassTime& p : first.passes) firstMs[p.name] += p.milliseconds;
    std::set<std::string> names;
    for (const PassTime& p : last.passes) {
      names.insert(p.name);
      const double delta = p.milliseconds - firstMs[p.name];
      passes += (passes.empty() ? "" : ", ") + p.name + " " + (delta >= 0 ? "+" : "") +
                fixedDecimals(delta, 1);
    }
    for (const auto& [name, ms] : firstMs)
      if (!names.count(name))
        passes += (passes.empty() ? "" : ", ") + name + " -" + fixedDecimals(ms, 1);
    std::string samples;
    for (size_t r = 0; r < std::min(first.frameSamples.size(), last.frameSamples.size()); ++r)
      samples += (samples.empty() ? "" : ", ") + fixedDecimals(first.frameSamples[r], 0) + "/" +
                 fixedDecimals(last.frameSamples[r], 0);
    std::string fps;
    for (const std::string& step : axis.steps)
      if (bySteps.count(step))
        fps += (fps.empty() ? "" : " / ") + fpsOf(bySteps[step]->milliseconds);
    rows << "<tr><td>" << htmlEscape(key) << "</td><td>" << fps << "</td><td>" << samples
         << "</td><td>" << htmlEscape(passes) << "</td><td class=" << (d > 0 ? "ok" : "bad") << ">"
         << htmlEscape(verdict) << "</td></tr>\n";
  }
  if (compared == 0) return "";
  std::string stepNames;
  for (const std::string& step : axis.steps) stepNames += (stepNames.empty() ? "" : " / ") + step;
  std::ostringstream h;
  h << "<p><b>Measured: " << axis.heading << ".</b> " << axis.paperSays
    << " Ours: " << axis.highCell << " is not slower than " << axis.lowCell << " in " << inverted
    << " of " << compared << " " << axis.rows << "; " << invertedEveryRound
    << " of those invert in every interleaved round (cost structure), the other "
    << inverted - invertedEveryRound
    << " only in the median (noise). The per-pass column shows where the time goes ("
    << axis.highShort << " minus " << axis.lowShort
    << ", ms per frame, medians).</p>\n"
       "<table><tr><th>cell</th><th>fps: "
    << htmlEscape(stepNames) << "</th><th>ms per round: " << htmlEscape(axis.lowShort) << "/"
    << htmlEscape(axis.highShort) << "</th><th>per pass, " << htmlEscape(axis.highShort)
    << " minus " << htmlEscape(axis.lowShort) << " (ms)</th><th>paper's trend</th></tr>\n"
    << rows.str() << "</table>\n";
  return h.str();
}

const TableAxis kConvolutionAxis = {
    "the convolution trend",
    &TableCell::blur,
    {"none", "3x3", "7x7"},
    "The paper's frame rate falls as the kernel grows (none, 3x3, 7x7) in every cell.",
    "the cell without convolution",
    "the 7x7 cell",
    "7x7",
    "none",
    "(M, S) pairs"};
const TableAxis kMapSizeAxis = {
    "the map-size trend",
    &TableCell::size,
    {"256", "512", "1024", "2048"},
    "The paper's frame rate falls as the shadow map grows (256² to 2048²) in every row, PCF's "
    "included.",
    "the 256² cell",
    "the 2048² cell",
    "2048²",
    "256²",
    "(C, M) rows"};
const TableAxis kOrderAxis = {
    "the order trend",
    &TableCell::order,
    {"M=4", "M=8", "M=16"},
    "The paper's frame rate falls as the order M grows (4, 8, 16: two, four and eight RGBA "
    "fetches per shaded pixel) in every cell.",
    "the M=4 cell",
    "the M=16 cell",
    "M=16",
    "M=4",
    "(C, S) pairs"};

// ---------------------------------------------------------------- Chan Figs. 3-10, 3-11
// H/SV per scene: every hybrid panel against the volumes panel of its scene.
std::string hybridAgainstVolumes(const FigureResult& fig) {
  std::ostringstream rows;
  int faster = 0, compared = 0;
  for (const PanelResult& h : fig.panels) {
    if (!timedRender(h) || h.spec.technique != "modern.hybrid") continue;
    const PanelResult* sv = nullptr;
    for (const PanelResult& p : fig.panels)
      if (timedRender(p) && p.spec.technique == "modern.volumes" &&
          sceneOf(fig, p) == sceneOf(fig, h))
        sv = &p;
    if (sv == nullptr) continue;
    ++compared;
    const double ratio = h.milliseconds / sv->milliseconds;
    int rounds = 0;
    const int fasterRounds = roundsGoing(h, *sv, -1, &rounds);
    const bool isFaster = direction(ratio) < 0;
    faster += isFaster ? 1 : 0;
    rows << "<tr><td>" << htmlEscape(h.spec.label) << "</td><td>"
         << fixedDecimals(h.milliseconds, 1) << " / " << fixedDecimals(sv->milliseconds, 1) << " = "
         << fixedDecimals(ratio, 2) << "</td><td>" << fasterRounds << " of " << rounds
         << "</td><td class=" << (isFaster ? "ok" : "bad") << ">"
         << (isFaster ? "holds (hybrid faster)" : "does not hold") << "</td></tr>\n";
  }
  if (compared == 0) return "";
  std::ostringstream h;
  h << "<p><b>Measured: hybrid (H) against shadow volumes (SV), per scene.</b> Chan: the hybrid "
       "is 30-100% faster than shadow volumes (H/SV 0.5-0.77). Ours, medians of the interleaved "
       "rounds: the hybrid is faster in "
    << faster << " of " << compared << " panels.</p>\n"
    << "<table><tr><th>hybrid panel</th><th>H / SV (ms)</th><th>rounds H faster</th>"
       "<th>Chan's trend</th></tr>\n"
    << rows.str() << "</table>\n";
  return h.str();
}

// The counters the captions used to quote, per panel, as this run measured them.
std::string fillCounters(const FigureResult& fig, bool timesToo) {
  const std::vector<std::pair<const char*, const char*>> names = {
      {"volume_overdraw", "volume fragments per pixel (overdraw)"},
      {"volume_coverage", "share of the image under volumes"},
      {"silhouette_fraction", "silhouette pixels"},
      {"volume_pass_fs_invocations", "volume-pass fragment-shader runs per pixel"},
      {"masked_overdraw", "volume fragments the mask lets update the stencil, per pixel"},
      {"mask_tile_fraction", "share of the image in tile boxes"}};
  std::ostringstream rows;
  for (const PanelResult& p : fig.panels) {
    if (!p.ok || p.spec.kind != PanelKind::kRender) continue;
    std::string cells;
    bool any = false;
    for (const auto& [name, words] : names) {
      const auto v = counter(p, name);
      any = any || v.has_value();
      const bool share = std::string(name).find("fraction") != std::string::npos ||
                         std::string(name) == "volume_coverage";
      cells +=
          "<td>" + (v ? (share ? percent(*v) : fixedDecimals(*v, 2)) : std::string("")) + "</td>";
    }
    if (!any) continue;
    rows << "<tr><td>" << htmlEscape(p.spec.label) << "</td>" << cells;
    if (timesToo) rows << "<td>" << fixedDecimals(p.milliseconds, 1) << "</td>";
    rows << "</tr>\n";
  }
  if (rows.str().empty()) return "";
  std::ostringstream h;
  h << "<table><tr><th>panel</th>";
  for (const auto& [name, words] : names)
    h << "<th>" << htmlEscape(words) << " <small><code>" << name << "</code></small></th>";
  if (timesToo) h << "<th>frame (ms)</th>";
  h << "</tr>\n" << rows.str() << "</table>\n";
  return h.str();
}

std::string chan310(const FigureResult& fig) {
  std::ostringstream h;
  std::string overdraws;
  for (const PanelResult& p : fig.panels)
    if (p.ok && p.spec.technique == "modern.volumes")
      if (const auto o = counter(p, "volume_overdraw"))
        overdraws += (overdraws.empty() ? "" : ", ") + sceneOf(fig, p) + " " +
                     fixedDecimals(*o, 1) +
                     (counter(p, "volume_coverage")
                          ? " over " + percent(*counter(p, "volume_coverage")) + " of the image"
                          : std::string());
  std::string silhouettes;
  std::map<std::string, std::pair<double, double>> range;  // scene -> min, max share
  for (const PanelResult& p : fig.panels)
    if (p.ok && p.spec.technique == "modern.hybrid")
      if (const auto s = counter(p, "silhouette_fraction")) {
        auto [it, fresh] = range.insert({sceneOf(fig, p), {*s, *s}});
        if (!fresh) it->second = {std::min(it->second.first, *s), std::max(it->second.second, *s)};
      }
  for (const auto& [scene, r] : range)
    silhouettes += (silhouettes.empty() ? "" : ", ") + scene + " " + percent(r.first) + "-" +
                   percent(r.second);
  if (overdraws.empty() && silhouettes.empty()) return "";
  h << "<p><b>Measured.</b> Shadow-volume overdraw (volume fragments per covered pixel): "
    << htmlEscape(overdraws)
    << ". Silhouette pixels of the hybrid across the map sizes: " << htmlEscape(silhouettes)
    << ".</p>\n"
    << fillCounters(fig, false);
  return h.str();
}

// ---------------------------------------------------------------- legacy/modern twins
// Every twin pair whose images differ beyond registry/twins.h's image bound, with this run's
// counts; the figure's caption says why (brabec-fig8: Gouraud against per-pixel lighting on
// the teapot's mesh).
std::string twinsBeyondImageBound(const FigureResult& fig) {
  std::string items;
  for (const PanelResult& p : fig.panels) {
    if (!p.ok || !p.twin || p.twin->image.withinBound) continue;
    const twins::ImageAgreement& a = p.twin->image;
    items += (items.empty() ? "" : "; ") + p.spec.label + " (" + p.spec.technique + " against " +
             p.twin->technique + "): " + std::to_string(a.beyondWhereMasksAgree) +
             " pixels beyond " + std::to_string(twins::kImageSteps) +
             "/255 where the masks agree, bound " + std::to_string(a.boundPixels) +
             ", largest channel difference " + fixedDecimals(a.maxAbs, 3) +
             "; their masks differ on " + std::to_string(p.twin->difference.mismatching) +
             " pixels";
  }
  if (items.empty()) return "";
  return "<p><b>Measured: twins beyond their image bound.</b> " + htmlEscape(items) +
         ". The bound (registry/twins.h) allows the cone-edge band and a few 8-bit steps for "
         "Gouraud against per-pixel shading; the image-difference pictures show where the rest "
         "lies.</p>\n";
}

// ---------------------------------------------------------------- error-vs-time
// Per shadow group (core/technique/technique.h shadowGroup): every technique's RMSE, the share
// of its squared error within 2 px of the reference's shadow edges, and its wrong pixels; then
// the group's largest RMSE against its smallest, and where that error lies.
const Technique* techniqueNamed(const std::string& name) {
  for (const Technique& t : allTechniques())
    if (t.name == name) return &t;
  return nullptr;
}

double bandShareOf(const PanelResult& p) {
  const double all = p.error->rmse * p.error->rmse * double(p.error->pixels);
  const double band =
      p.errorDetail->bandRmse * p.errorDetail->bandRmse * double(p.errorDetail->bandPixels);
  return all > 0 ? band / all : 0.0;
}

std::string errorVsTime(const FigureResult& fig) {
  std::vector<std::string> groups;
  std::map<std::string, std::vector<const PanelResult*>> byGroup;
  for (const PanelResult& p : fig.panels) {
    const Technique* t =
        p.ok && p.error && p.errorDetail ? techniqueNamed(p.spec.technique) : nullptr;
    if (t == nullptr) continue;
    const std::string g = shadowGroup(*t);
    if (!byGroup.count(g)) groups.push_back(g);
    byGroup[g].push_back(&p);
  }
  if (groups.empty()) return "";
  std::ostringstream rows, words;
  for (const std::string& g : groups) {
    auto& panels = byGroup[g];
    std::stable_sort(panels.begin(), panels.end(), [](const PanelResult* a, const PanelResult* b) {
      return a->error->rmse < b->error->rmse;
    });
    for (const PanelResult* p : panels)
      rows << "<tr><td>" << htmlEscape(g) << "</td><td>" << htmlEscape(p->spec.technique)
           << "</td><td>" << fixedDecimals(p->milliseconds, 1) << "</td><td>"
           << fixedDecimals(p->error->rmse, 4) << "</td><td>" << percent(bandShareOf(*p))
           << "</td><td>" << p->error->mismatching << "</td></tr>\n";
    const PanelResult& best = *panels.front();
    const PanelResult& worst = *panels.back();
    if (panels.size() < 2) continue;
    words << " " << g << ": the largest RMSE is " << htmlEscape(worst.spec.technique) << "'s ("
          << fixedDecimals(worst.error->rmse, 4) << ", the smallest "
          << htmlEscape(best.spec.technique) << "'s " << fixedDecimals(best.error->rmse, 4) << "); "
          << percent(bandShareOf(worst))
          << " of its squared error lies within 2 px of the reference's shadow edges (the "
             "outlines of the cast shadows and the terminators of curved blockers), "
          << worst.error->mismatching << " pixels off by more than 0.5.";
  }
  std::ostringstream h;
  h << "<p><b>Measured: where each group's error lies.</b>" << words.str()
    << " Band share: the share of a technique's squared error within 2 px of the reference's "
       "shadow edges; what is left lies beyond them (light leaking into the umbra, acne on lit "
       "surfaces).</p>\n<table><tr><th>group</th><th>technique</th><th>frame (ms)</th>"
       "<th>RMSE</th><th>band share</th><th>pixels off by more than 0.5</th></tr>\n"
    << rows.str() << "</table>\n";
  return h.str();
}

// ---------------------------------------------------------------- FigureSpec::bothMetrics
// Per scene and reference: which technique has the smallest RMSE by the area metric and which
// by the point metric, as this run measured them.
std::string smallestByMetric(const FigureResult& fig) {
  std::vector<std::pair<std::string, std::string>> order;  // (scene, reference)
  std::map<std::pair<std::string, std::string>, std::vector<const PanelResult*>> byGroup;
  for (const PanelResult& p : fig.panels) {
    if (!p.ok || !p.error || !p.pointError) continue;
    const std::pair<std::string, std::string> key = {
        p.spec.scene.empty() ? fig.spec.scene : p.spec.scene,
        p.spec.reference.empty() ? fig.spec.reference : p.spec.reference};
    if (!byGroup.count(key)) order.push_back(key);
    byGroup[key].push_back(&p);
  }
  std::ostringstream words;
  for (const auto& key : order) {
    const auto& panels = byGroup[key];
    if (panels.size() < 2) continue;
    const auto least = [&](auto metric) {
      return *std::min_element(
          panels.begin(), panels.end(),
          [&](const PanelResult* a, const PanelResult* b) { return metric(*a) < metric(*b); });
    };
    const PanelResult* area = least([](const PanelResult& p) { return p.error->rmse; });
    const PanelResult* point = least([](const PanelResult& p) { return p.pointError->rmse; });
    words << " " << htmlEscape(key.first) << " against " << htmlEscape(key.second)
          << ": the smallest area-metric RMSE is " << htmlEscape(area->spec.label) << "'s ("
          << fixedDecimals(area->error->rmse, 4) << "), the smallest point-metric RMSE "
          << htmlEscape(point->spec.label) << "'s (" << fixedDecimals(point->pointError->rmse, 4)
          << ")" << (area == point ? ", the same technique." : ".");
  }
  std::ostringstream rows;
  for (const auto& key : order)
    for (const PanelResult* p : byGroup[key])
      rows << "<tr><td>" << htmlEscape(key.first) << "</td><td>" << htmlEscape(p->spec.label)
           << "</td><td>" << htmlEscape(key.second) << "</td><td>"
           << fixedDecimals(p->error->rmse, 4) << "</td><td>"
           << fixedDecimals(p->pointError->rmse, 4) << "</td><td>"
           << (p->errorDetail ? percent(bandShareOf(*p)) : "") << "</td></tr>\n";
  if (rows.str().empty()) return "";
  return "<p><b>Measured: the smallest error by each metric.</b>" + words.str() +
         " Band share: the share of a panel's area-metric squared error within " +
         std::to_string(kBandRadiusPixels) +
         " px of the reference's shadow edges.</p>\n<table><tr><th>scene</th><th>panel</th>"
         "<th>reference</th><th>RMSE, area metric</th><th>RMSE, point metric</th><th>band "
         "share</th></tr>\n" +
         rows.str() + "</table>\n";
}

// ---------------------------------------------------------------- Chan Fig. 3-9
// The overdraw factor and the share of silhouette pixels, ours beside the thesis's (the panels'
// paperNumbers: "overdraw factor 79", "silhouette pixels 5% of the image").
std::string chan39(const FigureResult& fig) {
  std::string rows;
  for (const PanelResult& p : fig.panels) {
    if (!p.ok || p.spec.paperNumbers.empty()) continue;
    const auto overdraw = counter(p, "volume_overdraw");
    const auto silhouettes = counter(p, "silhouette_fraction");
    std::string ours;
    if (p.spec.technique == "modern.volumes" && overdraw)
      ours = "overdraw factor " + fixedDecimals(*overdraw, 1) +
             " (volume_overdraw: volume fragments / "
             "image pixels)";
    else if (p.spec.technique == "modern.hybrid" && silhouettes)
      ours = "silhouette pixels " + percent(*silhouettes) + " of the image (silhouette_fraction)";
    if (ours.empty()) continue;
    rows += "<tr><td>" + htmlEscape(p.spec.label) + "</td><td>" + htmlEscape(ours) +
            "</td><td class=paper>" + htmlEscape(p.spec.paperNumbers) + "</td></tr>\n";
  }
  if (rows.empty()) return "";
  return "<p><b>Measured: ours beside the thesis's Dragon Cage.</b> Our scene is a stand-in "
         "(the Stanford dragon in a cage of bars), so the numbers compare in kind, not in "
         "value.</p>\n<table><tr><th>panel</th><th>ours (this run)</th><th>thesis</th></tr>\n" +
         rows + "</table>\n";
}

// ---------------------------------------------------------------- Chan Fig. 3-7
// The passes of modern.hybrid and modern.volumes by their pass-table ids
// (modern/hybrid_shadows.cpp hybridPasses, modern/shadow_volumes.cpp volumesPasses).
constexpr const char* kHybridMapPass = "1";       // the shadow map (§3.1 step 1)
constexpr const char* kHybridClassifyPass = "3";  // the classification (§3.1 step 2)
constexpr const char* kHybridVolumePass = "5";    // volumes at silhouette pixels (step 3)
constexpr const char* kVolumesStencilPass = "3";  // modern.volumes' z-fail count
constexpr const char* kShadowMapTechnique = "modern.hw";
constexpr const char* kHybridTechnique = "modern.hybrid";
constexpr const char* kVolumesTechnique = "modern.volumes";

// The milliseconds of a panel's passes with pass-table id `id` (every part of it).
double passIdMilliseconds(const PanelResult& p, const std::string& id) {
  double ms = 0;
  for (const PassTime& pass : p.passes)
    if (pass.id == id) ms += pass.milliseconds;
  return ms;
}

// The render panel (not an overlay) of `technique` on `scene`, or null.
const PanelResult* scenePanel(const FigureResult& fig, const std::string& scene,
                              const std::string& technique) {
  for (const PanelResult& p : fig.panels)
    if (p.ok && p.spec.kind == PanelKind::kRender && p.spec.errorsOf.empty() &&
        p.spec.technique == technique && sceneOf(fig, p) == scene)
      return &p;
  return nullptr;
}

// Per scene, the pixels the shadow map and the hybrid decide otherwise than the volumes (the
// counters of the overlay panels, figures/disagreement.h); each column's error against the
// figure's reference; and where the hybrid's time goes beside the volumes'.
std::string chan37(const FigureResult& fig) {
  std::string rows, errorRows, timeRows;
  int errorScenes = 0, hybridBelowMap = 0, volumesAboveMapToo = 0, timeScenes = 0, hybridSlower = 0;
  for (const PanelResult& p : fig.panels) {
    if (!p.ok || p.spec.errorsOf.size() != 2) continue;
    const std::string scene = sceneOf(fig, p);
    const auto first = counter(p, kWrongPixelsCounter + p.spec.errorsOf[0]);
    const auto second = counter(p, kWrongPixelsCounter + p.spec.errorsOf[1]);
    const auto both = counter(p, kBothWrongCounter);
    if (first && second && both) {
      const int w = p.spec.width ? p.spec.width : fig.spec.width;
      const int h = p.spec.height ? p.spec.height : fig.spec.height;
      const double pixels = double(w) * double(h);
      rows += "<tr><td>" + htmlEscape(scene) + "</td><td>" + fixedDecimals(*first, 0) + " (" +
              percent(*first / pixels) + ")</td><td>" + fixedDecimals(*second, 0) + " (" +
              percent(*second / pixels) + ")</td><td>" + fixedDecimals(*both, 0) + "</td><td>" +
              (*first > 0 ? percent((*first - *both) / *first) : std::string("-")) + "</td></tr>\n";
    }
    const PanelResult* sm = scenePanel(fig, scene, kShadowMapTechnique);
    const PanelResult* hy = scenePanel(fig, scene, kHybridTechnique);
    const PanelResult* sv = scenePanel(fig, scene, kVolumesTechnique);
    if (sm && hy && sv && sm->error && hy->error && sv->error) {
      ++errorScenes;
      const bool below = hy->error->rmse <= sm->error->rmse;
      hybridBelowMap += below ? 1 : 0;
      volumesAboveMapToo += !below && sv->error->rmse > sm->error->rmse ? 1 : 0;
      errorRows += "<tr><td>" + htmlEscape(scene) + "</td><td>" +
                   fixedDecimals(sm->error->rmse, 4) + "</td><td>" +
                   fixedDecimals(hy->error->rmse, 4) + "</td><td>" +
                   fixedDecimals(sv->error->rmse, 4) + "</td><td class=" + (below ? "ok" : "bad") +
                   ">" + (below ? "yes" : "no") + "</td></tr>\n";
    }
    if (hy && sv && hy->milliseconds > 0 && sv->milliseconds > 0) {
      ++timeScenes;
      const bool slower = hy->milliseconds > sv->milliseconds;
      hybridSlower += slower ? 1 : 0;
      const double extra =
          passIdMilliseconds(*hy, kHybridMapPass) + passIdMilliseconds(*hy, kHybridClassifyPass);
      const double saved =
          passIdMilliseconds(*sv, kVolumesStencilPass) - passIdMilliseconds(*hy, kHybridVolumePass);
      const auto share = counter(*hy, "silhouette_fraction");
      const auto masked = counter(*hy, "masked_overdraw");
      const auto overdraw = counter(*sv, "volume_overdraw");
      timeRows +=
          "<tr><td>" + htmlEscape(scene) + "</td><td>" + fixedDecimals(hy->milliseconds, 1) +
          " / " + fixedDecimals(sv->milliseconds, 1) + " = " +
          fixedDecimals(hy->milliseconds / sv->milliseconds, 2) + "</td><td>" +
          (share ? percent(*share) : std::string("-")) + "</td><td>" +
          (masked && overdraw ? fixedDecimals(*masked, 2) + " of " + fixedDecimals(*overdraw, 2)
                              : std::string("-")) +
          "</td><td>" + fixedDecimals(extra, 1) + "</td><td>" + fixedDecimals(saved, 1) +
          "</td></tr>\n";
    }
  }
  std::string h;
  if (!rows.empty())
    h += "<p><b>Measured: scored pixels decided otherwise than the shadow volumes</b> (lit or "
         "in shadow, at half visibility; the scored pixels of docs/error.md, surfaces facing the "
         "light; shares of the whole image), per scene; the last column is the share of the "
         "shadow map's wrong pixels that the hybrid decides right.</p>\n<table><tr><th>scene</th>"
         "<th>shadow map wrong</th><th>hybrid wrong</th><th>both wrong</th><th>of the shadow "
         "map's, corrected by the hybrid</th></tr>\n" +
         rows + "</table>\n";
  if (errorScenes > 0)
    h += "<p><b>Measured: error against the figure's reference</b> (RMSE over the scored pixels, "
         "the metric named under each panel): the hybrid's error is at most the shadow map's "
         "with the same map on " +
         std::to_string(hybridBelowMap) + " of " + std::to_string(errorScenes) + " scenes" +
         (volumesAboveMapToo > 0
              ? "; where it is above, so are the exact shadow volumes on " +
                    std::to_string(volumesAboveMapToo) + " of " +
                    std::to_string(errorScenes - hybridBelowMap) +
                    " (a metric that integrates over the pixel counts a hard edge, exact at the "
                    "pixel centre, against a filtered one)"
              : std::string()) +
         ".</p>\n<table><tr><th>scene</th><th>shadow map</th><th>hybrid</th><th>shadow "
         "volumes</th><th>hybrid at most the shadow map</th></tr>\n" +
         errorRows + "</table>\n";
  if (timeScenes > 0) {
    h += "<p><b>Measured: where the hybrid's time goes</b> (this run's frame and pass times, "
         "each a median of the panel's timed frames): the hybrid is slower than the volumes on " +
         std::to_string(hybridSlower) + " of " + std::to_string(timeScenes) +
         " scenes. Its extra passes, the shadow map and the classification (a second, "
         "shadow-mapped draw of the scene), are paid in full; its volume pass saves time only "
         "where the renderer rejects the masked fragments before shading them (llvmpipe tests "
         "the stencil bit after rasterising; only the tile boxes of mask=tiles skip work, "
         "docs/volumes.md)";
    h += hybridSlower > 0 ? std::string(
                                "; Chan §3.4.1: \"Ordinary shadow volumes will clearly run "
                                "faster for scenes of sufficiently low shadow complexity.\"")
                          : std::string(".");
    h += "</p>\n<table><tr><th>scene</th><th>H / SV (ms)</th><th>silhouette pixels</th>"
         "<th>volume fragments per pixel: through the mask of all</th><th>H: shadow map + "
         "classification (ms)</th><th>volume pass time saved (ms)</th></tr>\n" +
         timeRows + "</table>\n";
  }
  return h;
}

// ---------------------------------------------------------------- Chan Fig. 4-8
// The milliseconds of a panel's passes whose name contains `part` ("camera").
double passMilliseconds(const PanelResult& p, const std::string& part) {
  double ms = 0;
  for (const PassTime& pass : p.passes)
    if (pass.name.find(part) != std::string::npos) ms += pass.milliseconds;
  return ms;
}

bool isBicubic(const PanelResult& p) {
  const auto it = p.spec.params.find("kernel");
  return p.spec.technique == "modern.gems16" && it != p.spec.params.end() &&
         it->second == "bicubic";
}

// Per map size: the bicubic 16-sample frame against one comparison (the thesis: about 8x) and
// against the narrow smoothie (the thesis: "much faster than using the bicubic filter"), with the
// camera passes, where the 16 comparisons are made.
std::string chan48(const FigureResult& fig) {
  std::ostringstream rows;
  int compared = 0, withSmoothie = 0, smoothieFaster = 0;
  std::string smoothieWidth;  // the smoothie panels' --param width, as the figure sets it
  for (const PanelResult& b : fig.panels) {
    if (!timedRender(b) || !isBicubic(b)) continue;
    const PanelResult *plain = nullptr, *smoothie = nullptr;
    for (const PanelResult& p : fig.panels) {
      if (!timedRender(p) || texelsOf(fig, p) != texelsOf(fig, b)) continue;
      if (p.spec.technique == "modern.hw" && plain == nullptr) plain = &p;
      if (p.spec.technique == "modern.smoothies" && smoothie == nullptr) smoothie = &p;
    }
    if (plain == nullptr) continue;
    ++compared;
    const auto paperB = paperMilliseconds(b.spec.paperNumbers);
    const auto paperPlain = paperMilliseconds(plain->spec.paperNumbers);
    const double cameraB = passMilliseconds(b, "camera");
    const double cameraPlain = passMilliseconds(*plain, "camera");
    rows << "<tr><td>" << texelsOf(fig, b) << "²</td><td>" << fixedDecimals(b.milliseconds, 1)
         << " / " << fixedDecimals(plain->milliseconds, 1) << " = "
         << fixedDecimals(b.milliseconds / plain->milliseconds, 2) << "</td><td class=paper>"
         << (paperB && paperPlain
                 ? fixedDecimals(*paperB, 0) + " / " + fixedDecimals(*paperPlain, 0) + " = " +
                       fixedDecimals(*paperB / *paperPlain, 2)
                 : std::string("-"))
         << "</td><td>" << fixedDecimals(cameraB, 1) << " / " << fixedDecimals(cameraPlain, 1)
         << " = " << fixedDecimals(cameraPlain > 0 ? cameraB / cameraPlain : 0.0, 2) << "</td><td>";
    if (smoothie != nullptr) {
      if (const auto w = smoothie->spec.params.find("width"); w != smoothie->spec.params.end())
        smoothieWidth = w->second;
      ++withSmoothie;
      smoothieFaster += direction(smoothie->milliseconds / b.milliseconds) < 0 ? 1 : 0;
      const auto paperS = paperMilliseconds(smoothie->spec.paperNumbers);
      rows << fixedDecimals(smoothie->milliseconds / b.milliseconds, 2) << "</td><td class=paper>"
           << (paperS && paperB ? fixedDecimals(*paperS / *paperB, 2) : std::string("-"));
    } else {
      rows << "-</td><td class=paper>-";
    }
    rows << "</td></tr>\n";
  }
  if (compared == 0) return "";
  std::ostringstream h;
  h << "<p><b>Measured: the bicubic 16-sample PCF against one comparison and against "
       "smoothies.</b> Frame times are medians of the interleaved rounds on this run's "
       "renderer; the thesis's are on a GeForce FX 5800 Ultra. The camera pass is where the "
       "16 comparisons (or the one) are made; the light pass is the same in both. The thesis's "
       "smoothies are faster than its bicubic filter at every map size (\"still much faster "
       "than using the bicubic filter\", §4.4); ours at "
    << smoothieFaster << " of " << withSmoothie
    << ".</p>\n"
       "<table><tr><th>map</th><th>bicubic / one comparison (ms)</th><th>thesis</th>"
       "<th>camera pass: bicubic / one comparison (ms)</th><th>smoothie"
    << htmlEscape(smoothieWidth.empty() ? "" : " (width " + smoothieWidth + ")")
    << " / bicubic</th><th>thesis</th></tr>\n"
    << rows.str() << "</table>\n";
  return h.str();
}

// ---------------------------------------------------------------- CSM Fig. 9
std::string csmFig9(const FigureResult& fig) {
  const PanelResult *vsm = nullptr, *csm = nullptr;
  for (const PanelResult& p : fig.panels) {
    if (!p.ok || !p.error || !p.errorDetail) continue;
    if (p.spec.technique == "modern.vsm") vsm = &p;
    if (p.spec.technique == "modern.csm") csm = &p;
  }
  if (!vsm || !csm) return "";
  auto line = [](const char* name, const PanelResult& p) {
    const ErrorDetail& d = *p.errorDetail;
    return std::string(name) + ": RMSE " + fixedDecimals(p.error->rmse, 3) +
           ", within 2 px of the "
           "reference's shadow edges " +
           fixedDecimals(d.bandRmse, 3) +
           "; umbra pixels beyond that band shown more than 20% lit " + percent(d.leakShare) +
           " of " + std::to_string(d.umbraPixels) + "; deep umbra (over " +
           std::to_string(kDeepUmbraPixels) + " px from any edge, " +
           std::to_string(d.deepUmbraPixels) + " pixels): mean visibility " +
           fixedDecimals(d.deepUmbraMean, 4) + ", " + percent(d.deepLeakShare) +
           " shown more than " + fixedDecimals(100.0 * kDeepLeakThreshold, 0) + "% lit";
  };
  // The share of the squared error inside the edge band: where RMSE ranks them.
  auto bandShare = [](const PanelResult& p) {
    const double all = p.error->rmse * p.error->rmse * double(p.error->pixels);
    const double band =
        p.errorDetail->bandRmse * p.errorDetail->bandRmse * double(p.errorDetail->bandPixels);
    return all > 0 ? band / all : 0.0;
  };
  const ErrorDetail &v = *vsm->errorDetail, &c = *csm->errorDetail;
  std::ostringstream h;
  h << "<p><b>Measured</b> (against the figure's reference): " << htmlEscape(line("VSM", *vsm))
    << ". " << htmlEscape(line("CSM", *csm)) << ". ";
  const bool csmWorseRmse = csm->error->rmse > vsm->error->rmse;
  const bool vsmBleeds = v.deepLeakShare > c.deepLeakShare;
  h << "RMSE: " << (csmWorseRmse ? "VSM lower (better) than CSM" : "CSM lower (better) than VSM")
    << ". Deep-umbra pixels shown more than " << fixedDecimals(100.0 * kDeepLeakThreshold, 0)
    << "% lit, out of reach of a blurred penumbra: VSM " << percent(v.deepLeakShare) << ", CSM "
    << percent(c.deepLeakShare) << ": "
    << (vsmBleeds ? "VSM bleeds more, as the paper says"
                  : "VSM does not bleed more, not as the "
                    "paper says")
    << ". RMSE counts every pixel: " << percent(bandShare(*csm))
    << " of CSM's squared error (VSM: " << percent(bandShare(*vsm))
    << ") lies within 2 pixels of the shadow edges, so RMSE ranks the two by their edges, not by "
       "the faint bleeding inside the sphere's and box's shadows that Fig. 9 is about; the "
       "deep-umbra share measures that. The bench's bleeding scene (docs/bench.md) is built to "
       "make VSM bleed and tests the claim there.";
  h << "</p>\n";
  return h.str();
}

}  // namespace

std::optional<double> paperMilliseconds(const std::string& text) {
  static const std::regex time(R"((\d+(?:\.\d+)?)(?:\s*-\s*(\d+(?:\.\d+)?))?\s*(fps|ms)\b)");
  std::smatch m;
  if (!std::regex_search(text, m, time)) return std::nullopt;
  double v = std::stod(m[1]);
  if (m[2].matched) v = 0.5 * (v + std::stod(m[2]));
  if (!(v > 0)) return std::nullopt;
  return m[3] == "fps" ? 1000.0 / v : v;
}

std::vector<TrendCell> timingTrend(const FigureResult& fig) {
  std::vector<const PanelResult*> cells;
  for (const PanelResult& p : fig.panels)
    if (timedRender(p) && paperMilliseconds(p.spec.paperNumbers)) cells.push_back(&p);
  std::vector<TrendCell> out;
  for (const PanelResult* p : cells) {
    const PanelResult* base = nullptr;
    for (const PanelResult* q : cells)
      if (sceneOf(fig, *q) == sceneOf(fig, *p) && texelsOf(fig, *q) == texelsOf(fig, *p)) {
        base = q;
        break;
      }
    if (base == nullptr || base == p) continue;
    TrendCell c;
    c.label = p->spec.label;
    c.baseline = base->spec.label;
    c.ours = p->milliseconds;
    c.oursBaseline = base->milliseconds;
    c.paper = *paperMilliseconds(p->spec.paperNumbers);
    c.paperBaseline = *paperMilliseconds(base->spec.paperNumbers);
    const int paperWay = direction(c.paper / c.paperBaseline);
    const int oursWay = direction(c.ours / c.oursBaseline);
    c.roundsAgreeing = roundsGoing(*p, *base, paperWay, &c.rounds);
    if (oursWay == paperWay)
      c.verdict = std::string("holds (") + directionWord(oursWay) + ")";
    else
      c.verdict = std::string("does not hold: paper ") + directionWord(paperWay) + ", ours " +
                  directionWord(oursWay) +
                  (c.roundsAgreeing == 0 ? " in every round" : " in the median only (noise)");
    out.push_back(c);
  }
  return out;
}

std::string measuredHtml(const FigureResult& fig) {
  const std::string id = fig.spec.sourceId.empty() ? fig.spec.id : fig.spec.sourceId;
  std::string h = trendTable(timingTrend(fig));
  if (id == "csm-table1")
    h += tableTrend(fig, kConvolutionAxis) + tableTrend(fig, kMapSizeAxis) +
         tableTrend(fig, kOrderAxis);
  if (id == "brabec-fig7" || id == "brabec-fig8") h += passBreakdown(fig);
  if (id == "brabec-fig8") h += depthBiasCounts(fig);
  h += twinsBeyondImageBound(fig);
  if (id == "chan-3-11") h += hybridAgainstVolumes(fig) + fillCounters(fig, true);
  if (id == "chan-3-10") h += chan310(fig);
  if (id == "chan-3-9") h += chan39(fig);
  if (id == "error-vs-time") h += errorVsTime(fig);
  if (fig.spec.bothMetrics) h += smallestByMetric(fig);
  if (id == "chan-4-8") h += chan48(fig);
  if (id == "chan-3-7") h += chan37(fig);
  if (id == "csm-fig9") h += csmFig9(fig);
  return h.empty() ? "" : "<div class=measured>" + h + "</div>\n";
}

}  // namespace sl::figures
