#include "figures/course.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/base/errors.h"
#include "core/base/html.h"
#include "core/base/image.h"
#include "core/base/output_files.h"
#include "core/base/provenance.h"
#include "core/scene/scene_library.h"
#include "figures/report.h"
#include "registry/commands.h"
#include "registry/registry.h"
#include "teach/exercise_page.h"

namespace sl::figures {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// The lessons `shadowlab course` renders: the main job's small sizes (figures/figures.cpp), so
// that all 21 cost about half a minute.
constexpr int kLessonWidth = 320;
constexpr int kLessonHeight = 240;
constexpr int kLessonShadowMap = 256;
constexpr int kMinExercises = 2;  // per step (the course's contract: 2-3 exercises a lesson)
constexpr int kMaxExercises = 3;

const char* kTeacherDir = "teacher";
const char* kScopePage = "scope.html";
const char* kMeasureCompare = "compare";  // course.json "measure": run `shadowlab compare`

std::string courseFile() {
  return (fs::path(assetDirectory()) / "course" / "course.json").string();
}

std::vector<RenderOption> optionList(const json& list) {
  std::vector<RenderOption> out;
  for (const json& o : list) {
    if (!o.is_array() || o.size() != 2)
      throw InputError("course " + courseFile() + ": an option must be [key, value], got " +
                       o.dump());
    out.emplace_back(o.at(0).get<std::string>(), o.at(1).get<std::string>());
  }
  return out;
}

CourseExercise exerciseFrom(const json& j, const std::string& defaultSize) {
  CourseExercise e;
  e.id = j.at("id").get<std::string>();
  e.tryText = j.at("try").get<std::string>();
  e.question = j.at("question").get<std::string>();
  e.answer = j.at("answer").get<std::string>();
  e.lab = j.at("lab").get<bool>();
  e.gallery = j.value("gallery", std::string());
  e.measure = j.value("measure", std::string());
  if (!e.measure.empty() && e.measure != kMeasureCompare)
    throw InputError("course " + courseFile() + ": exercise " + e.id + " has measure '" +
                     e.measure + "'; the only measure is '" + kMeasureCompare + "'");
  GalleryEntry& p = e.pair;
  p.id = e.id;
  p.title = e.question;
  p.scene = j.at("scene").get<std::string>();
  cli::parseSize(j.value("size", defaultSize), p.width, p.height);
  p.common = optionList(j.value("common", json::array()));
  p.wrongTechnique = j.at("a").at("technique").get<std::string>();
  p.rightTechnique = j.at("b").at("technique").get<std::string>();
  p.wrong = optionList(j.at("a").at("options"));
  p.right = optionList(j.at("b").at("options"));
  p.closeup = {0, 0, p.width, p.height, 1};  // the lab opens on the whole frame
  return e;
}

std::string pictureName(const CourseExercise& e, bool sideA) {
  return e.id + (sideA ? "-a" : "-b") + ".png";
}

std::string lessonHref(const CourseSettings& s, const std::string& technique) {
  return s.lessonsHref + technique + "/index.html";
}

// The page's style: screen and print (each step on a page of its own, its pictures small enough
// that a step's exercises fit on it: the teacher's page prints on about one page a step; links
// print their text only; commands wrap).
const char* kStyle =
    "body{font:15px/1.45 system-ui,sans-serif;max-width:1050px;margin:1em auto;padding:0 1em;"
    "color:#222}\n"
    "section.step{border-top:2px solid #bbb;padding:.4em 0 .8em}\n"
    ".adds{font-style:italic}\n"
    "div.exercise{border-left:4px solid #9ab;padding:.1em .8em;margin:.8em 0;background:#f8f9fa}\n"
    "pre{white-space:pre-wrap;word-break:break-all;font-size:.82em;background:#f2f2ec;"
    "padding:.3em .5em;margin:.2em 0}\n"
    "code{font-size:.88em;background:#f2f2ec;padding:0 .2em}\n"
    ".pair{display:flex;flex-wrap:wrap;gap:1em}.pair figure{margin:0}\n"
    ".pair img{border:1px solid #999;max-width:100%;height:auto}\n"
    "figcaption{font-size:.85em;color:#444}\n"
    ".error{color:#b00}\n"
    ".answer{background:#eef7ee;padding:.3em .6em}\n"
    ".measured{background:#f3f0e6;padding:.3em .6em;font-size:.9em}\n"
    "table.scope{border-collapse:collapse}table.scope td,table.scope th{border:1px solid #ccc;"
    "padding:.3em .5em;vertical-align:top;text-align:left}\n"
    "footer{border-top:1px solid #ccc;margin-top:2em;font-size:.85em;color:#555}\n"
    "@page{margin:1.2cm}\n"
    "@media print{body{max-width:none;font-size:9pt;line-height:1.25}"
    "a{color:inherit;text-decoration:none}nav.toc{break-after:page}"
    "nav.toc .adds{display:none}nav.toc li{margin:0}"
    "section.step{break-inside:avoid-page;border:0;padding:0}"
    "section.step+section.step{break-before:page}"
    "div.exercise{break-inside:avoid;margin:.4em 0}.pair{flex-wrap:nowrap}"
    ".pair figure{flex:0 1 auto}.pair img{width:auto;max-height:3cm}"
    "pre{font-size:.72em}pre,code{background:none}p{margin:.3em 0}}\n";

// A text of course.json as HTML: escaped, and `...` (a command or an option) as <code>.
std::string prose(const std::string& text) {
  if (std::count(text.begin(), text.end(), '`') % 2 != 0)
    throw InputError("course " + courseFile() + ": an unpaired ` in: " + text);
  return htmlWithCode(text);
}

std::string head(const std::string& title) {
  return "<!doctype html>\n<html lang=en>\n<head>\n<meta charset=utf-8>\n<title>" +
         htmlEscape(title) + "</title>\n<style>\n" + kStyle + "</style>\n</head>\n<body>\n";
}

std::string footer(const std::string& command) {
  return "<footer><p>Made by <code>" + htmlEscape(command) + "</code>, shadowlab " +
         htmlEscape(buildCommit()) +
         ". Every picture's PNG text names the command that made it.</p></footer>\n";
}

// "</" would end a <script> element early: written "<\/" (the same JSON).
std::string scriptJson(const json& data) {
  std::string text;
  for (char c : data.dump(1)) {
    if (c == '/' && !text.empty() && text.back() == '<') text += '\\';
    text += c;
  }
  return text;
}

std::string commandsHtml(const CourseExercise& e, const std::string& labUrl) {
  std::string h = "<pre>" + htmlEscape(exerciseRenderCommand(e, true)) + "\n" +
                  htmlEscape(exerciseRenderCommand(e, false)) + "</pre>\n";
  if (e.lab)
    h += "<p><a class=lab href=\"" + htmlEscape(exerciseLabLink(e, labUrl)) +
         "\">open A and B in the lab</a> (<code>shadowlab serve</code> first)</p>\n";
  if (!e.gallery.empty())
    for (const GalleryEntry& g : galleryEntries())
      if (g.id == e.gallery)
        h += "<p>The gallery's artefact: <a class=gallery href=\"gallery/index.html#" +
             htmlEscape(g.id) + "\">" + htmlEscape(g.title) + "</a></p>\n";
  return h;
}

// An exercise's `shadowlab compare` run (measure "compare"): its command and its JSON line.
struct MeasuredCompare {
  std::string command;
  nlohmann::json line;
};
using MeasuredLines = std::map<std::string, MeasuredCompare>;  // by exercise id

MeasuredCompare runExerciseCompare(const CourseExercise& e) {
  std::vector<std::string> argv = {"shadowlab", "compare"};
  for (const std::string& a : exerciseCompareArguments(e)) argv.push_back(a);
  std::vector<char*> pointers;
  for (std::string& a : argv) pointers.push_back(a.data());
  const cli::Args args = cli::parse(int(pointers.size()), pointers.data());
  return {shellJoin(argv), runCompare(prepareCompare(args)).line};
}

// The numbers of a measured line that an answer may cite, as one sentence.
std::string measuredHtml(const MeasuredCompare& m) {
  const nlohmann::json& j = m.line;
  std::ostringstream h;
  h << "<p class=measured><b>Measured</b> when this page was written: <code>"
    << htmlEscape(m.command) << "</code> reports " << j.at("mismatching").get<long long>() << " of "
    << j.at("scored_pixels").get<long long>() << " scored pixels disagreeing ("
    << htmlEscape(j.at("metric").get<std::string>()) << " metric, RMSE "
    << j.at("rmse").get<double>() << "), and "
    << j.at("all_pixels").at("mismatching").get<long long>() << " of "
    << j.at("all_pixels").at("pixels").get<long long>()
    << " over all pixels; left out of the score: "
    << j.at("left_out").at("faces_away").get<long long>() << " facing away from the light, "
    << j.at("left_out").at("outside_light").get<long long>() << " outside its cone, "
    << j.at("left_out").at("no_receiver").get<long long>() << " with no receiver.</p>\n";
  return h.str();
}

// "Cascaded and parallel-split shadow maps" -> "cascaded-and-parallel-split-shadow-maps".
std::string anchorId(const std::string& text) {
  std::string id;
  for (unsigned char c : text) {
    if (std::isalnum(c))
      id += char(std::tolower(c));
    else if (!id.empty() && id.back() != '-')
      id += '-';
  }
  while (!id.empty() && id.back() == '-') id.pop_back();
  return id;
}

std::string scopeHtml(const Course& c, const std::string& command) {
  std::ostringstream h;
  h << head("shadowlab — " + c.title + ": what the course leaves out") << "<h1>"
    << htmlEscape(c.title) << ": what it leaves out</h1>\n<p>Back to <a href=\"index.html\">the "
    << "course</a>.</p>\n<p>" << prose(c.naming)
    << "</p>\n<p>The course follows five papers of "
       "2001-2007 and stops where they stop. These later or neighbouring topics are not "
       "covered; each line says what it is and where to read it.</p>\n<table class=scope>\n"
       "<tr><th>not covered</th><th>what it is</th><th>where to read it</th></tr>\n";
  for (const CourseScopeTopic& t : c.scope)
    h << "<tr id=\"scope-" << htmlEscape(anchorId(t.topic)) << "\"><td>" << htmlEscape(t.topic)
      << "</td><td>" << prose(t.what) << "</td><td>" << prose(t.read) << "</td></tr>\n";
  h << "</table>\n" << footer(command) << "</body>\n</html>\n";
  return h.str();
}

std::string indexHtml(const Course& c, const CourseSettings& s, const std::string& command) {
  std::ostringstream h;
  h << head("shadowlab — " + c.title) << "<h1>" << htmlEscape(c.title) << "</h1>\n<p>"
    << prose(c.intro) << "</p>\n<p>" << prose(c.order) << "</p>\n<p>" << prose(c.naming)
    << " <a href=\"" << kScopePage << "\">What the course leaves out, and where to read "
    << "it</a>.</p>\n<p>The <a href=\"gallery/index.html\">artefact gallery</a> "
    << "shows each classic artefact as a wrong/right pair; the exercises refer to it.</p>\n"
    << (s.report.href.empty() ? unlinkedFiguresHtml() : std::string())
    << "<nav class=toc><h2>The order</h2>\n<ol>\n";
  for (const CourseStep& st : c.steps)
    h << "<li><a href=\"#step-" << htmlEscape(st.id) << "\">"
      << htmlEscape(lessonTitle(st.techniques.front())) << "</a><br><span class=adds>adds "
      << prose(st.adds) << "</span></li>\n";
  h << "</ol>\n<p><a href=\"gallery/index.html\">The artefact gallery</a></p>\n</nav>\n";
  int n = 0;
  for (const CourseStep& st : c.steps) {
    ++n;
    h << "<section class=step id=\"step-" << htmlEscape(st.id) << "\">\n<h2>Step " << n << ": "
      << htmlEscape(lessonTitle(st.techniques.front())) << "</h2>\n<p class=adds>Adds "
      << prose(st.adds) << ".</p>\n<p>" << (st.techniques.size() > 1 ? "Lessons: " : "Lesson: ");
    for (size_t i = 0; i < st.techniques.size(); ++i)
      h << (i ? ", " : "") << "<a class=lesson href=\""
        << htmlEscape(lessonHref(s, st.techniques[i])) << "\">" << htmlEscape(st.techniques[i])
        << "</a>";
    h << "</p>\n";
    const std::vector<FigureLink> figures = figureLinksFor(st.techniques, s.report);
    if (!figures.empty())
      h << "<p class=figures>The report's figures of this step:</p>\n" << figureLinksHtml(figures);
    int k = 0;
    for (const CourseExercise& e : st.exercises) {
      h << "<div class=exercise id=\"ex-" << htmlEscape(e.id) << "\">\n<h3>Exercise " << n << "."
        << ++k << "</h3>\n<p><b>Try:</b> " << prose(e.tryText) << "</p>\n"
        << commandsHtml(e, s.labUrl) << "<p><b>Question:</b> " << htmlEscape(e.question)
        << "</p>\n</div>\n";
    }
    h << "</section>\n";
  }
  json data = json::array();
  for (const CourseStep& st : c.steps)
    for (const CourseExercise& e : st.exercises) {
      json ex = {{"id", e.id}, {"step", st.id}, {"lab", e.lab}};
      for (bool a : {true, false}) {
        json args = json::array();
        for (const std::string& x : exerciseRenderArguments(e, a)) args.push_back(x);
        ex[a ? "a" : "b"] = {{"technique", a ? e.pair.wrongTechnique : e.pair.rightTechnique},
                             {"arguments", args},
                             {"command", exerciseRenderCommand(e, a)}};
      }
      if (e.lab) ex["lab_link"] = exerciseLabLink(e, s.labUrl);
      data.push_back(ex);
    }
  h << footer(command) << "<script type=\"application/json\" id=course-data>\n"
    << scriptJson(data) << "\n</script>\n</body>\n</html>\n";
  return h.str();
}

std::string teacherHtml(const Course& c, const CourseSettings& s, const MeasuredLines& measured,
                        const std::string& command) {
  std::ostringstream h;
  h << head("shadowlab — " + c.title + ": answers") << "<h1>" << htmlEscape(c.title)
    << ": the teacher's page</h1>\n<p>The answers to the exercises of <a href=\"index.html\">the "
       "course</a>, beside the pictures each pair of commands makes (rendered by shadowlab with "
       "exactly those commands when this page was written).</p>\n";
  int n = 0;
  for (const CourseStep& st : c.steps) {
    ++n;
    h << "<section class=step id=\"step-" << htmlEscape(st.id) << "\">\n<h2>Step " << n << ": "
      << htmlEscape(lessonTitle(st.techniques.front())) << "</h2>\n";
    int k = 0;
    for (const CourseExercise& e : st.exercises) {
      h << "<div class=exercise id=\"ex-" << htmlEscape(e.id) << "\">\n<h3><a href=\"index.html#ex-"
        << htmlEscape(e.id) << "\">Exercise " << n << "." << ++k
        << "</a></h3>\n<p><b>Question:</b> " << htmlEscape(e.question)
        << "</p>\n<p class=answer><b>Answer:</b> " << htmlEscape(e.answer) << "</p>\n";
      if (const auto m = measured.find(e.id); m != measured.end()) h << measuredHtml(m->second);
      h << "<div class=pair>\n";
      for (bool a : {true, false}) {
        const std::vector<RenderOption>& own = a ? e.pair.wrong : e.pair.right;
        std::string label =
            (a ? "A: " : "B: ") + (a ? e.pair.wrongTechnique : e.pair.rightTechnique);
        for (const auto& [key, value] : own) label += " --" + key + " " + value;
        h << "<figure><img src=\"" << kTeacherDir << "/" << htmlEscape(pictureName(e, a))
          << "\" width=" << e.pair.width << " height=" << e.pair.height << " alt=\""
          << htmlEscape(label) << "\"><figcaption>" << htmlEscape(label)
          << "</figcaption></figure>\n";
      }
      h << "</div>\n" << commandsHtml(e, s.labUrl) << "</div>\n";
    }
    h << "</section>\n";
  }
  h << teach::gradedExercisesTeacherHtml(s.progress);
  h << footer(command) << "</body>\n</html>\n";
  return h.str();
}

}  // namespace

Course loadCourse() {
  const std::string file = courseFile();
  std::ifstream in(file);
  if (!in) throw InputError("cannot read the course " + file);
  try {
    const json doc = json::parse(in);
    Course c;
    c.title = doc.at("title").get<std::string>();
    c.intro = doc.at("intro").get<std::string>();
    c.order = doc.at("order").get<std::string>();
    c.naming = doc.at("naming").get<std::string>();
    for (const json& t : doc.at("scope"))
      c.scope.push_back({t.at("topic").get<std::string>(), t.at("what").get<std::string>(),
                         t.at("read").get<std::string>()});
    const std::string size = doc.at("size").get<std::string>();
    for (const json& s : doc.at("steps")) {
      CourseStep st;
      st.id = s.at("id").get<std::string>();
      st.techniques = s.at("techniques").get<std::vector<std::string>>();
      st.adds = s.at("adds").get<std::string>();
      for (const json& e : s.at("exercises")) st.exercises.push_back(exerciseFrom(e, size));
      if (st.techniques.empty())
        throw InputError("course " + file + ": step " + st.id + " has no technique");
      if (int(st.exercises.size()) < kMinExercises || int(st.exercises.size()) > kMaxExercises)
        throw InputError("course " + file + ": step " + st.id + " has " +
                         std::to_string(st.exercises.size()) + " exercises, not 2 or 3");
      c.steps.push_back(std::move(st));
    }
    return c;
  } catch (const json::exception& e) {
    throw InputError("course " + file + ": " + e.what());
  }
}

std::vector<std::string> exerciseRenderArguments(const CourseExercise& e, bool sideA) {
  return galleryRenderArguments(e.pair, sideA);
}

std::string exerciseRenderCommand(const CourseExercise& e, bool sideA) {
  std::vector<std::string> argv = {"shadowlab", "render"};
  for (const std::string& a : exerciseRenderArguments(e, sideA)) argv.push_back(a);
  argv.insert(argv.end(), {"--out", pictureName(e, sideA)});
  return shellJoin(argv);
}

std::vector<std::string> exerciseCompareArguments(const CourseExercise& e) {
  const GalleryEntry& p = e.pair;
  std::vector<std::string> a = {"--scene", p.scene, "--size",
                                std::to_string(p.width) + "x" + std::to_string(p.height)};
  for (const auto& [k, v] : p.common) a.insert(a.end(), {"--" + k, v});
  a.insert(a.end(), {"--a", p.wrongTechnique, "--b", p.rightTechnique});
  for (bool sideA : {true, false})
    for (const auto& [k, v] : sideA ? p.wrong : p.right) {
      if (k != "param")
        throw InputError("course " + courseFile() + ": exercise " + e.id +
                         " measures with "
                         "compare, which cannot set --" +
                         k + " for one side only");
      a.insert(a.end(), {sideA ? "--a-param" : "--b-param", v});
    }
  return a;
}

std::string exerciseLabLink(const CourseExercise& e, const std::string& labUrl) {
  if (!e.lab) throw InputError("exercise " + e.id + " has no lab link");
  // The exercises open on the whole frame: the lab's default view, so its zoom and centre
  // are left out of the link (as the lab leaves them out of its own address).
  std::string query = galleryLabQuery(e.pair);
  const std::string wholeFrame = "&zoom=1&center=0.5,0.5";
  if (query.size() > wholeFrame.size() &&
      query.compare(query.size() - wholeFrame.size(), wholeFrame.size(), wholeFrame) == 0)
    query.erase(query.size() - wholeFrame.size());
  return labUrl + "?" + query;
}

CourseSummary writeCourse(const std::string& dir, const CourseSettings& settings) {
  const Course course = loadCourse();
  CourseSummary summary;
  std::vector<std::string> techniques;
  for (const CourseStep& st : course.steps) {
    ++summary.steps;
    for (const std::string& t : st.techniques) techniques.push_back(t);
    summary.exercises += int(st.exercises.size());
  }
  checkDirectoryCreatable("--out", dir);
  // The exercises' pictures first: a command that does not parse or render fails the run
  // before anything is written.
  struct Rendered {
    std::string file;
    Image image;
    Provenance provenance;
  };
  std::vector<Rendered> pictures;
  std::map<std::vector<std::string>, size_t> made;  // equal commands (but --out) render once
  for (const CourseStep& st : course.steps)
    for (const CourseExercise& e : st.exercises)
      for (bool a : {true, false}) {
        const std::vector<std::string> arguments = exerciseRenderArguments(e, a);
        const Provenance provenance{exerciseRenderCommand(e, a),
                                    json{{"arguments", arguments}}.dump()};
        const auto same = made.find(arguments);
        if (same != made.end()) {
          pictures.push_back({pictureName(e, a), pictures[same->second].image, provenance});
          continue;
        }
        if (settings.progress) std::cerr << "[course] " << e.id << (a ? " A" : " B") << std::endl;
        made[arguments] = pictures.size();
        pictures.push_back({pictureName(e, a), toRgb(renderGalleryPicture(e.pair, a)), provenance});
      }
  summary.pictures = int(pictures.size());
  MeasuredLines measured;
  for (const CourseStep& st : course.steps)
    for (const CourseExercise& e : st.exercises)
      if (e.measure == kMeasureCompare) {
        if (settings.progress) std::cerr << "[course] " << e.id << " compare" << std::endl;
        measured[e.id] = runExerciseCompare(e);
      }
  // DIR itself is made now: an OutputSet whose destination's parent is missing renames its
  // temporary over the first missing folder, which would replace the gallery and the lessons.
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError("--out: cannot create " + dir + ": " + ec.message());
  OutputSet outputs;
  const std::string teacherDir =
      outputs.addDirectory("--out", (fs::path(dir) / kTeacherDir).string());
  if (settings.progress) std::cerr << "[course] the artefact gallery" << std::endl;
  summary.artefacts = writeGallery(dir, settings.labUrl);
  if (settings.writeLessons)
    for (const LessonLink& l : writeLessons((fs::path(dir) / "lessons").string(), techniques,
                                            settings.lessons, settings.progress))
      if (!l.error.empty()) summary.lessonErrors.push_back(l.technique + ": " + l.error);
  outputs.beginWriting();
  for (const Rendered& r : pictures)
    writePng((fs::path(teacherDir) / r.file).string(), r.image, 8, r.provenance);
  outputs.commit();
  const std::string command = commandLine();
  const std::string index = indexHtml(course, settings, command);
  const std::string teacher = teacherHtml(course, settings, measured, command);
  const std::string scope = scopeHtml(course, command);
  writeFileAtomically((fs::path(dir) / "teacher.html").string(),
                      [&](std::ostream& out) { out << teacher; });
  writeFileAtomically((fs::path(dir) / kScopePage).string(),
                      [&](std::ostream& out) { out << scope; });
  writeFileAtomically((fs::path(dir) / "index.html").string(),
                      [&](std::ostream& out) { out << index; });
  return summary;
}

std::string writeCourseForReport(const std::string& outDir, const ReportLinks& report,
                                 bool progress) {
  const auto start = std::chrono::steady_clock::now();
  CourseSettings s;
  s.writeLessons = false;
  s.lessonsHref = "../lessons/";
  s.report = report;
  std::ostringstream h;
  h << "<section id=course><h2>The course</h2>\n";
  try {
    const CourseSummary summary = writeCourse((fs::path(outDir) / "course").string(), s);
    const long seconds = std::lround(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (progress)
      std::cerr << "[course] " << summary.exercises << " exercises (" << summary.pictures
                << " pictures) and the gallery (" << summary.artefacts << " artefacts) in "
                << seconds << " s" << std::endl;
    h << "<p><a href=\"course/index.html\">The lessons in a teaching order</a> (" << summary.steps
      << " steps, what each adds, " << summary.exercises
      << " exercises; <code>shadowlab course --out DIR</code>), <a href=\"course/teacher.html\">"
         "the teacher's page</a> (answers and expected pictures) and <a "
         "href=\"course/gallery/index.html\">the artefact gallery</a>.</p>\n";
  } catch (const std::exception& e) {
    if (progress) std::cerr << "        course not written: " << e.what() << std::endl;
    h << "<p class=bad>The course could not be written: " << htmlEscape(e.what()) << "</p>\n";
  }
  h << "</section>\n";
  return h.str();
}

int runCourseCommand(const cli::Args& args) {
  const std::string out = args.required("out");
  CourseSettings s;
  s.labUrl = args.value("lab").value_or(kDefaultLabUrl);
  if (s.labUrl.rfind("http://", 0) != 0 && s.labUrl.rfind("https://", 0) != 0)
    throw InputError("--lab must be an http:// or https:// address, got '" + s.labUrl + "'");
  s.report.figures = figureRefs();  // no report beside the course: its steps name the figures
  s.lessons =
      LessonSettings{kDefaultScene, kLessonWidth, kLessonHeight, kLessonShadowMap, s.report};
  s.progress = !args.has("no-progress");
  const auto start = std::chrono::steady_clock::now();
  const CourseSummary summary = writeCourse(out, s);
  for (const std::string& e : summary.lessonErrors)
    std::cerr << "shadowlab: lesson not written: " << e << "\n";
  std::cout << "wrote " << (fs::path(out) / "index.html").string() << " and teacher.html ("
            << summary.steps << " steps, " << summary.exercises << " exercises, "
            << summary.pictures << " pictures, " << summary.artefacts << " artefacts, "
            << std::lround(
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count())
            << " s)" << std::endl;
  return summary.lessonErrors.empty() ? 0 : 3;
}

}  // namespace sl::figures
