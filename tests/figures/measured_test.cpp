// Captions state measured numbers, never typed ones. The sentences
// under a caption (figures/measured.h) are computed from the run; the captions themselves
// carry only configuration and the papers' quoted numbers.
#include "figures/measured.h"

#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <sstream>

#include "figures/figure_spec.h"

using namespace sl;
using namespace sl::figures;

namespace {

PanelResult timed(const std::string& label, const std::string& technique,
                  std::vector<double> samples, const std::string& paper = "", int texels = 0) {
  PanelResult p;
  p.ok = true;
  p.spec.label = label;
  p.spec.technique = technique;
  p.spec.paperNumbers = paper;
  p.spec.shadowMapTexels = texels;
  p.frameSamples = samples;
  std::vector<double> sorted = samples;
  std::sort(sorted.begin(), sorted.end());
  p.milliseconds = sorted[sorted.size() / 2];
  p.timedFrames = int(samples.size());
  return p;
}

// A pass as a render through core/technique/passes.h reports it: its name, time and the role its
// table declares (PassSpec::role), by which figures pair passes.
PassTime pass(const std::string& name, double ms, PassRole role) {
  PassTime t(name, ms);
  t.role = role;
  return t;
}

// The numbers of a text: "2x2" gives 2 and 2, "0.25" one number, "-1.5" gives 1.5.
std::vector<std::string> numbersIn(const std::string& text) {
  static const std::regex number(R"(\d+(?:\.\d+)?)");
  std::vector<std::string> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), number);
       it != std::sregex_iterator(); ++it)
    out.push_back(it->str());
  return out;
}

std::string trimmed(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

TEST(Measured, PaperTimesParse) {
  EXPECT_NEAR(*paperMilliseconds("25-30 fps on an SGI Octane VPro/8"), 1000.0 / 27.5, 1e-9);
  EXPECT_NEAR(*paperMilliseconds("about 10 fps"), 100.0, 1e-9);
  EXPECT_NEAR(*paperMilliseconds("39 fps, 10,000 triangles"), 1000.0 / 39, 1e-9);
  EXPECT_NEAR(*paperMilliseconds("129 ms"), 129.0, 1e-9);
  EXPECT_FALSE(paperMilliseconds(" fps").has_value());
  EXPECT_FALSE(paperMilliseconds("").has_value());
}

TEST(Measured, TimingTrendIsJudgedCellByCellWithItsRounds) {
  FigureResult fig;
  fig.spec.id = "brabec-fig7";
  fig.panels.push_back(timed("(a) unfiltered", "legacy.ramp", {100, 100, 100}, "25-30 fps"));
  fig.panels.push_back(timed("(b) PCF", "legacy.pcf", {180, 190, 185}, "about 10 fps"));
  // Slower in the paper; ours the same in the median, one round slower: noise.
  fig.panels.push_back(timed("(c) fast PCF", "legacy.fast-pcf", {101, 120, 99}, "15-20 fps"));
  // Slower in the paper, faster in ours in every round.
  fig.panels.push_back(timed("(d) fast 4x4", "legacy.fast-pcf", {80, 85, 90}, "about 5 fps"));
  const std::vector<TrendCell> cells = timingTrend(fig);
  ASSERT_EQ(cells.size(), 3u);
  EXPECT_EQ(cells[0].baseline, "(a) unfiltered");
  EXPECT_EQ(cells[0].verdict, "holds (slower)");
  EXPECT_EQ(cells[0].roundsAgreeing, 3);
  EXPECT_EQ(cells[1].verdict,
            "does not hold: paper slower, ours the same in the median only "
            "(noise)");
  EXPECT_EQ(cells[1].roundsAgreeing, 1);
  EXPECT_EQ(cells[2].verdict, "does not hold: paper slower, ours faster in every round");
  const std::string html = measuredHtml(fig);
  EXPECT_NE(html.find("holds in 1 of 3 cells"), std::string::npos) << html;
  EXPECT_NE(html.find("185.0 / 100.0 = 1.85"), std::string::npos) << "ours, from the medians";
}

TEST(Measured, ConvolutionTrendTellsNoiseFromCostStructure) {
  FigureResult fig;
  fig.spec.id = "csm-table1";
  fig.spec.shadowMapTexels = 512;
  fig.panels.push_back(timed("C=none PCF S=256", "modern.hw", {10, 10, 10}, "76 fps", 256));
  // M=4: 7x7 faster than none in every round (cost structure).
  fig.panels.push_back(timed("C=none M=4 S=256", "modern.csm", {140, 139, 141}, "64 fps", 256));
  fig.panels.push_back(timed("C=7x7 M=4 S=256", "modern.csm", {116, 118, 117}, "62 fps", 256));
  fig.panels.back().passes = {{"3 vertical Gaussian 7x7", 9.0}};
  // M=8: faster in the median, slower in one round (noise).
  fig.panels.push_back(timed("C=none M=8 S=256", "modern.csm", {150, 150, 150}, "55 fps", 256));
  fig.panels.push_back(timed("C=7x7 M=8 S=256", "modern.csm", {140, 170, 130}, "52 fps", 256));
  // M=16: slower, as the paper.
  fig.panels.push_back(timed("C=none M=16 S=256", "modern.csm", {200, 200, 200}, "47 fps", 256));
  fig.panels.push_back(timed("C=7x7 M=16 S=256", "modern.csm", {260, 250, 255}, "41 fps", 256));
  const std::string html = measuredHtml(fig);
  EXPECT_NE(html.find("not slower than the cell without convolution in 2 of 3"), std::string::npos)
      << html;
  EXPECT_NE(html.find("1 of those invert in every interleaved round (cost structure), the "
                      "other 1 only in the median (noise)"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("3 vertical Gaussian 7x7 +9.0"), std::string::npos) << "per-pass delta";
}

// Chan Fig. 4-8: the bicubic frame against one comparison and the smoothie against the bicubic,
// per map size, ours from the medians beside the thesis's from its panels' numbers.
TEST(Measured, ChanFourEightComparesBicubicWithOneComparisonAndSmoothies) {
  FigureResult fig;
  fig.spec.id = "chan-4-8";
  fig.panels.push_back(timed("256² shadow map", "modern.hw", {40, 40, 40}, "16 ms", 256));
  fig.panels.back().passes = {{"1 depth from light", 5.0},
                              {"2 camera pass with shadow test", 30.0}};
  fig.panels.push_back(timed("256² bicubic", "modern.gems16", {90, 100, 110}, "129 ms", 256));
  fig.panels.back().spec.params = {{"kernel", "bicubic"}};
  fig.panels.back().passes = {{"1 depth from light", 5.0},
                              {"2 camera pass, 16-sample bicubic PCF", 90.0}};
  fig.panels.push_back(timed("256² smoothie", "modern.smoothies", {50, 50, 50}, "19 ms", 256));
  fig.panels.back().spec.params = {{"width", "0.025"}};
  const std::string html = measuredHtml(fig);
  EXPECT_NE(html.find("100.0 / 40.0 = 2.50"), std::string::npos) << html;
  EXPECT_NE(html.find("129 / 16 = 8.06"), std::string::npos) << "the thesis's ratio: " << html;
  EXPECT_NE(html.find("90.0 / 30.0 = 3.00"), std::string::npos) << "camera passes: " << html;
  EXPECT_NE(html.find("<td>0.50</td>"), std::string::npos) << "smoothie / bicubic: " << html;
  EXPECT_NE(html.find("0.15"), std::string::npos) << "thesis 19 / 129: " << html;
  EXPECT_NE(html.find("width 0.025"), std::string::npos) << html;
  EXPECT_NE(html.find("ours at 1 of 1."), std::string::npos)
      << "50 ms is faster than 100: " << html;
}

// Chan Fig. 3-7: the wrong-pixel counts of the overlay panels, with their shares.
TEST(Measured, ChanThreeSevenCountsWrongPixelsPerScene) {
  FigureResult fig;
  fig.spec.id = "chan-3-7";
  fig.spec.width = 100;
  fig.spec.height = 50;
  PanelResult p;
  p.ok = true;
  p.spec.technique = "modern.volumes";
  p.spec.scene = "dragon";
  p.spec.errorsOf = {"modern.hw", "modern.hybrid"};
  p.counters = {{"wrong_pixels modern.hw", 250},
                {"wrong_pixels modern.hybrid", 20},
                {"wrong_pixels of both", 10}};
  fig.panels.push_back(p);
  const std::string html = measuredHtml(fig);
  EXPECT_NE(html.find("<td>dragon</td><td>250 (5.0%)</td><td>20 (0.40%)</td><td>10</td>"
                      "<td>96.0%</td>"),
            std::string::npos)
      << html;
}

// Chan Fig. 3-7: each column's error and where the hybrid's time goes, from the run's own
// panels (errors, pass times by pass-table id, counters); the §3.4.1 limit quoted when slower.
TEST(Measured, ChanThreeSevenStatesErrorsAndWhereTheHybridsTimeGoes) {
  FigureResult fig;
  fig.spec.id = "chan-3-7";
  fig.spec.scene = "brabec";
  const auto panel = [](const std::string& technique, double rmse, double ms) {
    PanelResult p;
    p.ok = true;
    p.spec.technique = technique;
    p.error = MaskDifference{};
    p.error->rmse = rmse;
    p.milliseconds = ms;
    return p;
  };
  PanelResult sm = panel("modern.hw", 0.02, 5.0);
  PanelResult hy = panel("modern.hybrid", 0.03, 40.0);
  PanelResult sv = panel("modern.volumes", 0.03, 30.0);
  hy.passes = {PassTime("map", 4.0), PassTime("classify", 16.0), PassTime("volumes", 2.0)};
  hy.passes[0].id = "1";
  hy.passes[1].id = "3";
  hy.passes[2].id = "5";
  sv.passes = {PassTime("z-fail", 6.0)};
  sv.passes[0].id = "3";
  hy.counters = {{"silhouette_fraction", 0.05}, {"masked_overdraw", 0.5}};
  sv.counters = {{"volume_overdraw", 3.0}};
  PanelResult overlay = sv;
  overlay.spec.errorsOf = {"modern.hw", "modern.hybrid"};
  fig.panels = {sm, hy, sv, overlay};
  const std::string html = measuredHtml(fig);
  EXPECT_NE(html.find("at most the shadow map's with the same map on 0 of 1 scenes; where it is "
                      "above, so are the exact shadow volumes on 1 of 1"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("<td>brabec</td><td>0.0200</td><td>0.0300</td><td>0.0300</td>"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("slower than the volumes on 1 of 1 scenes"), std::string::npos) << html;
  EXPECT_NE(html.find("Ordinary shadow volumes will clearly run faster"), std::string::npos)
      << html;
  EXPECT_NE(html.find("<td>40.0 / 30.0 = 1.33</td><td>5.0%</td><td>0.50 of 3.00</td><td>20.0</td>"
                      "<td>4.0</td>"),
            std::string::npos)
      << html;
}

// Every number in a caption is configuration (the figure's sizes, maps, panel parameters and
// labels, close-up magnifications) or the paper's, in a clause that names its source; a
// measured number (an overdraw, a ratio, a share) typed into a caption fails here. The
// technique constants a caption explains are listed with where they come from.
TEST(Measured, CaptionsCarryNoUnmeasuredNumbers) {
  const std::set<std::string> constants = {
      "0",   "1",  "2",  // structural words: "box 1", "between 0 and 1", "scaling by 2"
      "64",              // modern.hybrid's tile side (64x64 tiles, chan-3-11)
      "1.5",             // modern.gems16's sample offsets (-1.5..1.5 texels, gems-11-6to9)
      "0.5", "8",        // CSM's 8-bit basis storage, 0.5 = zero (csm-fig5, csm-fig6)
      "4",   "16",       // csm-fig3's orders M = 4, 8, 16 (a computed chart has no panels)
      "32",              // legacy_gl's kDifferenceDisplayGain: differences shown amplified 32x
      "12",              // --precision 12, Brabec–Seidel §6's 12-bit buffers (brabec-fig8)
  };
  static const std::regex source(
      R"(The paper:|paper's own|thesis's|chapter's|Chan's|Chan:|Annen|Brabec|Everitt|Kilgard|GeForce|SGI|Octane|their |Eq\. |Figs?\. |§)");
  for (const FigureSpec& f : figureList()) {
    std::set<std::string> config = {std::to_string(f.width), std::to_string(f.height),
                                    std::to_string(f.shadowMapTexels)};
    auto addAll = [&](const std::string& text) {
      for (const std::string& n : numbersIn(text)) config.insert(n);
    };
    addAll(f.title);
    addAll(f.paperFigure);
    addAll(f.paperNumbers);
    for (const Closeup& c : f.closeups) config.insert(std::to_string(c.magnify));
    for (const PanelSpec& p : f.panels) {
      addAll(p.label);
      for (const auto& [k, v] : p.params) addAll(v);
      config.insert(std::to_string(p.shadowMapTexels));
      config.insert(std::to_string(p.filter));
      config.insert(trimmed(p.cameraDistance));
      if (p.lightRadius) config.insert(trimmed(*p.lightRadius));
      for (const Closeup& c : p.ownCloseups) config.insert(std::to_string(c.magnify));
    }
    // Clauses: split at sentence ends (a full stop before a capital), semicolons and
    // parentheses; "Eq. 10-14" stays one clause.
    std::string clause;
    const std::string text = f.caption + ".";
    for (size_t i = 0; i < text.size(); ++i) {
      const char c = text[i];
      const bool end = c == ';' || c == '(' || c == ')' ||
                       (c == '.' && (i + 1 == text.size() ||
                                     (text[i + 1] == ' ' && i + 2 < text.size() &&
                                      std::isupper(static_cast<unsigned char>(text[i + 2])))));
      if (!end) {
        clause += c;
        continue;
      }
      if (!std::regex_search(clause, source)) {
        for (const std::string& n : numbersIn(clause)) {
          EXPECT_TRUE(config.count(n) || constants.count(n))
              << f.id << ": the caption's number " << n << " is neither configuration nor "
              << "quoted from a paper: \"" << clause << "\"";
        }
      }
      clause.clear();
    }
  }
}

// Table 1's map-size and order trends, with verdicts, as the convolution's.
TEST(Measured, MapSizeAndOrderTrendsHaveVerdicts) {
  FigureResult fig;
  fig.spec.id = "csm-table1";
  const auto cell = [&](const std::string& label, std::vector<double> samples, int texels) {
    fig.panels.push_back(timed(label, "modern.csm", samples, "50 fps", texels));
  };
  // PCF: slower at 2048² in every round (holds).
  cell("C=none PCF S=256", {10, 10, 10, 10, 10, 10, 10}, 256);
  cell("C=none PCF S=2048", {30, 31, 29, 30, 30, 30, 30}, 2048);
  // M=4: 2048² faster than 256² in every round (cost structure).
  cell("C=none M=4 S=256", {100, 100, 100, 100, 100, 100, 100}, 256);
  cell("C=none M=4 S=2048", {80, 81, 79, 80, 80, 80, 80}, 2048);
  fig.panels.back().passes = {{"4 mip-map", 3.5}};
  // M=16: 256² slower than M=4 in every round (holds); 2048² faster than M=4 in the median, but
  // three of seven rounds slower (noise).
  cell("C=none M=16 S=256", {150, 150, 150, 150, 150, 150, 150}, 256);
  cell("C=none M=16 S=2048", {200, 70, 200, 70, 200, 70, 70}, 2048);
  const std::string html = measuredHtml(fig);
  // Size: PCF holds, M=4 inverted in every round, M=16 200/70 vs 150: median 70 < 150, inverted,
  // three rounds going the paper's way.
  EXPECT_NE(html.find("Measured: the map-size trend"), std::string::npos) << html;
  EXPECT_NE(html.find("the 2048² cell is not slower than the 256² cell in 2 of 3 (C, M) rows; 1 "
                      "of those invert in every interleaved round"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("holds (2048² slower)"), std::string::npos);
  EXPECT_NE(html.find("inverted in every round (2048² faster): cost structure, not noise"),
            std::string::npos);
  EXPECT_NE(html.find("inverted in the median, the rounds disagree (3 of 7 go the paper's way): "
                      "noise"),
            std::string::npos);
  EXPECT_NE(html.find("4 mip-map +3.5"), std::string::npos) << "per-pass delta, 2048² minus 256²";
  // Order: S=256 holds (M=16 slower), S=2048 inverted in the median only.
  EXPECT_NE(html.find("Measured: the order trend"), std::string::npos) << html;
  EXPECT_NE(html.find("the M=16 cell is not slower than the M=4 cell in 1 of 2 (C, S) pairs; 0 "
                      "of those invert in every interleaved round"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("holds (M=16 slower)"), std::string::npos);
  // The PCF rows are no order (M) comparison.
  EXPECT_EQ(html.find("<td>C=none PCF</td><td>100.0 / 33.3"), html.rfind("<td>C=none PCF</td>"))
      << "PCF is in the size trend once and nowhere else";
}

// Brabec Fig. 8 explains its timing pass by pass, as Fig. 7, from the run's
// pass times; and its 12-bit claim is the run's counts.
TEST(Measured, BrabecFig8ExplainsItsTimingPassByPassAndCountsTheBiasTrade) {
  FigureResult fig;
  fig.spec.id = "brabec-fig8";
  fig.panels.push_back(timed("(a) unfiltered", "legacy.ramp", {100, 98, 99}, "about 15 fps"));
  using R = PassRole;
  fig.panels.back().passes = {
      pass("mesh feeding: triangles split", 0.0, R::kMesh),
      pass("1 light pass: depth ramp into alpha + copy to texture", 17.6, R::kLight),
      pass("2 camera pass: light depth ramp into alpha", 12.2, R::kCamera),
      pass("3 projective pass: subtract shadow map", 25.2, R::kProjective),
      pass("4 copy: shadow mask to 0 / 1", 7.9, R::kCopy),
      pass("5 lighting x shadow mask", 36.0, R::kLighting)};
  fig.panels.back().counters = {{kLeakPixelsCounter, 1013}, {kAcnePixelsCounter, 328}};
  fig.panels.push_back(timed("(b) fast PCF 2x2", "legacy.fast-pcf", {90, 88, 89}, "about 10 fps"));
  fig.panels.back().passes = {
      pass("mesh feeding: triangles split", 0.0, R::kMesh),
      pass("1 light pass: depth ramp in RGBA", 9.9, R::kLight),
      pass("2 copy to texture through the 3x3 packing convolution", 2.0, R::kCopyToTexture),
      pass("3 camera pass: light depth in RGBA", 18.4, R::kCamera),
      pass("4 projective pass: subtract packed map", 18.2, R::kProjective),
      pass("5 copy: colour table + colour matrix -> alpha", 1.8, R::kCopy),
      pass("7 lighting x shadow term", 38.7, R::kLighting)};
  fig.panels.push_back(timed("(c) unfiltered, 12-bit", "legacy.ramp", {101, 99, 100}));
  fig.panels.back().counters = {{kLeakPixelsCounter, 54}, {kAcnePixelsCounter, 4763}};
  const std::string html = measuredHtml(fig);
  EXPECT_NE(html.find("(b) fast PCF 2x2 against (a) unfiltered, pass by pass"), std::string::npos)
      << html;
  // The packing copy has no partner (a copy to texture is not a glCopyPixels copy); 2.0 ms of an
  // 89 ms frame.
  EXPECT_NE(html.find("adds: 2 copy to texture through the 3x3 packing convolution 2.0 ms, "
                      "together 2.0 ms, 2.2% of its frame"),
            std::string::npos)
      << html;
  // Paper: 100 ms against 66.7 ms, ratio 1.50: the added work would be a third of the frame.
  EXPECT_NE(html.find("The paper's ratio (1.50) needs the work (b) fast PCF 2x2 adds to cost "
                      "33.3% of its frame"),
            std::string::npos)
      << html;
  // 2.2% is under half of 33.3%: the filtering cannot be what orders the two frames.
  EXPECT_NE(html.find("its added passes cost 2.2%, too little to make the paper's ratio: the "
                      "paired passes"),
            std::string::npos)
      << html;
  // Paired: light -7.7, camera +6.2, projective -7.0, copy -6.1, lighting +2.7, mesh 0.
  EXPECT_NE(html.find("The paired passes differ by -11.9 ms in total, the most 1 light pass: "
                      "depth ramp in RGBA (-7.7 ms)"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("<tr><td>4 copy: shadow mask to 0 / 1</td><td>7.9</td><td>5 copy: "
                      "colour table + colour matrix -&gt; alpha</td><td>1.8</td></tr>"),
            std::string::npos)
      << "the mask copies pair up";
  EXPECT_NE(html.find("the leak falls 1013 -&gt; 54 pixels and the acne rises 328 -&gt; 4763 "
                      "pixels"),
            std::string::npos)
      << html;
}
