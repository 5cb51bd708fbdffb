// figures/report.h — what rendering a figure produced (files and numbers), and report.html.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/metrics.h"
#include "core/technique.h"
#include "figures/figure_spec.h"
#include "registry/twins.h"

namespace sl::figures {

struct ImageFile {
  std::string file;  // relative to the report
  std::string caption;
};

struct TwinResult {
  std::string technique;  // the other side: modern.X for legacy.X, and back
  std::string file;       // its image
  std::string diffFile;   // differenceHeatMap of the two visibility masks
  double milliseconds = 0;
  int timedFrames = 0;  // as PanelResult::timedFrames
  MaskDifference difference;
  // The images too (issue 18 item 5): a heat map of the largest channel difference, and the
  // agreement against registry/twins.h's image bound.
  std::string imageDiffFile;
  twins::ImageAgreement image;
};

struct PanelResult {
  PanelSpec spec;
  bool ok = false;
  std::string reason;             // why it is missing or failed (shown in red)
  std::vector<ImageFile> images;  // the panel's image(s); several for intermediates
  std::vector<ImageFile> closeups;
  // Frame time (sum of the pass times) and per-pass times: the steady-state medians
  // (core/frame_timing.h) over timedFrames frames after warmupFrames, where the time stands
  // beside a paper's number; timedFrames 0: one first frame in a fresh context.
  double milliseconds = 0;
  int warmupFrames = 0, timedFrames = 0;
  std::vector<PassTime> passes;
  std::map<std::string, double> counters;
  std::optional<MaskDifference> error;  // against the figure's reference
  std::string errorNote;                // why there is no error number
  std::optional<TwinResult> twin;
};

struct FigureResult {
  FigureSpec spec;
  std::vector<PanelResult> panels;
  double seconds = 0;     // wall time to make the figure
  std::string composite;  // the whole figure as one PNG (empty for tables)
};

struct ReportInfo {
  std::string renderer;  // GL_RENDERER of the default back end
  std::string date;
  double totalSeconds = 0;
  std::string benchHtml;  // the quick bench's section (figures/bench_report.cpp), if it ran
  std::string lessonsHtml;  // links to the lessons (figures/lesson.h lessonIndexHtml)
};

// Writes outDir/report.html (a gallery per paper; missing panels in red with the reason).
void writeReport(const std::string& outDir, const std::vector<FigureResult>& figures,
                 const ReportInfo& info);

}  // namespace sl::figures
