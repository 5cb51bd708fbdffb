// figures/report.cpp — report.html: one gallery per paper, the figures laid out as the papers
// lay them out, close-ups, legacy/modern pairs with their difference images, our numbers
// beside the paper's, and every missing panel in red with the reason.
#include "figures/report.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "core/base/decimal.h"
#include "core/base/errors.h"
#include "core/base/html.h"
#include "core/base/output_files.h"
#include "core/base/provenance.h"

namespace sl::figures {
namespace fs = std::filesystem;

namespace {

std::string msAndFps(double ms) {
  if (ms <= 0) return "";
  return fixedDecimals(ms, 1) + " ms (" + fixedDecimals(1000.0 / ms, 1) + " fps)";
}

// A frame time and how it was measured: a steady-state median (core/technique/frame_timing.h) or
// one first frame in a fresh context (marked, as it is not comparable with a paper's number).
std::string frameTime(double ms, int timedFrames) {
  if (ms <= 0) return "";
  if (timedFrames > 0)
    return msAndFps(ms) + " <small>median of " + std::to_string(timedFrames) + "</small>";
  return "<small>first frame</small> " + msAndFps(ms);
}

// The CPU of this machine: the first "model name" of /proc/cpuinfo, and the processor count.
std::string cpuModel() {
  std::ifstream in("/proc/cpuinfo");
  std::string line, model;
  int processors = 0;
  while (std::getline(in, line)) {
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    const std::string key = line.substr(0, line.find_last_not_of(" \t", colon - 1) + 1);
    if (key == "processor") ++processors;
    if (key == "model name" && model.empty()) {
      const auto start = line.find_first_not_of(' ', colon + 1);
      model = start == std::string::npos ? "" : line.substr(start);
    }
  }
  if (model.empty()) model = "unknown CPU";
  return processors > 0 ? model + " (" + std::to_string(processors) + " logical processors)"
                        : model;
}

// The load averages over 1, 5 and 15 minutes as the report is written (getloadavg(3)).
std::string loadAverages() {
  constexpr int kAverages = 3;
  double load[kAverages] = {};
  if (getloadavg(load, kAverages) != kAverages) return "unknown";
  return fixedDecimals(load[0], 2) + ", " + fixedDecimals(load[1], 2) + ", " +
         fixedDecimals(load[2], 2);
}

const char* kStyle = R"(
body { font-family: sans-serif; margin: 1.5em; color: #222; max-width: 1700px; }
h1 { margin-bottom: 0.2em; } h2 { border-bottom: 2px solid #888; margin-top: 2em; }
article { margin: 1.5em 0 2.5em; }
.caption { max-width: 70em; }
.grid { display: grid; gap: 6px; align-items: start; margin: 0.5em 0; }
figure { margin: 0; }
figure img { max-width: 100%; image-rendering: pixelated; border: 1px solid #ccc; }
figcaption { font-size: 0.85em; }
.missing { color: #c00; border: 2px dashed #c00; padding: 0.6em; font-size: 0.9em; }
.missing b { color: #c00; }
table { border-collapse: collapse; font-size: 0.85em; margin: 0.5em 0; }
td, th { border: 1px solid #bbb; padding: 2px 6px; text-align: left; vertical-align: top; }
th { background: #eee; }
.paper { color: #05a; }
.ok { color: #070; } .bad { color: #c00; }
.buffers { grid-column: 1 / -1; }
.plots { display: grid; grid-template-columns: repeat(auto-fit, minmax(480px, 1fr)); gap: 6px; }
.inter { display: flex; flex-wrap: wrap; gap: 6px; align-items: flex-start; }
.inter figure { max-width: 100%; }
.inter img { width: auto; height: auto; max-width: 100%; max-height: 240px; }
nav li { margin: 2px 0; }
)";

void writePanelCell(std::ostream& h, const PanelResult& p) {
  if (!p.ok) {
    h << "<div class=missing><b>missing: " << htmlEscape(p.spec.label) << "</b><br>"
      << htmlEscape(p.reason) << "</div>\n";
    return;
  }
  if (p.spec.kind == PanelKind::kIntermediates) {
    // A buffer strip spans the whole row of its grid and wraps its buffers there, each at its
    // own aspect ratio.
    h << "<div class=buffers><b>" << htmlEscape(p.spec.label) << "</b> ("
      << htmlEscape(p.spec.technique) << ")<div class=inter>";
    for (const ImageFile& im : p.images)
      h << "<figure><a href=\"" << htmlEscape(im.file) << "\"><img src=\"" << htmlEscape(im.file)
        << "\" alt=\"" << htmlEscape(im.caption) << "\"></a><figcaption>" << htmlEscape(im.caption)
        << "</figcaption></figure>";
    h << "</div></div>\n";
    return;
  }
  for (const ImageFile& im : p.images) {
    h << "<figure><a href=\"" << htmlEscape(im.file) << "\"><img src=\"" << htmlEscape(im.file)
      << "\" alt=\"" << htmlEscape(im.caption) << "\"></a><figcaption>" << htmlEscape(p.spec.label);
    // The technique after the label, unless the label names it already ("legacy.pcf (2001)").
    if (!p.spec.technique.empty() && p.spec.label.find(p.spec.technique) == std::string::npos)
      h << " — <code>" << htmlEscape(p.spec.technique) << "</code>";
    if (p.milliseconds > 0) h << "<br>" << frameTime(p.milliseconds, p.timedFrames);
    if (!p.spec.paperNumbers.empty())
      h << "<br><span class=paper>paper: " << htmlEscape(p.spec.paperNumbers) << "</span>";
    h << "</figcaption></figure>\n";
  }
}

// One error cell: RMSE, the share of wrong pixels and, small, the metric that measured them.
void writeError(std::ostream& h, const MaskDifference& e, const std::string& metric) {
  h << "RMSE " << fixedDecimals(e.rmse, 4) << ", wrong (|&Delta;|&gt;0.5) "
    << fixedDecimals(100.0 * double(e.mismatching) / double(std::max(1LL, e.pixels)), 2)
    << "% of scored pixels<br><small>" << htmlEscape(metric) << "</small>";
}

void writeNumbers(std::ostream& h, const FigureResult& f) {
  bool any = false;
  for (const PanelResult& p : f.panels)
    any = any || (p.spec.kind == PanelKind::kRender || p.spec.kind == PanelKind::kIntermediates);
  if (!any) return;
  // The figure's reference, or "reference" where a panel has its own (each cell names its truth).
  bool ownReference = f.spec.reference.empty();
  for (const PanelResult& p : f.panels)
    ownReference =
        ownReference || (!p.spec.reference.empty() && p.spec.reference != f.spec.reference);
  const std::string reference = htmlEscape(ownReference ? "reference" : f.spec.reference);
  const bool both = f.spec.bothMetrics;
  h << "<table><tr><th>panel</th><th>technique</th><th>frame time (ours)</th><th>passes</th>";
  if (both)
    h << "<th>error vs " << reference << ": area metric</th><th>error vs " << reference
      << ": point metric</th>";
  else
    h << "<th>error vs " << reference << "</th>";
  h << "<th>counters</th><th>paper</th></tr>\n";
  for (const PanelResult& p : f.panels) {
    if (p.spec.kind != PanelKind::kRender && p.spec.kind != PanelKind::kIntermediates) continue;
    h << "<tr><td>" << htmlEscape(p.spec.label) << "</td><td><code>" << htmlEscape(p.spec.technique)
      << "</code></td>";
    if (!p.ok) {
      h << "<td colspan=" << (both ? 5 : 4) << " class=bad>missing: " << htmlEscape(p.reason)
        << "</td>";
    } else {
      h << "<td>" << frameTime(p.milliseconds, p.timedFrames) << "</td><td>";
      for (const PassTime& pass : p.passes)
        h << htmlEscape(pass.name) << ": " << fixedDecimals(pass.milliseconds, 1) << " ms<br>";
      h << "</td><td>";
      if (p.error)
        writeError(h, *p.error, p.errorMetric);
      else
        h << htmlEscape(p.errorNote);
      if (both) {
        h << "</td><td>";
        if (p.pointError)
          writeError(h, *p.pointError, p.pointErrorMetric);
        else
          h << htmlEscape(p.errorNote.empty() ? "no point form of the reference" : p.errorNote);
      }
      h << "</td><td>";
      for (const auto& [name, value] : p.counters)
        h << htmlEscape(name) << ": " << fixedDecimals(value, 3) << "<br>";
      h << "</td>";
    }
    h << "<td class=paper>" << htmlEscape(p.spec.paperNumbers) << "</td></tr>\n";
  }
  h << "</table>\n";
}

// CSM Table 1: labels "C=.. M=.. S=.." pivot into rows (C, M) and columns (S). Each cell: the
// median frame rate of its rounds, their interquartile range, and whether the frame built a mip
// chain.
void writePivot(std::ostream& h, const FigureResult& f) {
  std::vector<std::string> rows, cols;
  std::map<std::pair<std::string, std::string>, const PanelResult*> cell;
  for (const PanelResult& p : f.panels) {
    const size_t at = p.spec.label.find(" S=");
    if (at == std::string::npos) return;
    const std::string row = p.spec.label.substr(0, at), col = p.spec.label.substr(at + 1);
    if (std::find(rows.begin(), rows.end(), row) == rows.end()) rows.push_back(row);
    if (std::find(cols.begin(), cols.end(), col) == cols.end()) cols.push_back(col);
    cell[{row, col}] = &p;
  }
  h << "<table><tr><th></th>";
  for (const auto& c : cols)
    h << "<th>" << htmlEscape(c) << "<br>ours / <span class=paper>paper</span></th>";
  h << "</tr>\n";
  for (const auto& r : rows) {
    h << "<tr><th>" << htmlEscape(r) << "</th>";
    for (const auto& c : cols) {
      const PanelResult* p = cell[{r, c}];
      h << "<td>";
      if (p && p->ok) {
        h << fixedDecimals(1000.0 / p->milliseconds, 1) << " fps <small>"
          << (p->timedFrames > 0 ? "median of " + std::to_string(p->timedFrames) : "first frame");
        // The interquartile range of the rounds, as frame rates (the slow quartile first).
        if (const Quartiles q = quartilesOf(p->frameSamples); q.q1 > 0)
          h << ", IQR " << fixedDecimals(1000.0 / q.q3, 1) << "-"
            << fixedDecimals(1000.0 / q.q1, 1);
        h << "; " << htmlEscape(mipmapUse(p->counters)) << "</small>";
      } else if (p) {
        h << "<span class=bad>missing: " << htmlEscape(p->reason) << "</span>";
      }
      if (p) h << " / <span class=paper>" << htmlEscape(p->spec.paperNumbers) << "</span>";
      h << "</td>";
    }
    h << "</tr>\n";
  }
  h << "</table>\n";
}

void writeTwins(std::ostream& h, const FigureResult& f) {
  bool any = false;
  for (const PanelResult& p : f.panels) any = any || p.twin.has_value();
  if (!any) return;
  h << "<h4>Legacy vs modern</h4><div class=grid style=\"grid-template-columns: repeat(4, "
       "1fr)\">\n";
  for (const PanelResult& p : f.panels) {
    if (!p.twin) continue;
    const TwinResult& t = *p.twin;
    h << "<figure><img src=\"" << htmlEscape(p.images.front().file) << "\" alt=\""
      << htmlEscape(p.spec.technique) << "\"><figcaption><code>" << htmlEscape(p.spec.technique)
      << "</code> " << frameTime(p.milliseconds, p.timedFrames) << "</figcaption></figure>\n";
    h << "<figure><img src=\"" << htmlEscape(t.file) << "\" alt=\"" << htmlEscape(t.technique)
      << "\"><figcaption><code>" << htmlEscape(t.technique) << "</code> "
      << frameTime(t.milliseconds, t.timedFrames) << "</figcaption></figure>\n";
    h << "<figure><img src=\"" << htmlEscape(t.diffFile)
      << "\" alt=\"difference\"><figcaption>|visibility difference| (black = equal, white = 1): "
      << t.difference.mismatching << " of " << t.difference.pixels << " pixels differ, max "
      << fixedDecimals(t.difference.maxAbs, 3) << ", RMSE " << fixedDecimals(t.difference.rmse, 4)
      << "</figcaption></figure>\n";
    // The images, not only the masks, against registry/twins.h's bound.
    h << "<figure><img src=\"" << htmlEscape(t.imageDiffFile)
      << "\" alt=\"image difference\"><figcaption>|image difference| (largest channel; black "
         "= within "
      << twins::kImageSteps << "/255, white = 16/255 or more): " << t.image.beyondSteps << " of "
      << t.image.pixels << " pixels differ by more than " << twins::kImageSteps << "/255 ("
      << t.image.beyondWhereMasksAgree << " where the masks agree; bound " << t.image.boundPixels
      << ", the spotlight cone's edge band), max " << fixedDecimals(t.image.maxAbs, 3) << ", RMSE "
      << fixedDecimals(t.image.rmse, 4)
      << " <span class=" << (t.image.withinBound ? "ok>within" : "bad>beyond")
      << " the bound</span></figcaption></figure>\n";
  }
  h << "</div>\n";
}

// The command that makes this figure again (with its --set overrides, figures/overrides.h).
std::string regenerateCommand(const FigureSpec& s) {
  std::string command = "shadowlab figures --only " + (s.sourceId.empty() ? s.id : s.sourceId);
  for (const std::string& o : s.overrides) command += " --set " + o;
  return command;
}

FigureRef refOf(const FigureSpec& f) {
  return {f.id, f.paper + ", " + f.paperFigure + ": " + f.title, figureTechniques(f)};
}

// A written lesson and what it teaches (teach/lesson.h lessonSubjects).
struct WrittenLesson {
  std::string technique, href;
  std::vector<std::string> subjects;
};

// The figure's links to the lessons beside the report that teach what it shows.
void writeLessonLinks(std::ostream& h, const FigureSpec& s,
                      const std::vector<WrittenLesson>& lessons) {
  const FigureRef ref = refOf(s);
  std::string links;
  for (const WrittenLesson& l : lessons)
    if (figureShows(ref, l.subjects))
      links += std::string(links.empty() ? "" : ", ") + "<a class=lesson href=\"" +
               htmlEscape(l.href) + "\"><code>" + htmlEscape(l.technique) + "</code></a>";
  if (!links.empty()) h << "<p class=lessons>Lessons: " << links << "</p>\n";
}

void writeFigure(std::ostream& h, const FigureResult& f,
                 const std::vector<WrittenLesson>& lessons) {
  const FigureSpec& s = f.spec;
  int missing = 0;
  for (const PanelResult& p : f.panels) missing += p.ok ? 0 : 1;
  h << "<article id=\"" << htmlEscape(s.id) << "\"><h3>" << htmlEscape(s.paperFigure) << " — "
    << htmlEscape(s.title) << " <small>(<code>" << htmlEscape(s.id) << "</code>)</small></h3>\n";
  h << "<p class=caption>" << htmlEscape(s.caption) << "</p>\n";
  writeLessonLinks(h, s, lessons);
  h << f.measured;  // figures/measured.h: the numbers this run measured, never typed
  // The panels' scenes (PanelSpec::scene, else the figure's), each once.
  std::vector<std::string> scenes;
  for (const PanelResult& p : f.panels) {
    const std::string& scene = p.spec.scene.empty() ? s.scene : p.spec.scene;
    if (std::find(scenes.begin(), scenes.end(), scene) == scenes.end()) scenes.push_back(scene);
  }
  if (scenes.empty()) scenes.push_back(s.scene);
  h << "<p><small>" << (scenes.size() > 1 ? "scenes " : "scene ");
  for (size_t i = 0; i < scenes.size(); ++i)
    h << (i > 0 ? ", " : "") << "<code>" << htmlEscape(scenes[i]) << "</code>";
  h << ", " << s.width << "x" << s.height << ", " << s.shadowMapTexels << "² shadow map; made in "
    << fixedDecimals(f.seconds, 1) << " s; regenerate: <code>" << htmlEscape(regenerateCommand(s))
    << "</code></small></p>\n";
  if (missing > 0)
    h << "<p class=bad>" << missing << " of " << f.panels.size()
      << " panels missing (reasons below, in red).</p>\n";
  const std::string grid = "<div class=grid style=\"grid-template-columns: repeat(" +
                           std::to_string(s.columns) + ", 1fr)\">\n";
  if (!s.table) {
    h << grid;
    for (const PanelResult& p : f.panels)
      if (p.spec.kind != PanelKind::kPlot) writePanelCell(h, p);
    h << "</div>\n";
    bool closeups = false;
    for (const PanelResult& p : f.panels) closeups = closeups || !p.closeups.empty();
    if (closeups) {
      h << "<h4>Close-ups of the red rectangles</h4>" << grid;
      for (const PanelResult& p : f.panels) {
        if (p.spec.kind == PanelKind::kPlot || !p.spec.closeups) continue;
        if (p.closeups.empty()) {
          writePanelCell(h, p);
          continue;
        }
        for (const ImageFile& im : p.closeups)
          h << "<figure><img src=\"" << htmlEscape(im.file) << "\" alt=\"" << htmlEscape(im.caption)
            << "\"><figcaption>" << htmlEscape(im.caption) << "</figcaption></figure>\n";
      }
      h << "</div>\n";
    }
  } else {
    for (const PanelResult& p : f.panels)
      if (!p.ok && p.spec.kind != PanelKind::kPlot) {
        h << "<p class=bad>missing panels: " << htmlEscape(p.reason)
          << " (and possibly others, see the table)</p>\n";
        break;
      }
  }
  for (const PanelResult& p : f.panels)
    if (p.spec.kind == PanelKind::kPlot) {
      h << "<div class=grid style=\"grid-template-columns: 1fr\">";
      writePanelCell(h, p);
      h << "</div>\n";
    }
  if (!f.composite.empty())
    h << "<p><small>The whole figure as one image: <a href=\"" << htmlEscape(f.composite) << "\">"
      << htmlEscape(f.composite) << "</a></small></p>\n";
  writeTwins(h, f);
  if (!f.roundsCsv.empty())
    h << "<p><small>Every interleaved round of every timed panel: <a href=\""
      << htmlEscape(f.roundsCsv) << "\">" << htmlEscape(f.roundsCsv) << "</a></small></p>\n";
  if (!s.paperNumbers.empty())
    h << "<p class=paper>The paper's numbers: " << htmlEscape(s.paperNumbers) << "</p>\n";
  bool pivot = s.table && !f.panels.empty();
  for (const PanelResult& p : f.panels)
    pivot = pivot && p.spec.label.find(" S=") != std::string::npos;
  if (pivot)
    writePivot(h, f);
  else
    writeNumbers(h, f);
  h << "</article>\n";
}

}  // namespace

std::vector<FigureRef> figureRefs() {
  std::vector<FigureRef> out;
  for (const FigureSpec& f : figureList()) out.push_back(refOf(f));
  return out;
}

ReportLinks reportLinksTo(const std::string& href, const std::vector<const FigureSpec*>& figures) {
  ReportLinks r;
  r.figures = figureRefs();
  r.href = href;
  for (const FigureSpec* f : figures) r.anchors[f->sourceId.empty() ? f->id : f->sourceId] = f->id;
  return r;
}

Quartiles quartilesOf(std::vector<double> samples) {
  if (samples.empty()) return {};
  std::sort(samples.begin(), samples.end());
  const auto at = [&](double q) {
    const double pos = q * double(samples.size() - 1);
    const size_t lo = size_t(pos);
    const size_t hi = std::min(lo + 1, samples.size() - 1);
    return samples[lo] + (pos - double(lo)) * (samples[hi] - samples[lo]);
  };
  return {at(0.25), at(0.75)};
}

std::string mipmapUse(const std::map<std::string, double>& counters) {
  const auto it = counters.find("mip-maps");
  if (it == counters.end()) return "no mip chain";
  return it->second > 0 ? "mip-maps built" : "no mip-maps";
}

void writeReport(const std::string& outDir, const std::vector<FigureResult>& figures,
                 const ReportInfo& info) {
  std::ostringstream h;
  h << "<!doctype html>\n<html lang=en><head><meta charset=utf-8><title>shadowlab — reproduced "
       "figures</title><style>"
    << kStyle << "</style></head><body>\n";
  h << "<h1>shadowlab — the papers' figures, re-made</h1>\n";
  h << "<p>Rendered " << htmlEscape(info.date) << " with " << htmlEscape(info.renderer) << " in "
    << fixedDecimals(info.totalSeconds, 0)
    << " s. Times are ours on this machine. Where a time stands beside a paper's number "
       "(blue; 2001-2007 hardware) or on a chart of times, it is the steady-state median: one "
       "GL context, warm-up frames first (shader compilation, first-use allocation), then the "
       "median of the timed frames of the sum of the pass times (\"median of N\"; per pass, "
       "the median of that pass). Other panels are rendered once in a fresh context; their "
       "time is marked \"first frame\" and includes those first-use costs. Error: the visibility "
       "mask against the ray-traced "
       "reference (RMSE, and the share of pixels off by more than 0.5). Missing panels are in "
       "red with the reason.</p>\n";
  // What made this report: the source, the command, the machine and its load.
  h << "<p class=provenance><small>Made by shadowlab <code>" << htmlEscape(buildCommit())
    << "</code>, command <code>" << htmlEscape(commandLine().empty() ? "unknown" : commandLine())
    << "</code>; CPU " << htmlEscape(cpuModel()) << "; GL " << htmlEscape(info.renderer)
    << "; load average (1, 5, 15 min) when the report was written: " << loadAverages()
    << ".</small></p>\n";
  // Index with a status per figure.
  h << "<nav><table><tr><th>paper</th><th>figure</th><th>id</th><th>panels made</th></tr>\n";
  for (const FigureResult& f : figures) {
    int ok = 0;
    for (const PanelResult& p : f.panels) ok += p.ok ? 1 : 0;
    const bool complete = ok == int(f.panels.size());
    h << "<tr><td>" << htmlEscape(f.spec.paper) << "</td><td><a href=\"#" << htmlEscape(f.spec.id)
      << "\">" << htmlEscape(f.spec.paperFigure) << " — " << htmlEscape(f.spec.title)
      << "</a></td><td><code>" << htmlEscape(f.spec.id)
      << "</code></td><td class=" << (complete ? "ok" : "bad") << ">" << ok << " / "
      << f.panels.size() << (complete ? "" : " (missing in red)") << "</td></tr>\n";
  }
  h << "</table></nav>\n";
  h << info.lessonsHtml;
  std::vector<WrittenLesson> lessons;
  for (const LessonLink& l : info.lessons)
    if (l.error.empty())
      lessons.push_back({l.technique, info.lessonsBase + l.href, lessonSubjects(l.technique)});
  std::string paper;
  for (const FigureResult& f : figures) {
    if (f.spec.paper != paper) {
      paper = f.spec.paper;
      h << "<h2>" << htmlEscape(paper) << "</h2>\n";
    }
    writeFigure(h, f, lessons);
  }
  h << info.benchHtml;
  // Self-check for readers and for tests/figures/report_test.cpp: every image must have
  // loaded; a broken one is outlined in red, logged to the console and counted on <body>.
  h << "<script>\nwindow.addEventListener('load', function () {\n"
       "  var ok = 0, broken = 0, distorted = 0;\n"
       "  document.querySelectorAll('img').forEach(function (img) {\n"
       "    if (img.complete && img.naturalWidth > 0) {\n"
       "      ok++;\n"
       // Shown at its own aspect ratio: layout rounds a box to whole CSS pixels, so a 2%
       // tolerance (a 50-pixel-high image off by one pixel) separates rounding from squashing.
       "      var w = img.getBoundingClientRect().width, h = img.getBoundingClientRect().height;\n"
       "      if (w > 0 && h > 0 && Math.abs((w / h) / (img.naturalWidth / img.naturalHeight) - 1)"
       " > 0.02) {\n"
       "        distorted++; img.style.outline = '3px solid orange';\n"
       "        console.warn('distorted image: ' + img.getAttribute('src'));\n"
       "      }\n"
       "      return;\n"
       "    }\n"
       "    broken++; img.style.outline = '3px solid red';\n"
       "    console.error('missing image: ' + img.getAttribute('src'));\n"
       "  });\n"
       "  document.body.setAttribute('data-images-ok', ok);\n"
       "  document.body.setAttribute('data-images-broken', broken);\n"
       "  document.body.setAttribute('data-images-distorted', distorted);\n"
       "});\n</script>\n";
  h << "</body></html>\n";
  // Written to a temporary and renamed: a failed run keeps the previous report whole.
  writeFileAtomically((fs::path(outDir) / "report.html").string(),
                      [&](std::ostream& out) { out << h.str(); });
}

}  // namespace sl::figures
