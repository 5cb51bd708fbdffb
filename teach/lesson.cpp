// teach/lesson.cpp — see lesson.h: the lesson text, rendering each side, legacy against modern,
// assembling and writing a lesson. The "why" blocks: lesson_why.cpp; the HTML: lesson_page.cpp.
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
#include "teach/lesson_parts.h"
#include "teach/pass_dump.h"

namespace sl::figures {
namespace lesson_detail {
namespace fs = std::filesystem;

// ---------------------------------------------------------------- the lesson text

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

// Every departure the pass tables of the page's techniques declare (each variant's too), pass by
// pass; a text shared by several passes (a helper they all call) is listed once. Each links to
// the first pass on the page that declares it, on the side whose run has that pass: a pass that
// runs only at some footprints (PCF's 2s at 3x3 and 4x4) is on the 4x4 side
// ("legacy.pcf-4x4-pass-2s"), not on the 2x2 one. A departure of a pass no side of the page
// runs (another variant's) is listed without a link.
std::vector<Departure> departuresOf(const std::vector<Side>& sides) {
  auto ran = [](const Side& s, const std::string& id) {
    for (const json& pass : s.passes["passes"])
      if (pass.value("id", "") == id) return true;
    return false;
  };
  std::vector<const Technique*> techniques;  // each technique once, in the sides' order
  for (const Side& side : sides)
    if (std::find(techniques.begin(), techniques.end(), side.technique) == techniques.end())
      techniques.push_back(side.technique);
  std::vector<Departure> out;
  for (const Technique* t : techniques)
    for (const PassTable* table : allPassTables(*t))
      for (const PassSpec& p : *table) {
        std::string anchor;
        for (const Side& s : sides)
          if (anchor.empty() && s.technique == t && ran(s, p.id))
            anchor = passAnchor(s.anchor, p.id);
        for (const std::string& d : p.deviations) {
          auto same =
              std::find_if(out.begin(), out.end(), [&](const Departure& o) { return o.text == d; });
          if (same == out.end())
            out.push_back({t->name, p.id, p.name, d, anchor});
          else if (same->anchor.empty() && !anchor.empty())  // a pass the page shows
            *same = {t->name, p.id, p.name, d, anchor};
        }
      }
  return out;
}

// ---------------------------------------------------------------- rendering

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
                             const std::string& outName, bool dump) {
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

// ---------------------------------------------------------------- assembling a lesson

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
  page.departures = departuresOf(page.sides);
  page.figures = figureLinksFor({t.name}, s.report);
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

}  // namespace lesson_detail
using namespace lesson_detail;

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

std::vector<std::string> lessonSubjects(const std::string& technique) {
  std::vector<std::string> out;
  for (const LessonText& text : allLessonTexts())
    for (const json& name : text.entry.value("techniques", json::array()))
      if (name == technique) out = stringList(text, "techniques");
  if (out.empty()) out.push_back(technique);
  return out;
}

bool figureShows(const FigureRef& figure, const std::vector<std::string>& subjects) {
  return std::any_of(figure.techniques.begin(), figure.techniques.end(), [&](const std::string& t) {
    return std::find(subjects.begin(), subjects.end(), t) != subjects.end();
  });
}

std::vector<FigureLink> figureLinksFor(const std::vector<std::string>& techniques,
                                       const ReportLinks& report) {
  std::vector<std::vector<std::string>> subjects;
  for (const std::string& t : techniques) subjects.push_back(lessonSubjects(t));
  std::vector<FigureLink> out;
  for (const FigureRef& f : report.figures) {
    if (std::none_of(subjects.begin(), subjects.end(),
                     [&](const std::vector<std::string>& s) { return figureShows(f, s); }))
      continue;
    const auto anchor = report.anchors.find(f.id);
    out.push_back({f.id, f.title,
                   report.href.empty() || anchor == report.anchors.end()
                       ? std::string()
                       : report.href + "#" + anchor->second});
  }
  return out;
}

std::string figureLinksHtml(const std::vector<FigureLink>& links) {
  if (links.empty()) return "";
  std::ostringstream h;
  h << "<ul class=\"report-figures\">\n";
  for (const FigureLink& l : links) {
    h << "<li>";
    if (l.href.empty())
      h << htmlEscape(l.title);
    else
      h << "<a href=\"" << htmlEscape(l.href) << "\">" << htmlEscape(l.title) << "</a>";
    h << " (<code>" << htmlEscape(l.id) << "</code>)</li>\n";
  }
  h << "</ul>\n";
  return h.str();
}

std::string unlinkedFiguresHtml() {
  return "<p class=\"report-figures-made\">A figure named without a link is not in a report beside "
         "this page: <code>shadowlab figures --only ID --out DIR</code> makes it in "
         "<code>DIR/report.html</code>; <code>shadowlab figures --out DIR</code> makes them all, "
         "with the lessons in <code>DIR/lessons/</code> and the course in <code>DIR/course/</code> "
         "linked to them.</p>\n";
}

std::string lessonTitle(const std::string& technique) {
  return field(lessonTextFor(technique), "title");
}

size_t whyPictureCount(const std::string& technique) {
  const LessonText text = lessonTextFor(technique);
  size_t n = 0;
  try {
    for (const json& block : text.entry.value("why", json::array()))
      n += block.value("renders", json::array()).size();
  } catch (const json::exception& e) {
    throw InputError("lesson text " + text.file + ": why: " + e.what());
  }
  return n;
}

std::vector<std::string> techniquesWithoutWhyPicture() {
  std::vector<std::string> out;
  for (const Technique& t : allTechniques())
    if (whyPictureCount(t.name) == 0) out.push_back(t.name);
  return out;
}

int runLessonCommand(const cli::Args& args, const std::vector<FigureRef>& figures) {
  const Technique& t = findTechnique(args.required("technique"));
  LessonSettings s;
  s.report.figures = figures;
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
