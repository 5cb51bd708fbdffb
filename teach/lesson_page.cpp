// teach/lesson_page.cpp — the lesson page's HTML: pass strips with captions, state cards and
// GLSL, legacy against modern, the "why" blocks (teach/lesson.h, teach/lesson_parts.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/base/errors.h"
#include "core/base/html.h"
#include "core/base/image.h"
#include "core/gl/shaders.h"
#include "core/scene/scene_library.h"
#include "registry/registry.h"
#include "registry/twins.h"
#include "teach/lesson_parts.h"
#include "teach/pass_dump.h"

namespace sl::figures::lesson_detail {
namespace fs = std::filesystem;

// ---------------------------------------------------------------- the page

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

// The anchor of a pass on the page: its side's anchor and its id in the pass table.
std::string passAnchor(const std::string& sideAnchor, const std::string& id) {
  return htmlEscape(sideAnchor) + "-pass-" + htmlEscape(id);
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

// A "replaces" entry (legacy.fast-pcf pass 6a) -> a link to that pass of the legacy side with
// the same footprint as `from` (the 4x4 twin's accumulation on the 4x4 legacy strip), when this
// page shows it; found by its id, the technique and the pass.
std::string replacesLink(const json& replaced, const std::vector<Side>& sides, const Side& from) {
  const std::string text = replacedPassText(replaced);
  const std::string technique = replaced.value("technique", ""), id = replaced.value("pass", "");
  for (const Side& s : sides) {
    if (s.technique->name != technique || s.tag != from.tag) continue;
    for (const json& pass : s.passes["passes"])  // the 4x4 accumulation is not in every run
      if (pass.value("id", "") == id)
        return "<a href=\"#" + passAnchor(s.anchor, id) + "\">" + htmlEscape(text) + "</a>";
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
             << replacesLink(r.is_object() ? r : json::object(), page.sides, side);
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
       << page.settings.height
       << "; a picture that needs another scene or shadow map says so in its command) and numbers "
          "from its own GL traces.</p>\n";
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
  if (!page.figures.empty()) html << " · <a href=\"#report-figures\">the report's figures</a>";
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

  if (!page.figures.empty()) {
    html << "<h2 id=\"report-figures\">The report's figures</h2>\n<p>The papers' figures as "
            "<code>shadowlab figures</code> re-makes them, with our numbers beside the papers', "
            "that show ";
    const std::vector<std::string> subjects = stringList(text, "techniques");
    for (size_t i = 0; i < subjects.size(); ++i)
      html << (i == 0 ? "" : i + 1 == subjects.size() ? " or " : ", ") << code(subjects[i]);
    html << ":</p>\n" << figureLinksHtml(page.figures);
    if (std::any_of(page.figures.begin(), page.figures.end(),
                    [](const FigureLink& l) { return l.href.empty(); }))
      html << unlinkedFiguresHtml();
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
    for (const Departure& d : page.departures) {
      const std::string pass =
          htmlEscape(d.technique + " pass " + d.passId + " (" + d.passName + ")");
      html << "<li>"
           << (d.anchor.empty() ? pass + " <i>(not run on this page)</i>"
                                : "<a href=\"#" + d.anchor + "\">" + pass + "</a>")
           << " — " << htmlEscape(d.text) << "</li>\n";
    }
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

}  // namespace sl::figures::lesson_detail
