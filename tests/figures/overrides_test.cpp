// `shadowlab figures --only ID --set key=value` re-makes one figure with
// parameters changed, into its own folder, with the overrides in the caption and file names.
#include "figures/overrides.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "core/base/errors.h"
#include "core/base/image.h"
#include "figures/figure_spec.h"

namespace fs = std::filesystem;
using namespace sl;
using namespace sl::figures;

namespace {

const FigureSpec& listed(const std::string& id) {
  for (const FigureSpec& f : figureList())
    if (f.id == id) return f;
  throw std::runtime_error("no figure " + id);
}

}  // namespace

TEST(FigureOverrides, ParsesEveryKnownKeyAndTechniqueParams) {
  const FigureOverrides o = parseOverrideList(
      {"size=320x240", "shadow-map=1024", "filter=4", "precision=float", "camera-distance=2.5",
       "light-radius=0.2", "light-position=1,5,-2", "order=8"});
  EXPECT_EQ(o.width, 320);
  EXPECT_EQ(o.height, 240);
  EXPECT_EQ(o.shadowMapTexels, 1024);
  EXPECT_EQ(o.filter, 4);
  EXPECT_EQ(o.precision, Precision::kFloat);
  EXPECT_FLOAT_EQ(o.scene.cameraDistance.value(), 2.5f);
  EXPECT_FLOAT_EQ(o.scene.lightRadius.value(), 0.2f);
  EXPECT_FLOAT_EQ(o.scene.lightPosition->y, 5.0f);
  EXPECT_EQ(o.params.at("order"), "8");
  EXPECT_EQ(o.slug().rfind("size-320x240--shadow-map-1024--filter-4--precision-float", 0), 0u)
      << o.slug();
}

TEST(FigureOverrides, BadPairsAreInputErrors) {
  for (const char* bad : {"shadow-map", "=3", "shadow-map=", "shadow-map=abc", "shadow-map=0",
                          "filter=17", "precision=16", "size=12", "camera-distance=-1",
                          "light-radius=-0.5", "light-position=1,2", "key with space=1"})
    EXPECT_THROW(parseOverrideList({bad}), InputError) << bad;
  EXPECT_THROW(parseOverrideList({"filter=2", "filter=4"}), InputError) << "given twice";
}

TEST(FigureOverrides, MapSizeReachesEveryPanelAndTheCaption) {
  const FigureSpec& fig = listed("brabec-fig7");
  const FigureSpec f = applyOverrides(fig, parseOverrideList({"shadow-map=1024"}));
  EXPECT_EQ(f.id, "brabec-fig7--shadow-map-1024");
  EXPECT_EQ(f.sourceId, "brabec-fig7");
  EXPECT_EQ(f.fileSuffix, "--shadow-map-1024");
  EXPECT_EQ(f.shadowMapTexels, 1024);
  for (const PanelSpec& p : f.panels) EXPECT_EQ(p.shadowMapTexels, 0) << "the figure's: 1024";
  EXPECT_NE(f.caption.find("shadow-map=1024 in 4 panels (listed: 512)"), std::string::npos)
      << f.caption;
  ASSERT_EQ(f.overrides.size(), 1u);
  EXPECT_EQ(f.overrides[0], "shadow-map=1024");
  // The panels it changes carry it (figure.png draws it into their labels).
  int marked = 0;
  for (const PanelSpec& p : f.panels)
    if (!p.overridden.empty()) {
      ++marked;
      EXPECT_EQ(p.overridden, std::vector<std::string>{"shadow-map=1024"}) << p.label;
    }
  EXPECT_EQ(marked, 4) << "the caption's count";
  for (const PanelSpec& p : fig.panels) EXPECT_TRUE(p.overridden.empty()) << "the listed figure";
}

TEST(FigureOverrides, PanelMapSizesAndTechniqueParamsAreReplaced) {
  // CSM Table 1: every cell has its own map size; order only reaches the CSM cells.
  const FigureSpec& table = listed("csm-table1");
  const FigureSpec f =
      applyOverrides(table, parseOverrideList({"shadow-map=256", "order=8", "camera-distance=2"}));
  int csm = 0;
  for (const PanelSpec& p : f.panels) {
    EXPECT_EQ(p.shadowMapTexels, 0) << p.label;
    EXPECT_FLOAT_EQ(p.cameraDistance, 2.0f);
    if (p.technique == "modern.csm") {
      ++csm;
      EXPECT_EQ(p.params.at("order"), "8") << p.label;
    } else {
      EXPECT_EQ(p.params.count("order"), 0u) << "modern.hw has no order";
    }
  }
  EXPECT_EQ(csm, 36);
  EXPECT_NE(f.caption.find("order=8 in 36 panels (listed: 16, 4, 8)"), std::string::npos)
      << f.caption;
}

TEST(FigureOverrides, KeysTheFigureDoesNotReadAreInputErrors) {
  const FigureSpec& fig = listed("brabec-fig7");
  EXPECT_THROW(applyOverrides(fig, parseOverrideList({"order=8"})), InputError)
      << "no technique of brabec-fig7 has --param order";
  EXPECT_THROW(applyOverrides(fig, parseOverrideList({"light-radius=0.2"})), InputError)
      << "only reference.soft reads the light radius";
  EXPECT_THROW(applyOverrides(fig, parseOverrideList({"shadow-map=65536"})), InputError)
      << "above GL_MAX_TEXTURE_SIZE";
  EXPECT_THROW(applyOverrides(fig, parseOverrideList({"light-position=0,0,0"})), InputError)
      << "the light would sit on its target";
  EXPECT_THROW(applyOverrides(listed("csm-fig3"), parseOverrideList({"size=100x100"})), InputError)
      << "a computed chart renders no scene";
  // The light radius does reach chan-4-9 (reference.soft, and the figure's reference).
  const FigureSpec f = applyOverrides(listed("chan-4-9"), parseOverrideList({"light-radius=0.3"}));
  for (const PanelSpec& p : f.panels) EXPECT_FLOAT_EQ(p.lightRadius.value(), 0.3f);
}

// On a cheap figure: the real program re-makes everitt-fig5
// (32² map) with a 64² map into its own folder; every file name and the caption say so; bad
// input exits 2 with one line.
TEST(FigureOverrides, FiguresCommandRemakesIntoItsOwnFolder) {
  const fs::path dir = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "figures" / "overrides";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string base = std::string(SHADOWLAB_BINARY) + " figures --no-progress --out " +
                           dir.string() + " --only everitt-fig5";
  const int raw = std::system((base + " --set shadow-map=64 >/dev/null 2>&1").c_str());
  ASSERT_EQ(WEXITSTATUS(raw), 0);
  const fs::path folder = dir / "everitt-fig5--shadow-map-64";
  ASSERT_TRUE(fs::is_directory(folder));
  int pngs = 0, marked = 0;
  for (const auto& e : fs::directory_iterator(folder)) {
    ++pngs;
    EXPECT_NE(e.path().filename().string().find("--shadow-map-64"), std::string::npos) << e.path();
    // Every panel PNG and figure.png say what made them, as render's PNGs do.
    if (e.path().extension() != ".png") continue;
    const auto text = readPngText(e.path().string());
    EXPECT_EQ(text.count("Software"), 1u) << e.path();
    ASSERT_EQ(text.count("shadowlab:parameters"), 1u) << e.path();
    const nlohmann::json made = nlohmann::json::parse(text.at("shadowlab:parameters"));
    EXPECT_EQ(made["figure"], "everitt-fig5--shadow-map-64") << e.path();
    if (made.contains("set") && made["set"] == nlohmann::json{"shadow-map=64"}) ++marked;
  }
  EXPECT_GT(pngs, 2);
  EXPECT_GT(marked, 0) << "the panels the override changed name it";
  std::ifstream in(dir / "report.html");
  std::stringstream html;
  html << in.rdbuf();
  EXPECT_NE(html.str().find("Re-made with --set shadow-map=64"), std::string::npos);
  EXPECT_NE(html.str().find("shadowlab figures --only everitt-fig5 --set shadow-map=64"),
            std::string::npos);
  const std::string err = (dir / "err.txt").string();
  const int bad = std::system((base + " --set filter=x 2>" + err).c_str());
  EXPECT_EQ(WEXITSTATUS(bad), 2);
  std::ifstream e(err);
  std::string line, rest;
  std::getline(e, line);
  EXPECT_NE(line.find("--set filter"), std::string::npos) << line;
  EXPECT_FALSE(std::getline(e, rest)) << "one line";
}
