// The bench's machinery (measure/bench.h): the sweep declares only what a technique declares,
// the Pareto front, the error metrics and a tiny end-to-end run with CSV, JSON and plot.
#include "measure/bench.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/base/errors.h"
#include "core/scene/scene_library.h"
#include "core/technique/plan.h"
#include "measure/sweep.h"
#include "reference/reference.h"
#include "registry/registry.h"

namespace sl::figures {
namespace {
namespace fs = std::filesystem;

TEST(BenchSweep, OnlyDeclaredParamsAreSwept) {
  Technique t;
  t.name = "modern.test";
  t.params = {integerParam("order", 16, 1, 64, "M")};
  const auto variants = sweepVariants(t, RenderParams{}, true);
  ASSERT_FALSE(variants.empty());
  EXPECT_EQ(variants[0].label, "default");
  bool sawOrder = false;
  for (const BenchVariant& v : variants) {
    for (const auto& [k, value] : v.params.extra) {
      EXPECT_EQ(k, "order") << v.label;
      sawOrder = true;
    }
    EXPECT_EQ(v.params.filter, RenderParams{}.filter) << "no filter sweep without PCF: " << v.label;
  }
  EXPECT_TRUE(sawOrder);
}

TEST(BenchSweep, ReferencesAreNotSwept) {
  EXPECT_EQ(sweepVariants(findTechnique("reference.hard"), RenderParams{}, false).size(), 1u);
}

BenchRow row(const std::string& technique, double ms, double rmse) {
  BenchRow r;
  r.scene = "s";
  r.technique = technique;
  r.frameMs = ms;
  r.primaryReference = "reference.hard";
  r.hard.all.rmse = rmse;
  return r;
}

TEST(BenchPareto, KeepsOnlyUndominatedRows) {
  // (time, error): a (1, 0.5), b (2, 0.2), c (3, 0.3) dominated by b, d (4, 0.1), and a
  // reference (0.5, 0) that is left out by construction.
  const std::vector<BenchRow> rows = {row("a", 1, 0.5), row("b", 2, 0.2), row("c", 3, 0.3),
                                      row("d", 4, 0.1), row("reference.hard", 0.5, 0.0)};
  const std::vector<size_t> front = paretoFront(rows, "s");
  EXPECT_EQ(front, (std::vector<size_t>{0, 1, 3}));
}

TEST(BenchErrors, LeakCountsLitUmbraOutsideTheBand) {
  Image reference(4, 1, 1, 0.0f), mask(4, 1, 1, 0.0f), region(4, 1, 1, 1.0f), band(4, 1, 1, 0.0f);
  mask.data = {0.0f, 0.5f, 0.1f, 1.0f};  // two of four umbra pixels more than 20% lit
  band.data = {0, 0, 0, 1};              // the last one is on the edge band: not a leak
  const ErrorSet e = measureErrors(mask, reference, region, band);
  EXPECT_DOUBLE_EQ(e.leakShare, 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(e.all.maxAbs, 1.0);
  EXPECT_EQ(e.band.pixels, 1);
}

// The plots' families: the 2001 pipelines, their GLSL twins (as registry/twins.h
// pairs them), the later papers; references are the truth and go on no plot.
TEST(BenchPlots, FamiliesSplitLegacyTwinsAndLaterPapers) {
  EXPECT_EQ(plotFamily("legacy.hw"), "legacy");
  EXPECT_EQ(plotFamily("legacy.fast-pcf"), "legacy");
  EXPECT_EQ(plotFamily("modern.hw"), "modern twins");
  EXPECT_EQ(plotFamily("modern.fast-pcf"), "modern twins");
  EXPECT_EQ(plotFamily("modern.csm"), "later papers");
  EXPECT_EQ(plotFamily("modern.gems16"), "later papers");
  EXPECT_EQ(plotFamily("reference.hard"), "");
  EXPECT_EQ(plotFamily("reference.soft"), "");
}

TEST(BenchRun, TinyRunWritesCsvJsonAndPlot) {
  const fs::path dir = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "bench";
  fs::remove_all(dir);
  fs::create_directories(dir);
  BenchOptions o;
  o.quick = true;
  o.scenes = {"brabec"};  // also adds the planner scene brabec-light-away
  o.techniques = {"modern.hw"};
  o.width = 128;
  o.height = 96;
  o.timedFrames = 1;
  o.warmupFrames = 1;
  o.progress = false;
  std::ostringstream json;
  const BenchResult r = runBenchmark(o, json);
  ASSERT_FALSE(r.rows.empty());
  for (const BenchRow& row : r.rows) {
    EXPECT_EQ(row.status, "ok") << row.variant;
    EXPECT_GT(row.frameMs, 0.0);
    EXPECT_FALSE(row.passes.empty());
  }
  size_t lines = 0;
  for (char c : json.str()) lines += c == '\n';
  EXPECT_EQ(lines, r.rows.size()) << "one JSON object per row";
  writeCsv((dir / "bench.csv").string(), r.rows);
  std::ifstream csv(dir / "bench.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_NE(header.find("hard_band_rmse"), std::string::npos);
  EXPECT_NE(header.find("hard_point_rmse"), std::string::npos) << "the pixel-centre column";
  EXPECT_NE(header.find("temporal_change"), std::string::npos);
  EXPECT_NE(header.find("pareto_rank"), std::string::npos);
  EXPECT_NE(json.str().find("\"pareto_rank\":1"), std::string::npos) << json.str();
  for (size_t i = 1; i < r.rows.size(); ++i)
    EXPECT_LE(r.rows[i - 1].scene, r.rows[i].scene) << "sorted by scene, then time";
  EXPECT_NE(json.str().find("\"temporal_change\""), std::string::npos);
  EXPECT_NE(json.str().find("\"vs_reference_hard_centre\""), std::string::npos);
  bool farRows = false;
  for (const BenchRow& row : r.rows)
    farRows |= row.scene == std::string(kMinificationScene) + kFarSceneSuffix;
  EXPECT_TRUE(farRows) << "modern.hw also runs on the minification scene";
  bool plannerRows = false;
  for (const BenchRow& row : r.rows) plannerRows |= row.scene == "brabec-light-away";
  EXPECT_TRUE(plannerRows);
  // Per scene with a non-zero error (brabec and the minification scene trees-far) one plot per
  // technique family present (plotFamily); the planner scene (no pixel lit, every RMSE 0) gets none
  // and a note saying why, on the page and in sceneNotes.
  const BenchPlots plots = writePlots(dir.string(), r);
  std::set<std::string> files;
  for (const BenchPlot& plot : plots.plots) {
    files.insert(fs::path(plot.path).filename().string());
    EXPECT_GT(fs::file_size(plot.path), 1000u);
  }
  // modern.hw alone: the "modern twins" family only, no empty legacy or later-papers plot.
  EXPECT_EQ(files, (std::set<std::string>{"bench-brabec-modern-twins.png",
                                          "bench-trees-far-modern-twins.png"}));
  for (const BenchPlot& plot : plots.plots) EXPECT_NE(plot.scene, "brabec-light-away");
  ASSERT_TRUE(plots.notes.count("brabec-light-away"));
  EXPECT_NE(plots.notes.at("brabec-light-away").find("RMSE is 0"), std::string::npos);
  EXPECT_TRUE(r.sceneNotes.count("brabec-light-away"));
  // Readable plots: no reference among the plotted points, at most a handful
  // of series per plot, and x and y ranges fitted to the plot's family and the scene's Pareto
  // front (every point inside, within a factor 1.5 of the extremes).
  for (const BenchPlot& plot : plots.plots) {
    const std::string base = plot.path.substr(0, plot.path.size() - 4);
    std::ifstream dat(base + ".dat"), gp(base + ".gp");
    std::stringstream datText, gpText;
    datText << dat.rdbuf();
    gpText << gp.rdbuf();
    const std::string data = datText.str();
    EXPECT_EQ(data.find("reference."), std::string::npos) << plot.path;
    const std::string script = gpText.str();
    const size_t series = size_t(std::count(data.begin(), data.end(), '#')) - 1;
    EXPECT_LE(series, 9u) << plot.path;
    double xLo = 0, xHi = 0, yLo = 0, yHi = 0;
    ASSERT_EQ(std::sscanf(script.substr(script.find("set xrange")).c_str(), "set xrange [%lf:%lf]",
                          &xLo, &xHi),
              2)
        << script;
    ASSERT_EQ(std::sscanf(script.substr(script.find("set yrange")).c_str(), "set yrange [%lf:%lf]",
                          &yLo, &yHi),
              2)
        << script;
    double dataXLo = 1e300, dataXHi = 0, dataYLo = 1e300, dataYHi = 0;
    const std::vector<size_t> front = paretoFront(r.rows, plot.scene);
    for (size_t i = 0; i < r.rows.size(); ++i) {
      const BenchRow& row = r.rows[i];
      const bool onFront = std::find(front.begin(), front.end(), i) != front.end();
      if (row.scene == plot.scene && row.status == "ok" &&
          (plotFamily(row.technique) == plot.family || onFront) && row.primary().all.rmse > 0) {
        dataXLo = std::min(dataXLo, row.frameMs);
        dataXHi = std::max(dataXHi, row.frameMs);
        dataYLo = std::min(dataYLo, row.primary().all.rmse);
        dataYHi = std::max(dataYHi, row.primary().all.rmse);
      }
    }
    EXPECT_LT(xLo, dataXLo) << plot.path;
    EXPECT_GT(xHi, dataXHi) << plot.path;
    EXPECT_GT(xLo, dataXLo / 1.5) << plot.path << ": x range not fitted to the data";
    EXPECT_LT(xHi, dataXHi * 1.5) << plot.path << ": x range not fitted to the data";
    EXPECT_LT(yLo, dataYLo) << plot.path;
    EXPECT_GT(yHi, dataYHi) << plot.path;
    EXPECT_GT(yLo, dataYLo / 1.5) << plot.path;
    EXPECT_LT(yHi, dataYHi * 1.5) << plot.path;
    // At least three labelled ticks on each log axis, inside its range, whatever its width
    // (gnuplot's own ticks sit at powers of ten only: a range within a decade would get one).
    auto ticksIn = [&](const std::string& axis, double lo, double hi) {
      const std::string key = "set " + axis + "tics (";
      const size_t at = script.find(key);
      if (at == std::string::npos) return size_t(0);
      const size_t first = at + key.size();
      std::istringstream list(script.substr(first, script.find(')', first) - first));
      size_t inside = 0;
      for (std::string value; std::getline(list, value, ',');) {
        const double v = std::stod(value);
        inside += v >= lo && v <= hi;
      }
      return inside;
    };
    EXPECT_GE(ticksIn("x", xLo, xHi), 3u) << script;
    EXPECT_GE(ticksIn("y", yLo, yHi), 3u) << script;
  }
  EXPECT_FALSE(plots.pareto.at("brabec").empty());
}

// ---- Temporal stability, the claim scenes, the fair claims -------------------------

constexpr int kSmallWidth = 256, kSmallHeight = 192;  // the quick bench's window

RenderParams smallParams() {
  RenderParams p;
  p.width = kSmallWidth;
  p.height = kSmallHeight;
  return p;
}

Image everywhere() { return Image(kSmallWidth, kSmallHeight, 1, 1.0f); }

TEST(BenchTemporal, LightShiftIsAFifthOfATexelSideways) {
  const Scene scene = builtinScene("brabec");
  const double shift = lightShiftWorld(scene);
  const SpotLight& l = scene.light;
  // A 512 map spans 2 d tan(cone / 2) at the target's distance d.
  const double side = 2.0 * glm::length(l.target - l.position) *
                      std::tan(glm::radians(0.5 * double(l.coneDegrees)));
  EXPECT_NEAR(shift, kLightShiftTexels * side / kLightShiftMapTexels, 1e-6 * side);
  const Scene moved = shiftLight(scene, shift);
  const glm::vec3 step = moved.light.position - l.position;
  EXPECT_NEAR(glm::length(step), shift, 1e-5);
  EXPECT_NEAR(glm::dot(glm::normalize(step), glm::normalize(l.target - l.position)), 0.0, 1e-5)
      << "sideways: perpendicular to the light's axis";
  // Float round-off of two additions (positions of size ~10 in float: 1e-6 relative).
  EXPECT_LT(glm::length((moved.light.target - l.target) - step), 1e-5)
      << "the target moves with the light";
}

// The references are deterministic: with the light at rest their masks do not change (the
// soft one included: its random streams are seeded per row and sub-pixel point).
TEST(BenchTemporal, ZeroForTheReferencesOfAStaticLight) {
  const Scene scene = builtinScene("brabec");
  const Scene still = shiftLight(scene, 0.0);
  RenderParams p = smallParams();
  p.extra[reference::kPixelParam] = reference::kPixelArea;
  for (const char* name : {"reference.hard", "reference.soft"}) {
    const Frame a = renderTechnique(findTechnique(name), scene, p);
    const Frame b = renderTechnique(findTechnique(name), still, p);
    EXPECT_EQ(meanAbsChange(a.visibility, b.visibility, everywhere()), 0.0) << name;
  }
}

// A nearest-compare shadow map snaps every edge to its texel grid: a fifth of a texel of light
// motion flips whole texels' worth of edge pixels, more than the true shadow moves.
TEST(BenchTemporal, NearestCompareChangesMoreThanTheTruth) {
  const Scene scene = builtinScene("brabec");
  const Scene moved = shiftLight(scene, lightShiftWorld(scene));
  RenderParams p = smallParams();
  p.extra["compare"] = "nearest";
  const Technique& hw = findTechnique("modern.hw");
  const double map = meanAbsChange(renderTechnique(hw, scene, p).visibility,
                                   renderTechnique(hw, moved, p).visibility, everywhere());
  RenderParams area = smallParams();
  area.extra[reference::kPixelParam] = reference::kPixelArea;
  const Technique& ref = findTechnique("reference.hard");
  const double truth = meanAbsChange(renderTechnique(ref, scene, area).visibility,
                                     renderTechnique(ref, moved, area).visibility, everywhere());
  std::cout << "mean |change| under the light motion: nearest compare " << map
            << ", reference.hard pixel=area " << truth << "\n";
  EXPECT_GT(map, 0.0);
  EXPECT_GT(map, truth);
}

// The minification scene (Annen Fig. 10): the trees with the camera 3 times farther from its
// target see the same ground at 3 times the distance, so each pixel covers about 3 times as
// many shadow-map texels (the planner's estimate is a 95th percentile over a view that now
// also holds more ground: at least three quarters of the factor), and at the claim's 2048
// map many texels in every pixel.
TEST(BenchScenes, FarSceneMinifiesTheShadowMap) {
  const Scene near = builtinScene(kMinificationScene);
  const Scene far = farScene(near);
  EXPECT_EQ(far.name, std::string(kMinificationScene) + kFarSceneSuffix);
  const Technique& hw = findTechnique("modern.hw");
  RenderParams claimMap = smallParams();
  claimMap.shadowMapTexels = kMinificationMapTexels;
  const double before = planFrame(near, hw, claimMap).maxShadowTexelsPerPixel;
  const double after = planFrame(far, hw, claimMap).maxShadowTexelsPerPixel;
  std::cout << "texels per pixel: trees " << before << ", trees-far " << after << "\n";
  EXPECT_GT(after, 0.75 * kFarCameraFactor * before);
  EXPECT_GT(after, 1.0) << "the claim's map is minified in the far view";
  // What the claim compares, written for a look (test-output/bench-far/).
  const fs::path dir = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "bench-far";
  fs::create_directories(dir);
  RenderParams area = smallParams();
  area.extra[reference::kPixelParam] = reference::kPixelArea;
  const Frame truth = renderTechnique(findTechnique("reference.hard"), far, area);
  writePng((dir / "reference-hard-area.png").string(), truth.color);
  writePng((dir / "reference-hard-area-mask.png").string(), truth.visibility, 16);
  RenderParams fig10 = claimMap;
  fig10.extra["blur"] = kCsmFig10Blur;
  writePng((dir / "modern.csm-mask.png").string(),
           renderTechnique(findTechnique("modern.csm"), far, fig10).visibility, 16);
  writePng((dir / "modern.gems16-mask.png").string(),
           renderTechnique(findTechnique("modern.gems16"), far, claimMap).visibility, 16);
}

// Chan §4.2's width from the light: a caster whose centre lies at depth b on the light's axis.
TEST(BenchScenes, SmoothieWidthIsTheLightRadiusSeenFromTheCaster) {
  Scene scene = builtinScene("analytic");  // light 4 above the ground, a thin box at 1.0
  const SpotLight& l = scene.light;
  double b = 0.0;
  int casters = 0;
  for (const Object& o : scene.objects)
    if (o.castsShadow) {
      const Bounds box = worldBounds(o);
      b += glm::length(l.position - 0.5f * (box.lo + box.hi));
      ++casters;
    }
  ASSERT_EQ(casters, 1) << "the analytic scene has one caster, straight below the light";
  const double expected =
      double(l.radius) / (2.0 * b * std::tan(glm::radians(0.5 * double(l.coneDegrees))));
  EXPECT_NEAR(smoothieWidthFromLight(scene), expected, 1e-6);
  scene.light.radius *= 2.0f;
  EXPECT_NEAR(smoothieWidthFromLight(scene), 2.0 * expected, 2e-6) << "proportional to R";
}

BenchRow claimRow(const std::string& scene, const std::string& technique,
                  const std::string& variant, double areaRmse, double pointRmse, double ms = 10.0) {
  BenchRow r;
  r.scene = scene;
  r.technique = technique;
  r.variant = variant;
  r.frameMs = ms;
  r.primaryReference = kPrimaryHardReference;
  r.hard.all.rmse = r.soft.all.rmse = areaRmse;
  r.hardPoint.all.rmse = r.softPoint.all.rmse = pointRmse;
  return r;
}

const ClaimCheck* claim(const std::vector<ClaimCheck>& claims, const std::string& id,
                        const std::string& scene) {
  for (const ClaimCheck& c : claims)
    if (c.id == id && c.scene == scene) return &c;
  return nullptr;
}

TEST(BenchClaims, VerdictsRestOnTheFairSetups) {
  BenchResult r;
  // gems16: better than samples=1 against the pixel area, worse against the pixel centre.
  // The verdict rests on the edge band; RMSE and the temporal change beside
  // (the fence's quick-bench numbers: 16 samples lose on RMSE but flicker less).
  r.rows.push_back(claimRow("brabec", "modern.gems16", "default", 0.080, 0.038));
  r.rows.back().hard.band.rmse = 0.20;
  r.rows.back().temporalChange = 0.0049;
  r.rows.push_back(claimRow("brabec", "modern.gems16", "samples=1", 0.065, 0.028));
  r.rows.back().hard.band.rmse = 0.26;
  r.rows.back().temporalChange = 0.0073;
  // Smoothies: the best width of the sweep beats modern.hw, the width from the light does not.
  r.rows.push_back(claimRow("brabec", "modern.smoothies", "width=0.01", 0.001, 0.001));
  r.rows.push_back(
      claimRow("brabec", "modern.smoothies", kSmoothieWidthFromLightVariant, 0.5, 0.5));
  r.rows.back().params.extra["width"] = "0.0062";
  r.rows.push_back(claimRow("brabec", "modern.hw", "default", 0.1, 0.1));
  // Hybrid and volumes on an ordinary scene: not the fill-bound setting.
  r.rows.push_back(claimRow("brabec", "modern.hybrid", "default", 0.05, 0.05, 1.0));
  r.rows.push_back(claimRow("brabec", "modern.volumes", "default", 0.05, 0.05, 2.0));
  r.masks["brabec|modern.hybrid|default"] = Image(4, 4, 1, 1.0f);
  r.masks["brabec|modern.volumes|default"] = Image(4, 4, 1, 1.0f);
  // CSM on a bench scene (no minification) beats PCF: no minification claim there. On the
  // far trees the claim reads CSM's Fig. 10 row (5x5 kernel), not a default one, against the
  // better PCF; the numbers are the quick bench's (trees-far, 2048 map, 256x192).
  r.rows.push_back(claimRow("brabec", "modern.csm", "default", 0.01, 0.01));
  r.rows.push_back(claimRow("brabec", "modern.pcf", "default", 0.02, 0.02));
  const std::string far = std::string(kMinificationScene) + kFarSceneSuffix;
  r.rows.push_back(claimRow(far, "modern.csm", kCsmFig10Variant, 0.081, 0.179));
  r.rows.back().temporalChange = 0.0010;
  r.rows.push_back(claimRow(far, "modern.csm", "default", 0.5, 0.5));  // must not be read
  r.rows.push_back(claimRow(far, "modern.pcf", "default", 0.152, 0.057));
  r.rows.back().temporalChange = 0.0023;
  r.rows.push_back(claimRow(far, "modern.gems16", "default", 0.137, 0.058));
  r.rows.back().temporalChange = 0.0016;
  r.sceneNotes[kFillBoundScene] = "scene not present (assets/scenes/fill-bound.json)";
  const std::vector<ClaimCheck> claims = checkClaims(r);

  const ClaimCheck* gems = claim(claims, "gems16-vs-1", "brabec");
  ASSERT_NE(gems, nullptr);
  EXPECT_EQ(gems->verdict,
            "agrees (band RMSE lower; RMSE not lower; temporal change lower: flickers less)")
      << "the edge error decides; RMSE and flicker are reported beside it";
  EXPECT_NE(gems->setup.find("pixel=area"), std::string::npos) << gems->setup;

  const ClaimCheck* smoothies = claim(claims, "smoothies-soft", "brabec");
  ASSERT_NE(smoothies, nullptr);
  EXPECT_EQ(smoothies->verdict, "disagrees") << "the width from the light, not the sweep's best";
  EXPECT_NE(smoothies->setup.find("0.0062"), std::string::npos) << smoothies->setup;

  EXPECT_EQ(claim(claims, "csm-minification", "brabec"), nullptr)
      << "CSM's minification claim is checked on the far scene only";
  const ClaimCheck* csm = claim(claims, "csm-minification", far);
  ASSERT_NE(csm, nullptr);
  EXPECT_EQ(csm->verdict, "agrees") << "0.081 against the better PCF (gems16, 0.137), and "
                                       "steadier (0.0010 against 0.0016)";
  EXPECT_NE(csm->measured.find("modern.gems16"), std::string::npos) << csm->measured;
  EXPECT_NE(csm->setup.find("5x5"), std::string::npos) << csm->setup;
  EXPECT_NE(csm->setup.find(std::to_string(kMinificationMapTexels)), std::string::npos)
      << csm->setup;
  // With CSM's error above the better PCF's, the claim disagrees (the verdict is measured).
  BenchResult worse = r;
  for (BenchRow& row : worse.rows)
    if (row.scene == far && row.technique == "modern.csm" && row.variant == kCsmFig10Variant)
      row.hard.all.rmse = 0.2;
  const std::vector<ClaimCheck> worseClaims = checkClaims(worse);
  const ClaimCheck* against = claim(worseClaims, "csm-minification", far);
  ASSERT_NE(against, nullptr);
  EXPECT_EQ(against->verdict, "disagrees on error (flickers less)");

  EXPECT_EQ(claim(claims, "hybrid-vs-volumes", "brabec"), nullptr)
      << "the hybrid's claim is about fill-bound scenes";
  const ClaimCheck* hybrid = claim(claims, "hybrid-vs-volumes", kFillBoundScene);
  ASSERT_NE(hybrid, nullptr);
  EXPECT_EQ(hybrid->verdict, "not measured (scene not present)");
  // With the fill-bound scene measured, the hybrid's claim is checked there.
  BenchResult fill;
  fill.rows.push_back(claimRow(kFillBoundScene, "modern.hybrid", "default", 0.05, 0.05, 1.0));
  fill.rows.push_back(claimRow(kFillBoundScene, "modern.volumes", "default", 0.05, 0.05, 2.0));
  fill.masks[std::string(kFillBoundScene) + "|modern.hybrid|default"] = Image(4, 4, 1, 1.0f);
  fill.masks[std::string(kFillBoundScene) + "|modern.volumes|default"] = Image(4, 4, 1, 1.0f);
  const std::vector<ClaimCheck> fillClaims = checkClaims(fill);
  const ClaimCheck* measured = claim(fillClaims, "hybrid-vs-volumes", kFillBoundScene);
  ASSERT_NE(measured, nullptr);
  EXPECT_EQ(measured->verdict, "agrees") << "same masks, half the time: " << measured->measured;
  // The same medians with spreads that overlap: the verdict says the time order is not firm.
  BenchResult spread = fill;
  for (BenchRow& row : spread.rows) {
    row.framesTimed = 5;
    row.q1Ms = 0.5;
    row.q3Ms = 2.5;
  }
  const std::vector<ClaimCheck> spreadClaims = checkClaims(spread);
  const ClaimCheck* unsure = claim(spreadClaims, "hybrid-vs-volumes", kFillBoundScene);
  ASSERT_NE(unsure, nullptr);
  EXPECT_EQ(unsure->verdict.rfind("agrees (time ranking within the spread", 0), 0u)
      << unsure->verdict;
  // The hybrid slower: the verdict says why, in the run's pass times (its shadow map and
  // classification, pass ids 1 and 3, against the volume pass time saved, 3 -> 5) and Chan's
  // own limit (§3.4.1).
  BenchResult slow = fill;
  slow.rows[0].frameMs = 3.0;
  slow.rows[0].passes = {PassTime("map", 0.5), PassTime("classify", 1.0), PassTime("vol", 0.25)};
  slow.rows[0].passes[0].id = "1";
  slow.rows[0].passes[1].id = "3";
  slow.rows[0].passes[2].id = "5";
  slow.rows[1].passes = {PassTime("z-fail", 1.0)};
  slow.rows[1].passes[0].id = "3";
  const std::vector<ClaimCheck> slowClaims = checkClaims(slow);
  const ClaimCheck* slower = claim(slowClaims, "hybrid-vs-volumes", kFillBoundScene);
  ASSERT_NE(slower, nullptr);
  EXPECT_EQ(slower->verdict.rfind("disagrees (not cheaper)", 0), 0u) << slower->verdict;
  EXPECT_NE(slower->verdict.find("classification passes took 1.5 ms, its volume pass saved "
                                 "0.75 ms (1 -> 0.25 ms"),
            std::string::npos)
      << slower->verdict;
  EXPECT_NE(slower->verdict.find("§3.4.1: \"Ordinary shadow volumes will clearly run faster"),
            std::string::npos)
      << slower->verdict;
  for (const ClaimCheck& c : claims) {
    if (c.verdict.rfind("not measured", 0) != 0 && c.scene != "-") {
      EXPECT_FALSE(c.setup.empty()) << c.id << " on " << c.scene << " must cite its setup";
    }
  }
}

// ---- Which technique at this budget ------------------------------------------

BenchRow sceneRow(const std::string& scene, const std::string& technique,
                  const std::string& variant, double ms, double rmse) {
  BenchRow r = row(technique, ms, rmse);
  r.scene = scene;
  r.variant = variant;
  return r;
}

int rankOf(const std::vector<BenchRow>& rows, const std::string& technique) {
  for (const BenchRow& r : rows)
    if (r.technique == technique) return r.paretoRank;
  return -1;
}

TEST(BenchPareto, RanksArePeeledFronts) {
  // (time, error) in scene s: a (1, 0.5), b (2, 0.2), d (4, 0.1) form the first front;
  // c (3, 0.3) is dominated by b only: second front; e (5, 0.4) is dominated by c (and b, d):
  // third front; f equal to b shares b's rank (neither dominates the other). The reference
  // and a row that did not run are not ranked; scene t is ranked on its own.
  std::vector<BenchRow> rows = {row("a", 1, 0.5),
                                row("b", 2, 0.2),
                                row("c", 3, 0.3),
                                row("d", 4, 0.1),
                                row("e", 5, 0.4),
                                row("f", 2, 0.2),
                                row("reference.hard", 0.5, 0.0),
                                row("broken", 0.1, 0.0)};
  rows.back().status = "invalid: no";
  rows.push_back(sceneRow("t", "g", "default", 9, 0.9));
  assignParetoRanks(rows);
  EXPECT_EQ(rankOf(rows, "a"), 1);
  EXPECT_EQ(rankOf(rows, "b"), 1);
  EXPECT_EQ(rankOf(rows, "d"), 1);
  EXPECT_EQ(rankOf(rows, "f"), 1) << "an equal row is not dominated";
  EXPECT_EQ(rankOf(rows, "c"), 2);
  EXPECT_EQ(rankOf(rows, "e"), 3);
  EXPECT_EQ(rankOf(rows, "reference.hard"), 0) << "the truth is not a competitor";
  EXPECT_EQ(rankOf(rows, "broken"), 0);
  EXPECT_EQ(rankOf(rows, "g"), 1) << "alone on its scene";
  // The first front is paretoFront's (which keeps one of two equal rows).
  for (size_t i : paretoFront(rows, "s")) EXPECT_EQ(rows[i].paretoRank, 1) << rows[i].technique;
}

TEST(BenchOutput, SortedBySceneThenTimeWithFailedRowsLast) {
  std::vector<BenchRow> rows = {
      sceneRow("fence", "x", "default", 3, 0.1), sceneRow("brabec", "y", "default", 5, 0.1),
      sceneRow("brabec", "z", "default", 0, 0.0), sceneRow("brabec", "w", "default", 1, 0.1),
      sceneRow("fence", "v", "default", 2, 0.1)};
  rows[2].status = "invalid: rejected";  // did not run: its time 0 means nothing
  sortRowsBySceneThenTime(rows);
  std::vector<std::string> order;
  for (const BenchRow& r : rows) order.push_back(r.scene + " " + r.technique);
  EXPECT_EQ(order,
            (std::vector<std::string>{"brabec w", "brabec y", "brabec z", "fence v", "fence x"}));
}

TEST(BenchBudget, RanksVariantsWithinTheBudgetByError) {
  std::vector<BenchRow> rows = {
      sceneRow("s", "fast-bad", "default", 2, 0.30),          // within, worst error
      sceneRow("s", "mid-good", "filter=4", 10, 0.05),        // within, best error
      sceneRow("s", "edge", "default", 20, 0.10),             // exactly at the budget: within
      sceneRow("s", "slow", "default", 30, 0.01),             // best error but over budget
      sceneRow("s", "reference.hard", "pixel=area", 1, 0.0),  // never ranked
      sceneRow("s", "broken", "filter=1", 0, 0.0),
      sceneRow("t", "other", "default", 25, 0.2)};  // scene t: nothing within
  rows[5].status = "invalid: rejected";
  assignParetoRanks(rows);
  const std::vector<BudgetRanking> ranking = rankWithinBudget(rows, 20.0);
  ASSERT_EQ(ranking.size(), 2u);
  EXPECT_EQ(ranking[0].scene, "s");
  ASSERT_EQ(ranking[0].within.size(), 3u);
  EXPECT_EQ(rows[ranking[0].within[0]].technique, "mid-good");
  EXPECT_EQ(rows[ranking[0].within[1]].technique, "edge");
  EXPECT_EQ(rows[ranking[0].within[2]].technique, "fast-bad");
  EXPECT_EQ(ranking[0].overBudget, 1);
  EXPECT_EQ(ranking[0].notRun, 1);
  EXPECT_EQ(ranking[1].scene, "t");
  EXPECT_TRUE(ranking[1].within.empty());
  EXPECT_EQ(ranking[1].overBudget, 1);

  std::ostringstream table;
  printBudgetRanking(table, rows, 20.0);
  const std::string text = table.str();
  EXPECT_NE(text.find("scene s: 3 variants within budget"), std::string::npos) << text;
  EXPECT_NE(text.find("1 variant over budget"), std::string::npos) << text;
  EXPECT_EQ(text.find("reference.hard"), std::string::npos) << "references are not ranked";
  EXPECT_LT(text.find("mid-good"), text.find("fast-bad")) << text;
}

TEST(BenchBudget, ParsesOnlyPositiveNumbers) {
  EXPECT_DOUBLE_EQ(parseBudgetMs("20"), 20.0);
  EXPECT_DOUBLE_EQ(parseBudgetMs("0.5"), 0.5);
  for (const char* bad : {"abc", "0", "-1", "", "20ms", "0x10", "inf", "nan"})
    EXPECT_THROW(parseBudgetMs(bad), InputError) << bad;
}

TEST(BenchSweep, VariantsATechniqueRejectsOrRepeatsAreNotSwept) {
  for (bool quick : {true, false}) {
    for (const char* name : {"legacy.fast-pcf", "modern.fast-pcf"}) {
      const auto variants = sweepVariants(findTechnique(name), RenderParams{}, quick);
      bool sawFilter4 = false;
      for (const BenchVariant& v : variants) {
        EXPECT_TRUE(v.params.filter == 2 || v.params.filter == 4)
            << name << " " << v.label << ": fast PCF takes footprints 2 and 4 only";
        sawFilter4 |= v.params.filter == 4;
      }
      EXPECT_TRUE(sawFilter4) << name;
    }
    bool pcfFilter1 = false;  // plain PCF still sweeps the unfiltered footprint
    for (const BenchVariant& v : sweepVariants(findTechnique("legacy.pcf"), RenderParams{}, quick))
      pcfFilter1 |= v.params.filter == 1;
    EXPECT_TRUE(pcfFilter1);
    // modern.vsm: storage=8 is rejected, storage=float and bleed-reduction=0 are its defaults.
    for (const BenchVariant& v : sweepVariants(findTechnique("modern.vsm"), RenderParams{}, quick))
      EXPECT_TRUE(v.label != "storage=8" && v.label != "storage=float" &&
                  v.label != "bleed-reduction=0")
          << v.label;
  }
  // The CSM Table 1 grid: its 512 / order 16 / blur 3 cell is the default variant, and its
  // 256 / 16 / 3 cell is shadow-map=256.
  for (const BenchVariant& v : sweepVariants(findTechnique("modern.csm"), RenderParams{}, false)) {
    EXPECT_NE(v.label, "table1 shadow-map=512 order=16 blur=3");
    EXPECT_NE(v.label, "table1 shadow-map=256 order=16 blur=3");
    EXPECT_NE(v.label, "storage=8") << "modern.csm's default storage";
  }
}

std::string runShadowlab(const std::string& args, int& status) {
  std::string out;
  FILE* pipe = popen((std::string(SHADOWLAB_BINARY) + " " + args + " 2>&1").c_str(), "r");
  if (!pipe) return "popen failed";
  std::array<char, 4096> buffer{};
  while (fgets(buffer.data(), int(buffer.size()), pipe)) out += buffer.data();
  status = pclose(pipe);
  return out;
}

TEST(BenchCommand, BudgetMustBeAPositiveNumber) {
  // Refused before any work: one line, exit 2.
  for (const char* bad : {"abc", "0", "-1"}) {
    int status = 0;
    const std::string out = runShadowlab(std::string("bench --quick --budget-ms ") + bad, status);
    ASSERT_TRUE(WIFEXITED(status)) << out;
    EXPECT_EQ(WEXITSTATUS(status), 2) << bad << ": " << out;
    EXPECT_NE(out.find("--budget-ms"), std::string::npos) << out;
    EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << "one line: " << out;
  }
}

TEST(BenchCommand, HelpListsDefaultsScenesAndFiles) {
  int status = 0;
  const std::string help = runShadowlab("bench --help", status);
  EXPECT_EQ(status, 0) << help;
  for (const std::string& scene : benchScenes(false))
    EXPECT_NE(help.find(scene), std::string::npos) << scene << " missing from: " << help;
  for (const char* text : {"--budget-ms", "[out/bench]", "256x192", "400x300", "bench-SCENE.png",
                           "bench-SCENE.dat", "bench-SCENE.gp", "--csv FILE", "JSON line",
                           "fill-bound", "trees-far", "brabec-light-away"})
    EXPECT_NE(help.find(text), std::string::npos) << text << " missing from: " << help;
}

// The light-bleeding scene makes the Fig. 9 claim testable. VSM must leak on
// it (the scene is built for that), so the verdict is "agrees" or "disagrees", never "not
// exercised"; the real bench renders it (two techniques and the reference, quick window).
TEST(BenchClaims, BleedingSceneExercisesTheNoLeakClaim) {
  BenchOptions o;
  o.quick = true;
  o.progress = false;
  o.scenes = {kBleedingScene};
  o.outDir = (std::filesystem::path(SHADOWLAB_TEST_OUTPUT_DIR) / "bench-bleeding").string();
  std::ostringstream json;
  const BenchResult r = runBenchmark(o, json);
  const std::vector<ClaimCheck> claims = checkClaims(r);
  const ClaimCheck* leak = claim(claims, "csm-no-leak", kBleedingScene);
  ASSERT_NE(leak, nullptr);
  EXPECT_EQ(leak->verdict.find("not exercised"), std::string::npos) << leak->measured;
  EXPECT_EQ(leak->verdict, "agrees") << leak->measured;
  for (const BenchRow& row : r.rows) {
    if (row.technique == "modern.vsm") {
      EXPECT_GT(row.hard.leakShare, 0.01) << "VSM bleeds on the scene built for it";
    }
  }
  // The same run measures the baselines after VSM: EVSM4 and MSM keep the plank's shadow closed
  // where VSM shows the fence through it, and EVSM2's positive warp alone leaks a little (the
  // error columns repeat exactly from run to run; only the times vary).
  const ClaimCheck* order = claim(claims, "filtered-leak-order", kBleedingScene);
  ASSERT_NE(order, nullptr);
  EXPECT_EQ(order->verdict, "agrees") << order->measured;
}

TEST(BenchTiming, SpreadIsTheInterquartileRangeAndLargeAboveTheNamedShare) {
  BenchRow r = row("a", 10.0, 0.1);
  r.framesTimed = 5;
  r.q1Ms = 9.0;
  r.q3Ms = 9.0 + kSpreadFlagRatio * 10.0;  // exactly at the bound: not flagged
  EXPECT_DOUBLE_EQ(r.iqrMs(), kSpreadFlagRatio * 10.0);
  EXPECT_FALSE(r.spreadLarge());
  r.q3Ms += 0.5;
  EXPECT_TRUE(r.spreadLarge());
  // Overlapping interquartile ranges: this run cannot order the two by time.
  BenchRow b = row("b", 12.0, 0.1);
  b.q1Ms = 11.0;
  b.q3Ms = 13.0;
  EXPECT_FALSE(timesWithinSpread(r, b)) << "b has no timed frames: nothing to judge";
  b.framesTimed = 5;
  EXPECT_TRUE(timesWithinSpread(r, b)) << "[9, 12] and [11, 13] overlap";
  b.q1Ms = 12.5;
  EXPECT_FALSE(timesWithinSpread(r, b));
  EXPECT_FALSE(timesWithinSpread(b, r)) << "symmetric";
}

TEST(BenchMerge, RanksAreRecomputedOverEveryFileWithinSceneAndWindow) {
  // Run 1 alone: a (1 ms, 0.5) and b (2 ms, 0.2) are both on the front. Run 2 adds c (1 ms,
  // 0.1), which dominates both; d is the same scene at another window, ranked on its own.
  const fs::path dir = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "bench-merge";
  fs::create_directories(dir);
  auto withWindow = [](BenchRow r, int w, int h) {
    r.params.width = w;
    r.params.height = h;
    return r;
  };
  std::vector<BenchRow> one = {withWindow(row("a", 1, 0.5), 64, 48),
                               withWindow(row("b", 2, 0.2), 64, 48)};
  assignParetoRanks(one);
  ASSERT_EQ(one[0].paretoRank, 1);
  ASSERT_EQ(one[1].paretoRank, 1);
  std::ofstream(dir / "one.jsonl") << benchRowJsonLine(one[0]) << "\n"
                                   << benchRowJsonLine(one[1]) << "\n"
                                   << R"({"claim": "x", "verdict": "agrees"})"
                                   << "\n";
  BenchRow d = withWindow(row("d", 9, 0.9), 128, 96);
  d.paretoRank = 7;  // whatever its run said
  std::ofstream(dir / "two.jsonl")
      << benchRowJsonLine(withWindow(row("c", 1, 0.1), 64, 48)) << "\n\n"
      << benchRowJsonLine(d) << "\n";
  const std::vector<nlohmann::json> merged =
      mergeBenchRows({(dir / "one.jsonl").string(), (dir / "two.jsonl").string()});
  ASSERT_EQ(merged.size(), 4u) << "the claim and the blank line are skipped";
  std::map<std::string, nlohmann::json> rank;
  for (const nlohmann::json& j : merged) rank[j["technique"]] = j["pareto_rank"];
  EXPECT_EQ(rank["c"], 1);
  EXPECT_EQ(rank["a"], 2) << "dominated by c (as fast, lower error)";
  EXPECT_EQ(rank["b"], 2);
  EXPECT_EQ(rank["d"], 1) << "another window: ranked on its own";
  EXPECT_EQ(merged[0]["frame_ms"], 1.0) << "every other field as it was";
  // A line that is not a row names its file and line.
  std::ofstream(dir / "bad.jsonl") << benchRowJsonLine(one[0]) << "\n[1, 2]\n";
  try {
    mergeBenchRows({(dir / "bad.jsonl").string()});
    FAIL() << "a JSON array is not a bench row";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.jsonl line 2"), std::string::npos) << e.what();
  }
}

TEST(BenchRowJson, ParamsAreTheTechniquesFullEffectiveSetAndUnreadOptionsNull) {
  // GPU Gems PCF reads the map side and its --params, not --filter or --precision (it used to
  // print filter=2 precision=8 in every row); PCF reads --filter.
  BenchRow gems = row("modern.gems16", 1, 0.1);
  gems.params.filter = 3;  // given to the run, not read by the technique
  const nlohmann::json g = nlohmann::json::parse(benchRowJsonLine(gems));
  EXPECT_TRUE(g["filter"].is_null()) << g.dump();
  EXPECT_TRUE(g["precision"].is_null()) << g.dump();
  EXPECT_EQ(g["shadow_map"], gems.params.shadowMapTexels);
  for (const std::string& key : paramKeys(findTechnique("modern.gems16")))
    EXPECT_TRUE(g["params"].contains(key)) << key << ": every declared --param, at its default";
  EXPECT_FALSE(g["params"].contains("filter"));
  BenchRow pcf = row("modern.pcf", 1, 0.1);
  pcf.params.filter = 3;
  const nlohmann::json p = nlohmann::json::parse(benchRowJsonLine(pcf));
  EXPECT_EQ(p["filter"], 3);
  EXPECT_EQ(p["params"]["filter"], 3);
  // The CSV: empty cells where the JSON has null.
  std::ostringstream csv;
  writeCsvRows(csv, {gems});
  std::string header, line;
  std::istringstream in(csv.str());
  std::getline(in, header);
  std::getline(in, line);
  // orbit "", shadow_map, filter and precision empty, then the params object.
  EXPECT_NE(line.find(",\"\"," + std::to_string(gems.params.shadowMapTexels) + ",,,\"{"),
            std::string::npos)
      << line;
}

// The CSV's cells of one row by column name.
std::map<std::string, std::string> csvCells(const std::vector<BenchRow>& rows) {
  std::ostringstream csv;
  writeCsvRows(csv, rows);
  std::istringstream in(csv.str());
  std::string header, line;
  std::getline(in, header);
  std::getline(in, line);
  // The cells this test reads hold no quotes or commas; skip the quoted ones whole.
  auto split = [](const std::string& text) {
    std::vector<std::string> cells{""};
    bool quoted = false;
    for (char c : text) {
      if (c == '"') quoted = !quoted;
      if (c == ',' && !quoted)
        cells.emplace_back();
      else
        cells.back() += c;
    }
    return cells;
  };
  const std::vector<std::string> names = split(header), values = split(line);
  EXPECT_EQ(names.size(), values.size()) << line;
  std::map<std::string, std::string> out;
  for (size_t i = 0; i < names.size() && i < values.size(); ++i) out[names[i]] = values[i];
  return out;
}

TEST(BenchCsv, UnmeasuredCellsAreEmptyNotZero) {
  // A scene measured without reference.soft: the soft columns are empty, the hard ones numbers.
  BenchRow hardOnly = row("modern.hw", 2.0, 0.25);
  hardOnly.framesTimed = 1;
  hardOnly.softMeasured = false;
  std::map<std::string, std::string> cells = csvCells({hardOnly});
  EXPECT_EQ(cells.at("hard_rmse"), "0.25");
  EXPECT_EQ(cells.at("hard_point_leak_share"), "0");
  for (const char* column : {"soft_rmse", "soft_band_max_abs", "soft_leak_share", "soft_point_rmse",
                             "soft_point_leak_share"})
    EXPECT_EQ(cells.at(column), "") << column;
  // Measured against reference.soft: its columns are numbers, 0 included.
  hardOnly.softMeasured = true;
  cells = csvCells({hardOnly});
  EXPECT_EQ(cells.at("soft_rmse"), "0");
  EXPECT_EQ(cells.at("soft_point_leak_share"), "0");
  // A variant that did not run: no time and no error.
  BenchRow refused = row("modern.vsm", 0.0, 0.0);
  refused.status = "--param storage: not one of ...";
  refused.softMeasured = true;
  cells = csvCells({refused});
  for (const char* column : {"frame_ms", "wall_ms", "hard_rmse", "soft_rmse", "hard_point_rmse",
                             "metric", "scored_pixels", "left_out_share", "frames_timed"})
    EXPECT_EQ(cells.at(column), "") << column;
}

TEST(SweepFiles, TheGuidesExamplesLoad) {
  // docs/user-guide.md "Sweeps": the minimal and the full example are valid specs.
  for (const char* name : {"sweep-minimal.json", "sweep-full.json"}) {
    std::ifstream in(fs::path(SHADOWLAB_SOURCE_DIR) / "docs" / "examples" / name);
    ASSERT_TRUE(in) << name;
    const SweepPlan plan = planSweep(nlohmann::json::parse(in));
    EXPECT_FALSE(plan.rows.empty()) << name;
    for (const SweepRow& r : plan.rows) {  // each row sweeps only what its technique reads
      if (r.variant.find("filter=") != std::string::npos) {
        EXPECT_TRUE(readsOption(*r.technique, CommonOption::kFilter)) << name << r.variant;
      }
    }
  }
  std::ifstream in(fs::path(SHADOWLAB_SOURCE_DIR) / "docs" / "examples" / "sweep-full.json");
  const SweepPlan full = planSweep(nlohmann::json::parse(in));
  EXPECT_EQ(full.views.size(), 2u * 2u * 3u) << "scenes x sizes x orbits";
  EXPECT_EQ(full.repeat, 5);
  EXPECT_FALSE(full.softReference);
}

}  // namespace
}  // namespace sl::figures
