// `shadowlab lesson TECHNIQUE --out DIR` (teach/lesson.h): one self-contained
// page per technique with the paper's idea, every pass, the twin, legacy against modern and the
// known departures; bad input is one line and exit 2 with nothing written.
#include "teach/lesson.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "command_util.h"
#include "core/base/html.h"
#include "core/gl/shaders.h"
#include "registry/registry.h"

namespace sl {
namespace {
namespace fs = std::filesystem;
using test::slurp;

// Small renders: the page's content does not depend on the size, and the suite stays fast.
const char* kSmall = " --size 160x120 --shadow-map 128";

std::string lessonArgs(const std::string& technique, const fs::path& out) {
  return "lesson " + technique + " --out " + out.string() + kSmall;
}

// Every src="..." of a page.
std::vector<std::string> imageSources(const std::string& html) {
  static const std::regex kImg(R"re(<img src="([^"]+)")re");
  std::vector<std::string> out;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), kImg); it != std::sregex_iterator();
       ++it)
    out.push_back((*it)[1].str());
  return out;
}

size_t count(const std::string& html, const std::string& what) {
  size_t n = 0;
  for (size_t at = html.find(what); at != std::string::npos; at = html.find(what, at + 1)) ++n;
  return n;
}

// assets/lessons/*.json names every technique of the registry exactly once, with a title.
TEST(Lesson, EveryTechniqueHasOneLessonText) {
  const std::vector<std::string> missing = figures::techniquesWithoutLesson();
  EXPECT_TRUE(missing.empty()) << "no entry in assets/lessons/*.json for " << missing.front();
  for (const Technique& t : allTechniques()) {
    std::string title;
    EXPECT_NO_THROW(title = figures::lessonTitle(t.name)) << t.name;
    EXPECT_FALSE(title.empty()) << t.name;
  }
}

// The lesson a student following Brabec & Seidel §4 reads: the idea with Eq. (1) and Figs. 5-6,
// the legacy strip and the shader twin pass by pass, legacy against modern, the departures,
// and every picture beside the page.
TEST(Lesson, FastPcfTeachesBrabecSeidelSection4) {
  const fs::path dir = test::testDir("lesson", true) / "fast-pcf";
  const test::CommandResult r =
      test::runBinary(SHADOWLAB_BINARY, lessonArgs("legacy.fast-pcf", dir), dir.parent_path());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = slurp(dir / "index.html");
  for (const char* must :
       {"§4", "Eq. (1)", "Fig. 5", "Fig. 6", "(ds/2, dt/2)", "id=\"legacy.fast-pcf\"",
        "id=\"modern.fast-pcf\"", "id=\"compare\"", "fast-pcf 2x2 faithful 8-bit",
        "Why the images differ", "id=\"departures\"", "DEVIATION (Brabec",
        "shadowlab render --scene brabec --technique legacy.fast-pcf",
        "shadowlab render --scene brabec --technique modern.fast-pcf",
        "shadowlab lesson legacy.fast-pcf"})
    EXPECT_NE(html.find(must), std::string::npos) << "the lesson lacks " << must;
  // Every pass has a state card (recorded, or the visible "not recorded").
  EXPECT_GT(count(html, "<section class=\"pass\""), 4u);
  EXPECT_EQ(count(html, "<section class=\"pass\""), count(html, "<div class=\"state-card"));
  // Every picture is a file beside the page, linked relatively; no network.
  const std::vector<std::string> images = imageSources(html);
  EXPECT_GT(images.size(), 10u);
  for (const std::string& src : images) {
    EXPECT_EQ(src.find('/'), std::string::npos) << src;
    EXPECT_TRUE(fs::exists(dir / src)) << src;
  }
  EXPECT_EQ(html.find("http://"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "diff-mask.png"));
  EXPECT_TRUE(fs::exists(dir / "diff-image.png"));
  // Nothing but the page and its pictures: the folder is a lesson a second run may replace.
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_TRUE(e.path().extension() == ".png" || e.path().filename() == "index.html") << e.path();
  const test::CommandResult again =
      test::runBinary(SHADOWLAB_BINARY, lessonArgs("legacy.fast-pcf", dir), dir.parent_path());
  EXPECT_EQ(again.status, 0) << again.err;
}

// A technique without a twin shows its own passes and no comparison.
TEST(Lesson, TechniqueWithoutTwinShowsItsOwnPasses) {
  const fs::path dir = test::testDir("lesson", true) / "gems4";
  const test::CommandResult r =
      test::runBinary(SHADOWLAB_BINARY, lessonArgs("modern.gems4", dir), dir.parent_path());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = slurp(dir / "index.html");
  EXPECT_NE(html.find("Fig. 11-4"), std::string::npos);
  EXPECT_NE(html.find("id=\"modern.gems4\""), std::string::npos);
  EXPECT_EQ(html.find("id=\"compare\""), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "diff-mask.png"));
  EXPECT_GT(count(html, "<section class=\"pass\""), 0u);
}

TEST(Lesson, UnknownTechniqueIsOneLineExit2AndWritesNothing) {
  const fs::path base = test::testDir("lesson", true);
  const test::CommandResult r =
      test::runBinary(SHADOWLAB_BINARY, lessonArgs("legacy.nope", base / "out"), base);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("unknown technique 'legacy.nope'"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(base / "out"));
  const test::CommandResult none = test::runBinary(SHADOWLAB_BINARY, "lesson --out x", base);
  EXPECT_EQ(none.status, 2);
  EXPECT_NE(none.err.find("technique"), std::string::npos) << none.err;
}

// An existing folder holding anything but a previous lesson or dump is refused, untouched.
TEST(Lesson, RefusesAFolderWithOtherFiles) {
  const fs::path dir = test::testDir("lesson", true) / "mine";
  fs::create_directories(dir);
  { std::ofstream(dir / "notes.txt") << "mine"; }
  const test::CommandResult r =
      test::runBinary(SHADOWLAB_BINARY, lessonArgs("legacy.hw", dir), dir.parent_path());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(slurp(dir / "notes.txt"), "mine");
  EXPECT_FALSE(fs::exists(dir / "index.html"));
}

// Every pass of both strips shows the GL state the trace layer recorded (core/gl/gl_trace.h,
// passes.json "state") and the paper section its PassTimer declares.
TEST(Lesson, ShowsTheGlStateOfEveryPass) {
  const fs::path dir = test::testDir("lesson", true) / "fast-pcf";
  const test::CommandResult r =
      test::runBinary(SHADOWLAB_BINARY, lessonArgs("modern.fast-pcf", dir), dir.parent_path());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = slurp(dir / "index.html");
  EXPECT_EQ(html.find("state card: not recorded"), std::string::npos)
      << "a pass without its GL state card";
  EXPECT_EQ(html.find("paper section not recorded"), std::string::npos);
  // Brabec & Seidel §4's state: the Eq. (1) kernel, the colour table and the colour matrix.
  for (const char* line : {"GL_CONVOLUTION_2D", "3x3 kernel", "GL_COLOR_TABLE",
                           "colour matrix: load [0 0 0 0; 0 0 0 0; 0 0 0 0; 1 1 1 1]"})
    EXPECT_NE(html.find(line), std::string::npos) << "no " << line << " on the legacy cards";
}

// The modern twin's passes show the GLSL lines they run, exactly as the embedded shader has
// them, and link the legacy pass they replace (passes.json "glsl" and "replaces", from the
// `// @pass` markers of the shaders, which every modern technique's shaders carry).
TEST(Lesson, TwinPassesShowTheirGlslLinesAndTheLegacyPassTheyReplace) {
  bool markers = false;
  for (const auto& [name, text] : embeddedShaders())
    markers = markers || text.find("@pass") != std::string::npos;
  ASSERT_TRUE(markers) << "no embedded shader carries a // @pass marker";
  const fs::path dir = test::testDir("lesson", true) / "fast-pcf";
  const test::CommandResult r =
      test::runBinary(SHADOWLAB_BINARY, lessonArgs("modern.fast-pcf", dir), dir.parent_path());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = slurp(dir / "index.html");
  EXPECT_NE(html.find("replaces <a href=\"#legacy.fast-pcf-pass-"), std::string::npos)
      << "no modern pass links the legacy pass it replaces";
  // The excerpts: "<file> lines a-b" then the numbered lines; each line as in the shader.
  static const std::regex kExcerpt(
      R"re(<div class="glsl"><div class="card-title">([^<]+) lines (\d+)-(\d+)</div>(?:<div class="glsl-title">[^<]*</div>)?<pre>)re");
  size_t excerpts = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), kExcerpt);
       it != std::sregex_iterator(); ++it, ++excerpts) {
    const std::string file = fs::path((*it)[1].str()).filename().string();
    std::istringstream shader(shaderSource(file));
    std::vector<std::string> lines;
    for (std::string l; std::getline(shader, l);) lines.push_back(l);
    const int first = std::stoi((*it)[2].str());
    ASSERT_GE(first, 1);
    ASSERT_LE(size_t(first), lines.size());
    // The excerpt's first line: its number, then the shader's line `first` as it is.
    const size_t pre = size_t(it->position(0) + it->length(0));
    const size_t end = html.find('\n', pre);
    const std::string shown = html.substr(pre, end - pre);
    const std::string expected =
        std::to_string(first) + "</span> " + htmlEscape(lines[size_t(first - 1)]);
    EXPECT_EQ(shown.substr(shown.size() - std::min(shown.size(), expected.size())), expected)
        << file << ":" << first;
  }
  EXPECT_GT(excerpts, 0u) << "the modern passes show no GLSL";
}

}  // namespace
}  // namespace sl
