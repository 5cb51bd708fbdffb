// modern.gems16 / modern.gems4 (Bunnell & Pellacini, GPU Gems ch. 11) on the analytic scene.
//
// Each hardware lookup is a bilinear 2x2 percentage-closer filter (Fig. 11-3), so it changes
// by at most |du| + |dv| when its coordinate moves by (du, dv) texels. That Lipschitz bound
// turns the chapter's claims into inequalities we can check between pixels.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/errors.h"
#include "filtered_shadows_util.h"

namespace sl {
namespace {
using namespace sl::testing_filtered;

// The analytic scene seen from just under the occluder, looking straight down at the corner
// (2/3, 2/3) of its shadow on the ground: the view is all ground, half umbra, half lit, and
// about 0.66 x 0.5 units wide.
Scene zoomedAnalytic() {
  Scene scene = builtinScene("analytic");
  scene.camera.position = {0.6f, 0.9f, 0.6f};
  scene.camera.target = {0.6f, 0.0f, 0.6f};
  scene.camera.up = {0.0f, 0.0f, -1.0f};
  scene.camera.nearPlane = 0.1f;
  return scene;
}

float minOf(const Image& m) { return *std::min_element(m.data.begin(), m.data.end()); }
float maxOf(const Image& m) { return *std::max_element(m.data.begin(), m.data.end()); }

// Horizontal and vertical neighbour pairs whose visibility jumps by more than half.
int hardEdges(const Image& m) {
  int n = 0;
  for (int y = 0; y + 1 < m.height; ++y)
    for (int x = 0; x + 1 < m.width; ++x)
      n += (std::abs(m.at(x, y) - m.at(x + 1, y)) > 0.5f) +
           (std::abs(m.at(x, y) - m.at(x, y + 1)) > 0.5f);
  return n;
}

TEST(Gems, SixteenSamplesHaveFewerHardEdgesThanOne) {
  const Scene scene = zoomedAnalytic();
  // 2048^2: 0.0027 units per texel against 0.0026 per pixel, so that a single 2x2 lookup
  // spreads an edge over about one pixel (hard) and the 4x4 region over about four (soft).
  const Frame one =
      renderByName("modern.gems16", scene, smallParams(256, 192, 2048, {{"samples", "1"}}));
  const Frame sixteen = renderByName("modern.gems16", scene, smallParams(256, 192, 2048));
  for (const Frame* f : {&one, &sixteen}) {
    ASSERT_TRUE(allFinite(f->visibility));
    EXPECT_GE(minOf(f->visibility), 0.0f);
    EXPECT_LE(maxOf(f->visibility), 1.0f);
    EXPECT_LT(minOf(f->visibility), 0.01f);  // an umbra exists
  }
  const int hardOne = hardEdges(one.visibility), hardSixteen = hardEdges(sixteen.visibility);
  EXPECT_GT(hardOne, 50) << "one lookup should leave a jagged edge";
  EXPECT_LT(hardSixteen, hardOne / 4) << "16 samples: " << hardSixteen << ", 1: " << hardOne;
}

TEST(Gems, FourDitheredSamplesAverageToSixteenOverEach2x2Block) {
  const Scene scene = zoomedAnalytic();
  // A small map (64^2) magnified on screen keeps the shadow-map coordinates of the four
  // pixels of a block within a fraction of a texel, where the bound below is tight.
  const int kTexels = 64;
  const RenderParams p = smallParams(256, 192, kTexels);
  const Frame four = renderByName("modern.gems4", scene, p);
  const Frame sixteen = renderByName("modern.gems16", scene, p);
  ASSERT_TRUE(allFinite(four.visibility));
  EXPECT_GE(minOf(four.visibility), 0.0f);
  EXPECT_LE(maxOf(four.visibility), 1.0f);
  // Fig. 11-4: the four pixels of a 2x2 block (even x, even y) take the dither offsets
  // (0,0), (1,1), (0,1), (1,0), which together cover all 16 samples of §11.3 once. So the
  // block's mean of gems4 equals the block's mean of gems16, up to how far each pixel's
  // lookup point lies from the others (|du| + |dv| texels per lookup, at most 2 pixels).
  int penumbraBlocks = 0, ditheredBlocks = 0;
  for (int y = 0; y + 1 < p.height; y += 2)
    for (int x = 0; x + 1 < p.width; x += 2) {
      const glm::vec3 g0 = groundPointOf(scene, p, float(x), float(y));
      const glm::vec3 g1 = groundPointOf(scene, p, float(x + 1), float(y + 1));
      if (std::abs(g0.x) > 2.5f || std::abs(g0.z) > 2.5f) continue;  // ground inside the map
      const glm::vec2 t0 = shadowTexelOf(scene, kTexels, g0),
                      t1 = shadowTexelOf(scene, kTexels, g1);
      const glm::vec2 tx =
          shadowTexelOf(scene, kTexels, groundPointOf(scene, p, float(x + 1), float(y)));
      const float spread = std::abs(t1.x - t0.x) + std::abs(t1.y - t0.y) + std::abs(tx.x - t0.x) +
                           std::abs(tx.y - t0.y);
      double mean4 = 0, mean16 = 0;
      bool occluderInBlock = false;
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          mean4 += four.visibility.at(x + dx, y + dy) / 4.0;
          mean16 += sixteen.visibility.at(x + dx, y + dy) / 4.0;
          // The occluder itself does not receive shadows (1 in both): skip blocks it covers.
          occluderInBlock |=
              std::abs(groundPointOf(scene, p, float(x + dx), float(y + dy)).x) < 0.75f &&
              std::abs(groundPointOf(scene, p, float(x + dx), float(y + dy)).z) < 0.75f;
        }
      if (occluderInBlock || mean16 < 0.02 || mean16 > 0.98) continue;
      ++penumbraBlocks;
      // Also the residual v4 - v16 differs between the pixels of the block: the dither.
      float lo = 1, hi = -1;
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const float r =
              four.visibility.at(x + dx, y + dy) - sixteen.visibility.at(x + dx, y + dy);
          lo = std::min(lo, r);
          hi = std::max(hi, r);
        }
      ditheredBlocks += (hi - lo) > 2.0f * spread + 0.02f;
      // 8-bit visibility attachments add 1/255 per image.
      EXPECT_NEAR(mean4, mean16, spread + 2.0 / 255.0) << "block at " << x << "," << y;
    }
  EXPECT_GT(penumbraBlocks, 20) << "the test needs penumbra blocks to say anything";
  EXPECT_GT(ditheredBlocks, penumbraBlocks / 4) << "gems4 must differ from gems16 per pixel";
}

TEST(Gems, DitherRepeatsWithPeriodTwo) {
  // The residual of the dither (gems4 - gems16) at (x, y) and (x + 2, y) comes from the same
  // four of the sixteen samples: it may differ only by the lookup points' motion over two
  // pixels, whereas at (x + 1, y) it comes from four other samples.
  const Scene scene = zoomedAnalytic();
  const int kTexels = 64;
  const RenderParams p = smallParams(256, 192, kTexels);
  const Frame four = renderByName("modern.gems4", scene, p);
  const Frame sixteen = renderByName("modern.gems16", scene, p);
  auto residual = [&](int x, int y) {
    return four.visibility.at(x, y) - sixteen.visibility.at(x, y);
  };
  double periodTwo = 0, periodOne = 0;
  int n = 0;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x + 2 < p.width; ++x) {
      const float v = sixteen.visibility.at(x, y);
      if (v < 0.05f || v > 0.95f) continue;  // penumbra only
      const glm::vec3 g = groundPointOf(scene, p, float(x), float(y));
      if (std::abs(g.x) < 0.75f && std::abs(g.z) < 0.75f) continue;  // occluder covers it
      const glm::vec2 a = shadowTexelOf(scene, kTexels, g);
      const glm::vec2 b =
          shadowTexelOf(scene, kTexels, groundPointOf(scene, p, float(x + 2), float(y)));
      const float motion = std::abs(b.x - a.x) + std::abs(b.y - a.y);
      // Both images move: 2 * motion, plus 8-bit quantisation of each of the four values.
      EXPECT_NEAR(residual(x, y), residual(x + 2, y), 2.0f * motion + 4.0f / 255.0f)
          << x << "," << y;
      periodTwo += std::abs(residual(x, y) - residual(x + 2, y));
      periodOne += std::abs(residual(x, y) - residual(x + 1, y));
      ++n;
    }
  ASSERT_GT(n, 50);
  EXPECT_LT(periodTwo, 0.5 * periodOne) << "neighbours one apart use other samples";
}

// ---------------------------------------------------------------- --param kernel=bicubic
// The uniform cubic B-spline as a function of the distance d from a texel centre (Mitchell &
// Netravali 1988, B = 1, C = 0), written independently of bicubic_pcf.frag's per-axis
// polynomials w0..w3 (Sigg & Hadwiger's form): the two must agree.
double cubicBSpline(double d) {
  d = std::abs(d);
  if (d < 1.0) return 2.0 / 3.0 - d * d + 0.5 * d * d * d;
  if (d < 2.0) return (2.0 - d) * (2.0 - d) * (2.0 - d) / 6.0;
  return 0.0;
}

TEST(Gems, CubicBSplineOfTheTestHasItsKnownValuesAndSumsToOne) {
  // Known values: 2/3 and 1/6 at the centre and one texel away; 23/48 and 1/48 half a texel and
  // one and a half away (the weights of a lookup half-way between two texel centres).
  EXPECT_DOUBLE_EQ(cubicBSpline(0.0), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(cubicBSpline(1.0), 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(cubicBSpline(-0.5), 23.0 / 48.0);
  EXPECT_DOUBLE_EQ(cubicBSpline(1.5), 1.0 / 48.0);
  EXPECT_DOUBLE_EQ(cubicBSpline(2.0), 0.0);
  // Partition of unity: the four texels within 2 of any lookup point weigh 1 in all.
  constexpr double kRoundoff = 1e-12;  // four double products summed
  for (double a : {0.0, 0.13, 0.5, 0.77, 0.999}) {
    double sum = 0;
    for (int i = -1; i <= 2; ++i) sum += cubicBSpline(a - i);
    EXPECT_NEAR(sum, 1.0, kRoundoff) << "a = " << a;
  }
}

TEST(Gems, BicubicKernelIsDeclaredOnceOnGemsSixteen) {
  const ParamSpec* kernel = findParam(findTechnique("modern.gems16"), "kernel");
  ASSERT_NE(kernel, nullptr) << "modern.gems16 declares --param kernel";
  EXPECT_EQ(kernel->kind, ParamSpec::Kind::kChoice);
  EXPECT_EQ(kernel->choices, (std::vector<std::string>{"box", "bicubic"}));
  EXPECT_EQ(kernel->defaultText(), "box") << "GPU Gems' own filter stays the default";
  EXPECT_NE(describeParam(*kernel).find("bicubic"), std::string::npos) << describeParam(*kernel);
  // `shadowlab list`, the lab and --param checking read the declaration: gems4 has none.
  EXPECT_EQ(findParam(findTechnique("modern.gems4"), "kernel"), nullptr);
}

TEST(Gems, BicubicKernelNeedsSixteenSamples) {
  const Scene scene = builtinScene("analytic");
  EXPECT_THROW(renderByName("modern.gems16", scene,
                            smallParams(32, 32, 32, {{"kernel", "bicubic"}, {"samples", "4"}})),
               InputError);
  EXPECT_THROW(renderByName("modern.gems16", scene, smallParams(32, 32, 32, {{"kernel", "cubic"}})),
               InputError);
}

// Chan 2004 Fig. 4-8's "bicubic (16 samples)": each pixel's visibility is the B-spline-weighted
// sum of 16 single comparisons at the texel centres around its lookup point. On the analytic
// scene the light looks straight down, so the map holds the occluder's top face (an axis-aligned
// square in texel space) over the ground, and which texels are in shadow is known exactly: the
// rendered visibility must equal the sum computed here from cubicBSpline, at every pixel.
TEST(Gems, BicubicVisibilityIsTheBSplineWeightedSumOfSixteenComparisons) {
  const Scene scene = zoomedAnalytic();
  // A small map magnified on screen (about 33 pixels per texel) so that the penumbra, four
  // texels wide, spans many pixels at many fractions a between texel centres.
  constexpr int kTexels = 64;
  const RenderParams p = smallParams(256, 192, kTexels, {{"kernel", "bicubic"}});
  const Frame f = renderByName("modern.gems16", scene, p);
  ASSERT_TRUE(allFinite(f.visibility));
  // The occluder's outline in texel space: its top face (nearest the light) seen from above.
  const glm::vec2 c0 = shadowTexelOf(scene, kTexels, {-0.5f, 1.01f, -0.5f});
  const glm::vec2 c1 = shadowTexelOf(scene, kTexels, {0.5f, 1.01f, 0.5f});
  const glm::vec2 lo = glm::min(c0, c1), hi = glm::max(c0, c1);
  // A texel whose centre lies this close to the outline may fall either way when rasterised.
  constexpr float kAmbiguousTexels = 0.02f;
  auto shadowed = [&](int i, int j, bool* ambiguous) {
    const glm::vec2 c(float(i) + 0.5f, float(j) + 0.5f);
    const glm::vec2 dLo = c - lo, dHi = hi - c;
    const float margin = std::min(std::min(dLo.x, dLo.y), std::min(dHi.x, dHi.y));
    *ambiguous = *ambiguous || std::abs(margin) < kAmbiguousTexels;
    return margin > 0.0f;
  };
  // The visibility attachment is float: what differs is the lookup point, which the shader
  // computes from the interpolated world position and this test from the pixel centre's ray,
  // each in float (about 1e-5 texel at 64 texels); the weighted sum moves by at most about 1
  // per texel moved. 1e-4 is ten times that (measured worst: 3e-6); a wrong weight is off by
  // far more (box weights: 0.2 at the penumbra's edge).
  constexpr float kTolerance = 1e-4f;
  int penumbra = 0, checked = 0;
  float worst = 0;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const glm::vec3 g = groundPointOf(scene, p, float(x), float(y));
      const glm::vec2 t = shadowTexelOf(scene, kTexels, g);
      double expected = 0;
      bool ambiguous = false;
      for (int j = int(std::floor(t.y)) - 3; j <= int(std::floor(t.y)) + 3; ++j)
        for (int i = int(std::floor(t.x)) - 3; i <= int(std::floor(t.x)) + 3; ++i) {
          const double w = cubicBSpline(t.x - (i + 0.5)) * cubicBSpline(t.y - (j + 0.5));
          if (w == 0.0) continue;
          expected += shadowed(i, j, &ambiguous) ? 0.0 : w;
        }
      if (ambiguous) continue;
      ++checked;
      const float got = f.visibility.at(x, y);
      penumbra += expected > 0.02 && expected < 0.98;
      worst = std::max(worst, std::abs(got - float(expected)));
      EXPECT_NEAR(got, expected, kTolerance)
          << "pixel " << x << "," << y << ", lookup point " << t.x << "," << t.y << " texels";
      if (::testing::Test::HasFailure()) return;  // one message, not thousands
    }
  EXPECT_GT(checked, p.width * p.height / 2) << "most pixels must be checked";
  EXPECT_GT(penumbra, 1000) << "the test needs penumbra pixels to say anything";
  RecordProperty("worst", std::to_string(worst));
}

TEST(Gems, BadSampleCountIsAnInputError) {
  const Scene scene = builtinScene("analytic");
  EXPECT_THROW(renderByName("modern.gems4", scene, smallParams(32, 32, 32, {{"samples", "8"}})),
               InputError);
}

}  // namespace
}  // namespace sl
