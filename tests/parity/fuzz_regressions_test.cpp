// Cases found by the differential fuzzer (imaging_fuzz.h, build/bin/imaging_fuzz), reduced by
// hand from its minimised sequences. I-M are departures of the reference (Mesa 7.8.2) from
// the OpenGL 1.2.1 specification: each test asserts the specification's answer for the
// emulation and the measured one for the reference, as departures_test.cpp does, and the
// fuzzer's generator stays clear of it (imaging_fuzz.cpp, "Generator constraints"). The
// accumulation case is a tie rule, not a departure.
#include "parity/parity_util.h"

namespace sl::imaging::testing {
namespace {

const std::vector<uint8_t> kPixel = {200, 60, 120, 255};

Outcome both(Backend b, const Scenario& s) {
  return runOn(b, s, /*accumulation=*/b != Backend::kOsmesa);
}

// H. Accumulation ties: a GL_LOAD of 0.5 makes every odd byte value v an exact tie
//    v/2 = k + 0.5 before the 16-bit buffer's rounding, whose precision and rounding are the
//    implementation's (4.2.4); GL_RETURN then rounds to nearest (2.13.9). The two buffers
//    round the tie differently, so a returned tie may be k or k + 1 on either side (the
//    fuzzer's "accumulation: a tie within the 16-bit buffer's rounding"; seeds 802, 2351,
//    10719 found ties one or more buffer steps from k + 0.5 after GL_MULT). No departure: not
//    a truncation by the reference; even values, which are no
//    ties, agree exactly.
TEST(FuzzRegressions, AccumulationTiesGoEitherWay) {
  SL_REQUIRE_REFERENCE();
  std::vector<uint8_t> ramp(size_t(kParityW) * kParityH * 4);
  for (size_t i = 0; i < ramp.size(); ++i) ramp[i] = uint8_t((i / 4) % 256);
  auto scenario = [&ramp](Outcome& o) {
    putImage(kParityW, kParityH, ramp);
    glAccum(GL_LOAD, 0.5f);
    glAccum(GL_RETURN, 1.0f);
    appendBytes(o, readWindow());
  };
  const Outcome e = runOn(Backend::kOsmesa, scenario, /*accumulation=*/false);
  const Outcome r = runOn(Backend::kReference, scenario);
  ASSERT_EQ(e.bytes.size(), ramp.size());
  ASSERT_EQ(r.bytes.size(), ramp.size());
  int differing = 0;
  for (size_t i = 0; i < ramp.size(); ++i) {
    const int v = ramp[i];
    if (v % 2 == 0) {
      EXPECT_EQ(e.bytes[i], v / 2) << i;
      EXPECT_EQ(r.bytes[i], v / 2) << i;
    } else {
      EXPECT_TRUE(e.bytes[i] == v / 2 || e.bytes[i] == v / 2 + 1) << i;
      EXPECT_TRUE(r.bytes[i] == v / 2 || r.bytes[i] == v / 2 + 1) << i;
      differing += e.bytes[i] != r.bytes[i];
    }
  }
  EXPECT_GT(differing, 0);  // the two buffers' roundings do differ on some ties
}

// I. With GL_MINMAX_SINK "all RGBA pixel groups are discarded immediately after the minmax
//    operation" (3.6.5 Minmax): glCopyPixels writes nothing. The reference honours the sink on
//    glReadPixels only, and writes the copy (fuzzer seeds 117, 22).
TEST(FuzzRegressions, AdditionalI_MinmaxSinkIgnoredByCopyPixels) {
  SL_REQUIRE_REFERENCE();
  auto scenario = [](Outcome& o) {
    putImage(1, 1, kPixel);
    glMinmax(GL_MINMAX, GL_RGBA, GL_TRUE);
    glEnable(GL_MINMAX);
    float px[4] = {-1, -1, -1, -1};
    glReadPixels(0, 0, 1, 1, GL_RGBA, GL_FLOAT, px);
    o.floats.assign(px, px + 4);
    glWindowPos2i(1, 0);
    glCopyPixels(0, 0, 1, 1, GL_COLOR);
    appendBytes(o, readWindow());
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  EXPECT_EQ(e.floats[0], -1.0f);  // glReadPixels: consumed on both
  EXPECT_EQ(r.floats[0], -1.0f);
  EXPECT_EQ(e.bytes[4], 0);    // pixel (1,0) keeps the cleared window
  EXPECT_EQ(r.bytes[4], 200);  // written anyway
}

// J. "If CONVOLUTION_1D is enabled, the one-dimensional convolution filter is applied only to
//    the one-dimensional texture images" (3.6.5 Convolution), and post-convolution scale and
//    bias only where a convolution is performed (EXT_convolution): glTexImage2D is untouched.
//    The reference changes the 2D image (fuzzer seeds 160, 582).
TEST(FuzzRegressions, AdditionalJ_OneDimensionalFilterChangesTexImage2D) {
  SL_REQUIRE_REFERENCE();
  auto scenario = [](Outcome& o) {
    const float half[4] = {0.5f, 0.5f, 0.5f, 0.5f};
    glConvolutionFilter1D(GL_CONVOLUTION_1D, GL_RGBA, 1, GL_RGBA, GL_FLOAT, half);
    glEnable(GL_CONVOLUTION_1D);
    glPixelTransferf(GL_POST_CONVOLUTION_GREEN_SCALE, 2.0f);
    GLuint tex = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, kPixel.data());
    resetImaging();
    uint8_t t[4] = {};
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, t);
    o.bytes.assign(t, t + 4);
    glDeleteTextures(1, &tex);
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  EXPECT_EQ(e.bytes, kPixel);
  EXPECT_NE(r.bytes, kPixel);
  ::testing::Test::RecordProperty(
      "reference_texel", std::to_string(r.bytes[0]) + "," + std::to_string(r.bytes[1]) + "," +
                             std::to_string(r.bytes[2]) + "," + std::to_string(r.bytes[3]));
}

// K. glCopyTexImage2D processes the groups "exactly as for CopyPixels" (3.8.2), once: a
//    histogram counts each pixel once. The reference counts each twice (it runs the pipeline
//    twice there, as AdditionalD shows for the color matrix; fuzzer seeds 5, 617).
TEST(FuzzRegressions, AdditionalK_CopyTexImageCountsTheHistogramTwice) {
  SL_REQUIRE_REFERENCE();
  auto scenario = [](Outcome& o) {
    putImage(1, 1, kPixel);
    glHistogram(GL_HISTOGRAM, 2, GL_RGBA, GL_FALSE);
    glEnable(GL_HISTOGRAM);
    GLuint tex = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glCopyTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 0, 0, 1, 1, 0);
    float counts[8] = {};
    glGetHistogram(GL_HISTOGRAM, GL_FALSE, GL_RGBA, GL_FLOAT, counts);
    o.floats.assign(counts, counts + 8);
    glDeleteTextures(1, &tex);
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  // R = 200/255 and A = 1 fall in entry 1, G = 60/255 and B = 120/255 in entry 0.
  EXPECT_EQ(e.floats, (std::vector<float>{0, 1, 1, 0, 1, 0, 0, 1}));
  EXPECT_EQ(r.floats, (std::vector<float>{0, 2, 2, 0, 2, 0, 0, 2}));
}

// L. Components are clamped only in the final conversion (3.6.5): a pre-convolution scale of
//    2 followed by a filter of 0.5 gives the pixel back on glTexImage2D. The reference clamps
//    before convolving there (fuzzer seeds 23, 102), as AdditionalD found for glCopyTexImage2D.
TEST(FuzzRegressions, AdditionalL_TexImage2DClampsBeforeConvolving) {
  SL_REQUIRE_REFERENCE();
  auto scenario = [](Outcome& o) {
    const float half[4] = {0.5f, 0.5f, 0.5f, 0.5f};
    glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 1, 1, GL_RGBA, GL_FLOAT, half);
    glEnable(GL_CONVOLUTION_2D);
    glPixelTransferf(GL_RED_SCALE, 2.0f);
    GLuint tex = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, kPixel.data());
    resetImaging();
    uint8_t t[4] = {};
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, t);
    o.bytes.assign(t, t + 4);
    glDeleteTextures(1, &tex);
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  EXPECT_EQ(e.bytes[0], 200);  // 200 * 2 * 0.5
  EXPECT_EQ(r.bytes[0], 128);  // clamp(400/255) * 0.5, rounded
}

// M. glCopyColorTable takes the pixels "exactly as if ... passed to CopyPixels ..., stopping
//    after the final expansion to RGBA" (3.6.3): no color matrix. The reference runs them
//    through the color matrix (and the other enabled stages; fuzzer seeds 487, 606, 2392).
TEST(FuzzRegressions, AdditionalM_CopyColorTableAppliesTheColorMatrix) {
  SL_REQUIRE_REFERENCE();
  auto scenario = [](Outcome& o) {
    putImage(1, 1, kPixel);
    const float half[16] = {0.5f, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    glMatrixMode(GL_COLOR);
    glLoadMatrixf(half);
    glMatrixMode(GL_MODELVIEW);
    glCopyColorTable(GL_COLOR_TABLE, GL_RGBA, 0, 0, 1);
    float back[4] = {};
    glGetColorTable(GL_COLOR_TABLE, GL_RGBA, GL_FLOAT, back);
    o.floats.assign(back, back + 4);
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  EXPECT_NEAR(e.floats[0], 200.0f / 255.0f, kFloatTolerance);
  EXPECT_NEAR(r.floats[0], 100.0f / 255.0f, 1.0f / 255.0f);  // halved (stored as 8 bits)
}

// Table index ties: the index is round(clamp(c) * (N - 1)) (3.6.5 Color Table Lookup); where a
// box filter makes c * (N - 1) exactly k + 0.5, single-precision sums may land on either
// side, so either entry is the specification's answer (fuzzer seed 141915: a 6x5 box of 1/30
// before a 256-entry post-color-matrix table). Here a 2x1 box of 0.5 over alphas 100 and 101.
TEST(FuzzRegressions, TableIndexTiesGoEitherWay) {
  SL_REQUIRE_REFERENCE();
  auto scenario = [](Outcome& o) {
    putImage(2, 1, {100, 100, 100, 100, 101, 101, 101, 101});
    const float box[8] = {0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f};
    glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 2, 1, GL_RGBA, GL_FLOAT, box);
    glEnable(GL_CONVOLUTION_2D);  // GL_REDUCE: one pixel, c = 100.5 / 255
    std::vector<float> table(256 * 4);
    for (int i = 0; i < 256; ++i)
      for (int c = 0; c < 4; ++c) table[size_t(i) * 4 + c] = float(255 - i) / 255.0f;
    glColorTable(GL_POST_CONVOLUTION_COLOR_TABLE, GL_RGBA, 256, GL_RGBA, GL_FLOAT, table.data());
    glEnable(GL_POST_CONVOLUTION_COLOR_TABLE);
    glWindowPos2i(4, 0);
    glCopyPixels(0, 0, 2, 1, GL_COLOR);
    appendBytes(o, readWindow());
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  for (int c = 0; c < 4; ++c) {
    const size_t i = 4 * 4 + size_t(c);                                      // pixel (4, 0)
    EXPECT_TRUE(e.bytes[i] == 155 || e.bytes[i] == 154) << int(e.bytes[i]);  // T[100] or T[101]
    EXPECT_TRUE(r.bytes[i] == 155 || r.bytes[i] == 154) << int(r.bytes[i]);
  }
}

}  // namespace
}  // namespace sl::imaging::testing
