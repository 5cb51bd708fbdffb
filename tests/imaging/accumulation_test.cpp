// GL_RETURN of the emulated accumulation buffer on an 8-bit window (imaging/accumulation.cpp):
// each component becomes trunc(clamp(value * k / 32767, 0, 1) * 255 + 0.5) of its 16-bit
// fixed-point accumulator value k, computed here in double from the buffer itself, whichever
// form wrote it (the float vector form where it reproduced the table, else the table).
#include <gtest/gtest.h>

#include "imaging/internal.h"
#include "imaging_test_util.h"

namespace sl::imaging::detail {
namespace {
using namespace sl::imaging::testing;

constexpr int kWidth = 67, kHeight = 45;  // rows of no round length: vectors and a tail
constexpr double kAccumSteps = 32767.0;   // the buffer's fixed point (accumulation.cpp)

std::vector<uint8_t> expectedReturn(const State& s, float value) {
  std::vector<uint8_t> out(s.accum.size());
  for (size_t i = 0; i < out.size(); ++i) {
    const double v = double(value) * (double(s.accum[i]) / kAccumSteps);
    out[i] = uint8_t((v > 0.0 ? (v < 1.0 ? v : 1.0) : 0.0) * 255.0 + 0.5);
  }
  return out;
}

TEST(AccumulationReturn, EveryValueGivesTheExactConversion) {
  constexpr bool kEmulatedAccum = false;
  auto ctx = emulatedContext(kWidth, kHeight, ColorFormat::kRgba8, kEmulatedAccum);
  putImage(kWidth, kHeight, patternImage(kWidth, kHeight, 3));
  glClear(GL_ACCUM_BUFFER_BIT);
  glAccum(GL_LOAD, 0.75f);
  glAccum(GL_ACCUM, -0.5f);  // negative accumulator values too (clamped to 0 by RETURN)
  glAccum(GL_ACCUM, 0.25f);
  // 0.9: the float form misses one of the 65535 table entries, so the table writes it.
  for (float value : {1.0f, 0.25f, 0.9f, 1.0f / 3.0f, 2.0f, 4.0f, -1.0f, 0.0f}) {
    SCOPED_TRACE(value);
    glAccum(GL_RETURN, value);
    const State& s = *currentState();
    EXPECT_EQ(readRgba8(0, 0, kWidth, kHeight), expectedReturn(s, value));
    if (value == 1.0f && vectorMapsAvailable()) {
      EXPECT_TRUE(s.returnVectorExact);
    }
  }
}

}  // namespace
}  // namespace sl::imaging::detail
