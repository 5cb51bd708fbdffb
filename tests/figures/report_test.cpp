// tests/figures/report_test.cpp — `shadowlab figures` and report.html, checked in a real
// browser: headless Chromium loads the report, every image must load and the
// console must stay free of errors; a screenshot is saved for people to look at.
//
// Only cheap figures are rendered (--only), so the suite stays fast. Without Chromium the
// browser tests skip with a message saying how to install it.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "figures/diagnostics.h"
#include "figures/figure_spec.h"
#include "figures/plots.h"
#include "registry/registry.h"

namespace fs = std::filesystem;
using namespace sl;
using namespace sl::figures;

namespace {

struct Command {
  int status = -1;
  std::string output;  // stdout and stderr together
};

Command run(const std::string& command) {
  Command r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buffer{};
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) r.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string readFile(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path outputDir(const std::string& name) {
  const fs::path dir = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "figures" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string chromium() {
  for (const char* name : {"chromium", "chromium-browser", "google-chrome"}) {
    const Command r = run(std::string("command -v ") + name);
    if (r.status == 0) return name;
  }
  return "";
}

// The flags that keep headless Chromium quiet and offline.
std::string chromiumCommand(const std::string& exe, const fs::path& profile) {
  return exe +
         " --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
         "--disable-background-networking --disable-component-update --disable-sync "
         "--allow-file-access-from-files --virtual-time-budget=5000 --user-data-dir=" +
         profile.string() + " --enable-logging=stderr --v=0 ";
}

// Renders one figure into `dir` with the real program; returns its output.
Command renderFigure(const std::string& id, const fs::path& dir) {
  return run(std::string(SHADOWLAB_BINARY) + " figures --out " + dir.string() + " --only " + id);
}

// Sources of every <img> in the report.
std::vector<std::string> imageSources(const std::string& html) {
  std::vector<std::string> out;
  const std::regex img("<img src=\"([^\"]+)\"");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), img); it != std::sregex_iterator();
       ++it)
    out.push_back((*it)[1]);
  return out;
}

int bodyCount(const std::string& dom, const std::string& attribute) {
  const std::regex re(attribute + "=\"([0-9]+)\"");
  std::smatch m;
  if (!std::regex_search(dom, m, re)) return -1;
  return std::stoi(m[1]);
}

// Console errors and failed loads as Chromium logs them with --enable-logging=stderr.
std::vector<std::string> consoleErrors(const std::string& log) {
  std::vector<std::string> out;
  std::istringstream in(log);
  std::string line;
  while (std::getline(in, line))
    if (line.find("CONSOLE") != std::string::npos || line.find("Uncaught") != std::string::npos ||
        line.find("ERR_FILE_NOT_FOUND") != std::string::npos ||
        line.find("Failed to load resource") != std::string::npos)
      out.push_back(line);
  return out;
}

}  // namespace

// Every figure of the papers that the report reproduces has an entry (the list typed in here).
TEST(FigureList, HoldsEveryFigureOfThePapers) {
  const std::set<std::string> required = {"brabec-fig7",
                                          "brabec-fig8",
                                          "brabec-fig3-packing",
                                          "brabec-fig5-packing",
                                          "everitt-fig2",
                                          "everitt-fig4",
                                          "everitt-fig5",
                                          "everitt-fig6",
                                          "gems-11-6to9",
                                          "csm-fig1",
                                          "csm-fig3",
                                          "csm-fig4",
                                          "csm-fig5",
                                          "csm-fig6",
                                          "csm-fig7",
                                          "csm-fig8",
                                          "csm-fig9",
                                          "csm-fig10",
                                          "csm-table1",
                                          "chan-2-4",
                                          "chan-2-5",
                                          "chan-3-1",
                                          "chan-3-5",
                                          "chan-3-7",
                                          "chan-3-9",
                                          "chan-3-10",
                                          "chan-3-11",
                                          "chan-4-1",
                                          "chan-4-4",
                                          "chan-4-8",
                                          "chan-4-9",
                                          "chan-4-10"};
  std::set<std::string> ids;
  for (const FigureSpec& f : figureList()) {
    EXPECT_TRUE(ids.insert(f.id).second) << "duplicate figure id " << f.id;
    EXPECT_FALSE(f.caption.empty()) << f.id;
    EXPECT_FALSE(f.panels.empty()) << f.id;
    EXPECT_GT(f.columns, 0) << f.id;
    for (const Closeup& c : f.closeups) {
      EXPECT_TRUE(c.x >= 0 && c.y >= 0 && c.x + c.w <= 1 && c.y + c.h <= 1) << f.id;
      EXPECT_GE(c.magnify, 2) << f.id;
    }
  }
  for (const std::string& id : required) EXPECT_TRUE(ids.count(id)) << "missing entry " << id;
}

// Annen et al. Eq. 11: f(0) = 1/2 exactly (every sine vanishes), and the truncated series
// converges to the step away from the discontinuity. For M = 16 the Gibbs overshoot decays
// like 1/(M |t|): at |t| = 0.25 the error bound 2/(pi^2 * 2M * |t|) ~ 0.013 < 0.02.
TEST(CsmReconstruction, FollowsEquation11) {
  EXPECT_NEAR(csmVisibility(0.0, 4, 0, 0, 1, false), 0.5, 1e-12);
  EXPECT_NEAR(csmVisibility(-0.25, 16, 0, 0, 1, false), 1.0, 0.02);
  EXPECT_NEAR(csmVisibility(0.25, 16, 0, 0, 1, false), 0.0, 0.02);
  // M = 1 by hand: 1/2 - 2 sin(pi t)/pi.
  for (double t : {-0.3, -0.1, 0.2, 0.45})
    EXPECT_NEAR(csmVisibility(t, 1, 0, 0, 1, false), 0.5 - 2.0 * std::sin(M_PI * t) / M_PI, 1e-12);
  // Scaling by 2 and clamping makes d - z = 0 fully lit (§3.2.2).
  EXPECT_NEAR(csmVisibility(0.0, 4, 0, 0, 2, true), 1.0, 1e-12);
  // The offset puts the reconstruction's first maximum at d - z = 0.
  const double offset = csmOffsetFor(4, 0.0);
  EXPECT_GT(offset, 0.0);
  const double atZero = csmVisibility(0.0, 4, 0, offset, 1, false);
  EXPECT_GE(atZero, csmVisibility(-0.01, 4, 0, offset, 1, false));
  EXPECT_GE(atZero, csmVisibility(0.01, 4, 0, offset, 1, false));
}

// The density colour code: one pixel per texel is pure green, 4 (magnified) blue, 1/4 red.
TEST(TexelDensity, ColourCode) {
  float c[3];
  densityColor(1.0f, c);
  EXPECT_FLOAT_EQ(c[1], 1.0f);
  EXPECT_FLOAT_EQ(c[0] + c[2], 0.0f);
  densityColor(4.0f, c);
  EXPECT_FLOAT_EQ(c[2], 1.0f);
  densityColor(0.25f, c);
  EXPECT_FLOAT_EQ(c[0], 1.0f);
  densityColor(0.0f, c);  // degenerate input stays finite
  EXPECT_TRUE(std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]));
}

// --only renders one figure; a panel whose technique is not in the registry is listed in red
// with the reason instead of being skipped.
TEST(FiguresCommand, OnlyOneFigureAndMissingPanelsListed) {
  const fs::path dir = outputDir("gems");
  const Command r = renderFigure("gems-11-6to9", dir);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("[1/3] gems-11-6to9"), std::string::npos)
      << "no progress bar: " << r.output;
  const std::string html = readFile(dir / "report.html");
  ASSERT_FALSE(html.empty());
  EXPECT_EQ(html.find("id=\"brabec-fig7\""), std::string::npos) << "--only rendered more";
  const auto gems = std::find_if(figureList().begin(), figureList().end(),
                                 [](const FigureSpec& f) { return f.id == "gems-11-6to9"; });
  ASSERT_NE(gems, figureList().end());
  for (const PanelSpec& p : gems->panels) {
    bool present = false;
    for (const Technique& t : allTechniques()) present = present || t.name == p.technique;
    if (!present) {
      EXPECT_NE(html.find("technique " + p.technique + " is not available yet"), std::string::npos)
          << p.technique << " is missing but not listed";
    }
  }
  for (const std::string& src : imageSources(html))
    EXPECT_TRUE(fs::exists(dir / src)) << "report references a missing file " << src;
}

TEST(FiguresCommand, UnknownFigureIsAnInputError) {
  const Command r = run(std::string(SHADOWLAB_BINARY) + " figures --out " +
                        outputDir("unknown").string() + " --only no-such-figure");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("unknown figure 'no-such-figure'"), std::string::npos) << r.output;
}

// The report in a browser: every image loads, no console error.
TEST(ReportInBrowser, LoadsEveryImageWithoutConsoleErrors) {
  const std::string exe = chromium();
  if (exe.empty())
    GTEST_SKIP() << "chromium is not installed (Debian: apt-get install -y chromium, listed in "
                    "scripts/setup.sh); the browser check is skipped";
  const fs::path dir = outputDir("browser");
  // Everitt Fig. 5 is cheap (two 512x384 frames with a 32x32 map) and has close-ups and a
  // legacy/modern pair; CSM Fig. 3 adds a gnuplot chart.
  // brabec-fig3-packing adds a buffer strip of ten buffers.
  for (const char* id : {"everitt-fig5", "brabec-fig3-packing"}) {
    const Command r = renderFigure(id, dir);
    ASSERT_EQ(r.status, 0) << r.output;
  }
  const fs::path report = dir / "report.html";
  const std::string html = readFile(report);
  const size_t images = imageSources(html).size();
  ASSERT_GT(images, 0u);

  const fs::path profile = dir / "chromium-profile";
  const Command dom =
      run(chromiumCommand(exe, profile) + "--dump-dom file://" + fs::absolute(report).string());
  ASSERT_EQ(dom.status, 0) << dom.output;
  EXPECT_EQ(bodyCount(dom.output, "data-images-broken"), 0) << dom.output;
  EXPECT_EQ(bodyCount(dom.output, "data-images-ok"), int(images));
  // Every image at its own aspect ratio (buffer strips were squashed).
  EXPECT_EQ(bodyCount(dom.output, "data-images-distorted"), 0) << dom.output;
  const auto errors = consoleErrors(dom.output);
  EXPECT_TRUE(errors.empty()) << "console: " << (errors.empty() ? "" : errors.front());

  const fs::path shot = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "figures" / "report-screenshot.png";
  fs::remove(shot);
  const Command s =
      run(chromiumCommand(exe, profile) + "--window-size=1400,1800 --screenshot=" + shot.string() +
          " file://" + fs::absolute(report).string());
  EXPECT_EQ(s.status, 0) << s.output;
  EXPECT_TRUE(fs::exists(shot) && fs::file_size(shot) > 0) << s.output;
  std::cout << "screenshot: " << shot << std::endl;
}

// The check itself must catch a missing image: delete one and the browser reports it.
TEST(ReportInBrowser, CatchesAMissingImage) {
  const std::string exe = chromium();
  if (exe.empty()) GTEST_SKIP() << "chromium is not installed; the browser check is skipped";
  const fs::path dir = outputDir("broken");
  const Command r = renderFigure("everitt-fig5", dir);
  ASSERT_EQ(r.status, 0) << r.output;
  const std::vector<std::string> sources = imageSources(readFile(dir / "report.html"));
  ASSERT_FALSE(sources.empty());
  fs::remove(dir / sources.front());
  const Command dom = run(chromiumCommand(exe, dir / "chromium-profile") + "--dump-dom file://" +
                          fs::absolute(dir / "report.html").string());
  // The same file may be shown twice (a panel and its legacy/modern pair): count references.
  const int references = int(std::count(sources.begin(), sources.end(), sources.front()));
  EXPECT_EQ(bodyCount(dom.output, "data-images-broken"), references) << dom.output;
  EXPECT_FALSE(consoleErrors(dom.output).empty()) << "the console error was not seen";
}

// The aspect-ratio check must catch a squashed image: the report's old rule for buffer strips
// (a fixed height in a narrow cell) put back into the page distorts them, and the page says so.
TEST(ReportInBrowser, CatchesASquashedBufferStrip) {
  const std::string exe = chromium();
  if (exe.empty()) GTEST_SKIP() << "chromium is not installed; the browser check is skipped";
  const fs::path dir = outputDir("squashed");
  const Command r = renderFigure("brabec-fig3-packing", dir);
  ASSERT_EQ(r.status, 0) << r.output;
  std::string html = readFile(dir / "report.html");
  const std::string squash = ".inter img { height: 180px; width: 40px; max-width: 40px; }\n";
  const size_t style = html.find("</style>");
  ASSERT_NE(style, std::string::npos);
  html.insert(style, squash);
  std::ofstream(dir / "squashed.html") << html;
  const Command dom = run(chromiumCommand(exe, dir / "chromium-profile") + "--dump-dom file://" +
                          fs::absolute(dir / "squashed.html").string());
  EXPECT_GT(bodyCount(dom.output, "data-images-distorted"), 0) << dom.output;
}
