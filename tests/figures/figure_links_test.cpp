// tests/figures/figure_links_test.cpp — the links between the lessons and the report's figures
// (teach/lesson.h figureShows and figureLinksFor, figures/report.h reportLinksTo and the report's
// "Lessons:" line): every figure of the list is linked from at least one lesson; a figure's
// entry in the report links back every lesson that links it, and only those; a report of an
// --only run is linked only for the figures it holds, a --set run at its version's article; a
// page with no report beside it names its figures without a link.
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

#include "figures/figure_spec.h"
#include "figures/report.h"
#include "registry/registry.h"
#include "teach/lesson.h"

using namespace sl;
using namespace sl::figures;
namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<const FigureSpec*> everyFigure() {
  std::vector<const FigureSpec*> out;
  for (const FigureSpec& f : figureList()) out.push_back(&f);
  return out;
}

const FigureSpec& figureById(const std::string& id) {
  for (const FigureSpec& f : figureList())
    if (f.id == id) return f;
  throw std::runtime_error("no figure " + id);
}

// The ids of the report's figures each lesson links (teach/lesson.h figureLinksFor), as a lesson
// beside the report at OUT/lessons/T/ links them: "../../report.html#ID".
std::map<std::string, std::set<std::string>> lessonLinks(const ReportLinks& report) {
  std::map<std::string, std::set<std::string>> out;
  for (const Technique& t : allTechniques())
    for (const FigureLink& l : figureLinksFor({t.name}, report)) {
      const std::string prefix = report.href + "#";
      if (l.href.rfind(prefix, 0) == 0) out[t.name].insert(l.href.substr(prefix.size()));
    }
  return out;
}

}  // namespace

// Each figure shows a technique that has a lesson: none is left without a lesson linking it
// (the figures issue 39 found unlinked among them).
TEST(FigureLinks, EveryFigureIsLinkedFromALesson) {
  const std::map<std::string, std::set<std::string>> links =
      lessonLinks(reportLinksTo("../../report.html", everyFigure()));
  std::set<std::string> linked;
  for (const auto& [technique, ids] : links) linked.insert(ids.begin(), ids.end());
  for (const FigureSpec& f : figureList()) {
    EXPECT_FALSE(figureTechniques(f).empty()) << f.id << " names no technique";
    EXPECT_TRUE(linked.count(f.id)) << f.id << " is linked from no lesson";
  }
  for (const char* id : {"brabec-fig3-packing", "brabec-fig5-packing", "csm-fig3", "csm-fig6",
                         "csm-fig9", "chan-2-4", "chan-2-5", "chan-3-5", "chan-4-4", "everitt-fig2",
                         "everitt-fig4", "everitt-fig5", "everitt-fig6"})
    EXPECT_TRUE(linked.count(id)) << id;
  // A figure's techniques are its panels' (and, where no panel renders one, its `lessons`):
  // Brabec Fig. 5's buffer strip is fast PCF's, both of whose lessons link it.
  EXPECT_TRUE(links.at("legacy.fast-pcf").count("brabec-fig5-packing"));
  EXPECT_TRUE(links.at("modern.fast-pcf").count("brabec-fig5-packing"));
  EXPECT_FALSE(links.at("legacy.pcf").count("brabec-fig5-packing"));
  EXPECT_TRUE(links.at("modern.csm").count("csm-fig3")) << "a chart without panels";
}

// The report written with every figure and a lesson per technique: each figure's article links
// exactly the lessons that link it, and at least one.
TEST(FigureLinks, TheReportLinksBackEveryLessonThatLinksAFigure) {
  const fs::path out = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "figure-links" / "all";
  fs::remove_all(out);
  fs::create_directories(out);
  std::vector<FigureResult> results;
  for (const FigureSpec& f : figureList()) results.push_back(FigureResult{f, {}, 0, "", ""});
  ReportInfo info;
  for (const Technique& t : allTechniques())
    info.lessons.push_back({t.name, t.name + "/index.html", t.name, ""});
  writeReport(out.string(), results, info);
  const std::string html = slurp(out / "report.html");

  std::map<std::string, std::set<std::string>> back;  // figure -> the lessons its article links
  static const std::regex kArticle(R"re(<article id="([^"]+)">([\s\S]*?)</article>)re");
  static const std::regex kLesson(R"re(<a class=lesson href="lessons/([^/"]+)/index.html")re");
  for (auto a = std::sregex_iterator(html.begin(), html.end(), kArticle);
       a != std::sregex_iterator(); ++a) {
    const std::string body = (*a)[2].str();
    std::set<std::string>& lessons = back[(*a)[1].str()];
    for (auto l = std::sregex_iterator(body.begin(), body.end(), kLesson);
         l != std::sregex_iterator(); ++l)
      lessons.insert((*l)[1].str());
  }
  ASSERT_EQ(back.size(), figureList().size());
  for (const auto& [id, lessons] : back) EXPECT_FALSE(lessons.empty()) << id << " links no lesson";

  std::map<std::string, std::set<std::string>> forth;  // figure -> the lessons that link it
  for (const auto& [technique, ids] :
       lessonLinks(reportLinksTo("../../report.html", everyFigure())))
    for (const std::string& id : ids) forth[id].insert(technique);
  for (const auto& [id, lessons] : back)
    EXPECT_EQ(lessons, forth[id]) << id << ": the lessons its article links, against the ones "
                                  << "that link it";
}

// An --only run: the lessons beside its report link the figures it holds and name the others;
// a --set run's figure is linked at its version's article.
TEST(FigureLinks, AReportOfSomeFiguresLinksOnlyThose) {
  const std::vector<const FigureSpec*> some = {&figureById("brabec-fig7")};
  const std::vector<FigureLink> pcf = figureLinksFor({"legacy.pcf"}, reportLinksTo("r.html", some));
  std::map<std::string, std::string> href;
  for (const FigureLink& l : pcf) href[l.id] = l.href;
  EXPECT_EQ(href.at("brabec-fig7"), "r.html#brabec-fig7");
  EXPECT_EQ(href.at("brabec-fig3-packing"), "") << "not in the report: named, not linked";
  const std::string page = figureLinksHtml(pcf);
  EXPECT_NE(page.find("<a href=\"r.html#brabec-fig7\">"), std::string::npos) << page;
  EXPECT_EQ(page.find("href=\"r.html#brabec-fig3-packing\""), std::string::npos) << page;
  EXPECT_NE(page.find("<code>brabec-fig3-packing</code>"), std::string::npos) << page;

  FigureSpec remade = figureById("brabec-fig7");
  remade.sourceId = remade.id;
  remade.id = "brabec-fig7--shadow-map-1024";
  int remadeLinks = 0;
  for (const FigureLink& l : figureLinksFor({"legacy.pcf"}, reportLinksTo("r.html", {&remade}))) {
    if (l.id != "brabec-fig7") continue;
    EXPECT_EQ(l.href, "r.html#brabec-fig7--shadow-map-1024");
    ++remadeLinks;
  }
  EXPECT_EQ(remadeLinks, 1);

  ReportLinks none;  // `shadowlab lesson`: every figure named, none linked
  none.figures = figureRefs();
  const std::vector<FigureLink> named = figureLinksFor({"legacy.pcf"}, none);
  EXPECT_FALSE(named.empty());
  for (const FigureLink& l : named) EXPECT_EQ(l.href, "") << l.id;
}
