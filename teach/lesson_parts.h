// teach/lesson_parts.h — what the three parts of a lesson share (internal to teach/): the lesson
// text, the rendered sides and their comparison, the "why" blocks, the page. lesson.cpp renders
// and assembles, lesson_why.cpp makes the "why" blocks, lesson_page.cpp writes the HTML.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/base/image.h"
#include "core/technique/technique.h"
#include "registry/twins.h"
#include "teach/lesson.h"
#include "teach/pass_dump.h"

namespace sl::figures::lesson_detail {
using nlohmann::json;

// Heat-map full scale (core/base/image.h differenceHeatMap): a mask difference of a whole
// visibility step shows white, as in the report; an image difference of a quarter of full
// brightness shows white (shading differences are small: at full scale 1 they would be black).
constexpr float kMaskDiffFullScale = 1.0f;
constexpr float kImageDiffFullScale = 0.25f;
// Shown widths on the page (pixels): a pass image is scaled to its natural width within these
// bounds (its height follows, aspect kept); a per-channel panel is a thumbnail.
constexpr int kMinShownWidth = 200;
constexpr int kMaxShownWidth = 560;
constexpr int kChannelShownWidth = 150;
// Frames kept by the lesson renderer: a lesson shows at most four (technique and twin, at the
// 2x2 and the 4x4 footprint), and the main job writes legacy.X then modern.X, which reuse them.
constexpr size_t kCachedFrames = 4;
// The footprints a PCF lesson shows when the twin table has both (Brabec & Seidel §3-4): 2x2,
// the paper's fast case, and 4x4, which needs the accumulation buffer (four groups or phases).
constexpr int kSmallFootprint = 2;
constexpr int kLargeFootprint = 4;

struct LessonText {
  std::string file;  // assets/lessons/<family>.json
  std::string paper;
  json entry;  // {"techniques", "title", "sections", "idea", "equations", "figures", ...}
};

// One departure from the paper, as a pass of a technique's table declares it
// (core/technique/pass_table.h PassSpec::deviations).
struct Departure {
  std::string technique;
  std::string passId;
  std::string passName;
  std::string text;
  std::string anchor;  // the pass's id on the page ("legacy.pcf-4x4-pass-2s"); empty: not shown
};

// One technique as the lesson shows it: its frame, its dump (teach/pass_dump.h) and the command
// that re-makes the dump.
struct Side {
  const Technique* technique = nullptr;
  std::string role;    // "legacy", "modern" (a twin's two sides) or "own" (no twin)
  std::string tag;     // "" for the lesson's first footprint, "4x4" for the second one
  std::string anchor;  // the side's id on the page: "legacy.pcf", "legacy.pcf-4x4"
  RenderParams params;
  std::shared_ptr<const Frame> frame;
  std::vector<PassDumpImage> images;
  json passes;         // passes.json of the dump
  std::string prefix;  // file prefix on the lesson page: "<technique>_"
  std::string renderCommand;
};

// One picture of a "why" block: rendered by the lesson with the parameters the lesson text
// names, captioned with those words and what the run measured.
struct WhyPicture {
  std::string file;      // "why-1-2.png"
  std::string caption;   // the lesson text's words
  std::string measured;  // from the run: the share of the image in shadow
  std::string command;   // the `shadowlab render` command that makes the same image
  Image image;
};

// A "why" block of the lesson text: a question a student asks about a pass, the answer, and the
// pictures (or the traced numbers) that make it visible.
struct WhyBlock {
  std::string title;
  std::vector<std::string> text;
  std::vector<WhyPicture> pictures;
  std::string tableHtml;   // numbers from the page's own GL traces ("planes", "parts")
  std::string figureHtml;  // a diagram drawn from the pass table ("tiling")
};

struct Comparison {
  twins::TwinPair pair;
  size_t legacy = 0, modern = 0;  // the two sides of LessonPage::sides
  std::string tag;                // the sides' tag: "" or "4x4"
  twins::Agreement mask;
  long long imagePixels = 0;
  long long imageDiffering = 0;          // max over RGB of |legacy - modern| > one 8-bit step
  long long imageDifferingMaskSame = 0;  // of those, where the masks are identical
  double imageMaxAbs = 0.0;
  Image maskHeat, imageHeat;
};

struct LessonPage {
  const Technique* technique = nullptr;
  LessonText text;
  LessonSettings settings;
  // Per twin pair legacy, then modern (the 2x2 pair first); or the technique alone.
  std::vector<Side> sides;
  std::vector<Comparison> comparisons;
  std::vector<WhyBlock> why;  // the lesson text's "why" blocks with their pictures
  std::vector<Departure> departures;
  std::vector<FigureLink> figures;  // the report's figures that show the lesson's techniques
  std::string lessonCommand;
  std::string commit;
};

// The lesson text's fields: a string, a list of strings, a list of {"ref", "text"} pairs; an
// InputError naming the file when the field has another type.
std::string field(const LessonText& t, const char* key);
std::vector<std::string> stringList(const LessonText& t, const char* key);
std::vector<std::pair<std::string, std::string>> refList(const LessonText& t, const char* key);
// printf-style number for the page.
std::string fmt(double v, const char* format);
// <code>text</code>, escaped.
std::string code(const std::string& text);
// The id of a pass's section on the page: "<side anchor>-pass-<pass id>", escaped.
std::string passAnchor(const std::string& sideAnchor, const std::string& id);
// "2x2", "4x4".
std::string footprintTag(int filter);
// The render parameters of the lesson's settings (scene size and shadow map).
RenderParams paramsForSettings(const LessonSettings& s);
// `shadowlab render` re-making a side's pictures (with its mask and dump when `dump`).
std::string renderCommandFor(const Technique& t, const RenderParams& p, const LessonSettings& s,
                             const std::string& outName, bool dump = true);
// The files of a comparison: "diff-mask.png" for the first pair, "diff-mask-4x4.png" after.
std::string diffFile(const std::string& stem, const std::string& tag);
// The lesson text's "why" blocks with their pictures rendered (lesson_why.cpp).
std::vector<WhyBlock> whyBlocks(const LessonText& text, const std::vector<Side>& sides,
                                const LessonSettings& s, const Scene& scene);
// The whole page (lesson_page.cpp).
std::string pageHtml(const LessonPage& page);

}  // namespace sl::figures::lesson_detail
