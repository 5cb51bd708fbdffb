// glGetMinmax (glspec121 6.1.10 "Minmax Query", packed as GetTexImage packs, 6.1.4): what the
// user reads from a reset table and from a table that has seen values outside [0,1], for
// GL_FLOAT and for the normalised integer types (our choice, stated at
// imaging/histogram.cpp emGetMinmax and in docs/imaging.md "Minmax").
#include <cfloat>
#include <cmath>

#include "imaging/imaging_test_util.h"

namespace sl::imaging::testing {
namespace {

// 3.6.3: the reset state holds the maximum representable value as each minimum and the
// minimum representable value as each maximum; the table is IEEE single.
constexpr float kResetMin = FLT_MAX;
constexpr float kResetMax = -FLT_MAX;

std::vector<float> minmaxFloats(GLenum format, int components, GLboolean reset = GL_FALSE) {
  std::vector<float> mm(size_t(2 * components), -7.0f);
  glGetMinmax(GL_MINMAX, reset, format, GL_FLOAT, mm.data());
  return mm;
}

// One RGBA8 pixel through glReadPixels with minmax enabled and the given red scale and bias.
void readOnePixelThroughMinmax(const std::vector<uint8_t>& rgba, float redScale, float redBias) {
  putImage(1, 1, rgba);
  glPixelTransferf(GL_RED_SCALE, redScale);
  glPixelTransferf(GL_RED_BIAS, redBias);
  glEnable(GL_MINMAX);
  readRgbaF(0, 0, 1, 1);
  glDisable(GL_MINMAX);
  glPixelTransferf(GL_RED_SCALE, 1.0f);
  glPixelTransferf(GL_RED_BIAS, 0.0f);
}

TEST(MinmaxQuery, ResetTableReadsTheRepresentableExtremesAsFloat) {
  auto ctx = emulatedContext(2, 2);
  glMinmax(GL_MINMAX, GL_RGBA, GL_FALSE);
  EXPECT_EQ(minmaxFloats(GL_RGBA, 4),
            (std::vector<float>{kResetMin, kResetMin, kResetMin, kResetMin, kResetMax, kResetMax,
                                kResetMax, kResetMax}));
  EXPECT_TRUE(drainErrors().empty());
}

// Table 6.1: the components the table does not hold read 0 (R, G, B) and 1 (A).
TEST(MinmaxQuery, ResetTableOfFewerComponentsReadsTable61Constants) {
  auto ctx = emulatedContext(2, 2);
  glMinmax(GL_MINMAX, GL_LUMINANCE_ALPHA, GL_FALSE);
  EXPECT_EQ(minmaxFloats(GL_RGBA, 4),
            (std::vector<float>{kResetMin, 0, 0, kResetMin, kResetMax, 0, 0, kResetMax}));
  glMinmax(GL_MINMAX, GL_RGB, GL_FALSE);
  EXPECT_EQ(minmaxFloats(GL_RGBA, 4), (std::vector<float>{kResetMin, kResetMin, kResetMin, 1,
                                                          kResetMax, kResetMax, kResetMax, 1}));
}

// 4.3.2 "Conversion to L" sums R + G + B: three FLT_MAX overflow single precision. The user
// reads the representable extreme, never an infinity.
TEST(MinmaxQuery, LuminanceOfAResetRgbaTableSaturatesInsteadOfInfinity) {
  auto ctx = emulatedContext(2, 2);
  glMinmax(GL_MINMAX, GL_RGBA, GL_FALSE);
  const std::vector<float> l = minmaxFloats(GL_LUMINANCE, 1);
  EXPECT_EQ(l, (std::vector<float>{kResetMin, kResetMax}));
  const std::vector<float> la = minmaxFloats(GL_LUMINANCE_ALPHA, 2);
  EXPECT_EQ(la, (std::vector<float>{kResetMin, kResetMin, kResetMax, kResetMax}));
  for (float v : la) EXPECT_TRUE(std::isfinite(v)) << v;
}

// Normalised integer types clamp to [0,1] first (4.3.2 "Final Conversion", table 4.7): the
// minimum reads the type's largest value, the maximum 0.
TEST(MinmaxQuery, ResetTableReadsClampedExtremesAsIntegers) {
  auto ctx = emulatedContext(2, 2);
  glMinmax(GL_MINMAX, GL_RGBA, GL_FALSE);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  uint8_t ub[8];
  glGetMinmax(GL_MINMAX, GL_FALSE, GL_RGBA, GL_UNSIGNED_BYTE, ub);
  EXPECT_EQ(std::vector<uint8_t>(ub, ub + 8),
            (std::vector<uint8_t>{255, 255, 255, 255, 0, 0, 0, 0}));
  GLbyte b[8];
  glGetMinmax(GL_MINMAX, GL_FALSE, GL_RGBA, GL_BYTE, b);
  EXPECT_EQ(b[0], 127);  // table 4.7: c = [(2^8 - 1) f - 1] / 2 at f = 1
  EXPECT_EQ(b[4], 0);    // f = 0 gives -1/2, rounded half up to 0
  GLushort us[8];
  glGetMinmax(GL_MINMAX, GL_FALSE, GL_RGBA, GL_UNSIGNED_SHORT, us);
  EXPECT_EQ(us[0], 65535);
  EXPECT_EQ(us[4], 0);
  GLuint ui[8];
  glGetMinmax(GL_MINMAX, GL_FALSE, GL_RGBA, GL_UNSIGNED_INT, ui);
  EXPECT_EQ(ui[0], 4294967295u);
  EXPECT_EQ(ui[4], 0u);
  EXPECT_TRUE(drainErrors().empty());
}

// 3.6.5 gives the table at least the colour range of 2.1.1: extremes outside [0,1] come back
// as they are in GL_FLOAT (and clamped in the integer types).
TEST(MinmaxQuery, FloatReturnsExtremesOutsideZeroOne) {
  auto ctx = emulatedContext(2, 2);
  glMinmax(GL_MINMAX, GL_RGBA, GL_FALSE);
  readOnePixelThroughMinmax({200, 60, 120, 255}, 1.5f, 0.0f);   // R = 1.5 * 200/255
  readOnePixelThroughMinmax({200, 60, 120, 255}, 1.0f, -0.9f);  // R = 200/255 - 0.9
  const std::vector<float> mm = minmaxFloats(GL_RGBA, 4);
  // Tolerance: the emulation computes each in single precision (a few ulps of 1).
  EXPECT_NEAR(mm[0], 200.0f / 255.0f - 0.9f, 1e-6f);
  EXPECT_NEAR(mm[4], 1.5f * 200.0f / 255.0f, 1e-6f);
  EXPECT_NEAR(mm[1], 60.0f / 255.0f, 1e-6f);  // G, B, A saw one value each
  EXPECT_NEAR(mm[5], 60.0f / 255.0f, 1e-6f);
  uint8_t ub[8];
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetMinmax(GL_MINMAX, GL_FALSE, GL_RGBA, GL_UNSIGNED_BYTE, ub);
  EXPECT_EQ(ub[0], 0);    // -0.116 clamped
  EXPECT_EQ(ub[4], 255);  // 1.18 clamped
}

// 6.1.10: with reset TRUE the values before the reset are returned, and every value is reset
// "whether returned or not" (a GL_RED query resets G, B and A too).
TEST(MinmaxQuery, GetWithResetReturnsTheOldValuesAndResetsEveryComponent) {
  auto ctx = emulatedContext(2, 2);
  glMinmax(GL_MINMAX, GL_RGBA, GL_FALSE);
  readOnePixelThroughMinmax({200, 60, 120, 255}, 1.0f, 0.0f);
  const std::vector<float> red = minmaxFloats(GL_RED, 1, GL_TRUE);
  EXPECT_NEAR(red[0], 200.0f / 255.0f, 1e-6f);
  EXPECT_NEAR(red[1], 200.0f / 255.0f, 1e-6f);
  EXPECT_EQ(minmaxFloats(GL_RGBA, 4),
            (std::vector<float>{kResetMin, kResetMin, kResetMin, kResetMin, kResetMax, kResetMax,
                                kResetMax, kResetMax}));
  // And the table fills again from there; glResetMinmax empties it the same way.
  readOnePixelThroughMinmax({10, 20, 30, 40}, 1.0f, 0.0f);
  EXPECT_NEAR(minmaxFloats(GL_RGBA, 4)[0], 10.0f / 255.0f, 1e-6f);
  glResetMinmax(GL_MINMAX);
  EXPECT_EQ(minmaxFloats(GL_RGBA, 4)[0], kResetMin);
  EXPECT_TRUE(drainErrors().empty());
}

}  // namespace
}  // namespace sl::imaging::testing
