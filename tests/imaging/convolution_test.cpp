// Convolution: glspec121 3.6.5 "Convolution" equations, table 3.14, the three border modes
// (REDUCE, CONSTANT_BORDER, REPLICATE_BORDER: HP_convolution_border_modes), REDUCE output
// size, 1x1 images, kernels larger than the image, separable filters, filter and
// post-convolution scale/bias. Expectations come from a direct transcription of the
// equations below (double precision), not from imaging/.
#include "imaging/imaging_test_util.h"

namespace sl::imaging::testing {
namespace {

constexpr int kW = 12, kH = 9;  // window; the source is its lower-left kSrcW x kSrcH
constexpr int kSrcW = 6, kSrcH = 5;

struct Kernel {
  int w, h;
  std::vector<double> rgba;  // w*h*4, row j bottom-up
};

// Cs'[i', j'] under each border mode, then C[i', j'] = sum_n sum_m Cs'[i'+n, j'+m] Cf[n, m]
// and Cr[i, j] = C[i - Cw, j - Ch] for the bordered modes. `filtered[c]` false: the component
// passes through (table 3.14), taken under the filter centre.
std::vector<double> convolveModel(const std::vector<uint8_t>& src, int ws, int hs, const Kernel& k,
                                  GLenum border, const double borderColor[4],
                                  const bool filtered[4], int& ow, int& oh) {
  const int cw = k.w / 2, ch = k.h / 2;
  const bool reduce = border == GL_REDUCE;
  ow = reduce ? ws - k.w + 1 : ws;
  oh = reduce ? hs - k.h + 1 : hs;
  std::vector<double> out(size_t(std::max(ow, 0)) * std::max(oh, 0) * 4, 0.0);
  auto source = [&](int x, int y, int c) -> double {
    if (border == GL_REPLICATE_BORDER) {
      x = std::clamp(x, 0, ws - 1);
      y = std::clamp(y, 0, hs - 1);
    } else if (x < 0 || x >= ws || y < 0 || y >= hs) {
      return borderColor[c];
    }
    return src[(size_t(y) * kW + x) * 4 + c] / 255.0;  // the source sits in the window
  };
  for (int j = 0; j < oh; ++j)
    for (int i = 0; i < ow; ++i) {
      const int i0 = reduce ? i : i - cw, j0 = reduce ? j : j - ch;
      for (int c = 0; c < 4; ++c) {
        double sum = 0.0;
        if (!filtered[c]) {
          sum = source(i0 + cw, j0 + ch, c);
        } else {
          for (int m = 0; m < k.h; ++m)
            for (int n = 0; n < k.w; ++n)
              sum += source(i0 + n, j0 + m, c) * k.rgba[(size_t(m) * k.w + n) * 4 + c];
        }
        out[(size_t(j) * ow + i) * 4 + c] = sum;
      }
    }
  return out;
}

Kernel kernel(int w, int h, unsigned seed) {
  Kernel k{w, h, std::vector<double>(size_t(w) * h * 4)};
  uint32_t s = seed;
  for (double& v : k.rgba) {
    s = s * 1664525u + 1013904223u;
    v = double(int(s >> 26)) / 64.0 - 0.2;  // multiples of 1/64 in [-0.2, 0.8)
  }
  return k;
}

// Copies the convolved source to the right half and checks it against the model: the
// framebuffer holds round(clamp(v) * 255) (2.13.9). One step is allowed only where the model
// value lies within 1e-6 of a rounding tie (float arithmetic may go either way there).
void expectCopyMatches(const std::vector<double>& model, int ow, int oh) {
  const auto got = readRgba8(0, 0, kW, kH);
  for (int j = 0; j < oh; ++j)
    for (int i = 0; i < ow; ++i)
      for (int c = 0; c < 4; ++c) {
        const double v = std::clamp(model[(size_t(j) * ow + i) * 4 + c], 0.0, 1.0) * 255.0;
        const int want = int(std::floor(v + 0.5));
        const int have = got[(size_t(j) * kW + kSrcW + i) * 4 + c];
        const bool tie = std::fabs(v - std::floor(v) - 0.5) < 1e-6 * 255.0;
        if (tie) {
          EXPECT_LE(std::abs(have - want), 1);
        } else {
          ASSERT_EQ(have, want) << "output (" << i << "," << j << ") component " << c;
        }
      }
}

struct BorderCase {
  GLenum border;
  int fw, fh;
};

class ConvolutionBorders : public ::testing::TestWithParam<BorderCase> {};

TEST_P(ConvolutionBorders, MatchesTheEquations) {
  const auto [border, fw, fh] = GetParam();
  auto ctx = emulatedContext(kW, kH);
  const auto src = patternImage(kW, kH, 17);
  putImage(kW, kH, src);
  const Kernel k = kernel(fw, fh, fw * 10 + fh);
  std::vector<float> kf(k.rgba.begin(), k.rgba.end());
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, fw, fh, GL_RGBA, GL_FLOAT, kf.data());
  glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, GLint(border));
  const float bc[4] = {0.25f, 0.5f, 1.0f, 0.0f};
  glConvolutionParameterfv(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_COLOR, bc);
  glEnable(GL_CONVOLUTION_2D);
  glWindowPos2i(kSrcW, 0);
  glCopyPixels(0, 0, kSrcW, kSrcH, GL_COLOR);
  glDisable(GL_CONVOLUTION_2D);
  ASSERT_TRUE(drainErrors().empty());
  const double bcd[4] = {0.25, 0.5, 1.0, 0.0};
  const bool all[4] = {true, true, true, true};
  int ow = 0, oh = 0;
  const auto model = convolveModel(src, kSrcW, kSrcH, k, border, bcd, all, ow, oh);
  if (border == GL_REDUCE) {  // "reduced by Wf - 1 and Hf - 1"
    EXPECT_EQ(ow, kSrcW - fw + 1);
    EXPECT_EQ(oh, kSrcH - fh + 1);
  }
  expectCopyMatches(model, ow, oh);
}

INSTANTIATE_TEST_SUITE_P(
    ModesAndSizes, ConvolutionBorders,
    ::testing::Values(BorderCase{GL_REDUCE, 3, 3}, BorderCase{GL_CONSTANT_BORDER, 3, 3},
                      BorderCase{GL_REPLICATE_BORDER, 3, 3}, BorderCase{GL_REDUCE, 1, 1},
                      BorderCase{GL_CONSTANT_BORDER, 4, 2}, BorderCase{GL_REPLICATE_BORDER, 2, 5},
                      BorderCase{GL_CONSTANT_BORDER, 9, 9}, BorderCase{GL_REPLICATE_BORDER, 9, 7}));

// Table 3.14 with the specification's pass-through: each filter internal format.
class ConvolutionFormats : public ::testing::TestWithParam<GLenum> {};

TEST_P(ConvolutionFormats, ComponentsFollowTable314) {
  const GLenum format = GetParam();
  auto ctx = emulatedContext(kW, kH);
  const auto src = patternImage(kW, kH, 23);
  putImage(kW, kH, src);
  Kernel k = kernel(3, 3, 5);
  // Components are selected from the filter data (table 3.15): L and I from R, A from A.
  Kernel stored = k;
  bool filtered[4] = {true, true, true, true};
  for (size_t t = 0; t < 9; ++t) {
    double* p = &stored.rgba[t * 4];
    switch (format) {
      case GL_ALPHA: filtered[0] = filtered[1] = filtered[2] = false; break;
      case GL_LUMINANCE:
        p[1] = p[2] = p[0];
        filtered[3] = false;
        break;
      case GL_LUMINANCE_ALPHA: p[1] = p[2] = p[0]; break;
      case GL_INTENSITY: p[1] = p[2] = p[3] = p[0]; break;
      case GL_RGB: filtered[3] = false; break;
      default: break;
    }
  }
  std::vector<float> kf(k.rgba.begin(), k.rgba.end());
  glConvolutionFilter2D(GL_CONVOLUTION_2D, format, 3, 3, GL_RGBA, GL_FLOAT, kf.data());
  glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, GL_REPLICATE_BORDER);
  glEnable(GL_CONVOLUTION_2D);
  glWindowPos2i(kSrcW, 0);
  glCopyPixels(0, 0, kSrcW, kSrcH, GL_COLOR);
  glDisable(GL_CONVOLUTION_2D);
  const double none[4] = {0, 0, 0, 0};
  int ow = 0, oh = 0;
  expectCopyMatches(
      convolveModel(src, kSrcW, kSrcH, stored, GL_REPLICATE_BORDER, none, filtered, ow, oh), ow,
      oh);
  // Table 6.1: the query returns the stored components, constants for the others.
  float back[9 * 4];
  glGetConvolutionFilter(GL_CONVOLUTION_2D, GL_RGBA, GL_FLOAT, back);
  const float a0 = back[3];
  switch (format) {
    case GL_LUMINANCE:
    case GL_INTENSITY:
      EXPECT_EQ(back[1], 0.0f);
      EXPECT_EQ(a0, 1.0f);
      break;
    case GL_ALPHA:
      EXPECT_EQ(back[0], 0.0f);
      EXPECT_FLOAT_EQ(a0, float(k.rgba[3]));
      break;
    case GL_RGB: EXPECT_EQ(a0, 1.0f); break;
    default: EXPECT_FLOAT_EQ(a0, float(k.rgba[3])); break;
  }
  EXPECT_TRUE(drainErrors().empty());
}

INSTANTIATE_TEST_SUITE_P(EveryFilterFormat, ConvolutionFormats,
                         ::testing::Values(GL_ALPHA, GL_LUMINANCE, GL_LUMINANCE_ALPHA, GL_INTENSITY,
                                           GL_RGB, GL_RGBA));

// REDUCE with a kernel larger than the image: "the output is simply null, with no error".
TEST(Convolution, ReduceLargerThanImageGivesNothing) {
  auto ctx = emulatedContext(kW, kH);
  putImage(kW, kH, patternImage(kW, kH, 2));
  const auto before = readRgba8(0, 0, kW, kH);
  const float k[5 * 5 * 4] = {};
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 5, 5, GL_RGBA, GL_FLOAT, k);
  glEnable(GL_CONVOLUTION_2D);
  glWindowPos2i(kSrcW, 0);
  glCopyPixels(0, 0, 3, 3, GL_COLOR);
  glDisable(GL_CONVOLUTION_2D);
  EXPECT_TRUE(drainErrors().empty());
  EXPECT_EQ(readRgba8(0, 0, kW, kH), before);
}

// A 1x1 image with a 3x3 kernel under CONSTANT_BORDER: every tap but the centre reads the
// border colour.
TEST(Convolution, OneByOneImageConstantBorder) {
  auto ctx = emulatedContext(kW, kH);
  putImage(1, 1, {100, 0, 200, 255});
  float k[9 * 4];
  for (float& v : k) v = 0.1f;
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, k);
  glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, GL_CONSTANT_BORDER);
  const float bc[4] = {1.0f, 0.5f, 0.0f, 0.25f};
  glConvolutionParameterfv(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_COLOR, bc);
  glEnable(GL_CONVOLUTION_2D);
  const auto f = readRgbaF(0, 0, 1, 1);
  const double src[4] = {100 / 255.0, 0, 200 / 255.0, 1};
  for (int c = 0; c < 4; ++c)
    EXPECT_NEAR(f[c], std::clamp(0.1 * src[c] + 0.8 * bc[c], 0.0, 1.0), 1e-6) << c;
}

// Separable: C = sum_n sum_m Cs'[i+n, j+m] row[n] column[m]; scale/bias of SEPARABLE_2D at
// definition (3.6.3) and post-convolution scale/bias (3.6.5).
TEST(Convolution, SeparableWithFilterAndPostScaleBias) {
  auto ctx = emulatedContext(kW, kH);
  const auto src = patternImage(kW, kH, 29);
  putImage(kW, kH, src);
  const float row[3 * 4] = {0.25f, 0.5f, 0.0f,  1.0f,  0.5f, 0.25f,
                            1.0f,  0.0f, 0.25f, 0.25f, 0.0f, 0.0f};
  const float column[2 * 4] = {1.0f, 0.5f, 0.5f, 1.0f, 0.5f, 0.5f, 0.5f, 0.0f};
  const float scale[4] = {2.0f, 1.0f, 1.0f, 1.0f}, bias[4] = {0.0f, 0.125f, 0.0f, 0.0f};
  glConvolutionParameterfv(GL_SEPARABLE_2D, GL_CONVOLUTION_FILTER_SCALE, scale);
  glConvolutionParameterfv(GL_SEPARABLE_2D, GL_CONVOLUTION_FILTER_BIAS, bias);
  glSeparableFilter2D(GL_SEPARABLE_2D, GL_RGBA, 3, 2, GL_RGBA, GL_FLOAT, row, column);
  glEnable(GL_SEPARABLE_2D);
  glPixelTransferf(GL_POST_CONVOLUTION_RED_SCALE, 0.5f);
  glPixelTransferf(GL_POST_CONVOLUTION_ALPHA_BIAS, -0.25f);
  const auto f = readRgbaF(0, 0, kSrcW, kSrcH);  // REDUCE: (6-3+1) x (5-2+1), stride kSrcW
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i)
      for (int c = 0; c < 4; ++c) {
        double sum = 0;
        for (int m = 0; m < 2; ++m)
          for (int n = 0; n < 3; ++n) {
            const double r = row[n * 4 + c] * scale[c] + bias[c];
            const double col = column[m * 4 + c] * scale[c] + bias[c];
            sum += src[(size_t(j + m) * kW + i + n) * 4 + c] / 255.0 * r * col;
          }
        const double post = c == 0 ? sum * 0.5 : (c == 3 ? sum - 0.25 : sum);
        EXPECT_NEAR(f[(size_t(j) * kSrcW + i) * 4 + c], std::clamp(post, 0.0, 1.0), 2e-6)
            << i << "," << j << " c" << c;
      }
}

// Brabec–Seidel Eq. (1): the 3x3 packing kernel collects R from the lower-left, G from the
// lower-middle, B from the middle-left and A from the centre pixel (their Fig. 5), with four
// non-zero taps of nine.
TEST(Convolution, BrabecSeidelPackingKernelEq1) {
  auto ctx = emulatedContext(kW, kH);
  const auto src = patternImage(kW, kH, 31);
  putImage(kW, kH, src);
  float kernel[9 * 4] = {};
  kernel[(0 * 3 + 0) * 4 + 0] = 1;  // row 0 (bottom), column 0: R
  kernel[(0 * 3 + 1) * 4 + 1] = 1;  // row 0, column 1: G
  kernel[(1 * 3 + 0) * 4 + 2] = 1;  // row 1, column 0: B
  kernel[(1 * 3 + 1) * 4 + 3] = 1;  // row 1, column 1 (centre): A
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, kernel);
  glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, GL_REPLICATE_BORDER);
  glEnable(GL_CONVOLUTION_2D);
  GLuint tex = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glCopyTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 0, 0, 8, 8, 0);
  glDisable(GL_CONVOLUTION_2D);
  std::vector<uint8_t> packed(8 * 8 * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, packed.data());
  auto at = [&](int x, int y, int c) {  // replicate border: clamp into the 8x8 source
    return src[(size_t(std::clamp(y, 0, 7)) * kW + std::clamp(x, 0, 7)) * 4 + c];
  };
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const uint8_t* p = &packed[(size_t(y) * 8 + x) * 4];
      EXPECT_EQ(p[0], at(x - 1, y - 1, 0));
      EXPECT_EQ(p[1], at(x, y - 1, 1));
      EXPECT_EQ(p[2], at(x - 1, y, 2));
      EXPECT_EQ(p[3], at(x, y, 3));
    }
  glDeleteTextures(1, &tex);
  EXPECT_TRUE(drainErrors().empty());
}

TEST(Convolution, QueriesAndLimits) {
  auto ctx = emulatedContext(4, 4);
  GLint v = 0;
  glGetConvolutionParameteriv(GL_CONVOLUTION_2D, GL_MAX_CONVOLUTION_WIDTH, &v);
  EXPECT_EQ(v, 9);  // the reference's limit (spec minimum 3)
  glGetConvolutionParameteriv(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, &v);
  EXPECT_EQ(GLenum(v), GLenum(GL_REDUCE));  // initial state
  glGetConvolutionParameteriv(GL_CONVOLUTION_1D, GL_CONVOLUTION_HEIGHT, &v);
  EXPECT_EQ(drainErrors(), std::vector<GLenum>{GL_INVALID_ENUM});  // no height for 1D
  const float k[10 * 4] = {};
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 10, 1, GL_RGBA, GL_FLOAT, k);
  EXPECT_EQ(drainErrors(), std::vector<GLenum>{GL_INVALID_VALUE});
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 1, 1, GL_INTENSITY, GL_FLOAT, k);
  EXPECT_EQ(drainErrors(), std::vector<GLenum>{GL_INVALID_ENUM});
  glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, GL_ONE);
  EXPECT_EQ(drainErrors(), std::vector<GLenum>{GL_INVALID_ENUM});
}

}  // namespace
}  // namespace sl::imaging::testing
