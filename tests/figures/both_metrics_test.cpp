// tests/figures/both_metrics_test.cpp — a figure that asks for both error metrics of
// docs/error.md (FigureSpec::bothMetrics) gets, for every render panel, its error by the area
// metric and by the point metric in its numbers table. The figure that does so, 2001-vs-2015,
// is rendered by the real program (`shadowlab figures --only`), as the main job renders it.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "figures/figure_spec.h"
#include "registry/registry.h"

namespace fs = std::filesystem;
using namespace sl;
using namespace sl::figures;

namespace {

constexpr const char* kFigureId = "2001-vs-2015";

const FigureSpec* listed(const std::string& id) {
  for (const FigureSpec& f : figureList())
    if (f.id == id) return &f;
  return nullptr;
}

std::string run(const std::string& command, int* status) {
  std::string output;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return output;
  std::array<char, 4096> buffer{};
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) output.append(buffer.data(), n);
  const int s = pclose(pipe);
  *status = WIFEXITED(s) ? WEXITSTATUS(s) : -1;
  return output;
}

std::string readFile(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

// The entry: rows of scenes, every panel a technique of the registry, each area-light technique
// scored against the soft reference, and both metrics asked for.
TEST(BothMetrics, EarlyAgainstLateIsDeclaredWithBothMetrics) {
  const FigureSpec* f = listed(kFigureId);
  ASSERT_NE(f, nullptr);
  EXPECT_TRUE(f->bothMetrics);
  EXPECT_FALSE(f->table);
  ASSERT_FALSE(f->panels.empty());
  EXPECT_EQ(f->panels.size() % size_t(f->columns), 0u) << "every scene a full row";
  for (const PanelSpec& p : f->panels) {
    EXPECT_EQ(p.kind, PanelKind::kRender) << p.label;
    EXPECT_FALSE(p.scene.empty()) << p.label;
    const Technique* t = nullptr;
    for (const Technique& candidate : allTechniques())
      if (candidate.name == p.technique) t = &candidate;
    ASSERT_NE(t, nullptr) << p.technique;
    EXPECT_EQ(p.reference == "reference.soft", t->light == Technique::Light::kArea) << p.label;
  }
}

// Rendered: every render panel's row of the numbers table holds an error by each metric, both
// against the reference the panel is scored by.
TEST(BothMetrics, EveryRenderPanelHasTheAreaAndThePointError) {
  const FigureSpec* f = listed(kFigureId);
  ASSERT_NE(f, nullptr);
  const fs::path dir = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "figures" / "both-metrics";
  fs::remove_all(dir);
  fs::create_directories(dir);
  int status = -1;
  const std::string output = run(std::string(SHADOWLAB_BINARY) + " figures --no-progress --out " +
                                     dir.string() + " --only " + kFigureId,
                                 &status);
  ASSERT_EQ(status, 0) << output;
  const std::string html = readFile(dir / "report.html");
  const size_t begin = html.find("<article id=\"" + std::string(kFigureId) + "\"");
  ASSERT_NE(begin, std::string::npos);
  const std::string article = html.substr(begin, html.find("</article>", begin) - begin);
  EXPECT_NE(article.find("area metric</th>"), std::string::npos);
  EXPECT_NE(article.find("point metric</th>"), std::string::npos);
  // The numbers table's rows, one per render panel, in panel order: "<tr><td>LABEL</td><td><code>".
  size_t at = 0;
  int rows = 0;
  for (const PanelSpec& p : f->panels) {
    const std::string start = "<tr><td>" + p.label + "</td><td><code>";
    at = article.find(start, at);
    ASSERT_NE(at, std::string::npos) << "no numbers row for " << p.label;
    const std::string row = article.substr(at, article.find("</tr>", at) - at);
    const std::string truth = p.reference.empty() ? f->reference : p.reference;
    EXPECT_NE(row.find("area metric vs " + truth), std::string::npos) << row;
    EXPECT_NE(row.find("point metric vs " + truth), std::string::npos) << row;
    EXPECT_EQ(row.find("missing"), std::string::npos) << row;
    ++at;
    ++rows;
  }
  EXPECT_EQ(rows, int(f->panels.size()));
  // The sentence below the caption is computed from the run.
  EXPECT_NE(article.find("Measured: the smallest error by each metric."), std::string::npos);
}
