// tests/figures/course_test.cpp — the course (figures/course.h): its order names every technique
// once and only techniques that have a lesson; every exercise's `shadowlab render` commands parse
// with the CLI's parser and name options their techniques read; a lab exercise's link uses only
// the lab's URL keys (docs/lab.md), and an exercise without one has an option the lab lacks;
// writeCourse writes every page, picture, lesson and the gallery, and every relative link and
// anchor of the two pages resolves.
#include "figures/course.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/base/errors.h"
#include "core/base/html.h"
#include "core/scene/scene_library.h"
#include "figures/report.h"
#include "registry/cli.h"
#include "registry/commands.h"
#include "registry/registry.h"
#include "teach/exercise.h"

using namespace sl;
using namespace sl::figures;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> splitWords(const std::string& command) {
  std::vector<std::string> words;
  std::istringstream in(command);
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

cli::Args parseCommand(const std::string& command) {
  std::vector<std::string> words = splitWords(command);
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  return cli::parse(int(argv.size()), argv.data());
}

// The query keys lab/web/lab.js readUrlState knows (docs/lab.md "Links").
const std::set<std::string> kLabKeys = {"scene",       "size",           "view",         "a",
                                        "b",           "light-position", "orbit",        "zoom",
                                        "center",      "wipe",           "a-shadow-map", "a-filter",
                                        "a-precision", "a-param",        "b-shadow-map", "b-filter",
                                        "b-precision", "b-param"};

std::vector<std::string> queryKeys(const std::string& link) {
  const std::string query = link.substr(link.find('?') + 1);
  std::vector<std::string> keys;
  std::istringstream in(query);
  for (std::string item; std::getline(in, item, '&');)
    keys.push_back(item.substr(0, item.find('=')));
  return keys;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> matches(const std::string& html, const std::regex& re) {
  std::vector<std::string> out;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), re); it != std::sregex_iterator();
       ++it)
    out.push_back((*it)[1]);
  return out;
}

// Every relative href and src of `page` names an existing file, and every "#anchor" an id of
// the page it points to.
void expectLinksResolve(const fs::path& page) {
  const std::string html = slurp(page);
  const std::regex link(R"re((?:href|src)="([^"]*)")re");
  const std::regex id(R"re(\bid="?([A-Za-z0-9._-]+))re");
  int checked = 0;
  for (const std::string& href : matches(html, link)) {
    if (href.rfind("http://", 0) == 0 || href.rfind("https://", 0) == 0) continue;
    const std::string file = href.substr(0, href.find('#'));
    const fs::path target = file.empty() ? page : page.parent_path() / file;
    EXPECT_TRUE(fs::is_regular_file(target)) << page << ": " << href;
    if (href.find('#') != std::string::npos && fs::is_regular_file(target)) {
      const std::vector<std::string> ids = matches(slurp(target), id);
      const std::string anchor = href.substr(href.find('#') + 1);
      EXPECT_NE(std::find(ids.begin(), ids.end(), anchor), ids.end()) << page << ": " << href;
    }
    ++checked;
  }
  EXPECT_GT(checked, 0) << page;
}

}  // namespace

TEST(Course, OrderNamesEveryTechniqueOnceEachWithALesson) {
  const Course course = loadCourse();
  std::map<std::string, int> seen;
  for (const CourseStep& st : course.steps) {
    ASSERT_FALSE(st.techniques.empty()) << st.id;
    EXPECT_FALSE(st.adds.empty()) << st.id;
    // A step is one lesson text: its techniques share the title (lessonTitle throws without one).
    const std::string title = lessonTitle(st.techniques.front());
    for (const std::string& t : st.techniques) {
      ++seen[t];
      EXPECT_NO_THROW(findTechnique(t)) << t;
      EXPECT_EQ(lessonTitle(t), title) << st.id << ": " << t;
    }
  }
  for (const Technique& t : allTechniques()) EXPECT_EQ(seen[t.name], 1) << t.name;
  EXPECT_EQ(seen.size(), allTechniques().size());
  // The teaching order: hardware shadow maps first, the ray-traced references last.
  EXPECT_EQ(course.steps.front().techniques.front(), "legacy.hw");
  EXPECT_EQ(course.steps.back().techniques.front(), "reference.soft");
}

TEST(Course, EveryExerciseCommandParsesAndNamesOptionsItsTechniqueReads) {
  const Course course = loadCourse();
  std::set<std::string> ids;
  int exercises = 0;
  for (const CourseStep& st : course.steps) {
    EXPECT_GE(st.exercises.size(), 2u) << st.id;
    EXPECT_LE(st.exercises.size(), 3u) << st.id;
    for (const CourseExercise& e : st.exercises) {
      ++exercises;
      EXPECT_TRUE(ids.insert(e.id).second) << "two exercises named " << e.id;
      EXPECT_FALSE(e.question.empty() || e.answer.empty() || e.tryText.empty()) << e.id;
      if (!e.gallery.empty()) {  // names an entry of the artefact gallery
        bool found = false;
        for (const GalleryEntry& g : galleryEntries()) found = found || g.id == e.gallery;
        EXPECT_TRUE(found) << e.id << ": no gallery entry " << e.gallery;
      }
      for (bool a : {true, false}) {
        const std::string command = exerciseRenderCommand(e, a);
        SCOPED_TRACE(command);
        const cli::Args args = parseCommand(command);
        EXPECT_EQ(args.command, "render");
        EXPECT_EQ(args.required("technique"), a ? e.pair.wrongTechnique : e.pair.rightTechnique);
        EXPECT_EQ(args.required("scene"), e.pair.scene);
        EXPECT_NO_THROW(loadScene(e.pair.scene));
        const Technique& t = findTechnique(args.required("technique"));
        EXPECT_NO_THROW(rejectIgnoredOptions(t, cli::givenCommonOptions(args)));
        EXPECT_NO_THROW(cli::renderParams(args));
        EXPECT_NO_THROW(cli::sceneAdjustments(args));
      }
      if (e.lab) {
        const std::string link = exerciseLabLink(e, kDefaultLabUrl);
        EXPECT_EQ(link.rfind(kDefaultLabUrl, 0), 0u) << link;
        for (const std::string& k : queryKeys(link))
          EXPECT_TRUE(kLabKeys.count(k)) << e.id << ": " << k;
      } else {
        // No lab link only because an option has no key in the lab's URL.
        EXPECT_THROW(exerciseLabLink(e, kDefaultLabUrl), InputError);
        bool lacking = false;
        for (const auto* list : {&e.pair.common, &e.pair.wrong, &e.pair.right})
          for (const auto& [key, value] : *list)
            lacking = lacking || (!kLabKeys.count(key) && !kLabKeys.count("a-" + key));
        EXPECT_TRUE(lacking) << e.id << " could have a lab link";
      }
    }
  }
  EXPECT_GE(exercises, 2 * int(course.steps.size()));
}

// The main job's course (writeCourseForReport): OUT/course/ over the lessons in OUT/lessons/,
// written here small (their size does not change what is linked).
TEST(Course, WritesEveryPagePictureAndTheGalleryOverTheMainJobsLessons) {
  const fs::path out = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "course" / "main-job";
  fs::remove_all(out);
  const Course course = loadCourse();
  std::vector<std::string> techniques;
  for (const CourseStep& st : course.steps)
    techniques.insert(techniques.end(), st.techniques.begin(), st.techniques.end());
  for (const LessonLink& l : writeLessons((out / "lessons").string(), techniques,
                                          LessonSettings{"brabec", 160, 120, 128, {}}, false))
    EXPECT_TRUE(l.error.empty()) << l.technique << ": " << l.error;
  // The report beside the course (its figures without panels: what is checked is the links).
  std::vector<const FigureSpec*> figures;
  std::vector<FigureResult> results;
  for (const FigureSpec& f : figureList()) {
    figures.push_back(&f);
    results.push_back(FigureResult{f, {}, 0, "", ""});
  }
  writeReport(out.string(), results, ReportInfo{});
  const std::string section =
      writeCourseForReport(out.string(), reportLinksTo("../report.html", figures), false);
  for (const char* href :
       {"course/index.html", "course/teacher.html", "course/gallery/index.html"}) {
    EXPECT_NE(section.find(std::string("href=\"") + href + "\""), std::string::npos) << section;
    EXPECT_TRUE(fs::is_regular_file(out / href)) << href;
  }
  EXPECT_EQ(section.find("could not"), std::string::npos) << section;
  const fs::path dir = out / "course";
  for (const CourseStep& st : course.steps)
    for (const CourseExercise& e : st.exercises)
      for (const char* side : {"-a.png", "-b.png"})
        EXPECT_TRUE(fs::is_regular_file(dir / "teacher" / (e.id + side))) << e.id << side;
  const std::string index = slurp(dir / "index.html"), teacher = slurp(dir / "teacher.html");
  for (const std::string* page : {&index, &teacher}) {
    EXPECT_NE(page->find("@media print"), std::string::npos);
    EXPECT_NE(page->find("Made by <code>"), std::string::npos);
  }
  for (const CourseStep& st : course.steps) {
    for (const std::string& t : st.techniques)
      EXPECT_NE(index.find("href=\"../lessons/" + t + "/index.html\""), std::string::npos) << t;
    // The step links the report's figures of its lessons (teach/lesson.h figureLinksFor).
    const std::string step = index.substr(index.find("id=\"step-" + st.id + "\""));
    const std::string own = step.substr(0, step.find("<section", 1));
    for (const FigureLink& l :
         figureLinksFor(st.techniques, reportLinksTo("../report.html", figures)))
      EXPECT_NE(own.find("<a href=\"../report.html#" + l.id + "\">"), std::string::npos)
          << st.id << ": " << l.id;
    for (const CourseExercise& e : st.exercises) {
      EXPECT_NE(index.find(htmlEscape(e.question.substr(0, 40))), std::string::npos) << e.id;
      EXPECT_EQ(index.find(htmlEscape(e.answer.substr(0, 60))), std::string::npos)
          << e.id << ": answer on the students' page";
      EXPECT_NE(teacher.find(htmlEscape(e.answer.substr(0, 40))), std::string::npos) << e.id;
    }
  }
  // The scope page: linked from the students' page, one row per topic the course leaves out.
  EXPECT_NE(index.find("href=\"scope.html\""), std::string::npos);
  const std::string scope = slurp(dir / "scope.html");
  for (const CourseScopeTopic& t : course.scope)
    EXPECT_NE(scope.find(htmlEscape(t.topic)), std::string::npos) << t.topic;
  // A measured exercise's answer stands beside the compare line run for the page.
  for (const CourseStep& st : course.steps)
    for (const CourseExercise& e : st.exercises)
      if (!e.measure.empty()) {
        std::vector<std::string> argv = {"shadowlab", "compare"};
        for (const std::string& a : exerciseCompareArguments(e)) argv.push_back(a);
        std::string command;
        for (const std::string& a : argv) command += (command.empty() ? "" : " ") + a;
        EXPECT_NE(teacher.find("<p class=measured><b>Measured</b> when this page was written: "
                               "<code>" +
                               htmlEscape(command) + "</code>"),
                  std::string::npos)
            << e.id;
      }
  // The graded exercises (teach/exercise_page.h): each on the teacher's page with its model
  // answer graded PASS when the page was written (a failing model answer is shown as an error).
  for (const sl::teach::Exercise& e : sl::teach::exercises()) {
    const size_t at = teacher.find("<div class=exercise id=\"graded-" + e.id + "\">");
    ASSERT_NE(at, std::string::npos) << e.id;
    const std::string block = teacher.substr(at, teacher.find("</div>", at) - at);
    EXPECT_NE(block.find("<b>PASS</b>: "), std::string::npos) << e.id << ": " << block;
    EXPECT_EQ(block.find("class=error"), std::string::npos) << e.id << ": " << block;
  }
  // Every relative link (the lessons' included) and anchor resolves.
  expectLinksResolve(dir / "index.html");
  expectLinksResolve(dir / "teacher.html");
  expectLinksResolve(dir / "scope.html");
}

// The course leaves out what a 2026 reader will ask about, and says where to read it; "CSM"
// names both meanings.
TEST(Course, ScopeNamesWhatItLeavesOutAndBothMeaningsOfCsm) {
  const Course course = loadCourse();
  std::string topics;
  for (const CourseScopeTopic& t : course.scope) {
    EXPECT_FALSE(t.what.empty()) << t.topic;
    EXPECT_FALSE(t.read.empty()) << t.topic;
    topics += t.topic + "\n";
  }
  // ESM, EVSM, MSM, PCSS and cascaded maps are in the course (issue #41), so no longer out of
  // scope.
  for (const char* topic : {"Perspective", "light-space", "Omnidirectional", "Normal-offset"})
    EXPECT_NE(topics.find(topic), std::string::npos) << topic;
  EXPECT_NE(course.naming.find("convolution shadow maps"), std::string::npos);
  EXPECT_NE(course.naming.find("cascaded shadow maps"), std::string::npos);
  EXPECT_NE(course.order.find("references come last"), std::string::npos);
  for (const char* covered : {"PCSS", "ESM", "EVSM", "MSM", "Cascaded", "parallel-split"})
    EXPECT_EQ(topics.find(covered), std::string::npos) << covered << " is in the course";
}

// Exercise 14.2's answer says that shadow volumes and the ray-traced hard shadow disagree on no
// scored pixel, and that the pixels that differ are among those the metric leaves out: the
// compare the teacher's page runs must say so.
TEST(Course, VolumesAgainstRaysAnswerHoldsOnItsCompareRun) {
  const Course course = loadCourse();
  int measured = 0;
  for (const CourseStep& st : course.steps)
    for (const CourseExercise& e : st.exercises) {
      if (e.id != "volumes-against-rays") continue;
      ASSERT_EQ(e.measure, "compare");
      std::vector<std::string> argv = {"shadowlab", "compare"};
      for (const std::string& a : exerciseCompareArguments(e)) argv.push_back(a);
      std::vector<char*> pointers;
      for (std::string& a : argv) pointers.push_back(a.data());
      const nlohmann::json line =
          runCompare(prepareCompare(cli::parse(int(pointers.size()), pointers.data()))).line;
      EXPECT_EQ(line.at("mismatching").get<long long>(), 0) << line.dump();
      const long long all = line.at("all_pixels").at("mismatching").get<long long>();
      const long long leftOut = line.at("all_pixels").at("pixels").get<long long>() -
                                line.at("scored_pixels").get<long long>();
      // Not vacuous: most of the frame is scored, and the differing pixels fit in the rest.
      EXPECT_GT(line.at("scored_pixels").get<long long>(), leftOut) << line.dump();
      EXPECT_LE(all, leftOut) << line.dump();
      ++measured;
    }
  EXPECT_EQ(measured, 1);
}

TEST(Course, MeasuredCompareRefusesAnOptionForOneSideOnly) {
  const CourseExercise e = [] {
    Course c = loadCourse();
    CourseExercise x = c.steps.front().exercises.front();
    x.pair.wrong = {{"shadow-map", "64"}};
    return x;
  }();
  // A side option compare cannot set for one side only is an input error, not a silent drop.
  EXPECT_THROW(exerciseCompareArguments(e), InputError);
}
