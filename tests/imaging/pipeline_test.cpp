// The pipeline as a whole and the remaining stages: glspec121 3.6.5 stage order with
// everything enabled, scale/bias and GL_MAP_COLOR, the color matrix stack (3.6.3, 2.10.2,
// 6.1.6), histogram and minmax (3.6.5, 6.1.9-6.1.10), NaN/Inf/negative inputs, 16-bit and
// float destinations, the Brabec–Seidel color table + sum-into-alpha matrix (their Fig. 4),
// and the accumulation buffer emulation against OSMesa's real one (4.2.4).
#include "imaging/imaging_test_util.h"
#include "imaging/internal.h"

namespace sl::imaging::testing {
namespace {

// Brabec–Seidel §3, Fig. 4: the table maps 0 to 0 and anything else to 64 (63 in alpha, so a
// fully shadowed pixel sums to 64 + 64 + 64 + 63 = 255); the matrix sums R+G+B+A into A.
TEST(Pipeline, BrabecSeidelTableAndSumIntoAlpha) {
  auto ctx = emulatedContext(16, 1);
  // Masks with 0..4 channels in shadow (non-zero), in every combination of channels.
  std::vector<uint8_t> src;
  std::vector<int> expected;
  for (int mask = 0; mask < 16; ++mask) {
    int sum = 0;
    for (int c = 0; c < 4; ++c) {
      const bool shadow = (mask >> c) & 1;
      src.push_back(shadow ? uint8_t(37 + 50 * c) : 0);
      sum += shadow ? (c == 3 ? 63 : 64) : 0;
    }
    expected.push_back(sum);
  }
  putImage(16, 1, src);
  std::vector<uint8_t> table(256 * 4);
  for (int i = 0; i < 256; ++i)
    for (int c = 0; c < 4; ++c) table[i * 4 + c] = i == 0 ? 0 : (c == 3 ? 63 : 64);
  glColorTable(GL_COLOR_TABLE, GL_RGBA, 256, GL_RGBA, GL_UNSIGNED_BYTE, table.data());
  glEnable(GL_COLOR_TABLE);
  const float sumIntoAlpha[16] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  glMatrixMode(GL_COLOR);
  glLoadMatrixf(sumIntoAlpha);
  glMatrixMode(GL_MODELVIEW);
  glWindowPos2i(0, 0);
  glCopyPixels(0, 0, 16, 1, GL_COLOR);
  glDisable(GL_COLOR_TABLE);
  glMatrixMode(GL_COLOR);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  const auto got = readRgba8(0, 0, 16, 1);
  for (int p = 0; p < 16; ++p) {
    EXPECT_EQ(got[p * 4 + 3], expected[p]) << "mask " << p;
    EXPECT_EQ(got[p * 4 + 0], 0);
  }
  EXPECT_EQ(expected[15], 255);
  EXPECT_TRUE(drainErrors().empty());
}

// Every stage enabled: the result equals the stages applied by hand in the order of 3.6.5.
TEST(Pipeline, StageOrderWithEverythingEnabled) {
  auto ctx = emulatedContext(4, 4);
  const std::vector<uint8_t> px = {51, 102, 153, 204};
  putImage(1, 1, px);
  // 1. scale/bias
  glPixelTransferf(GL_RED_SCALE, 2.0f);
  glPixelTransferf(GL_BLUE_BIAS, -0.25f);
  // 2. MAP_COLOR applies all four maps (initially one entry of 0): G -> 1 - G through a
  // 2-entry map, R, B and A through 256-entry identities (which quantise to 1/255).
  const float inv[2] = {1.0f, 0.0f};
  glPixelMapfv(GL_PIXEL_MAP_G_TO_G, 2, inv);
  std::vector<float> identity(256);
  for (int i = 0; i < 256; ++i) identity[i] = float(i) / 255.0f;
  for (GLenum map : {GL_PIXEL_MAP_R_TO_R, GL_PIXEL_MAP_B_TO_B, GL_PIXEL_MAP_A_TO_A})
    glPixelMapfv(map, 256, identity.data());
  glPixelTransferi(GL_MAP_COLOR, GL_TRUE);
  // 3. color table: RGB squares (width 256)
  std::vector<float> sq(256 * 3);
  for (int i = 0; i < 256; ++i) sq[i * 3] = sq[i * 3 + 1] = sq[i * 3 + 2] = float(i * i) / 65025.0f;
  glColorTable(GL_COLOR_TABLE, GL_RGB, 256, GL_RGB, GL_FLOAT, sq.data());
  glEnable(GL_COLOR_TABLE);
  // 4. 1x1 convolution times 1.5 (REDUCE keeps 1x1) + post-convolution bias
  const float k[4] = {1.5f, 1.5f, 1.5f, 1.5f};
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 1, 1, GL_RGBA, GL_FLOAT, k);
  glEnable(GL_CONVOLUTION_2D);
  glPixelTransferf(GL_POST_CONVOLUTION_ALPHA_BIAS, -0.5f);
  // 5. post-convolution table: alpha halves (ALPHA table, width 2: index 0 -> 0, 1 -> 0.5)
  const float half[2] = {0.0f, 0.5f};
  glColorTable(GL_POST_CONVOLUTION_COLOR_TABLE, GL_ALPHA, 2, GL_ALPHA, GL_FLOAT, half);
  glEnable(GL_POST_CONVOLUTION_COLOR_TABLE);
  // 6. color matrix swaps R and B, then post scale on G
  const float swap[16] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1};
  glMatrixMode(GL_COLOR);
  glLoadMatrixf(swap);
  glMatrixMode(GL_MODELVIEW);
  glPixelTransferf(GL_POST_COLOR_MATRIX_GREEN_SCALE, 4.0f);
  // 7. post-matrix table: LUMINANCE identity of width 2 (indices 0 / 1)
  const float steps[2] = {0.0f, 1.0f};
  glColorTable(GL_POST_COLOR_MATRIX_COLOR_TABLE, GL_LUMINANCE, 2, GL_LUMINANCE, GL_FLOAT, steps);
  glEnable(GL_POST_COLOR_MATRIX_COLOR_TABLE);
  // 8-9. histogram and minmax see the final groups
  glHistogram(GL_HISTOGRAM, 2, GL_RGBA, GL_FALSE);
  glEnable(GL_HISTOGRAM);
  glMinmax(GL_MINMAX, GL_RGBA, GL_FALSE);
  glEnable(GL_MINMAX);
  const auto f = readRgbaF(0, 0, 1, 1);
  // By hand:
  double c[4] = {51 / 255.0, 102 / 255.0, 153 / 255.0, 204 / 255.0};
  c[0] *= 2.0;  // 1
  c[2] -= 0.25;
  c[1] = inv[int(std::floor(std::clamp(c[1], 0.0, 1.0) * 1 + 0.5))];  // 2 (index 0 -> 1)
  for (int i : {0, 2, 3}) c[i] = identity[tableIndex(float(c[i]), 256)];
  for (int i = 0; i < 3; ++i) {  // 3
    const int idx = tableIndex(float(c[i]), 256);
    c[i] = double(idx * idx) / 65025.0;
  }
  for (double& v : c) v *= 1.5;  // 4
  c[3] -= 0.5;
  c[3] = half[tableIndex(float(c[3]), 2)];  // 5
  std::swap(c[0], c[2]);                    // 6
  c[1] *= 4.0;
  for (int i = 0; i < 3; ++i) c[i] = steps[tableIndex(float(c[i]), 2)];  // 7
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(f[i], std::clamp(c[i], 0.0, 1.0), 1e-6) << i;
  float mm[8];
  glGetMinmax(GL_MINMAX, GL_FALSE, GL_RGBA, GL_FLOAT, mm);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(mm[4 + i], c[i], 1e-6) << i;  // the same group
  GLuint counts[8];
  glGetHistogram(GL_HISTOGRAM, GL_FALSE, GL_RGBA, GL_UNSIGNED_INT, counts);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(counts[tableIndex(float(c[i]), 2) * 4 + i], 1u) << i;
  EXPECT_TRUE(drainErrors().empty());
}

// NaN, infinities and negative values through DrawPixels(GL_FLOAT) into a float buffer:
// scale/bias keeps them, a table clamps them to [0,1] before indexing, the final
// conversion clamps and never leaves NaN in the buffer.
TEST(Pipeline, NanInfAndNegativeInputs) {
  auto ctx = emulatedContext(4, 1, ColorFormat::kRgba32f);
  const float nan = std::nanf(""), inf = INFINITY;
  const float src[16] = {nan,   -inf,  inf,   -0.5f, 2.0f, -1.0f, 0.5f,  nan,
                         0.25f, 0.75f, -0.0f, 1.0f,  inf,  nan,   -2.0f, 0.5f};
  glPixelTransferf(GL_RED_SCALE, 0.5f);  // any non-identity stage: the emulation runs
  glWindowPos2i(0, 0);
  glDrawPixels(4, 1, GL_RGBA, GL_FLOAT, src);
  glPixelTransferf(GL_RED_SCALE, 1.0f);
  const auto got = readRgbaF(0, 0, 4, 1);
  for (int i = 0; i < 16; ++i) {
    const float v = (i % 4 == 0) ? src[i] * 0.5f : src[i];
    const float want = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
    EXPECT_FALSE(std::isnan(got[i])) << i;
    EXPECT_EQ(got[i], want) << i;
  }
  // A table indexes NaN as 0 and infinities as the ends.
  const float t[8] = {0.1f, 0.2f, 0.3f, 0.4f, 0.9f, 0.8f, 0.7f, 0.6f};
  glColorTable(GL_COLOR_TABLE, GL_RGBA, 2, GL_RGBA, GL_FLOAT, t);
  glEnable(GL_COLOR_TABLE);
  glDrawPixels(4, 1, GL_RGBA, GL_FLOAT, src);
  glDisable(GL_COLOR_TABLE);
  const auto looked = readRgbaF(0, 0, 1, 1);
  EXPECT_FLOAT_EQ(looked[0], 0.1f);  // NaN -> index 0
  EXPECT_FLOAT_EQ(looked[1], 0.2f);  // -inf -> index 0
  EXPECT_FLOAT_EQ(looked[2], 0.7f);  // +inf -> index 1
  EXPECT_FLOAT_EQ(looked[3], 0.4f);  // -0.5 -> index 0
  EXPECT_TRUE(drainErrors().empty());
}

// The destination's precision is kept: 16-bit and float colour buffers receive the
// transformed values at their own precision (not through 8 bits).
TEST(Pipeline, SixteenBitAndFloatDestinations) {
  for (ColorFormat format : {ColorFormat::kRgba16, ColorFormat::kRgba32f}) {
    auto ctx = emulatedContext(2, 1, format);
    const float src[4] = {0.123456f, 0.5f, 0.987654f, 1.0f};
    glPixelTransferf(GL_GREEN_SCALE, 0.3f);
    glWindowPos2i(0, 0);
    glDrawPixels(1, 1, GL_RGBA, GL_FLOAT, src);
    glWindowPos2i(1, 0);
    glCopyPixels(0, 0, 1, 1, GL_COLOR);  // green scaled again
    glPixelTransferf(GL_GREEN_SCALE, 1.0f);
    const auto got = readRgbaF(0, 0, 2, 1);
    // Half a step of the buffer's precision (16 bits: 1/65535; float: exact to 1e-7).
    const float tol = format == ColorFormat::kRgba16 ? 0.5f / 65535.0f + 1e-7f : 1e-7f;
    EXPECT_NEAR(got[0], 0.123456f, tol) << colorFormatName(format);
    EXPECT_NEAR(got[1], 0.15f, tol) << colorFormatName(format);
    EXPECT_NEAR(got[5], 0.045f, 2 * tol) << colorFormatName(format);
    EXPECT_TRUE(drainErrors().empty());
  }
}

TEST(Pipeline, ColorMatrixStackAndQueries) {
  auto ctx = emulatedContext(2, 2);
  GLint v = 0;
  glGetIntegerv(GL_MAX_COLOR_MATRIX_STACK_DEPTH, &v);
  EXPECT_EQ(v, 4);
  glMatrixMode(GL_COLOR);
  glGetIntegerv(GL_MATRIX_MODE, &v);
  EXPECT_EQ(GLenum(v), GLenum(GL_COLOR));
  const float a[16] = {2, 0, 0, 0, 0, 3, 0, 0, 0, 0, 4, 0, 1, 0, 0, 1};
  glLoadMatrixf(a);
  glPushMatrix();
  glMultMatrixf(a);  // a * a
  float m[16];
  glGetFloatv(GL_COLOR_MATRIX, m);
  EXPECT_EQ(m[0], 4.0f);
  EXPECT_EQ(m[12], 3.0f);  // 2 * 1 + 1 * 1
  glGetIntegerv(GL_COLOR_MATRIX_STACK_DEPTH, &v);
  EXPECT_EQ(v, 2);
  glPushMatrix();
  glPushMatrix();
  glPushMatrix();  // fifth entry: overflow
  EXPECT_EQ(drainErrors(), std::vector<GLenum>{GL_STACK_OVERFLOW});
  for (int i = 0; i < 4; ++i) glPopMatrix();
  EXPECT_EQ(drainErrors(), std::vector<GLenum>{GL_STACK_UNDERFLOW});
  glGetFloatv(GL_COLOR_MATRIX, m);
  EXPECT_EQ(m[0], 2.0f);
  // Other matrix modes still reach the driver.
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glTranslatef(1, 2, 3);
  glGetFloatv(GL_MODELVIEW_MATRIX, m);
  EXPECT_EQ(m[13], 2.0f);
  glGetIntegerv(GL_MATRIX_MODE, &v);
  EXPECT_EQ(GLenum(v), GLenum(GL_MODELVIEW));
  EXPECT_TRUE(drainErrors().empty());
}

TEST(Pipeline, HistogramMinmaxAndSink) {
  auto ctx = emulatedContext(4, 2);
  const std::vector<uint8_t> px = {0, 64, 128, 255, 255, 191, 128, 0};
  putImage(2, 1, px);
  glHistogram(GL_HISTOGRAM, 4, GL_RGB, GL_TRUE);  // sink
  glEnable(GL_HISTOGRAM);
  glMinmax(GL_MINMAX, GL_RGBA, GL_FALSE);
  glEnable(GL_MINMAX);
  glWindowPos2i(0, 1);
  glCopyPixels(0, 0, 2, 1, GL_COLOR);
  GLuint counts[4 * 4];
  glGetHistogram(GL_HISTOGRAM, GL_TRUE, GL_RGBA, GL_UNSIGNED_INT, counts);
  // index = round(c * 3): R 0 -> 0, 1 -> 3; G 64/255 -> 1, 191/255 -> 2; B 128/255 -> 2 twice.
  EXPECT_EQ(counts[0 * 4 + 0], 1u);
  EXPECT_EQ(counts[3 * 4 + 0], 1u);
  EXPECT_EQ(counts[1 * 4 + 1], 1u);
  EXPECT_EQ(counts[2 * 4 + 1], 1u);
  EXPECT_EQ(counts[2 * 4 + 2], 2u);
  EXPECT_EQ(counts[0 * 4 + 3], 1u);  // RGB histogram: A reads the constant 1 (table 6.1)
  float mm[8];
  glGetMinmax(GL_MINMAX, GL_FALSE, GL_RGBA, GL_FLOAT, mm);
  EXPECT_EQ(mm[0], 3.40282347e38f);  // sink: minmax not performed, still the initial state
  glDisable(GL_HISTOGRAM);
  glDisable(GL_MINMAX);
  const auto got = readRgba8(0, 1, 2, 1);
  EXPECT_EQ(got, std::vector<uint8_t>(8, 0));  // sink: no fragments
  EXPECT_TRUE(drainErrors().empty());
}

// The accumulation buffer emulation (a context without one) against Debian OSMesa's real
// 16-bit accumulation buffer, on the same sequence of operations.
std::vector<uint8_t> accumulationSequence(bool realBuffer) {
  auto ctx = emulatedContext(16, 8, ColorFormat::kRgba8, realBuffer);
  EXPECT_EQ(ctx->caps().accumRedBits, realBuffer ? 16 : 0);
  std::vector<uint8_t> out;
  // Every value stays inside [-1, 1] (outside, results are undefined: 4.2.4).
  glClearAccum(0.0f, -0.2f, 0.2f, 0.0f);
  glClear(GL_ACCUM_BUFFER_BIT);
  for (int pass = 0; pass < 4; ++pass) {
    putImage(16, 8, patternImage(16, 8, 40 + pass));
    glAccum(GL_ACCUM, 0.2f);
  }
  glAccum(GL_RETURN, 1.0f);
  auto a = readRgba8(0, 0, 16, 8);
  out.insert(out.end(), a.begin(), a.end());
  glAccum(GL_MULT, 0.6f);
  glAccum(GL_ADD, 0.2f);
  glEnable(GL_SCISSOR_TEST);
  glScissor(2, 1, 9, 5);
  glAccum(GL_LOAD, 0.4f);
  glDisable(GL_SCISSOR_TEST);
  glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_TRUE);
  glAccum(GL_RETURN, 1.0f);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  a = readRgba8(0, 0, 16, 8);
  out.insert(out.end(), a.begin(), a.end());
  GLint bits = 0;
  glGetIntegerv(GL_ACCUM_RED_BITS, &bits);
  out.push_back(uint8_t(bits));
  EXPECT_TRUE(drainErrors().empty());
  return out;
}

TEST(Accumulation, EmulationMatchesOsmesaRealBuffer) {
  // Inputs are bytes and factors are fifths: exact results in steps are n/5 after the first
  // RETURN, 81.6 + 0.12 S (S a byte sum) after MULT 0.6 / ADD 0.2, and multiples of 0.2
  // inside the reloaded box: at least 0.02 step from a rounding tie, while 16-bit
  // accumulation (1/32767 per operation) moves results by under 0.006 step.
  const auto real = accumulationSequence(true);
  const auto emulated = accumulationSequence(false);
  ASSERT_EQ(real.size(), emulated.size());
  for (size_t i = 0; i < real.size(); ++i) ASSERT_EQ(emulated[i], real[i]) << i;
}

TEST(Accumulation, ErrorsAndReturnClamps) {
  auto ctx = emulatedContext(4, 4, ColorFormat::kRgba8, false);
  glAccum(GL_TEXTURE_2D, 1.0f);
  EXPECT_EQ(drainErrors(), std::vector<GLenum>{GL_INVALID_ENUM});
  putImage(1, 1, {200, 100, 50, 255});
  glAccum(GL_LOAD, 1.0f);
  glAccum(GL_RETURN, 2.0f);  // 2 * 200/255 clamps to 1
  const auto got = readRgba8(0, 0, 1, 1);
  EXPECT_EQ(got, (std::vector<uint8_t>{255, 200, 100, 255}));
}

}  // namespace
}  // namespace sl::imaging::testing

namespace sl::imaging::testing {
namespace {

// The 8-bit path (fast_paths.cpp) computes exactly what the float path computes: read the
// same transformed pixels once as floats (general path, then the final conversion by hand)
// and once as unsigned bytes (byte path).
TEST(Pipeline, BytePathMatchesFloatPath) {
  auto ctx = emulatedContext(32, 16);
  putImage(32, 16, patternImage(32, 16, 77));
  std::vector<float> t(64 * 4);
  for (size_t i = 0; i < t.size(); ++i) t[i] = float((i * 37) % 64) / 63.0f;
  glColorTable(GL_COLOR_TABLE, GL_RGBA, 64, GL_RGBA, GL_FLOAT, t.data());
  glEnable(GL_COLOR_TABLE);
  glColorTable(GL_POST_COLOR_MATRIX_COLOR_TABLE, GL_LUMINANCE_ALPHA, 64, GL_RGBA, GL_FLOAT,
               t.data());
  glEnable(GL_POST_COLOR_MATRIX_COLOR_TABLE);
  const float m[16] = {0.3f, 0.2f, -0.1f, 0.25f, 0.5f, 0.1f, 0.2f, 0.25f,
                       0.0f, 0.6f, 0.3f,  0.25f, 0.1f, 0.0f, 0.5f, 0.25f};
  glMatrixMode(GL_COLOR);
  glLoadMatrixf(m);
  glMatrixMode(GL_MODELVIEW);
  glPixelTransferf(GL_POST_COLOR_MATRIX_GREEN_SCALE, 1.3f);
  glPixelTransferf(GL_POST_COLOR_MATRIX_BLUE_BIAS, 0.05f);
  glPixelTransferf(GL_RED_SCALE, 0.9f);
  const auto f = readRgbaF(0, 0, 32, 16);
  const auto b = readRgba8(0, 0, 32, 16);
  for (size_t i = 0; i < b.size(); ++i) ASSERT_EQ(b[i], toByte(f[i])) << i;
}

}  // namespace
}  // namespace sl::imaging::testing

namespace sl::imaging::testing {
namespace {

// glPushAttrib / glPopAttrib save and restore the emulated imaging enables and pixel-mode
// parameters with the driver's own (6.1.12, tables 6.17-6.21), as legacy passes rely on.
TEST(Pipeline, PushPopAttribRestoresImagingState) {
  auto ctx = emulatedContext(2, 2);
  glPushAttrib(GL_PIXEL_MODE_BIT | GL_ENABLE_BIT);
  glEnable(GL_COLOR_TABLE);
  glEnable(GL_CONVOLUTION_2D);
  glPixelTransferf(GL_RED_SCALE, 0.5f);
  glPixelTransferf(GL_POST_COLOR_MATRIX_BLUE_BIAS, 0.25f);
  glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, GL_REPLICATE_BORDER);
  glEnable(GL_DEPTH_TEST);
  glPopAttrib();
  EXPECT_FALSE(glIsEnabled(GL_COLOR_TABLE));
  EXPECT_FALSE(glIsEnabled(GL_CONVOLUTION_2D));
  EXPECT_FALSE(glIsEnabled(GL_DEPTH_TEST));  // the driver's own state too
  float v = 0;
  glGetFloatv(GL_RED_SCALE, &v);
  EXPECT_EQ(v, 1.0f);
  glGetFloatv(GL_POST_COLOR_MATRIX_BLUE_BIAS, &v);
  EXPECT_EQ(v, 0.0f);
  GLint mode = 0;
  glGetConvolutionParameteriv(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, &mode);
  EXPECT_EQ(GLenum(mode), GLenum(GL_REDUCE));
  // GL_ENABLE_BIT alone restores the enables but keeps pixel-mode parameters.
  glPushAttrib(GL_ENABLE_BIT);
  glEnable(GL_HISTOGRAM);
  glPixelTransferf(GL_GREEN_BIAS, 0.125f);
  glPopAttrib();
  EXPECT_FALSE(glIsEnabled(GL_HISTOGRAM));
  glGetFloatv(GL_GREEN_BIAS, &v);
  EXPECT_EQ(v, 0.125f);
  EXPECT_TRUE(drainErrors().empty());
}

// Where the visual has no accumulation buffer the emulation keeps one, and its clear value
// belongs to GL_ACCUM_BUFFER_BIT (table 6.16, "accum-buffer"): popped with the driver's state.
TEST(Pipeline, PushPopAttribRestoresTheEmulatedAccumulationClearValue) {
  constexpr bool kVisualAccumulation = false;  // the emulation's own buffer
  auto ctx = emulatedContext(2, 2, ColorFormat::kRgba8, kVisualAccumulation);
  ASSERT_TRUE(detail::currentState()->emulateAccum);
  glPushAttrib(GL_ACCUM_BUFFER_BIT);
  glClearAccum(0.5f, 0.25f, 0.125f, 1.0f);
  float v[4] = {-1, -1, -1, -1};
  glGetFloatv(GL_ACCUM_CLEAR_VALUE, v);
  EXPECT_EQ(v[0], 0.5f);
  glPopAttrib();
  glGetFloatv(GL_ACCUM_CLEAR_VALUE, v);
  for (float c : v) EXPECT_EQ(c, 0.0f);  // the initial value (table 6.16)
  // Another group leaves it.
  glClearAccum(0.5f, 0.5f, 0.5f, 0.5f);
  glPushAttrib(GL_COLOR_BUFFER_BIT);
  glClearAccum(0.0f, 0.0f, 0.0f, 0.0f);
  glPopAttrib();
  glGetFloatv(GL_ACCUM_CLEAR_VALUE, v);
  EXPECT_EQ(v[0], 0.0f);
  EXPECT_TRUE(drainErrors().empty());
}

}  // namespace
}  // namespace sl::imaging::testing

namespace sl::imaging::testing {
namespace {

// glCopyTexImage2D / glCopyTexSubImage2D with a depth internal format copy depth components
// (3.8.2); the RGBA stages of 3.6.5 do not apply, even while they are enabled.
TEST(CopyTexImage, DepthTexturesBypassTheColourStages) {
  auto ctx = emulatedContext(4, 4);
  glClearDepth(0.25);
  glClear(GL_DEPTH_BUFFER_BIT);
  glPixelTransferf(GL_RED_SCALE, 0.5f);  // a colour stage that is not identity
  GLuint tex = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glCopyTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, 0, 0, 4, 4, 0);
  EXPECT_TRUE(drainErrors().empty());
  glClearDepth(0.75);
  glClear(GL_DEPTH_BUFFER_BIT);
  glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, 2, 4);  // the left half becomes 0.75
  EXPECT_TRUE(drainErrors().empty());
  glPixelTransferf(GL_RED_SCALE, 1.0f);
  std::vector<float> depth(16, -1.0f);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  constexpr float kDepthStep = 1.0f / 16777215.0f;  // one step of the 24-bit depth buffer
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      EXPECT_NEAR(depth[size_t(y * 4 + x)], x < 2 ? 0.75f : 0.25f, kDepthStep) << x << "," << y;
  glDeleteTextures(1, &tex);
}

}  // namespace
}  // namespace sl::imaging::testing
