// tests/figures/entries_test.cpp — the entries of csm-fig1, csm-fig10,
// csm-table1, everitt-fig6 and brabec-fig8 as the review asked for them (panel order, the
// paper's kernel, close-ups under strong minification, rounds, the timing disclaimer, the
// 12-bit panel and its counts), and the light's view of Everitt Fig. 6 colour-coded where the
// eye sees it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/scene/scene_library.h"
#include "figures/diagnostics.h"
#include "figures/figure_spec.h"

using namespace sl;
using namespace sl::figures;

namespace {

const FigureSpec& listed(const std::string& id) {
  for (const FigureSpec& f : figureList())
    if (f.id == id) return f;
  ADD_FAILURE() << id << " is not in figureList()";
  static const FigureSpec none;
  return none;
}

std::string param(const PanelSpec& p, const std::string& key) {
  const auto it = p.params.find(key);
  return it == p.params.end() ? "" : it->second;
}

std::string firstSentence(const std::string& caption) {
  return caption.substr(0, caption.find(". "));
}

}  // namespace

// Annen et al. §5: "The top row in Figure 10 shows aliasing ... in the PCF renderings. The bottom
// row shows the same scene rendered with CSMs." The camera moves away along each row.
TEST(FigureEntries, CsmFig10RowsAreThePapersPcfAboveCsm) {
  const FigureSpec& f = listed("csm-fig10");
  ASSERT_EQ(f.columns, 4);
  ASSERT_EQ(f.panels.size(), 8u);
  for (size_t i = 0; i < f.panels.size(); ++i) {
    const PanelSpec& p = f.panels[i];
    const bool top = i < 4;
    EXPECT_EQ(p.technique, top ? "modern.hw" : "modern.csm") << p.label;
    EXPECT_EQ(p.label.rfind(top ? "PCF" : "CSM", 0), 0u) << p.label;
    EXPECT_FLOAT_EQ(p.cameraDistance, float(i % 4 + 1)) << p.label;
    if (!top) {
      EXPECT_EQ(param(p, "filtering"), "trilinear");
      EXPECT_EQ(param(p, "blur"), "5") << "the paper's caption: a 5x5 filter kernel";
    }
  }
}

// Close-ups where the minification is strong (the two farthest columns, both rows, the same
// rectangle so that PCF and CSM compare pixel for pixel), none on the near columns.
TEST(FigureEntries, CsmFig10MagnifiesTheFarColumnsOfBothRows) {
  const FigureSpec& f = listed("csm-fig10");
  ASSERT_EQ(f.panels.size(), 8u);
  for (size_t i = 0; i < f.panels.size(); ++i) {
    const PanelSpec& p = f.panels[i];
    const bool far = p.cameraDistance >= 3.0f;
    EXPECT_EQ(p.closeups, far) << p.label;
    EXPECT_EQ(p.ownCloseups.size(), far ? 1u : 0u) << p.label;
    if (far && i >= 4) {
      const Closeup &pcf = f.panels[i - 4].ownCloseups.at(0), &csm = p.ownCloseups.at(0);
      EXPECT_EQ(pcf.x, csm.x);
      EXPECT_EQ(pcf.y, csm.y);
      EXPECT_EQ(pcf.w, csm.w);
      EXPECT_GT(csm.magnify, 1);
    }
  }
}

// Annen Fig. 1's CSM panel: "CSM with 7x7 blur and mip-mapping".
TEST(FigureEntries, CsmFig1BlursWithThePapersSevenBySeven) {
  const FigureSpec& f = listed("csm-fig1");
  ASSERT_FALSE(f.panels.empty());
  const PanelSpec& last = f.panels.back();
  EXPECT_EQ(last.technique, "modern.csm");
  EXPECT_EQ(param(last, "blur"), "7");
  EXPECT_EQ(param(last, "filtering"), "trilinear");
  EXPECT_NE(last.label.find("7x7"), std::string::npos) << last.label;
  EXPECT_EQ(f.caption.find("5x5"), std::string::npos) << "the caption still names the old kernel";
}

// Table 1: at least 7 interleaved rounds per cell, and the caption opens by
// saying a CPU rasteriser cannot reproduce the paper's GPU frame rates.
TEST(FigureEntries, CsmTable1TimesSevenRoundsAndSaysWhatACpuCannotReproduce) {
  const FigureSpec& f = listed("csm-table1");
  EXPECT_GE(f.timingRounds, 7);
  const std::string first = firstSentence(f.caption);
  EXPECT_NE(first.find("CPU rasteriser"), std::string::npos) << first;
  EXPECT_NE(first.find("cannot be reproduced"), std::string::npos) << first;
}

// Everitt Fig. 6 right: the light's view colour-coded, not the plain shaded light view.
TEST(FigureEntries, EverittFig6ColoursTheLightsView) {
  const FigureSpec& f = listed("everitt-fig6");
  ASSERT_EQ(f.panels.size(), 3u);
  EXPECT_EQ(f.panels[0].kind, PanelKind::kTexelDensity);
  EXPECT_EQ(f.panels[2].kind, PanelKind::kLightDensity);
}

// Brabec Fig. 8: the timing disclaimer first; (a) and (b) the paper's; (c) the 12-bit frame
// whose leak and acne the run counts beside (a)'s.
TEST(FigureEntries, BrabecFig8CountsTheTwelveBitTrade) {
  const FigureSpec& f = listed("brabec-fig8");
  const std::string first = firstSentence(f.caption);
  EXPECT_NE(first.find("CPU rasteriser"), std::string::npos) << first;
  EXPECT_NE(first.find("cannot be reproduced"), std::string::npos) << first;
  ASSERT_EQ(f.panels.size(), 3u);
  EXPECT_EQ(f.panels[0].technique, "legacy.ramp");
  EXPECT_EQ(f.panels[1].technique, "legacy.fast-pcf");
  EXPECT_FALSE(f.panels[0].paperNumbers.empty());
  EXPECT_FALSE(f.panels[1].paperNumbers.empty());
  const PanelSpec& twelve = f.panels[2];
  EXPECT_EQ(twelve.technique, "legacy.ramp");
  ASSERT_TRUE(twelve.precision.has_value());
  EXPECT_EQ(*twelve.precision, Precision::k12);
  // Two 12-bit steps, in depth-bias's 8-bit unit: 2 * 256 / 4096.
  constexpr double kTwoTwelveBitSteps = 2.0 * 256.0 / 4096.0;
  EXPECT_DOUBLE_EQ(std::stod(param(twelve, "depth-bias")), kTwoTwelveBitSteps);
  EXPECT_TRUE(twelve.paperNumbers.empty()) << "(c) is ours, no paper time beside it";
  EXPECT_TRUE(f.panels[0].countDepthErrors);
  EXPECT_FALSE(f.panels[1].countDepthErrors);
  EXPECT_TRUE(twelve.countDepthErrors);
}

// Everitt et al., Fig. 6: "The light's view (right) shows the very small portion of the light's
// image plane [that] needs high frequency sampling." On the dueling scene, the light-view pixels
// drawn blue (one texel over 2 or more eye pixels) must exist and be a far smaller share of the
// light's image than the blue share of the eye's image, and the light's surfaces the eye does
// not see (hidden behind the objects from the eye) must stay grey.
TEST(LightDensity, TheMagnifiedPartIsASmallPatchOfTheLightsView) {
  const Scene scene = loadScene("dueling");
  constexpr int kWidth = 512, kHeight = 384, kTexels = 512;  // everitt-fig6's size and map
  const DiagnosticViews v = renderDiagnostics(scene, kWidth, kHeight, kTexels, kHeight);
  ASSERT_EQ(v.lightDensity.width, kHeight);
  ASSERT_EQ(v.lightDensity.channels, 3);
  // densityColor's blue end: 4 or more eye pixels per texel is (0, 0, 1).
  float blue[3];
  densityColor(4.0f, blue);
  ASSERT_EQ(blue[2], 1.0f);
  // Above one pixel per texel densityColor's B is log2(pixels per texel) / 2 and R is 0: B above
  // 0.5 is more than 2 eye pixels per texel, the magnified end the dueling scene reaches (its
  // nearest ground is about 2.3; the unseen grey stays below 0.45).
  constexpr float kBlue = 0.5f;
  const auto blueShare = [&](const Image& im) {
    long n = 0;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x)
        n += im.at(x, y, 2) > kBlue && im.at(x, y, 0) == 0.0f ? 1 : 0;
    return double(n) / double(im.width * im.height);
  };
  const double eye = blueShare(v.texelDensity), light = blueShare(v.lightDensity);
  EXPECT_GT(eye, 0.02) << "the dueling scene's near ground is magnified in the eye's view";
  EXPECT_GT(light, 0.0) << "the magnified part must show in the light's view";
  // The paper's "very small portion": measured 2026-12-03 at the figure's size (512x384, 512²),
  // 6.4% of the eye's image against 0.28% of the light's (a 23rd); a quarter is a wide margin.
  EXPECT_LT(light, 0.25 * eye) << "eye " << eye << ", light " << light;
  // Grey where the eye does not see (R = G = B, the unlit background black): on the dueling
  // scene the ground behind the objects, seen from the eye, and the objects' far sides.
  long grey = 0, surface = 0;
  for (int y = 0; y < v.lightDensity.height; ++y)
    for (int x = 0; x < v.lightDensity.width; ++x) {
      const float r = v.lightDensity.at(x, y, 0), g = v.lightDensity.at(x, y, 1),
                  b = v.lightDensity.at(x, y, 2);
      if (r == 0.0f && g == 0.0f && b == 0.0f) continue;  // no geometry (or a black density)
      ++surface;
      grey += r == g && g == b ? 1 : 0;
    }
  ASSERT_GT(surface, 0);
  const double unseen = double(grey) / double(surface);
  // Measured 2026-12-03: 67% of the light's surface pixels unseen by the eye; with the
  // visibility test switched off (every light-view point inside the eye's frustum coloured)
  // 12%, only what lies outside the eye's frustum. Half-way between is the bound.
  constexpr double kUnseenAtLeast = 0.4;
  EXPECT_GT(unseen, kUnseenAtLeast) << "the eye's occlusion must leave the light's view grey";
}
