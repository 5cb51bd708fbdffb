// figures/report.h — what rendering a figure produced (files and numbers), and report.html.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/base/metrics.h"
#include "core/technique/technique.h"
#include "figures/figure_spec.h"
#include "registry/twins.h"
#include "teach/lesson.h"

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
  // The images too: a heat map of the largest channel difference, and the
  // agreement against registry/twins.h's image bound.
  std::string imageDiffFile;
  twins::ImageAgreement image;
};

// Where a panel's error against the reference lies (figures.cpp, as the bench measures it).
struct ErrorDetail {
  double bandRmse = 0;  // within 2 pixels of the reference's shadow edges
  long long bandPixels = 0;
  double leakShare = 0;  // umbra pixels (reference 0, outside the band) shown > 20% lit
  long long umbraPixels = 0;
  // The deep umbra: reference umbra farther than kDeepUmbraPixels from any reference edge, out
  // of reach of a blurred penumbra (CSM's and VSM's 5x5 kernels), where light is bleeding.
  double deepUmbraMean = 0;  // mean visibility shown there (0: dark, as it should be)
  double deepLeakShare = 0;  // share of it shown more than 5% lit
  long long deepUmbraPixels = 0;
};
constexpr int kDeepUmbraPixels = 8;
// A panel's pixel is "wrong" when its visibility is off the reference's by more than this.
constexpr double kWrongPixelThreshold = 0.5;
constexpr float kDeepLeakThreshold = 0.05f;

struct PanelResult {
  PanelSpec spec;
  bool ok = false;
  std::string reason;             // why it is missing or failed (shown in red)
  std::vector<ImageFile> images;  // the panel's image(s); several for intermediates
  std::vector<ImageFile> closeups;
  // Frame time (sum of the pass times) and per-pass times: the steady-state medians
  // (core/technique/frame_timing.h) over timedFrames frames after warmupFrames, where the time
  // stands beside a paper's number; timedFrames 0: one first frame in a fresh context.
  double milliseconds = 0;
  int warmupFrames = 0, timedFrames = 0;
  std::vector<double> frameSamples;  // the timed frames' times, one per interleaved round
  std::vector<PassTime> passes;
  std::map<std::string, double> counters;
  // Against the figure's reference, over the scored pixels of the one error definition
  // (registry/shadow_error.h); mismatching counts the pixels off by more than
  // kWrongPixelThreshold. errorMetric names the metric, the truth and the share left out.
  std::optional<MaskDifference> error;
  std::string errorMetric;
  std::optional<ErrorDetail> errorDetail;
  // FigureSpec::bothMetrics: the same mask against the reference's point form (pixel centres).
  std::optional<MaskDifference> pointError;
  std::string pointErrorMetric;
  std::string errorNote;  // why there is no error number
  std::optional<TwinResult> twin;
};

// The first and third quartiles of a panel's frame samples (linear interpolation between order
// statistics, as the bench's timing spread, measure/bench.h); {0, 0} for no samples.
struct Quartiles {
  double q1 = 0, q3 = 0;
};
Quartiles quartilesOf(std::vector<double> samples);

// What a frame's "mip-maps" counter (modern.csm) says: "mip-maps built", "no mip-maps" (the
// chain was skipped), or "no mip chain" for a technique that reports none.
std::string mipmapUse(const std::map<std::string, double>& counters);

struct FigureResult {
  FigureSpec spec;
  std::vector<PanelResult> panels;
  double seconds = 0;     // wall time to make the figure
  std::string composite;  // the whole figure as one PNG (empty for tables)
  std::string roundsCsv;  // its timed panels' every round (figures.cpp writeRoundsCsv), or empty
  std::string measured;   // figures/measured.h measuredHtml: what this run measured, in words
};

struct ReportInfo {
  std::string renderer;  // GL_RENDERER of the default back end
  std::string date;
  double totalSeconds = 0;
  std::string benchHtml;    // the quick bench's section (measure/bench_report.cpp), if it ran
  std::string lessonsHtml;  // links to the lessons (teach/lesson.h lessonIndexHtml)
  // The lessons written beside the report (hrefs relative to lessonsBase): each figure links
  // the ones that teach what it shows (teach/lesson.h figureShows).
  std::vector<LessonLink> lessons;
  std::string lessonsBase = "lessons/";
};

// The figure list as the lessons name it (teach/lesson.h FigureRef): id, title, techniques.
std::vector<FigureRef> figureRefs();
// How a page beside a report of `figures` links to it: `href` is report.html from the page's
// folder ("../../report.html" from OUT/lessons/T/); each figure by its article's id.
ReportLinks reportLinksTo(const std::string& href, const std::vector<const FigureSpec*>& figures);

// Writes outDir/report.html (a gallery per paper; missing panels in red with the reason).
void writeReport(const std::string& outDir, const std::vector<FigureResult>& figures,
                 const ReportInfo& info);

}  // namespace sl::figures
