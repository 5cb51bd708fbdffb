// teach/lesson.cpp — see lesson.h.
#include "teach/lesson.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

#include "core/base/errors.h"
#include "core/base/html.h"
#include "core/base/image.h"
#include "core/base/output_files.h"
#include "core/base/provenance.h"
#include "core/gl/shaders.h"
#include "core/scene/scene_library.h"
#include "registry/registry.h"
#include "registry/twins.h"
#include "teach/pass_dump.h"

namespace sl::figures {
namespace {
namespace fs = std::filesystem;
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

// ---------------------------------------------------------------- the lesson text

struct LessonText {
  std::string file;  // assets/lessons/<family>.json
  std::string paper;
  json entry;  // {"techniques", "title", "sections", "idea", "equations", "figures", ...}
};

std::vector<LessonText> allLessonTexts() {
  const fs::path dir = fs::path(assetDirectory()) / "lessons";
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.path().extension() == ".json") files.push_back(e.path());
  if (ec) throw InputError("cannot read the lesson texts in " + dir.string() + ": " + ec.message());
  std::sort(files.begin(), files.end());
  std::vector<LessonText> out;
  for (const fs::path& f : files) {
    std::ifstream in(f);
    json doc;
    try {
      doc = json::parse(in);
      for (const json& entry : doc.at("lessons"))
        out.push_back({f.filename().string(), doc.at("paper").get<std::string>(), entry});
    } catch (const json::exception& e) {
      throw InputError("lesson text " + f.string() + ": " + e.what());
    }
  }
  return out;
}

// The one entry naming `technique`; none, or two, is an InputError.
LessonText lessonTextFor(const std::string& technique) {
  std::vector<LessonText> found;
  for (const LessonText& t : allLessonTexts())
    for (const json& name : t.entry.value("techniques", json::array()))
      if (name == technique) found.push_back(t);
  if (found.empty())
    throw InputError("no lesson text for " + technique + " in " + assetDirectory() +
                     "/lessons/*.json");
  if (found.size() > 1)
    throw InputError("two lesson texts for " + technique + ": " + found[0].file + " and " +
                     found[1].file);
  return found[0];
}

// A string field of a lesson entry; InputError naming the file when it is not a string.
std::string field(const LessonText& t, const char* key) {
  try {
    return t.entry.at(key).get<std::string>();
  } catch (const json::exception& e) {
    throw InputError("lesson text " + t.file + ": " + key + ": " + e.what());
  }
}
std::vector<std::string> stringList(const LessonText& t, const char* key) {
  try {
    return t.entry.value(key, json::array()).get<std::vector<std::string>>();
  } catch (const json::exception& e) {
    throw InputError("lesson text " + t.file + ": " + key + ": " + e.what());
  }
}
// [{"ref", "text"}] of a lesson entry.
std::vector<std::pair<std::string, std::string>> refList(const LessonText& t, const char* key) {
  std::vector<std::pair<std::string, std::string>> out;
  try {
    for (const json& r : t.entry.value(key, json::array()))
      out.emplace_back(r.at("ref").get<std::string>(), r.at("text").get<std::string>());
  } catch (const json::exception& e) {
    throw InputError("lesson text " + t.file + ": " + key + ": " + e.what());
  }
  return out;
}

// ---------------------------------------------------------------- known departures

// One departure from the paper, as a pass of a technique's table declares it
// (core/technique/pass_table.h PassSpec::deviations).
struct Departure {
  std::string technique;
  std::string passId;
  std::string passName;
  std::string text;
};

// Every departure the pass tables of `techniques` declare (each variant's too), pass by pass; a
// text shared by several passes (a helper they all call) is listed once, under the first.
std::vector<Departure> departuresOf(const std::vector<const Technique*>& techniques) {
  std::vector<Departure> out;
  for (const Technique* t : techniques)
    for (const PassTable* table : allPassTables(*t))
      for (const PassSpec& p : *table)
        for (const std::string& d : p.deviations)
          if (std::none_of(out.begin(), out.end(), [&](const Departure& o) { return o.text == d; }))
            out.push_back({t->name, p.id, p.name, d});
  return out;
}

// ---------------------------------------------------------------- rendering

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

class FrameCache {
 public:
  std::shared_ptr<const Frame> render(const Technique& t, const Scene& scene, const RenderParams& p,
                                      const std::string& sceneName) {
    const std::string key = t.name + "|" + sceneName + "|" + std::to_string(p.width) + "x" +
                            std::to_string(p.height) + "|" + std::to_string(p.shadowMapTexels) +
                            "|" + std::to_string(p.filter) + "|" + precisionName(p.precision) +
                            "|" + json(p.extra).dump();
    for (const auto& [k, f] : frames_)
      if (k == key) return f;
    auto frame = std::make_shared<const Frame>(renderTechnique(t, scene, p));
    frames_.emplace_back(key, frame);
    if (frames_.size() > kCachedFrames) frames_.erase(frames_.begin());
    return frame;
  }

 private:
  std::vector<std::pair<std::string, std::shared_ptr<const Frame>>> frames_;
};

// `shadowlab render` re-making a side's pictures: the options its technique reads, its --params.
std::string renderCommandFor(const Technique& t, const RenderParams& p, const LessonSettings& s,
                             const std::string& outName, bool dump = true) {
  std::vector<std::string> a = {
      "shadowlab",   "render", "--scene", s.scene,
      "--technique", t.name,   "--size",  std::to_string(p.width) + "x" + std::to_string(p.height)};
  if (readsOption(t, CommonOption::kShadowMap))
    a.insert(a.end(), {"--shadow-map", std::to_string(p.shadowMapTexels)});
  if (readsOption(t, CommonOption::kFilter))
    a.insert(a.end(), {"--filter", std::to_string(p.filter)});
  if (readsOption(t, CommonOption::kPrecision) && p.precision != Precision::k8)
    a.insert(a.end(), {"--precision", precisionName(p.precision)});
  for (const auto& [k, v] : p.extra) a.insert(a.end(), {"--param", k + "=" + v});
  a.insert(a.end(), {"--out", outName + ".png"});
  if (dump)
    a.insert(a.end(), {"--mask", outName + "-mask.png", "--dump-passes", outName + "-passes"});
  return shellJoin(a);
}

Side renderSide(const Technique& t, const RenderParams& p, const Scene& scene,
                const LessonSettings& s, FrameCache& cache, const std::string& role,
                const std::string& tag) {
  Side side;
  side.technique = &t;
  side.role = role;
  side.tag = tag;
  side.anchor = tag.empty() ? t.name : t.name + "-" + tag;
  side.params = p;
  side.params.capturePasses = true;
  side.frame = cache.render(t, scene, side.params, s.scene);
  if (!allFinite(side.frame->visibility) ||
      (!side.frame->color.empty() && !allFinite(side.frame->color)))
    throw GlError(t.name + ": the image or mask has NaN or Inf");
  side.images = planPassDump(*side.frame, t.name);
  json parameters = {{"size", std::to_string(p.width) + "x" + std::to_string(p.height)},
                     {"params", p.extra}};
  if (readsOption(t, CommonOption::kShadowMap)) parameters["shadow_map"] = p.shadowMapTexels;
  if (readsOption(t, CommonOption::kFilter)) parameters["filter"] = p.filter;
  if (readsOption(t, CommonOption::kPrecision))
    parameters["precision"] = precisionName(p.precision);
  side.passes =
      passesJson(*side.frame,
                 PassDumpHeader{t.name, t.paper, scene.name, parameters,
                                twins::legacyTwinOf(t.name), twins::legacyTwinPassesOf(t.name)},
                 side.images);
  side.prefix = side.anchor + "_";
  side.renderCommand = renderCommandFor(t, p, s, side.anchor);
  return side;
}

// ---------------------------------------------------------------- legacy against modern

// ---------------------------------------------------------------- why: pictures made at lesson
// time

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

// One channel: the largest |a - b| over the colour channels of each pixel.
Image largestChannelDifference(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height || a.channels != b.channels)
    throw GlError("the legacy and modern images differ in size");
  Image out(a.width, a.height, 1);
  const int colour = std::min(a.channels, 3);
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int c = 0; c < colour; ++c)
        out.at(x, y) = std::max(out.at(x, y), std::fabs(a.at(x, y, c) - b.at(x, y, c)));
  return out;
}

Comparison compareSides(const twins::TwinPair& pair, const Side& legacy, const Side& modern) {
  Comparison c;
  c.pair = pair;
  const Frame& l = *legacy.frame;
  const Frame& m = *modern.frame;
  c.mask = twins::judge(pair, l.visibility, m.visibility);
  c.maskHeat = differenceHeatMap(l.visibility, m.visibility, kMaskDiffFullScale);
  const Image diff = largestChannelDifference(l.color, m.color);
  // Image values come from 8-bit buffers read as float: a one-step difference carries float
  // noise of 1e-7, far below half a step (as registry/twins.cpp judge).
  constexpr double kReadbackNoise = 1e-6;
  c.imagePixels = (long long)diff.width * diff.height;
  for (int y = 0; y < diff.height; ++y)
    for (int x = 0; x < diff.width; ++x) {
      const double d = diff.at(x, y);
      c.imageMaxAbs = std::max(c.imageMaxAbs, d);
      if (d <= twins::kOneStep + kReadbackNoise) continue;
      ++c.imageDiffering;
      if (std::fabs(double(l.visibility.at(x, y)) - double(m.visibility.at(x, y))) <=
          twins::kIdentical)
        ++c.imageDifferingMaskSame;
    }
  c.imageHeat = differenceHeatMap(diff, Image(diff.width, diff.height, 1), kImageDiffFullScale);
  return c;
}

// The twin pairs a lesson shows: the first of registry/twins.h whose legacy or modern side the
// technique is (the 8-bit faithful pair for the Brabec–Seidel techniques, linear compare for hw)
// and, when that one has the 2x2 footprint and the table has the same 8-bit pair at 4x4, that
// one too: PCF's 4x4 footprint is where the accumulation buffer and fast PCF's four phases
// appear (Brabec & Seidel §3, §4). Empty for a technique without a twin.
std::vector<twins::TwinPair> pairsOf(const std::string& technique) {
  std::vector<twins::TwinPair> out;
  for (const twins::TwinPair& p : twins::twinPairs()) {
    if ((p.legacy != technique && p.modern != technique) || p.precision != Precision::k8) continue;
    if (out.empty() ||
        (out.size() == 1 && out[0].filter == kSmallFootprint && p.filter == kLargeFootprint &&
         p.legacyExtra == out[0].legacyExtra && p.modernExtra == out[0].modernExtra))
      out.push_back(p);
  }
  return out;
}

std::string footprintTag(int filter) {
  return std::to_string(filter) + "x" + std::to_string(filter);
}

// ---------------------------------------------------------------- the page

struct LessonPage {
  const Technique* technique = nullptr;
  LessonText text;
  LessonSettings settings;
  // Per twin pair legacy, then modern (the 2x2 pair first); or the technique alone.
  std::vector<Side> sides;
  std::vector<Comparison> comparisons;
  std::vector<WhyBlock> why;  // the lesson text's "why" blocks with their pictures
  std::vector<Departure> departures;
  std::string lessonCommand;
  std::string commit;
};

std::string fmt(double v, const char* format) {
  char text[64];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

std::string percent(long long part, long long whole) {
  return whole > 0 ? fmt(100.0 * double(part) / double(whole), "%.3g%%") : "0%";
}

std::string code(const std::string& text) { return "<code>" + htmlEscape(text) + "</code>"; }

// The files and anchor of a comparison: "diff-mask.png" for the first pair, "diff-mask-4x4.png"
// for the second footprint.
std::string diffFile(const std::string& stem, const std::string& tag) {
  return stem + (tag.empty() ? "" : "-" + tag) + ".png";
}
std::string compareAnchor(const std::string& tag) {
  return tag.empty() ? "compare" : "compare-" + tag;
}

// The anchor of a pass on the page: its technique and its id in the pass table.
std::string passAnchor(const std::string& technique, const std::string& id) {
  return htmlEscape(technique) + "-pass-" + htmlEscape(id);
}

// The GL state card of a pass (passes.json "state": [{"group", "text", "before_pass"}] in call
// order; a "part" line names a part of a pass timed in several parts), or the visible note
// that none was recorded. An empty list is a record: the pass made no GL call (ray tracing).
// For slides: a line holding a word of the pass's "key_state" (declared by the technique,
// core/technique/pass_table.h PassSpec::keyState) is highlighted; runs of other lines that were
// set before the pass's timer or repeat a line shown above are folded into one line.
void writeStateCard(std::ostream& html, const json& pass) {
  constexpr size_t kShortestFoldedRun = 3;  // a fold of one or two lines saves nothing
  const json state = pass.value("state", json());
  if (!state.is_array()) {
    html << "<div class=\"state-card missing\">state card: not recorded</div>\n";
    return;
  }
  html << "<div class=\"state-card\"><div class=\"card-title\">GL state";
  if (state.empty()) {
    html << "</div><i>no GL call that changes state or draws was made in this pass</i></div>\n";
    return;
  }
  std::vector<std::string> keys;
  for (const json& k : pass.value("key_state", json::array()))
    if (k.is_string()) keys.push_back(k.get<std::string>());
  struct Line {
    std::string group, text;
    bool before = false, key = false, foldable = false;
  };
  std::vector<Line> lines;
  std::set<std::pair<std::string, std::string>> seen;
  for (const json& line : state) {
    Line l;
    l.group = line.is_object() ? line.value("group", "") : "";
    l.text = line.is_object() ? line.value("text", "") : line.dump();
    l.before = line.is_object() && line.value("before_pass", false);
    l.key = std::any_of(keys.begin(), keys.end(),
                        [&](const std::string& k) { return l.text.find(k) != std::string::npos; });
    const bool repeated = !seen.insert({l.group, l.text}).second;
    l.foldable = !l.key && l.group != "part" && (l.before || repeated);
    lines.push_back(std::move(l));
  }
  html << " <span class=\"hint\">(" << state.size() << " lines in call order"
       << (keys.empty() ? ""
                        : "; highlighted: the lines that matter for this pass, as its "
                          "technique declares them")
       << "; grey: set before the pass's timer started; folded: runs of setup and of lines "
          "repeated from above)</span></div><table>\n";
  std::string lastGroup;
  auto row = [&](const Line& l) {
    html << "<tr"
         << (l.group == "part" ? " class=\"part\""
             : l.key           ? " class=\"key\""
             : l.before        ? " class=\"before\""
                               : "")
         << "><td class=\"group\">" << (l.group == lastGroup ? "" : htmlEscape(l.group))
         << "</td><td>" << code(l.text) << "</td></tr>\n";
    lastGroup = l.group;
  };
  for (size_t i = 0; i < lines.size();) {
    size_t end = i;
    while (end < lines.size() && lines[end].foldable) ++end;
    if (end - i < kShortestFoldedRun) {
      row(lines[i]);
      ++i;
      continue;
    }
    const bool allBefore = std::all_of(lines.begin() + long(i), lines.begin() + long(end),
                                       [](const Line& l) { return l.before; });
    html << "<tr class=\"folded\"><td></td><td><details><summary>" << (end - i) << " lines "
         << (allBefore ? "of setup before the pass" : "of setup and repeated state")
         << "</summary><table>\n";
    lastGroup.clear();
    for (size_t k = i; k < end; ++k) row(lines[k]);
    html << "</table></details></td></tr>\n";
    lastGroup.clear();
    i = end;
  }
  html << "</table></div>\n";
}

// The GLSL lines a modern pass runs (passes.json "glsl": [{"file", "first_line",
// "last_line"}]), read from the embedded shaders; a range the build cannot show is named.
void writeGlsl(std::ostream& html, const json& pass) {
  const json ranges = pass.value("glsl", json());
  if (!ranges.is_array()) return;
  for (const json& r : ranges) {
    if (!r.is_object()) continue;
    const std::string file = r.value("file", "");
    const int first = r.value("first_line", 0), last = r.value("last_line", 0);
    const std::string name = fs::path(file).filename().string();
    const std::string title = r.value("title", "");
    html << "<div class=\"glsl\"><div class=\"card-title\">" << htmlEscape(file) << " lines "
         << first << "-" << last << "</div>";
    if (!title.empty()) html << "<div class=\"glsl-title\">" << htmlEscape(title) << "</div>";
    const auto& shaders = embeddedShaders();
    const auto it = shaders.find(name);
    std::vector<std::string> lines;
    if (it != shaders.end()) {
      std::istringstream in(it->second);
      for (std::string l; std::getline(in, l);) lines.push_back(l);
    }
    if (it == shaders.end() || first < 1 || last < first || size_t(last) > lines.size()) {
      html << "<p class=\"missing\">not shown: " << htmlEscape(file)
           << (it == shaders.end() ? " is not a shader of this build"
                                   : " has " + std::to_string(lines.size()) + " lines")
           << "</p></div>\n";
      continue;
    }
    html << "<pre>";
    for (int i = first; i <= last; ++i)
      html << "<span class=\"ln\">" << fmt(i, "%4.0f") << "</span> "
           << htmlEscape(lines[size_t(i - 1)]) << "\n";
    html << "</pre></div>\n";
  }
}

// "legacy.fast-pcf pass 6a accumulate" -> a link to that pass of the legacy side with the same
// footprint as `from` (the 4x4 twin's accumulation on the 4x4 legacy strip), when this page
// shows it.
std::string replacesLink(const std::string& text, const std::vector<Side>& sides,
                         const Side& from) {
  static const std::regex kPass(R"(^\s*([a-z]+\.[a-z0-9-]+) pass ([0-9a-z]+)\b.*)");
  std::smatch m;
  if (std::regex_match(text, m, kPass))
    for (const Side& s : sides) {
      if (s.technique->name != m[1].str() || s.tag != from.tag) continue;
      for (const json& pass : s.passes["passes"])  // the 4x4 accumulation is not in every run
        if (pass.value("id", "") == m[2].str())
          return "<a href=\"#" + passAnchor(s.anchor, m[2].str()) + "\">" + htmlEscape(text) +
                 "</a>";
    }
  return htmlEscape(text);
}

// A per-channel panel's own words: the bracketed end of its caption ("channel R (red): lower
// left alone"), the rest repeats the picture's caption.
std::string panelCaption(const json& image) {
  const std::string caption = image.value("caption", "");
  const size_t at = caption.rfind(" [");
  if (at == std::string::npos || caption.back() != ']') return caption;
  return caption.substr(at + 2, caption.size() - at - 3);
}

// The value legend of a file (passes.json "legend": {"kind", "low", "high", "note"}).
std::string legendHtml(const json& legend) {
  if (!legend.is_object()) return "";
  const bool diverging = legend.value("kind", "") == "diverging";
  std::ostringstream html;
  html << "<div class=\"legend\">" << fmt(legend.value("low", 0.0), "%.4g")
       << " <span class=\"bar\" style=\"background: "
       << (diverging ? "linear-gradient(to right, #00f, #fff, #f00)"
                     : "linear-gradient(to right, #000, #fff)")
       << "\"></span> " << fmt(legend.value("high", 1.0), "%.4g")
       << (diverging ? " (0 = white)" : "");
  const std::string note = legend.value("note", "");
  if (!note.empty()) html << "<br>" << htmlEscape(note);
  html << "</div>";
  return html.str();
}

void writeSide(std::ostream& html, const Side& side, const LessonPage& page) {
  std::map<std::string, const json*> images;
  for (const json& i : side.passes["images"]) images[i["file"].get<std::string>()] = &i;
  html << "<p>" << htmlEscape(side.technique->paper) << ": " << htmlEscape(side.technique->summary)
       << ".<br>Every picture of this strip is a file of <span class=\"cmd\">"
       << code(side.renderCommand) << "</span> (named under each picture, in the folder "
       << code(side.anchor + "-passes") << "). Times are of this one render.</p>\n";
  for (const json& pass : side.passes["passes"]) {
    const int number = pass.value("number", -1);
    const std::string id = pass.value("id", std::to_string(number));
    html << "<section class=\"pass\" id=\"" << passAnchor(side.anchor, id) << "\">\n<h3>"
         << (number >= 0 ? "Pass " + id + ": " : std::string())
         << htmlEscape(pass.value("name", ""));
    if (pass["milliseconds"].is_number())
      html << " <span class=\"time\">" << fmt(pass["milliseconds"].get<double>(), "%.2f ms")
           << "</span>";
    html << "</h3>\n<p class=\"meta\">";
    const json section = pass.value("section", json());
    html << (section.is_string() ? htmlEscape(section.get<std::string>())
                                 : "<span class=\"missing\">paper section not recorded</span>");
    const json source = pass.value("source", json());
    if (source.is_object() && !source.value("file", "").empty())
      html << " · " << code(source.value("file", "") + ": " + source.value("function", "") + "()");
    html << "</p>\n";
    const json replaces = pass.value("replaces", json());
    if (replaces.is_array() && !replaces.empty()) {
      html << "<p class=\"replaces\">replaces ";
      bool first = true;
      for (const json& r : replaces) {
        html << (first ? "" : ", ")
             << replacesLink(r.is_string() ? r.get<std::string>() : "", page.sides, side);
        first = false;
      }
      html << "</p>\n";
    }
    html << "<div class=\"pass-body\"><div class=\"images\">\n";
    bool groupOpen = false;  // a picture and its per-channel panels form one row
    for (const json& f : pass.value("files", json::array())) {
      const json& image = *images.at(f.get<std::string>());
      const bool isChannel = image.contains("channel");
      if (!isChannel) {
        html << (groupOpen ? "</div>" : "") << "<div class=\"pic-group\">";
        groupOpen = true;
      }
      const int width = image["width"].get<int>();
      const int shown =
          isChannel ? kChannelShownWidth : std::clamp(width, kMinShownWidth, kMaxShownWidth);
      const std::string file = side.prefix + f.get<std::string>();
      html << "<figure class=\"" << (isChannel ? "channel" : "picture")
           << "\" style=\"width: " << shown << "px\"><img src=\"" << htmlEscape(file) << "\" alt=\""
           << htmlEscape(f.get<std::string>()) << "\" style=\"width: " << shown
           << "px\"><figcaption>";
      if (isChannel)
        html << htmlEscape(panelCaption(image));
      else
        html << htmlEscape(image["caption"].get<std::string>()) << " <span class=\"file\">("
             << htmlEscape(f.get<std::string>()) << ", " << width << "x"
             << image["height"].get<int>() << ")</span>";
      html << legendHtml(image.value("legend", json())) << "</figcaption></figure>\n";
    }
    html << (groupOpen ? "</div>" : "") << "</div><div class=\"notes\">\n";
    writeStateCard(html, pass);
    writeGlsl(html, pass);
    html << "</div></div>\n</section>\n";
  }
}

void writeComparison(std::ostream& html, const LessonPage& page, const Comparison& c) {
  const Side& legacy = page.sides[c.legacy];
  const Side& modern = page.sides[c.modern];
  html << "<h2 id=\"" << compareAnchor(c.tag) << "\">Legacy against modern"
       << (page.comparisons.size() > 1 ? ", " + footprintTag(c.pair.filter) + " footprint" : "")
       << "</h2>\n<p>The pair <b>" << htmlEscape(c.pair.label)
       << "</b> of the twin table (registry/twins.cpp), on " << htmlEscape(page.settings.scene)
       << " at " << page.settings.width << "x" << page.settings.height
       << ". The masks against the pair's " << htmlEscape(c.mask.verdict)
       << (c.mask.withinBound ? " — <b>within the bound</b>."
                              : " — <b class=\"bad\">outside the bound</b>.")
       << " Why this bound: " << htmlEscape(c.pair.why) << ".</p>\n";
  html << "<table class=\"numbers\"><tr><th></th><th>pixels that differ</th><th>share</th>"
          "<th>largest difference</th></tr>\n";
  html << "<tr><td>visibility mask (any difference)</td><td>" << c.mask.differing << " of "
       << c.mask.all.pixels << "</td><td>" << percent(c.mask.differing, c.mask.all.pixels)
       << "</td><td>" << fmt(c.mask.all.maxAbs, "%.4g") << "</td></tr>\n";
  html << "<tr><td>image (more than one 8-bit step in a colour channel)</td><td>"
       << c.imageDiffering << " of " << c.imagePixels << "</td><td>"
       << percent(c.imageDiffering, c.imagePixels) << "</td><td>" << fmt(c.imageMaxAbs, "%.4g")
       << "</td></tr>\n</table>\n";
  html << "<p class=\"reason\"><b>Why the images differ.</b> ";
  if (c.imageDiffering == 0) {
    html << "They do not: every pixel agrees to one 8-bit step.";
  } else {
    const long long shadow = c.imageDiffering - c.imageDifferingMaskSame;
    html << c.imageDifferingMaskSame << " of the " << c.imageDiffering
         << " differing pixels lie where the two masks are identical: there the shading differs, "
            "not the shadow. The legacy side lights with OpenGL's fixed-function lighting, "
            "evaluated at the vertices and interpolated across each triangle (OpenGL 1.2.1 "
            "§2.13.1 and §3.5.1); the modern side evaluates the same lighting model at every "
            "fragment (modern/shaders/lighting.glsl). The two differ most where the light changes "
            "fastest across a triangle: the spotlight's cone edge and highlights on coarse "
            "meshes. "
         << shadow
         << " lie where the masks differ as well: the shadow term itself differs "
            "there, within the pair's bound above.";
  }
  html << "</p>\n<div class=\"images\">\n";
  auto figure = [&](const std::string& file, const std::string& caption) {
    html << "<figure class=\"picture\" style=\"width: " << kMaxShownWidth << "px\"><img src=\""
         << file << "\" alt=\"" << file << "\" style=\"width: " << kMaxShownWidth
         << "px\"><figcaption>" << caption << "</figcaption></figure>\n";
  };
  figure(legacy.prefix + "image.png", "legacy: " + htmlEscape(legacy.technique->name));
  figure(modern.prefix + "image.png", "modern: " + htmlEscape(modern.technique->name));
  figure(diffFile("diff-mask", c.tag),
         "|legacy mask - modern mask|: black = equal, dark blue = tiny, red, "
         "yellow, white = a whole visibility step");
  figure(diffFile("diff-image", c.tag),
         "max over R, G, B of |legacy image - modern image|: black = equal, white = " +
             fmt(kImageDiffFullScale, "%.2g") + " or more");
  html << "</div>\n<p>Re-made by this page's command (below); the two images and masks alone by "
       << code(legacy.renderCommand) << " and " << code(modern.renderCommand) << ".</p>\n";
}

// "legacy.pcf", or "legacy.pcf, 4x4 footprint" on a page that shows two footprints.
std::string sideLabel(const Side& s, const LessonPage& page) {
  if (page.comparisons.size() < 2) return s.technique->name;
  return s.technique->name + ", " + footprintTag(s.params.filter) + " footprint";
}

// The "why" blocks (WhyBlock): the answer, then the pictures rendered for it with their
// captions, what the run measured and the command that makes each.
void writeWhy(std::ostream& html, const LessonPage& page) {
  if (page.why.empty()) return;
  html << "<h2 id=\"why\">Why each step</h2>\n<p>The questions a student asks about the passes "
          "below, answered with pictures this page's run rendered (on "
       << htmlEscape(page.settings.scene) << " at " << page.settings.width << "x"
       << page.settings.height << ") and numbers from its own GL traces.</p>\n";
  for (size_t i = 0; i < page.why.size(); ++i) {
    const WhyBlock& w = page.why[i];
    html << "<div class=\"why\" id=\"why-" << i + 1 << "\"><h3>" << htmlEscape(w.title)
         << "</h3>\n";
    for (const std::string& p : w.text) html << "<p>" << htmlEscape(p) << "</p>\n";
    if (!w.pictures.empty()) {
      html << "<div class=\"images\">\n";
      for (const WhyPicture& p : w.pictures)
        html << "<figure class=\"picture\"><img src=\"" << htmlEscape(p.file) << "\" alt=\""
             << htmlEscape(p.caption)
             << "\" style=\"width: " << std::min(p.image.width, kMaxShownWidth)
             << "px\"><figcaption><b>" << htmlEscape(p.caption)
             << "</b><br><span class=\"measured\">" << htmlEscape(p.measured) << "</span><br>"
             << code(p.command) << "</figcaption></figure>\n";
      html << "</div>\n";
    }
    html << w.figureHtml << w.tableHtml << "</div>\n";
  }
}

std::string pageHtml(const LessonPage& page) {
  const Technique& t = *page.technique;
  const LessonText& text = page.text;
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>"
       << htmlEscape(t.name) << " — lesson</title>\n<style>\n"
       << "body { font-family: sans-serif; margin: 1.5em auto; max-width: 1250px; padding: 0 1em; "
          "line-height: 1.4; }\n"
       << "h2 { border-top: 2px solid #999; padding-top: 0.5em; margin-top: 1.6em; }\n"
       << "h3 { margin-bottom: 0.2em; }\n"
       << ".time { color: #555; font-weight: normal; font-size: 0.8em; }\n"
       << ".meta, .replaces { margin: 0.1em 0 0.5em; color: #333; font-size: 0.9em; }\n"
       << ".pass { border-top: 1px solid #ccc; }\n"
       << ".pass-body { display: flex; flex-wrap: wrap; gap: 1em; align-items: flex-start; }\n"
       << ".images { flex: 1 1 560px; }\n"
       << ".notes { flex: 1 1 420px; min-width: 0; }\n"
       << "figure { display: inline-block; vertical-align: top; margin: 0 0.8em 0.8em 0; }\n"
       << "figure img { height: auto; max-width: 100%; image-rendering: pixelated; "
          "border: 1px solid #999; }\n"
       << "figcaption { font-size: 0.82em; margin-top: 0.2em; }\n"
       << ".file { color: #666; }\n"
       << ".state-card, .glsl { border: 1px solid #bbb; background: #f7f7f2; padding: 0.4em; "
          "margin-bottom: 0.6em; font-size: 0.82em; overflow-x: auto; }\n"
       << ".card-title { font-weight: bold; margin-bottom: 0.2em; }\n"
       << ".state-card td { vertical-align: top; padding: 0 0.6em 0 0; }\n"
       << ".state-card .group { color: #0a5; white-space: nowrap; }\n"
       << ".state-card tr.before td { color: #777; }\n"
       << ".state-card tr.part td { font-weight: bold; padding-top: 0.4em; }\n"
       << ".state-card { max-height: 30em; overflow: auto; }\n.hint { font-weight: normal; color: "
          "#666; }\n"
       << ".state-card.missing, .missing { color: #a00; }\n"
       << "pre { margin: 0; font-size: 0.95em; }\n.ln { color: #999; }\n"
       << "table.numbers { border-collapse: collapse; }\n"
       << "table.numbers td, table.numbers th { border: 1px solid #ccc; padding: 0.2em 0.6em; }\n"
       << ".bad { color: #a00; }\ncode { font-size: 0.92em; }\n"
       << "dt { font-weight: bold; }\n"
       << ".legend { font-size: 0.9em; color: #444; }\n"
       << ".legend .bar { display: inline-block; width: 70px; height: 0.7em; "
          "border: 1px solid #999; vertical-align: middle; }\n"
       << ".glsl-title { color: #444; margin-bottom: 0.2em; }\n"
       << ".state-card tr.key td { background: #ffe9a8; font-weight: bold; }\n"
       << ".state-card details summary { color: #555; cursor: pointer; }\n"
       << ".why { border-left: 3px solid #9bd; padding-left: 0.8em; margin: 1em 0; }\n"
       << ".why figure { max-width: 420px; }\n.measured { color: #333; font-size: 0.9em; }\n"
       << "@media print {\n  body { max-width: none; margin: 0; font-size: 11pt; }\n"
       << "  .pass, h2, .why { break-before: page; page-break-before: always; }\n"
       << "  .pass { break-inside: avoid-page; }\n"
       << "  .state-card { max-height: none; overflow: visible; }\n"
       << "  .state-card tr.key td { background: none; text-decoration: underline; }\n"
       << "  a { color: inherit; text-decoration: none; }\n}\n"
       << "</style>\n</head>\n<body>\n";
  html << "<h1>" << htmlEscape(field(text, "title")) << "</h1>\n<p><b>" << htmlEscape(t.name)
       << "</b> — " << htmlEscape(text.paper) << ", " << htmlEscape(field(text, "sections"))
       << ".</p>\n<p>Contents: <a href=\"#idea\">the idea</a>";
  if (!page.why.empty()) html << " · <a href=\"#why\">why each step</a>";
  for (const Side& s : page.sides)
    html << " · <a href=\"#" << htmlEscape(s.anchor) << "\">" << htmlEscape(sideLabel(s, page))
         << " pass by pass</a>";
  for (const Comparison& c : page.comparisons)
    html << " · <a href=\"#" << compareAnchor(c.tag) << "\">legacy against modern"
         << (page.comparisons.size() > 1 ? " (" + footprintTag(c.pair.filter) + ")" : "") << "</a>";
  html << " · <a href=\"#departures\">known departures</a> · <a href=\"#made\">how this page was "
          "made</a></p>\n";

  html << "<h2 id=\"idea\">The idea (" << htmlEscape(field(text, "sections")) << ")</h2>\n";
  for (const std::string& p : stringList(text, "idea")) html << "<p>" << htmlEscape(p) << "</p>\n";
  const auto equations = refList(text, "equations");
  if (!equations.empty()) {
    html << "<dl>\n";
    for (const auto& [ref, what] : equations)
      html << "<dt>" << htmlEscape(ref) << "</dt><dd>" << code(what) << "</dd>\n";
    html << "</dl>\n";
  }
  const auto figures = refList(text, "figures");
  if (!figures.empty()) {
    html << "<p>The paper's figures this lesson refers to:</p><ul>\n";
    for (const auto& [ref, what] : figures)
      html << "<li><b>" << htmlEscape(ref) << "</b>: " << htmlEscape(what) << "</li>\n";
    html << "</ul>\n";
  }

  writeWhy(html, page);
  for (const Side& s : page.sides) {
    html << "<h2 id=\"" << htmlEscape(s.anchor) << "\">"
         << (s.role == "legacy"   ? "The 2001 pipeline: "
             : s.role == "modern" ? "The shader twin: "
                                  : "Pass by pass: ")
         << htmlEscape(sideLabel(s, page)) << "</h2>\n";
    writeSide(html, s, page);
  }
  for (const Comparison& c : page.comparisons) writeComparison(html, page, c);

  html << "<h2 id=\"departures\">Known departures</h2>\n<p>Where this implementation departs from "
          "the paper or the specification, the pass that departs declares it in its "
          "technique's pass table (and a <code>DEVIATION</code> comment says so in the source "
          "at the same place); these are the ones of the passes on this page.";
  html << " Further reading in the repository: ";
  bool first = true;
  for (const std::string& d : stringList(text, "docs")) {
    html << (first ? "" : ", ") << code(d);
    first = false;
  }
  html << ".</p>\n";
  if (page.departures.empty()) {
    html << "<p>None: every pass on this page follows its paper as written.</p>\n";
  } else {
    html << "<ul class=\"departures\">\n";
    for (const Departure& d : page.departures)
      html << "<li><a href=\"#" << passAnchor(d.technique, d.passId) << "\">"
           << htmlEscape(d.technique + " pass " + d.passId + " (" + d.passName + ")") << "</a> — "
           << htmlEscape(d.text) << "</li>\n";
    html << "</ul>\n";
  }

  html << "<h2 id=\"made\">How this page was made</h2>\n<p>" << code(page.lessonCommand)
       << " (shadowlab " << htmlEscape(page.commit) << ") rendered every picture on this page: "
       << "scene " << htmlEscape(page.settings.scene) << ", " << page.settings.width << "x"
       << page.settings.height << ", a " << page.settings.shadowMapTexels
       << "² shadow map where the technique reads one, the OSMesa back end (llvmpipe). Each "
          "pass strip says the <code>shadowlab render</code> command that writes the same "
          "pictures as a pass dump; every PNG carries its command in a tEXt chunk.</p>\n";
  html << "</body>\n</html>\n";
  return html.str();
}

// ---------------------------------------------------------------- assembling a lesson

RenderParams paramsForSettings(const LessonSettings& s);

// A part of an image, seen from the top ([x, y from the top, w, h] in pixels), enlarged `zoom`
// times with nearest-neighbour sampling so that single pixels stay visible.
Image croppedAndZoomed(const Image& image, const json& crop, int zoom) {
  int x = 0, top = 0, w = image.width, h = image.height;
  if (crop.is_array() && crop.size() == 4) {
    x = std::clamp(crop[0].get<int>(), 0, image.width - 1);
    top = std::clamp(crop[1].get<int>(), 0, image.height - 1);
    w = std::clamp(crop[2].get<int>(), 1, image.width - x);
    h = std::clamp(crop[3].get<int>(), 1, image.height - top);
  }
  zoom = std::max(zoom, 1);
  Image out(w * zoom, h * zoom, image.channels);
  const int bottom = image.height - top - h;  // rows are stored bottom-up
  for (int y = 0; y < out.height; ++y)
    for (int xx = 0; xx < out.width; ++xx)
      for (int c = 0; c < image.channels; ++c)
        out.at(xx, y, c) = image.at(x + xx / zoom, bottom + y / zoom, c);
  return out;
}

// The numbers of a traced line: "GL_S: GL_EYE_PLANE = (0.862, -0.43, ...)" -> {0.862, -0.43, ...}
// (those after the first '(' or '[').
std::vector<double> numbersOf(const std::string& text) {
  static const std::regex kNumber(R"([-+]?[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)");
  const size_t open = text.find_first_of("([");
  std::vector<double> out;
  if (open == std::string::npos) return out;
  const std::string tail = text.substr(open);
  for (auto it = std::sregex_iterator(tail.begin(), tail.end(), kNumber);
       it != std::sregex_iterator(); ++it)
    out.push_back(std::stod(it->str()));
  return out;
}

// Everitt Eq. 5 on both twins: the four EYE_LINEAR planes the legacy camera pass gives (unit 0)
// beside the rows of the matrix the shader twin loads (uWorldToShadowMap), as traced on this
// page's cards, with their largest difference. Empty when the page has no such pair of lines.
std::string planesTable(const std::vector<Side>& sides) {
  std::vector<std::vector<double>> planes(4), rows;
  std::string legacyName, modernName;
  const char* coords[] = {"GL_S", "GL_T", "GL_R", "GL_Q"};
  for (const Side& side : sides) {
    if (!side.tag.empty()) continue;
    for (const json& pass : side.passes["passes"])
      for (const json& line : pass.value("state", json::array())) {
        const std::string text = line.value("text", "");
        for (int i = 0; i < 4; ++i)
          if (text.rfind(std::string(coords[i]) + ": GL_EYE_PLANE = (", 0) == 0 &&
              text.find("(unit 0;") != std::string::npos && planes[size_t(i)].empty()) {
            planes[size_t(i)] = numbersOf(text);
            legacyName = side.technique->name;
          }
        if (text.rfind("uWorldToShadowMap = mat4 [", 0) == 0 && rows.empty()) {
          const std::vector<double> m = numbersOf(text);
          for (size_t r = 0; r + 1 < 5 && m.size() == 16; ++r)
            rows.emplace_back(m.begin() + long(4 * r), m.begin() + long(4 * r + 4));
          modernName = side.technique->name;
        }
      }
  }
  if (rows.size() != 4 ||
      std::any_of(planes.begin(), planes.end(), [](const auto& p) { return p.size() < 4; }))
    return "";
  std::ostringstream html;
  double largest = 0.0;
  html << "<table class=\"numbers\"><tr><th>row</th><th>" << htmlEscape(legacyName)
       << ": glTexGenfv(…, GL_EYE_PLANE) (pass card)</th><th>" << htmlEscape(modernName)
       << ": uWorldToShadowMap row (pass card)</th><th>largest |difference|</th></tr>\n";
  for (int i = 0; i < 4; ++i) {
    double d = 0.0;
    std::string a, b;
    for (int k = 0; k < 4; ++k) {
      d = std::max(d, std::fabs(planes[size_t(i)][size_t(k)] - rows[size_t(i)][size_t(k)]));
      a += (k ? ", " : "") + fmt(planes[size_t(i)][size_t(k)], "%.6g");
      b += (k ? ", " : "") + fmt(rows[size_t(i)][size_t(k)], "%.6g");
    }
    largest = std::max(largest, d);
    html << "<tr><td>" << coords[i] << "</td><td><code>(" << a << ")</code></td><td><code>(" << b
         << ")</code></td><td>" << fmt(d, "%.2g") << "</td></tr>\n";
  }
  html << "</table>\n<p class=\"measured\">Largest difference over the sixteen numbers: "
       << fmt(largest, "%.2g")
       << " (both printed with 6 significant digits; the two programs compute the same product "
          "in float).</p>\n";
  return html.str();
}

// The parts of a pass repeated per phase or group (the 4x4 footprint), with the traced lines
// of each part that hold one of `match` (the kernels of the packing copy, the texture matrix
// of the projective pass): a table of what changes from part to part.
std::string partsTable(const std::vector<Side>& sides, const json& block) {
  const std::string tag = footprintTag(kLargeFootprint);
  std::ostringstream html;
  for (const Side& side : sides) {
    if (side.tag != tag || side.role != "legacy") continue;
    for (const json& id : block.value("passes", json::array()))
      for (const json& pass : side.passes["passes"]) {
        if (pass.value("id", "") != id.get<std::string>()) continue;
        html << "<table class=\"numbers parts\"><tr><th colspan=2>"
             << htmlEscape(side.technique->name) << " at 4x4, pass "
             << htmlEscape(pass.value("id", "")) << " (" << htmlEscape(pass.value("name", ""))
             << "), as traced</th></tr>\n";
        std::string part;
        for (const json& line : pass.value("state", json::array())) {
          const std::string text = line.value("text", "");
          if (line.value("group", "") == "part") {
            const size_t open = text.rfind(" (");
            part = open == std::string::npos ? text : text.substr(open + 1);
            continue;
          }
          for (const json& m : block.value("match", json::array()))
            if (text.find(m.get<std::string>()) != std::string::npos &&
                text.find("load [1 0 0 0; 0 1 0 0; 0 0 1 0; 0 0 0 1]") == std::string::npos) {
              html << "<tr><td>" << htmlEscape(part) << "</td><td>" << code(text) << "</td></tr>\n";
              break;
            }
        }
        html << "</table>\n";
      }
  }
  return html.str();
}

// Brabec & Seidel §4's 4x4 footprint as four 2x2 phases: the 16 texels around the lookup point
// (the texel corner nearest to it, the dot), each phase's block in its colour with the channel
// that holds each texel (the packing's channel meaning, PassBuffer::channelMeaning: R lower left,
// G lower right, B upper left, A upper right). Drawn as SVG from the legacy 4x4 pass table.
std::string tilingFigure(const std::vector<Side>& sides) {
  constexpr int kCell = 44;  // pixels per texel in the drawing
  constexpr int kMargin = 10;
  const char* colours[] = {"#fbb", "#bdf", "#bfb", "#fe9"};
  const char* phases[] = {"upper-left", "upper-right", "lower-left", "lower-right"};
  const char* letters[2][2] = {{"B", "A"}, {"R", "G"}};  // [row from the top][column]
  const PassSpec* packing = nullptr;
  for (const Side& side : sides)
    if (side.tag == footprintTag(kLargeFootprint) && side.role == "legacy")
      for (const PassSpec& spec : side.technique->passes)
        for (const PassBuffer& b : spec.writes)
          if (b.centreChannel >= 0 && b.channelMeaning.size() == 4) packing = &spec;
  if (packing == nullptr) return "";
  const int size = 4 * kCell + 2 * kMargin;
  std::ostringstream svg;
  svg << "<svg class=\"tiling\" width=\"" << size << "\" height=\"" << size << "\" viewBox=\"0 0 "
      << size << " " << size << "\" font-family=\"sans-serif\" font-size=\"13\">\n";
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) {
      const int phase = (row / 2) * 2 + col / 2;
      const int x = kMargin + col * kCell, y = kMargin + row * kCell;
      svg << "<rect x=\"" << x << "\" y=\"" << y << "\" width=\"" << kCell << "\" height=\""
          << kCell << "\" fill=\"" << colours[phase] << "\" stroke=\"#888\"/>"
          << "<text x=\"" << x + kCell / 2 << "\" y=\"" << y + kCell / 2 + 5
          << "\" text-anchor=\"middle\">" << letters[row % 2][col % 2] << "</text>\n";
    }
  for (int phase = 0; phase < 4; ++phase) {
    const int x = kMargin + (phase % 2) * 2 * kCell, y = kMargin + (phase / 2) * 2 * kCell;
    svg << "<rect x=\"" << x << "\" y=\"" << y << "\" width=\"" << 2 * kCell << "\" height=\""
        << 2 * kCell << "\" fill=\"none\" stroke=\"#000\" stroke-width=\"2\"><title>"
        << phases[phase] << " phase</title></rect>\n";
  }
  svg << "<circle cx=\"" << kMargin + 2 * kCell << "\" cy=\"" << kMargin + 2 * kCell
      << "\" r=\"5\" fill=\"#000\"/>\n</svg>";
  std::ostringstream html;
  html << "<figure class=\"picture\">" << svg.str()
       << "<figcaption>The 4x4 footprint of one lookup as four 2x2 phases, one packed map each "
          "(pass "
       << htmlEscape(packing->id)
       << "; upper-left red, "
          "upper-right blue, lower-left green, lower-right yellow); the letter in each texel is "
          "the channel of that phase's packed map that holds it ("
       << htmlEscape(packing->writes.front().channelMeaning[0]) << " R, "
       << htmlEscape(packing->writes.front().channelMeaning[1]) << " G, "
       << htmlEscape(packing->writes.front().channelMeaning[2])
       << " B, upper right A); the dot "
          "is the texel corner nearest to the point.</figcaption></figure>\n";
  return html.str();
}

// The "why" blocks of the lesson text: [{"title", "text": [...], "renders": [{"technique",
// "params", "filter", "caption", "crop", "zoom"}], "table": "planes" | "parts", "passes",
// "match", "figure": "tiling"}]; each render is made here, on the lesson's scene and size.
std::vector<WhyBlock> whyBlocks(const LessonText& text, const std::vector<Side>& sides,
                                const LessonSettings& s, const Scene& scene) {
  std::vector<WhyBlock> out;
  const json blocks = text.entry.value("why", json::array());
  try {
    for (size_t b = 0; b < blocks.size(); ++b) {
      const json& block = blocks[b];
      WhyBlock w;
      w.title = block.at("title").get<std::string>();
      w.text = block.value("text", json::array()).get<std::vector<std::string>>();
      const json renders = block.value("renders", json::array());
      for (size_t r = 0; r < renders.size(); ++r) {
        const json& render = renders[r];
        const Technique& t = findTechnique(render.at("technique").get<std::string>());
        RenderParams p = paramsForSettings(s);
        p.filter = render.value("filter", p.filter);
        const json params = render.value("params", json::object());
        for (const auto& [k, v] : params.items()) p.extra[k] = v.get<std::string>();
        const Frame frame = renderTechnique(t, scene, p);
        WhyPicture pic;
        pic.file = "why-" + std::to_string(b + 1) + "-" + std::to_string(r + 1) + ".png";
        pic.caption = render.at("caption").get<std::string>();
        long long shadowed = 0;  // visibility below one half
        for (float v : frame.visibility.data) shadowed += v < 0.5f;
        const double share = frame.visibility.data.empty()
                                 ? 0.0
                                 : double(shadowed) / double(frame.visibility.data.size());
        pic.measured = fmt(100.0 * share, "%.1f") + "% of the image in shadow (visibility < 1/2)";
        pic.command = renderCommandFor(t, p, s, pic.file.substr(0, pic.file.size() - 4), false);
        pic.image =
            croppedAndZoomed(frame.color, render.value("crop", json()), render.value("zoom", 1));
        w.pictures.push_back(std::move(pic));
      }
      const std::string table = block.value("table", "");
      if (table == "planes") w.tableHtml = planesTable(sides);
      if (table == "parts") w.tableHtml = partsTable(sides, block);
      if (block.value("figure", "") == "tiling") w.figureHtml = tilingFigure(sides);
      out.push_back(std::move(w));
    }
  } catch (const json::exception& e) {
    throw InputError("lesson text " + text.file + ": why: " + e.what());
  }
  return out;
}

RenderParams paramsForSettings(const LessonSettings& s) {
  RenderParams p;
  p.width = s.width;
  p.height = s.height;
  p.shadowMapTexels = s.shadowMapTexels;
  return p;
}

std::string lessonCommandFor(const std::string& technique, const LessonSettings& s,
                             const std::string& out) {
  return shellJoin({"shadowlab", "lesson", technique, "--out", out, "--scene", s.scene, "--size",
                    std::to_string(s.width) + "x" + std::to_string(s.height), "--shadow-map",
                    std::to_string(s.shadowMapTexels)});
}

LessonPage prepareLesson(const Technique& t, const LessonSettings& s, const std::string& out,
                         FrameCache& cache) {
  LessonPage page;
  page.technique = &t;
  page.text = lessonTextFor(t.name);
  page.settings = s;
  page.lessonCommand = lessonCommandFor(t.name, s, out);
  page.commit = buildCommit();
  const Scene scene = loadScene(s.scene);
  const std::vector<twins::TwinPair> pairs = pairsOf(t.name);
  for (const twins::TwinPair& pair : pairs) {
    const RenderParams lp =
        twins::paramsFor(pair, true, s.width, s.height, s.shadowMapTexels, Backend::kOsmesa);
    const RenderParams mp =
        twins::paramsFor(pair, false, s.width, s.height, s.shadowMapTexels, Backend::kOsmesa);
    const std::string tag = &pair == &pairs.front() ? "" : footprintTag(pair.filter);
    page.sides.push_back(
        renderSide(findTechnique(pair.legacy), lp, scene, s, cache, "legacy", tag));
    page.sides.push_back(
        renderSide(findTechnique(pair.modern), mp, scene, s, cache, "modern", tag));
    const size_t l = page.sides.size() - 2, m = page.sides.size() - 1;
    page.comparisons.push_back(compareSides(pair, page.sides[l], page.sides[m]));
    page.comparisons.back().legacy = l;
    page.comparisons.back().modern = m;
    page.comparisons.back().tag = tag;
  }
  if (pairs.empty())
    page.sides.push_back(renderSide(t, paramsForSettings(s), scene, s, cache, "own", ""));
  page.why = whyBlocks(page.text, page.sides, s, scene);
  // Departures: what the pass tables of the page's techniques declare (each technique once).
  std::vector<const Technique*> shown;
  for (const Side& side : page.sides)
    if (std::find(shown.begin(), shown.end(), side.technique) == shown.end())
      shown.push_back(side.technique);
  page.departures = departuresOf(shown);
  return page;
}

// Writes every file of the page into `directory` (which exists and is empty).
void writeLessonFiles(const LessonPage& page, const std::string& directory) {
  const Provenance provenance{page.lessonCommand,
                              json({{"technique", page.technique->name},
                                    {"scene", page.settings.scene},
                                    {"size", std::to_string(page.settings.width) + "x" +
                                                 std::to_string(page.settings.height)},
                                    {"shadow_map", page.settings.shadowMapTexels}})
                                  .dump()};
  const fs::path dir(directory);
  for (const Side& s : page.sides) {
    for (const PassDumpImage& i : s.images)
      writePng((dir / (s.prefix + i.file)).string(), i.image, 8, provenance);
    if (s.role != "own")
      writePng((dir / (s.prefix + "image.png")).string(), s.frame->color, 8, provenance);
  }
  for (const Comparison& c : page.comparisons) {
    writePng((dir / diffFile("diff-mask", c.tag)).string(), c.maskHeat, 8, provenance);
    writePng((dir / diffFile("diff-image", c.tag)).string(), c.imageHeat, 8, provenance);
  }
  for (const WhyBlock& w : page.why)
    for (const WhyPicture& p : w.pictures) {
      const Provenance made{p.command, provenance.parameters};
      writePng((dir / p.file).string(), p.image, 8, made);
    }
  writeFileAtomically((dir / kDumpIndexFiles[1]).string(),
                      [&](std::ostream& out) { out << pageHtml(page); });
}

}  // namespace

std::string lessonIndexHtml(const std::vector<LessonLink>& links, const std::string& base) {
  if (links.empty()) return "";
  std::ostringstream h;
  h << "<section id=lessons><h2>Lessons: every pass of every technique</h2>\n<p>One page per "
       "technique (<code>shadowlab lesson TECHNIQUE --out DIR</code>): the paper's idea, each "
       "pass with its pictures, captions and GL state card, the shader twin with its GLSL "
       "lines, legacy against modern, and the known departures.</p>\n<ul class=lessons>\n";
  for (const LessonLink& l : links) {
    if (l.error.empty())
      h << "<li><a href=\"" << htmlEscape(base + l.href) << "\"><code>" << htmlEscape(l.technique)
        << "</code></a> — " << htmlEscape(l.title) << "</li>\n";
    else
      h << "<li class=bad><code>" << htmlEscape(l.technique) << "</code>: no lesson ("
        << htmlEscape(l.error) << ")</li>\n";
  }
  h << "</ul></section>\n";
  return h.str();
}

std::vector<std::string> techniquesWithoutLesson() {
  std::vector<std::string> out;
  const std::vector<LessonText> texts = allLessonTexts();
  for (const Technique& t : allTechniques()) {
    bool found = false;
    for (const LessonText& text : texts)
      for (const json& name : text.entry.value("techniques", json::array()))
        found = found || name == t.name;
    if (!found) out.push_back(t.name);
  }
  return out;
}

std::string lessonTitle(const std::string& technique) {
  return field(lessonTextFor(technique), "title");
}

int runLessonCommand(const cli::Args& args) {
  const Technique& t = findTechnique(args.required("technique"));
  LessonSettings s;
  if (auto v = args.value("scene")) s.scene = *v;
  if (auto v = args.value("size")) cli::parseSize(*v, s.width, s.height);
  constexpr int kLargestShadowMap = 1 << 16;  // the GL maximum is checked once a context exists
  if (auto v = args.value("shadow-map"))
    s.shadowMapTexels = cli::parsePositiveInt("--shadow-map", *v, kLargestShadowMap);
  const std::string out = args.required("out");
  OutputSet outputs;
  outputs.addInput(s.scene);
  outputs.addInput((fs::path(assetDirectory()) / "scenes" / (s.scene + ".json")).string());
  const std::string dir = outputs.addDirectory("--out", out);
  FrameCache cache;
  const LessonPage page = prepareLesson(t, s, out, cache);
  outputs.beginWriting();
  writeLessonFiles(page, dir);
  outputs.commit();
  size_t pictures = 0;
  for (const Side& side : page.sides) pictures += side.images.size();
  std::cout << "wrote " << (fs::path(out) / "index.html").string() << " (" << t.name << ", "
            << page.sides.size() << " technique" << (page.sides.size() > 1 ? "s" : "") << ", "
            << pictures << " pass pictures)" << std::endl;
  return 0;
}

std::vector<LessonLink> writeLessons(const std::string& lessonsDir,
                                     const std::vector<std::string>& techniques,
                                     const LessonSettings& settings, bool progress) {
  std::vector<LessonLink> links;
  FrameCache cache;
  for (const std::string& name : techniques) {
    LessonLink link{name, name + "/index.html", "", ""};
    if (progress) std::cerr << "[lesson] " << name << std::endl;
    try {
      const Technique& t = findTechnique(name);
      link.title = lessonTitle(name);
      OutputSet outputs;
      const std::string target = (fs::path(lessonsDir) / name).string();
      const std::string dir = outputs.addDirectory("lesson", target);
      const LessonPage page = prepareLesson(t, settings, target, cache);
      outputs.beginWriting();
      writeLessonFiles(page, dir);
      outputs.commit();
    } catch (const std::exception& e) {
      link.error = e.what();
      if (progress) std::cerr << "        lesson not written: " << e.what() << std::endl;
    }
    links.push_back(link);
  }
  return links;
}

}  // namespace sl::figures
