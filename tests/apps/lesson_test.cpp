// `shadowlab lesson TECHNIQUE --out DIR` (teach/lesson.h): one self-contained
// page per technique with the paper's idea, every pass, the twin, legacy against modern and the
// known departures; bad input is one line and exit 2 with nothing written.
#include "teach/lesson.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "command_util.h"
#include "core/base/html.h"
#include "core/base/image.h"
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

// Every href="#id" of a page names an id of the page (a departure of a pass that runs only at
// 4x4 links the 4x4 strip's section; tests/browser/check_pages.mjs checks all links in Chromium).
void expectFragmentsResolve(const std::string& html) {
  static const std::regex kFragment(R"re(href="#([^"]+)")re");
  static const std::regex kId(R"re(\bid="([^"]+)")re");
  std::set<std::string> ids;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), kId); it != std::sregex_iterator();
       ++it)
    ids.insert((*it)[1].str());
  int links = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), kFragment);
       it != std::sregex_iterator(); ++it, ++links)
    EXPECT_TRUE(ids.count((*it)[1].str())) << "#" << (*it)[1].str() << " names no id of the page";
  EXPECT_GT(links, 0);
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

// The share of the pixels of two pictures of the same size that differ by more than two 8-bit
// steps in some channel (1.0 when the sizes differ).
double differingShare(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height || a.channels != b.channels) return 1.0;
  constexpr float kTwoSteps = 2.0f / 255.0f;  // above PNG rounding of the same render
  long long differing = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int c = 0; c < a.channels; ++c)
        if (std::abs(a.at(x, y, c) - b.at(x, y, c)) > kTwoSteps) {
          ++differing;
          break;
        }
  return double(differing) / double(a.width * a.height);
}

// Every technique's lesson answers "why it works" with pictures rendered for the page: the
// lesson text names at least one render for each technique of the registry, and each lesson
// (one per lesson text; a twin pair shares one) writes every picture its text names, with its
// caption, what the run measured and the command that re-makes it. A block's first and last
// picture are the working and the breaking case: they differ on the part they show.
TEST(Lesson, EveryTechniqueAnswersWhyWithRenderedPictures) {
  const std::vector<std::string> missing = figures::techniquesWithoutWhyPicture();
  EXPECT_TRUE(missing.empty()) << "no rendered why picture in the lesson of " << missing.front()
                               << " (and " << missing.size() - 1 << " more)";
  std::set<std::string> titles;  // one lesson per lesson text
  const fs::path base = test::testDir("lesson", true) / "why";
  fs::create_directories(base);
  for (const Technique& t : allTechniques()) {
    if (!titles.insert(figures::lessonTitle(t.name)).second) continue;
    const size_t pictures = figures::whyPictureCount(t.name);
    if (pictures == 0) continue;  // reported above
    const fs::path dir = base / t.name;
    const test::CommandResult r = test::runBinary(SHADOWLAB_BINARY, lessonArgs(t.name, dir), base);
    ASSERT_EQ(r.status, 0) << t.name << ": " << r.err;
    const std::string html = slurp(dir / "index.html");
    const size_t why = html.find("<h2 id=\"why\">");
    ASSERT_NE(why, std::string::npos) << t.name << ": no why section";
    static const std::regex kWhyImage(R"re(<img src="(why-(\d+)-(\d+)\.png)")re");
    std::map<std::string, std::vector<std::string>> byBlock;  // block -> files, in order
    size_t shown = 0;
    for (auto it = std::sregex_iterator(html.begin() + long(why), html.end(), kWhyImage);
         it != std::sregex_iterator(); ++it, ++shown) {
      EXPECT_TRUE(fs::exists(dir / (*it)[1].str())) << t.name << ": " << (*it)[1];
      byBlock[(*it)[2].str()].push_back((*it)[1].str());
    }
    EXPECT_EQ(shown, pictures) << t.name << ": pictures on the page against the lesson text";
    EXPECT_GE(count(html, "% of the image in shadow"), pictures) << t.name;
    EXPECT_GE(count(html, "<code>shadowlab render --scene"), pictures) << t.name;
    for (const auto& [block, files] : byBlock) {
      if (files.size() < 2) continue;
      // The pair must show a difference on the part it crops: more than 1% of its pixels
      // (measured at this test's 160x120: from 3.1%, PCF 2x2 against 4x4, to 76%).
      constexpr double kVisibleShare = 0.01;
      EXPECT_GT(differingShare(readPng((dir / files.front()).string()),
                               readPng((dir / files.back()).string())),
                kVisibleShare)
          << t.name << ": " << files.front() << " and " << files.back() << " look the same";
    }
  }
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

// The text of one pass's section of a lesson: from its id to its end.
std::string passSection(const std::string& html, const std::string& anchor) {
  const size_t at = html.find("<section class=\"pass\" id=\"" + anchor + "\"");
  if (at == std::string::npos) return "";
  return html.substr(at, html.find("</section>", at) - at);
}

size_t countMatches(const std::string& text, const std::regex& re) {
  return size_t(
      std::distance(std::sregex_iterator(text.begin(), text.end(), re), std::sregex_iterator()));
}

// Annen et al. §4.1 pass by pass: all 2M basis values (M = 16: four sine and four cosine RGBA
// layers) under the pass that leaves them, the pictures after the whole blur under the
// vertical Gaussian (pass 3), the mip levels under pass 4, and no dump readback on any card.
TEST(Lesson, CsmShowsEveryBasisLayerUnderItsPass) {
  const fs::path dir = test::testDir("lesson", true) / "csm";
  const test::CommandResult r =
      test::runBinary(SHADOWLAB_BINARY, lessonArgs("modern.csm", dir), dir.parent_path());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = slurp(dir / "index.html");
  static const std::regex kLayer(
      R"re(<img src="modern\.csm_0(\d)[a-z]?-basis-(sin|cos)-k\d+-\d+\.png")re");
  std::map<std::string, std::set<std::string>> layersByPass;  // pass number -> sin/cos layers
  for (auto it = std::sregex_iterator(html.begin(), html.end(), kLayer);
       it != std::sregex_iterator(); ++it)
    layersByPass[(*it)[1].str()].insert(it->str());
  const std::string pass2 = passSection(html, "modern.csm-pass-2");
  const std::string pass3 = passSection(html, "modern.csm-pass-3");
  const std::string pass4 = passSection(html, "modern.csm-pass-4");
  ASSERT_FALSE(pass3.empty()) << "no vertical Gaussian pass";
  // M = 16: 2M = 32 values, four per RGBA layer, sine and cosine.
  constexpr size_t kLayers = 8;
  EXPECT_EQ(countMatches(pass3, kLayer), kLayers) << "pass 3 shows the blurred basis";
  EXPECT_EQ(countMatches(pass2, kLayer), kLayers) << "pass 2 shows its own output";
  EXPECT_EQ(pass2.find("after the whole Gaussian"), std::string::npos)
      << "after-blur pictures filed under pass 2";
  EXPECT_NE(pass3.find("after the whole Gaussian"), std::string::npos);
  EXPECT_NE(pass4.find("basis-sin-k1-4-level1"), std::string::npos) << "pass 4 has no picture";
  for (const std::string* pass : {&pass2, &pass3, &pass4})
    EXPECT_EQ(pass->find("glReadPixels"), std::string::npos) << "a dump readback on a card";
  EXPECT_NE(html.find("id=\"modern.csm-pass-5c\""), std::string::npos);
}

// Brabec & Seidel §3-4 at both footprints: the 4x4 strips with the accumulation passes, the
// four phases' kernels and offsets as traced, how they tile the footprint, 17 levels, merged
// pass titles without a part's name, the twin's 4x4 pass linked to the legacy 4x4 pass.
TEST(Lesson, FastPcfShowsTwoByTwoAndFourByFour) {
  const fs::path dir = test::testDir("lesson", true) / "fast-pcf-both";
  const test::CommandResult r =
      test::runBinary(SHADOWLAB_BINARY, lessonArgs("legacy.fast-pcf", dir), dir.parent_path());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = slurp(dir / "index.html");
  for (const char* id : {"legacy.fast-pcf", "modern.fast-pcf", "legacy.fast-pcf-4x4",
                         "modern.fast-pcf-4x4", "compare", "compare-4x4"})
    EXPECT_NE(html.find("id=\"" + std::string(id) + "\""), std::string::npos) << id;
  const std::string accumulate = passSection(html, "legacy.fast-pcf-4x4-pass-6a");
  const std::string back = passSection(html, "legacy.fast-pcf-4x4-pass-6b");
  EXPECT_NE(accumulate.find("glAccum(GL_ACCUM, 0.25)"), std::string::npos);
  EXPECT_NE(back.find("accumulation-result-alpha"), std::string::npos);
  EXPECT_NE(back.find("17 levels"), std::string::npos);
  EXPECT_EQ(html.find("(4 x 5 levels)"), std::string::npos);
  EXPECT_NE(html.find("<a href=\"#legacy.fast-pcf-4x4-pass-6a\">legacy.fast-pcf pass 6a"),
            std::string::npos)
      << "the 4x4 twin does not link the accumulation pass";
  // The titles of passes run once per phase name the pass, not its first part (pass 3, the
  // camera pass, runs in the first phase only: its one part keeps its name).
  static const std::regex kTitle(R"re(<h3>[^<]*\((upper|lower)-(left|right)\))re");
  for (const char* id : {"2", "4", "5", "6a"})
    EXPECT_EQ(
        countMatches(passSection(html, std::string("legacy.fast-pcf-4x4-pass-") + id), kTitle), 0u)
        << "pass " << id;
  // The four kernels and the four projective texture matrices, one per phase, and the tiling.
  EXPECT_NE(html.find("<svg class=\"tiling\""), std::string::npos);
  const size_t why = html.find("id=\"why\"");
  ASSERT_NE(why, std::string::npos);
  const std::string answers = html.substr(why, html.find("id=\"legacy.fast-pcf\"") - why);
  EXPECT_EQ(count(answers, "3x3 kernel"), 4u);
  for (const char* phase : {"(upper-left)", "(upper-right)", "(lower-left)", "(lower-right)"})
    EXPECT_NE(answers.find(phase), std::string::npos) << phase;
  EXPECT_NE(answers.find("colour matrix"), std::string::npos);
  EXPECT_EQ(html.find("The two part most"), std::string::npos);
  // 2x2 against 4x4, rendered for the page.
  EXPECT_TRUE(fs::exists(dir / "why-3-1.png"));
  EXPECT_TRUE(fs::exists(dir / "why-3-2.png"));
  EXPECT_TRUE(fs::exists(dir / "diff-mask-4x4.png"));
  expectFragmentsResolve(html);
}

TEST(Lesson, PcfShowsTheAccumulationPassAtFourByFour) {
  const fs::path dir = test::testDir("lesson", true) / "pcf-both";
  const test::CommandResult r =
      test::runBinary(SHADOWLAB_BINARY, lessonArgs("modern.pcf", dir), dir.parent_path());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = slurp(dir / "index.html");
  EXPECT_NE(passSection(html, "legacy.pcf-4x4-pass-5a").find("glAccum"), std::string::npos);
  EXPECT_NE(passSection(html, "legacy.pcf-4x4-pass-5b").find("accumulation-result-alpha"),
            std::string::npos);
  EXPECT_EQ(passSection(html, "legacy.pcf-pass-5a"), "") << "the 2x2 strip has no accumulation";
  EXPECT_NE(html.find("<a href=\"#legacy.pcf-4x4-pass-5a\">legacy.pcf pass 5a"), std::string::npos)
      << "the 4x4 twin does not link the accumulation pass";
  // The saved camera pass (2s) runs at 3x3 and 4x4 only: its departure links the 4x4 strip.
  EXPECT_NE(html.find("<li><a href=\"#legacy.pcf-4x4-pass-2s\">"), std::string::npos);
  expectFragmentsResolve(html);
}

// Everitt: the texgen planes beside the twin's matrix rows (the same numbers, 6 significant
// digits), polygon offset as three pictures of this run, the cards with their key lines
// highlighted and their setup folded, and a print layout of one pass per page.
TEST(Lesson, HardwareShadowMapAnswersWhyWithPicturesAndNumbers) {
  const fs::path dir = test::testDir("lesson", true) / "hw";
  const test::CommandResult r =
      test::runBinary(SHADOWLAB_BINARY, lessonArgs("legacy.hw", dir), dir.parent_path());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = slurp(dir / "index.html");
  static const std::regex kLargest(R"(Largest difference over the sixteen numbers: ([0-9.e+-]+))");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(html, m, kLargest)) << "no planes against matrix rows";
  // Both print float products with 6 significant digits: they agree to the last digit shown
  // of numbers below 10 (a unit in the 6th digit is 1e-5).
  EXPECT_LE(std::stod(m[1].str()), 1e-5);
  static const std::regex kPlane(R"(GL_S: GL_EYE_PLANE = \((-?[0-9.]+), )");
  ASSERT_TRUE(std::regex_search(html, m, kPlane));
  const std::string first = m[1].str();
  EXPECT_GE(std::count_if(first.begin(), first.end(), ::isdigit), 5) << first;
  for (int i = 1; i <= 3; ++i)
    EXPECT_TRUE(fs::exists(dir / ("why-3-" + std::to_string(i) + ".png"))) << i;
  for (const char* caption : {"no offset", "tuned offset", "too much offset",
                              "% of the image in shadow", "--param offset-factor=0"})
    EXPECT_NE(html.find(caption), std::string::npos) << caption;
  // Declared key lines: polygon offset on pass 1's card, the planes on pass 2's.
  static const std::regex kKey(
      R"re(<tr class="key"><td class="group">[^<]*</td><td><code>([^<]*)</code>)re");
  bool offset = false, plane = false;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), kKey); it != std::sregex_iterator();
       ++it) {
    offset = offset || (*it)[1].str().find("glPolygonOffset") != std::string::npos;
    plane = plane || (*it)[1].str().find("GL_EYE_PLANE") != std::string::npos;
  }
  EXPECT_TRUE(offset);
  EXPECT_TRUE(plane);
  EXPECT_NE(html.find("<details><summary>"), std::string::npos) << "no setup folded";
  EXPECT_NE(html.find("@media print"), std::string::npos);
  EXPECT_NE(html.find("break-before: page"), std::string::npos);
}

}  // namespace
}  // namespace sl
