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

}  // namespace
}  // namespace sl
