// The bounds of registry/twins.h judged on synthetic masks whose differences are known, so that the
// equivalence tests cannot pass by a judge that accepts everything.
#include <gtest/gtest.h>

#include "registry/twins.h"

namespace sl {
namespace {

// 100x100 mask: left half lit (1), right half umbra (0); the boundary runs between x = 49, 50.
Image halfShadow() {
  Image m(100, 100, 1, 1.0f);
  for (int y = 0; y < 100; ++y)
    for (int x = 50; x < 100; ++x) m.at(x, y) = 0.0f;
  return m;
}

twins::TwinPair pair(bool faithful) {
  twins::TwinPair p;
  p.label = "synthetic";
  p.faithful = faithful;
  return p;
}

TEST(TwinsJudge, IdenticalMasksPassBothBounds) {
  const Image a = halfShadow();
  EXPECT_TRUE(twins::judge(pair(true), a, a).withinBound);
  EXPECT_TRUE(twins::judge(pair(false), a, a).withinBound);
}

TEST(TwinsJudge, AFlippedPixelOffTheBandFailsBothBounds) {
  const Image a = halfShadow();
  Image b = a;
  b.at(10, 10) = 0.0f;  // 40 pixels from the boundary
  const twins::Agreement faithful = twins::judge(pair(true), a, b);
  EXPECT_FALSE(faithful.withinBound) << faithful.verdict;
  EXPECT_EQ(faithful.differing, 1);
  EXPECT_EQ(faithful.differingOutsideBand, 1);
  EXPECT_FALSE(twins::judge(pair(false), a, b).withinBound);
}

TEST(TwinsJudge, AFlippedPixelOnTheBoundaryIsATie) {
  const Image a = halfShadow();
  Image b = a;
  b.at(50, 10) = 1.0f;  // right next to the crossing
  EXPECT_TRUE(twins::judge(pair(true), a, b).withinBound);
  EXPECT_TRUE(twins::judge(pair(false), a, b).withinBound);
}

TEST(TwinsJudge, FaithfulAllowsOnlyOnePixelInTenThousand) {
  const Image a = halfShadow();  // 10^4 pixels: one tie allowed, two are too many
  Image b = a;
  b.at(50, 10) = 1.0f;
  b.at(50, 20) = 1.0f;
  EXPECT_FALSE(twins::judge(pair(true), a, b).withinBound);
}

TEST(TwinsJudge, OneEightBitStepEverywhereIsWithinTheFloatBoundOnly) {
  const Image a = halfShadow();
  Image b = a;
  for (float& v : b.data) v = v > 0.5f ? v - 1.0f / 255.0f : v + 1.0f / 255.0f;
  EXPECT_TRUE(twins::judge(pair(false), a, b).withinBound);
  EXPECT_FALSE(twins::judge(pair(true), a, b).withinBound);
  // Two steps are beyond the one-step bound off the band.
  for (float& v : b.data) v = v > 0.5f ? v - 1.0f / 255.0f : v + 1.0f / 255.0f;
  EXPECT_FALSE(twins::judge(pair(false), a, b).withinBound);
}

// Images: the cone-edge band of a 100x100 window is 2 x 2 (100 + 100) = 800 pixels; a staircase
// spotlight edge (the untessellated legacy image: whole ground cells lit in one and not in the
// other) exceeds it, a one-pixel seam along the cone does not, and pixels where the masks differ
// are not counted against it.
TEST(TwinsJudge, ImagesBeyondThreeStepsOnlyOnTheConeEdgeBand) {
  const Image mask = halfShadow();
  const Image grey(100, 100, 3, 0.5f);
  Image seam = grey;  // a lit/unlit seam one pixel wide along a 100-pixel edge
  for (int y = 0; y < 100; ++y)
    for (int c = 0; c < 3; ++c) seam.at(70, y, c) = 0.0f;
  const twins::ImageAgreement ok = twins::judgeImages(grey, seam, mask, mask);
  EXPECT_EQ(ok.boundPixels, 800);
  EXPECT_EQ(ok.beyondWhereMasksAgree, 100);
  EXPECT_TRUE(ok.withinBound) << ok.verdict;
  Image staircase = grey;  // 16x16 cells unlit along a diagonal edge: 6 cells of 256 pixels
  for (int k = 0; k < 6; ++k)
    for (int y = 16 * k; y < 16 * k + 16; ++y)
      for (int x = 16 * k; x < 16 * k + 16; ++x)
        for (int c = 0; c < 3; ++c) staircase.at(x, y, c) = 0.0f;
  const twins::ImageAgreement bad = twins::judgeImages(grey, staircase, mask, mask);
  EXPECT_EQ(bad.beyondWhereMasksAgree, 6 * 256);
  EXPECT_FALSE(bad.withinBound) << bad.verdict;
  // Three steps are allowed, four are not.
  Image threeSteps = grey, fourSteps = grey;
  for (float& v : threeSteps.data) v += 3.0f / 255.0f;
  for (float& v : fourSteps.data) v += 4.0f / 255.0f;
  EXPECT_EQ(twins::judgeImages(grey, threeSteps, mask, mask).beyondSteps, 0);
  EXPECT_EQ(twins::judgeImages(grey, fourSteps, mask, mask).beyondSteps, 10000);
  // Where the masks differ, the image may differ (the direct light the mask scales).
  Image shadowed = grey;
  for (int y = 0; y < 100; ++y)
    for (int x = 50; x < 100; ++x)
      for (int c = 0; c < 3; ++c) shadowed.at(x, y, c) = 0.1f;
  const twins::ImageAgreement masked =
      twins::judgeImages(grey, shadowed, mask, Image(100, 100, 1, 1.0f));
  EXPECT_EQ(masked.beyondSteps, 5000);
  EXPECT_EQ(masked.beyondWhereMasksAgree, 0);
  EXPECT_TRUE(masked.withinBound) << masked.verdict;
}

}  // namespace
}  // namespace sl
