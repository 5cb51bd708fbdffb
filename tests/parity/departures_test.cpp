// Where the reference (Mesa 7.8.2) departs from the OpenGL 1.2.1 specification: one named
// test per departure. Each asserts the specification's answer for the emulation and the
// departure for the reference, so the suite shows where and why the two differ.
// Departure1..8 are listed in ../shared/reference-gl/README.md; Additional* were found by
// this parity suite (same method: the specification's answer against the measured one).
#include <cfloat>

#include "parity/parity_util.h"

namespace sl::imaging::testing {
namespace {

// Source pixel (R, G, B, A) used by several departures, 8-bit.
const std::vector<uint8_t> kPixel = {200, 60, 120, 255};

Outcome both(Backend b, const Scenario& s) {
  return runOn(b, s, /*accumulation=*/b != Backend::kOsmesa);
}

// 1. ReadPixels(GL_FLOAT) after a convolution must clamp (4.3.2 "Final Conversion").
TEST(Departures, Departure1_FloatReadPixelsAfterConvolutionIsNotClamped) {
  SL_REQUIRE_REFERENCE();
  auto scenario = [](Outcome& o) {
    putImage(1, 1, kPixel);
    const float doubling[4] = {2, 2, 2, 2};  // 1x1 filter: every component times 2
    glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 1, 1, GL_RGBA, GL_FLOAT, doubling);
    glEnable(GL_CONVOLUTION_2D);
    appendFloats(o, readRgbaF(0, 0, 1, 1));
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  EXPECT_FLOAT_EQ(e.floats[0], 1.0f);                    // spec: 2 * 200/255 clamped
  EXPECT_FLOAT_EQ(r.floats[0], 2.0f * 200.0f / 255.0f);  // reference: unclamped
}

// 2. LUMINANCE tables index each replaced component with its own value (table 3.13).
TEST(Departures, Departure2_LuminanceTableIndexedWithRedForAll) {
  SL_REQUIRE_REFERENCE();
  auto scenario = [](Outcome& o) {
    putImage(1, 1, kPixel);
    std::vector<float> ramp(256);
    for (int i = 0; i < 256; ++i) ramp[i] = float(255 - i) / 255.0f;  // L_t[i] = 1 - i/255
    glColorTable(GL_COLOR_TABLE, GL_LUMINANCE, 256, GL_LUMINANCE, GL_FLOAT, ramp.data());
    glEnable(GL_COLOR_TABLE);
    appendFloats(o, readRgbaF(0, 0, 1, 1));
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  // Spec: G = L_t[index(G)] = 1 - 60/255; reference: L_t[index(R)] = 1 - 200/255.
  EXPECT_NEAR(e.floats[1], 195.0f / 255.0f, 1e-6f);
  EXPECT_NEAR(r.floats[1], 55.0f / 255.0f, 1e-6f);
}

// 3. The filter's internal format selects the convolved components (table 3.14) and is
//    returned per table 6.1.
TEST(Departures, Departure3_FilterInternalFormatIgnored) {
  SL_REQUIRE_REFERENCE();
  auto scenario = [](Outcome& o) {
    putImage(1, 1, kPixel);
    const float half[4] = {0.5f, 0.5f, 0.5f, 0.5f};
    glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGB, 1, 1, GL_RGBA, GL_FLOAT, half);
    glEnable(GL_CONVOLUTION_2D);
    glWindowPos2i(0, 0);
    glCopyPixels(0, 0, 1, 1, GL_COLOR);
    appendBytes(o, readWindow());
    float back[4];
    glGetConvolutionFilter(GL_CONVOLUTION_2D, GL_RGBA, GL_FLOAT, back);
    o.floats.assign(back, back + 4);
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  EXPECT_EQ(e.bytes[3], 255);    // spec: an RGB filter passes A unmodified
  EXPECT_EQ(r.bytes[3], 128);    // reference: A convolved with the unpacked 0.5
  EXPECT_EQ(e.floats[3], 1.0f);  // table 6.1: RGB returns A = 1
  EXPECT_EQ(r.floats[3], 0.5f);
}

// 4. glCopyColorTable / glCopyConvolutionFilter2D define a table / filter of the given size.
//    NOT REPRODUCED: on this configuration (OSMesa RGBA window, copies from the lower-left
//    corner) the reference defines both with the requested size and the framebuffer's
//    contents, like the emulation; the test records that, so a change on either side shows.
TEST(Departures, Departure4_CopiedTableAndFilterHaveZeroWidth_NotReproduced) {
  SL_REQUIRE_REFERENCE();
  auto scenario = [](Outcome& o) {
    putImage(kParityW, kParityH, patternImage(kParityW, kParityH, 4));
    glCopyColorTable(GL_COLOR_TABLE, GL_RGBA, 0, 0, 8);
    glCopyConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 0, 0, 3, 3);
    GLint w = -1, fw = -1;
    glGetColorTableParameteriv(GL_COLOR_TABLE, GL_COLOR_TABLE_WIDTH, &w);
    glGetConvolutionParameteriv(GL_CONVOLUTION_2D, GL_CONVOLUTION_WIDTH, &fw);
    o.floats = {float(w), float(fw)};
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  EXPECT_EQ(e.floats, (std::vector<float>{8, 3}));
  EXPECT_EQ(r.floats, (std::vector<float>{8, 3}));  // README: {0, 0}; not seen here
}

// 5. With GL_HISTOGRAM_SINK "no pixel values are returned" (3.6.5 Histogram).
TEST(Departures, Departure5_HistogramSinkStillWritesPixels) {
  SL_REQUIRE_REFERENCE();
  auto scenario = [](Outcome& o) {
    putImage(1, 1, kPixel);
    glHistogram(GL_HISTOGRAM, 16, GL_RGBA, GL_TRUE);
    glEnable(GL_HISTOGRAM);
    float px[4] = {-1, -1, -1, -1};
    glReadPixels(0, 0, 1, 1, GL_RGBA, GL_FLOAT, px);
    o.floats.assign(px, px + 4);
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  EXPECT_EQ(e.floats[0], -1.0f);                     // untouched
  EXPECT_NEAR(r.floats[0], 200.0f / 255.0f, 1e-6f);  // written anyway
}

// 6. A LUMINANCE histogram counts R only and returns (L, 0, 0, 1) (3.6.5, table 6.1).
TEST(Departures, Departure6_LuminanceHistogramAlsoCountsGreenAndBlue) {
  SL_REQUIRE_REFERENCE();
  auto scenario = [](Outcome& o) {
    putImage(1, 1, kPixel);
    glHistogram(GL_HISTOGRAM, 2, GL_LUMINANCE, GL_FALSE);
    glEnable(GL_HISTOGRAM);
    readRgbaF(0, 0, 1, 1);
    GLuint counts[8] = {};
    glGetHistogram(GL_HISTOGRAM, GL_FALSE, GL_RGBA, GL_UNSIGNED_INT, counts);
    for (GLuint c : counts) o.floats.push_back(float(c));
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  // R = 200/255 -> entry 1; G = 60/255 -> entry 0. Spec: entry 1 = (1, 0, 0, 1).
  EXPECT_EQ(e.floats[4 + 1], 0.0f);
  EXPECT_EQ(e.floats[1], 0.0f);
  EXPECT_EQ(r.floats[1], 1.0f);  // reference counted G in entry 0
}

// 7. A format that is not a pixel format is GL_INVALID_ENUM (EXT_convolution "Errors").
TEST(Departures, Departure7_IntensityPixelFormatIsInvalidOperation) {
  SL_REQUIRE_REFERENCE();
  auto scenario = [](Outcome& o) {
    const float f[4] = {1, 1, 1, 1};
    glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 1, 1, GL_INTENSITY, GL_FLOAT, f);
    o.errors = drainErrors();
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  EXPECT_EQ(e.errors, std::vector<GLenum>{GL_INVALID_ENUM});
  EXPECT_EQ(r.errors, std::vector<GLenum>{GL_INVALID_OPERATION});
}

// 8. Table data is scaled and biased unclamped, then clamped (3.6.3).
TEST(Departures, Departure8_TableDataClampedBeforeScaleAndBias) {
  SL_REQUIRE_REFERENCE();
  auto scenario = [](Outcome& o) {
    const float scale[4] = {0.5f, 0.5f, 0.5f, 0.5f};
    glColorTableParameterfv(GL_COLOR_TABLE, GL_COLOR_TABLE_SCALE, scale);
    const float data[8] = {1.6f, 1.6f, 1.6f, 1.6f, -0.4f, 0, 0, 0};
    glColorTable(GL_COLOR_TABLE, GL_RGBA, 2, GL_RGBA, GL_FLOAT, data);
    float back[8];
    glGetColorTable(GL_COLOR_TABLE, GL_RGBA, GL_FLOAT, back);
    o.floats.assign(back, back + 8);
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  EXPECT_FLOAT_EQ(e.floats[0], 0.8f);  // 1.6 * 0.5
  EXPECT_FLOAT_EQ(r.floats[0], 0.5f);  // clamp(1.6) * 0.5
}

// A. glReadPixels(GL_UNSIGNED_BYTE) after pixel transfer: 4.3.2 converts with c = 255 f;
//    the emulation rounds to nearest (as framebuffer writes do, 2.13.9); the reference
//    truncates.
TEST(Departures, AdditionalA_ReadPixelsUnsignedByteTruncates) {
  SL_REQUIRE_REFERENCE();
  auto scenario = [](Outcome& o) {
    putImage(1, 1, kPixel);
    glPixelTransferf(GL_RED_SCALE, 0.6f);  // 200 * 0.6 = 120 exactly; G + 0.3 step below
    glPixelTransferf(GL_GREEN_BIAS, 0.7f / 255.0f);
    appendBytes(o, readRgba8(0, 0, 1, 1));
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  EXPECT_EQ(e.bytes[1], 61);  // 60.7 rounds to 61
  EXPECT_EQ(r.bytes[1], 60);  // truncated
}

// B. glGetColorTable returns LUMINANCE as (L, 0, 0, 1) and INTENSITY as (I, 0, 0, 1)
//    (table 6.1); the reference repeats L in G and B, and I in G, B and A.
TEST(Departures, AdditionalB_GetColorTableRepeatsLuminance) {
  SL_REQUIRE_REFERENCE();
  auto scenario = [](Outcome& o) {
    const float data[4] = {0.25f, 0.5f, 0.75f, 1.0f};
    for (GLenum f : {GL_LUMINANCE, GL_INTENSITY}) {
      glColorTable(GL_COLOR_TABLE, f, 1, GL_RGBA, GL_FLOAT, data);
      float back[4];
      glGetColorTable(GL_COLOR_TABLE, GL_RGBA, GL_FLOAT, back);
      o.floats.insert(o.floats.end(), back, back + 4);
    }
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  EXPECT_EQ(e.floats, (std::vector<float>{0.25f, 0, 0, 1, 0.25f, 0, 0, 1}));
  EXPECT_EQ(r.floats, (std::vector<float>{0.25f, 0.25f, 0.25f, 1, 0.25f, 0.25f, 0.25f, 0.25f}));
}

// C. Minmax keeps unclamped extremes ("at least the same representable range as a floating
//    point number used to represent colors", 3.6.5); the reference returns them clamped.
TEST(Departures, AdditionalC_MinmaxClampsExtremes) {
  SL_REQUIRE_REFERENCE();
  auto scenario = [](Outcome& o) {
    putImage(1, 1, kPixel);
    glMinmax(GL_MINMAX, GL_RGBA, GL_FALSE);
    glEnable(GL_MINMAX);
    glPixelTransferf(GL_RED_SCALE, 1.5f);
    readRgbaF(0, 0, 1, 1);
    float mm[8];
    glGetMinmax(GL_MINMAX, GL_FALSE, GL_RGBA, GL_FLOAT, mm);
    o.floats.assign(mm, mm + 8);
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  EXPECT_NEAR(e.floats[4], 1.5f * 200.0f / 255.0f, 1e-6f);  // max R unclamped
  EXPECT_EQ(r.floats[4], 1.0f);
}

// C, on a reset table (our choice, stated at imaging/histogram.cpp
//    emGetMinmax): a GL_FLOAT query returns the reset state, "the maximum representable value"
//    as each minimum and "the minimum representable value" as each maximum (3.6.3, 6.1.10),
//    which the emulation's IEEE single table holds as +-FLT_MAX; a luminance pack saturates
//    there. The reference clamps: (1, 1, 1, 1) and (0, 0, 0, 0), and L = 1 + 1 + 1 = 3 for
//    the minimum (it sums the clamped components without clamping the sum). The normalised
//    integer types clamp on both sides, and there the two agree.
TEST(Departures, AdditionalC_ResetMinmaxReadsClampedExtremes) {
  SL_REQUIRE_REFERENCE();
  auto scenario = [](Outcome& o) {
    glMinmax(GL_MINMAX, GL_RGBA, GL_FALSE);
    float mm[8];
    glGetMinmax(GL_MINMAX, GL_FALSE, GL_RGBA, GL_FLOAT, mm);
    o.floats.assign(mm, mm + 8);
    float l[2];
    glGetMinmax(GL_MINMAX, GL_FALSE, GL_LUMINANCE, GL_FLOAT, l);
    o.floats.insert(o.floats.end(), l, l + 2);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    uint8_t ub[8];
    glGetMinmax(GL_MINMAX, GL_FALSE, GL_RGBA, GL_UNSIGNED_BYTE, ub);
    o.bytes.assign(ub, ub + 8);
    GLshort sh[8];
    glGetMinmax(GL_MINMAX, GL_FALSE, GL_RGBA, GL_SHORT, sh);
    for (GLshort v : sh) o.floats.push_back(v);
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  ASSERT_EQ(e.floats.size(), 18u);
  ASSERT_EQ(r.floats.size(), 18u);
  const std::vector<float> head(e.floats.begin(), e.floats.begin() + 10);
  EXPECT_EQ(head, (std::vector<float>{FLT_MAX, FLT_MAX, FLT_MAX, FLT_MAX, -FLT_MAX, -FLT_MAX,
                                      -FLT_MAX, -FLT_MAX, FLT_MAX, -FLT_MAX}));
  EXPECT_EQ(std::vector<float>(r.floats.begin(), r.floats.begin() + 10),
            (std::vector<float>{1, 1, 1, 1, 0, 0, 0, 0, 3, 0}));
  // Integer types: the same from both (min 1.0 and max 0 in the type's scale, table 4.7).
  EXPECT_EQ(e.bytes, (std::vector<uint8_t>{255, 255, 255, 255, 0, 0, 0, 0}));
  EXPECT_EQ(r.bytes, e.bytes);
  EXPECT_EQ(std::vector<float>(e.floats.begin() + 10, e.floats.end()),
            (std::vector<float>{32767, 32767, 32767, 32767, 0, 0, 0, 0}));
  EXPECT_EQ(std::vector<float>(r.floats.begin() + 10, r.floats.end()),
            std::vector<float>(e.floats.begin() + 10, e.floats.end()));
}

// D. On glCopyTexImage2D / glCopyTexSubImage2D each stage applies once (3.8.2: "processed
//    exactly as for CopyPixels"); the reference applies the color matrix (with its post
//    scale and bias) and the color tables twice there (measured by this suite: a 64-entry
//    ramp to 0.5 maps 231 to 57 instead of 115), and clamps before convolving.
TEST(Departures, AdditionalD_CopyTexAppliesColorMatrixTwice) {
  SL_REQUIRE_REFERENCE();
  auto matrixScenario = [](Outcome& o) {
    putImage(1, 1, kPixel);
    GLuint tex = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    const float half[16] = {0.5f, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    glMatrixMode(GL_COLOR);
    glLoadMatrixf(half);
    glMatrixMode(GL_MODELVIEW);
    glCopyTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 0, 0, 1, 1, 0);
    resetImaging();
    uint8_t t[4];
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, t);
    o.bytes.assign(t, t + 4);
    glDeleteTextures(1, &tex);
  };
  const Outcome em = both(Backend::kOsmesa, matrixScenario),
                rm = both(Backend::kReference, matrixScenario);
  EXPECT_EQ(em.bytes[0], 100);  // 200 * 0.5
  EXPECT_EQ(rm.bytes[0], 50);   // 200 * 0.5 * 0.5
}

// E. GL_LOAD replaces the accumulation buffer inside the scissor box only (4.2.4); in the
//    reference a scissored GL_LOAD after another GL_LOAD also rescales the values outside
//    the box (its integer accumulation shortcut keeps one scale for the whole buffer).
TEST(Departures, AdditionalE_ScissoredLoadRescalesOutsideTheBox) {
  SL_REQUIRE_REFERENCE();
  auto scenario = [](Outcome& o) {
    putImage(kParityW, kParityH, std::vector<uint8_t>(size_t(kParityW) * kParityH * 4, 200));
    glAccum(GL_LOAD, 0.2f);
    glEnable(GL_SCISSOR_TEST);
    glScissor(4, 4, 4, 4);
    glAccum(GL_LOAD, 0.6f);
    glDisable(GL_SCISSOR_TEST);
    glAccum(GL_RETURN, 1.0f);
    appendBytes(o, readWindow());
  };
  const Outcome e = runOn(Backend::kOsmesa, scenario, /*accumulation=*/false);
  const Outcome r = runOn(Backend::kReference, scenario);
  EXPECT_EQ(e.bytes[0], 40);   // outside the box: 0.2 * 200
  EXPECT_EQ(r.bytes[0], 120);  // rescaled to 0.6 * 200
  const size_t inside = (size_t(5) * kParityW + 5) * 4;
  EXPECT_EQ(e.bytes[inside], 120);
  EXPECT_EQ(r.bytes[inside], 120);
}

// F. Writes round to nearest (2.13.9); the reference's float-to-byte shortcut writes 255
//    for every value from 0.99609375 (0x3f7f0000), where 254 is nearest below 254.5/255.
TEST(Departures, AdditionalF_ReferenceSaturatesAbove0996) {
  SL_REQUIRE_REFERENCE();
  auto scenario = [](Outcome& o) {
    putImage(1, 1, {254, 254, 254, 254});
    const float gain = 254.2f / 254.0f;  // 254 -> 254.2: nearest byte 254, value 0.99686
    const float f[4] = {gain, gain, gain, gain};
    glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 1, 1, GL_RGBA, GL_FLOAT, f);
    glEnable(GL_CONVOLUTION_2D);
    glWindowPos2i(1, 0);
    glCopyPixels(0, 0, 1, 1, GL_COLOR);
    appendBytes(o, readWindow());
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  ASSERT_TRUE(inSaturationBand(254.2f / 255.0f));
  EXPECT_EQ(e.bytes[4], 254);
  EXPECT_EQ(r.bytes[4], 255);
}

// G. glCopyTexImage1D under a GL_REDUCE 1D filter defines a texture of the convolved width
//    W - Wf + 1 (3.8.2: processed as TexImage1D; 3.6.5: REDUCE "the resulting image is
//    smaller", as glCopyTexImage2D does on both); the reference keeps the source width W and
//    leaves the last Wf - 1 texels undefined (uninitialised memory: zeros in most runs, other
//    bytes in some), after the convolved ones (found by the 1D parity cases).
TEST(Departures, AdditionalG_CopyTexImage1DReduceKeepsTheSourceWidth) {
  SL_REQUIRE_REFERENCE();
  constexpr int kRow = 8, kFilterWidth = 3;
  auto scenario = [](Outcome& o) {
    putImage(kRow, 1, std::vector<uint8_t>(size_t(kRow) * 4, 200));
    const float f[kFilterWidth * 4] = {0.2f, 0.2f, 0.2f, 0.2f, 0.4f, 0.4f,
                                       0.4f, 0.4f, 0.2f, 0.2f, 0.2f, 0.2f};  // sums to 0.8
    glConvolutionFilter1D(GL_CONVOLUTION_1D, GL_RGBA, kFilterWidth, GL_RGBA, GL_FLOAT, f);
    glEnable(GL_CONVOLUTION_1D);  // REDUCE: the initial border mode
    GLuint tex = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_1D, tex);
    glCopyTexImage1D(GL_TEXTURE_1D, 0, GL_RGBA8, 0, 0, kRow, 0);
    glDisable(GL_CONVOLUTION_1D);
    GLint width = 0;
    glGetTexLevelParameteriv(GL_TEXTURE_1D, 0, GL_TEXTURE_WIDTH, &width);
    o.floats.push_back(float(width));
    std::vector<uint8_t> texels(size_t(width) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTexImage(GL_TEXTURE_1D, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
    appendBytes(o, texels);
    glDeleteTextures(1, &tex);
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  EXPECT_EQ(e.floats[0], float(kRow - kFilterWidth + 1));
  EXPECT_EQ(r.floats[0], float(kRow));
  ASSERT_EQ(e.bytes.size(), size_t(kRow - kFilterWidth + 1) * 4);
  ASSERT_EQ(r.bytes.size(), size_t(kRow) * 4);
  for (size_t i = 0; i < e.bytes.size(); ++i) {
    EXPECT_EQ(e.bytes[i], 160) << i;  // 0.8 * 200
    EXPECT_EQ(r.bytes[i], 160) << i;  // the convolved texels agree
  }
}

// Exact rounding ties may go either way in single precision (the reference README): both
// implementations agree everywhere except at pixels where the test proves the exact value
// is a tie, and there by one step.
TEST(Departures, RoundingTiesDifferByAtMostOneStep) {
  SL_REQUIRE_REFERENCE();
  const auto src = patternImage(kParityW, kParityH, 3);
  auto scenario = [&src](Outcome& o) {
    putImage(kParityW, kParityH, src);
    glPixelTransferf(GL_RED_SCALE, 0.5f);  // odd R values give exact x.5 ties
    glWindowPos2i(0, 0);
    glCopyPixels(0, 0, kParityW, kParityH, GL_COLOR);
    appendBytes(o, readWindow());
  };
  const Outcome e = both(Backend::kOsmesa, scenario), r = both(Backend::kReference, scenario);
  int ties = 0;
  for (size_t i = 0; i < src.size(); ++i) {
    const bool tie = i % 4 == 0 && src[i] % 2 == 1;  // 0.5 * odd = k + 0.5 exactly
    if (tie) {
      ++ties;
      EXPECT_LE(std::abs(int(e.bytes[i]) - int(r.bytes[i])), 1) << i;
    } else {
      EXPECT_EQ(e.bytes[i], r.bytes[i]) << i;
    }
  }
  EXPECT_GT(ties, 0);
}

}  // namespace
}  // namespace sl::imaging::testing
