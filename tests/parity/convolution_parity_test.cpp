// Parity of convolution (glspec121 3.6.3 "Convolution Filter Specification", 3.6.5
// "Convolution", table 3.14, HP_convolution_border_modes): 2D filters from 1x1 to 9x9 under
// the three border modes, every filter internal format, filter and post-convolution scale and
// bias, separable filters, kernels larger than the image and 1x1 images. Results go through
// glCopyPixels into the 8-bit framebuffer and are compared bit for bit.
#include "parity/parity_util.h"

namespace sl::imaging::testing {
namespace {

constexpr int kSrcW = 8;  // the left half of the window is the source, the right half the copy

// Filter weights in [-0.15, 0.35): sums stay mostly inside [0,1] so results are not all
// clamped, and are never near a rounding tie by construction of random floats.
std::vector<float> weights(int n, unsigned seed) {
  std::vector<float> w(size_t(n) * 4);
  uint32_t s = seed * 747796405u + 2891336453u;
  for (float& v : w) {
    s = s * 1664525u + 1013904223u;
    v = float(s >> 8) / float(1u << 24) * 0.5f - 0.15f;
  }
  return w;
}

// Makes filter data on which the reference's handling of filter formats (it convolves all
// four channels with the data as unpacked: its README, departure 3) and the specification's
// table 3.14 agree: components the format does not hold carry a unit tap at the centre,
// luminance/intensity data is replicated into the channels that share it.
std::vector<float> compatibleFilter(GLenum format, int w, int h, unsigned seed) {
  auto f = weights(w * h, seed);
  const int centre = (h / 2) * w + w / 2;
  for (int k = 0; k < w * h; ++k) {
    float* p = &f[size_t(k) * 4];
    const float delta = k == centre ? 1.0f : 0.0f;
    switch (format) {
      case GL_ALPHA: p[0] = p[1] = p[2] = delta; break;
      case GL_LUMINANCE:
        p[1] = p[2] = p[0];
        p[3] = delta;
        break;
      case GL_LUMINANCE_ALPHA: p[1] = p[2] = p[0]; break;
      case GL_INTENSITY: p[1] = p[2] = p[3] = p[0]; break;
      case GL_RGB: p[3] = delta; break;
      default: break;
    }
  }
  return f;
}

void setBorder(GLenum target, GLenum mode) {
  glConvolutionParameteri(target, GL_CONVOLUTION_BORDER_MODE, GLint(mode));
  const float border[4] = {0.2f, 0.9f, 0.4f, 0.6f};
  glConvolutionParameterfv(target, GL_CONVOLUTION_BORDER_COLOR, border);
}

// Copies the convolved left half to the right half and returns the whole window. The same
// pipeline read back as floats marks the bytes whose exact value lies in the band the
// reference saturates to 255 (parity_util.h).
void copyAndRead(Outcome& o, int srcW = kSrcW, int srcH = kParityH) {
  std::vector<float> exact(size_t(srcW) * srcH * 4, -1.0f);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, srcW, srcH, GL_RGBA, GL_FLOAT, exact.data());  // REDUCE: stride srcW
  glWindowPos2i(kSrcW, 0);
  glCopyPixels(0, 0, srcW, srcH, GL_COLOR);
  std::vector<uint8_t> band(size_t(kParityW) * kParityH * 4, 0);
  for (int y = 0; y < srcH; ++y)
    for (int x = 0; x < srcW && kSrcW + x < kParityW; ++x)
      for (int c = 0; c < 4; ++c)
        band[(size_t(y) * kParityW + kSrcW + x) * 4 + c] =
            inSaturationBand(exact[(size_t(y) * srcW + x) * 4 + c]) ? 1 : 0;
  appendBytes(o, readWindow());
  o.saturationBand = band;
}

struct FilterCase {
  int w, h;
  GLenum border;
  GLenum format;
};

std::string borderName(GLenum b) {
  return b == GL_REDUCE ? "Reduce" : b == GL_CONSTANT_BORDER ? "Constant" : "Replicate";
}
std::string formatName(GLenum f) {
  switch (f) {
    case GL_ALPHA: return "Alpha";
    case GL_LUMINANCE: return "Luminance";
    case GL_LUMINANCE_ALPHA: return "LuminanceAlpha";
    case GL_INTENSITY: return "Intensity";
    case GL_RGB: return "Rgb";
    default: return "Rgba";
  }
}

class Filter2DParity : public ::testing::TestWithParam<FilterCase> {};

TEST_P(Filter2DParity, CopyPixels) {
  SL_REQUIRE_REFERENCE();
  const FilterCase p = GetParam();
  checkParity([p](Outcome& o) {
    putImage(kParityW, kParityH, patternImage(kParityW, kParityH, 31));
    const auto f = compatibleFilter(p.format, p.w, p.h, p.w * 16 + p.h + p.format);
    glConvolutionFilter2D(GL_CONVOLUTION_2D, p.format, p.w, p.h, GL_RGBA, GL_FLOAT, f.data());
    setBorder(GL_CONVOLUTION_2D, p.border);
    glEnable(GL_CONVOLUTION_2D);
    copyAndRead(o);
  });
}

std::vector<FilterCase> filterCases() {
  std::vector<FilterCase> cases;
  const int sizes[][2] = {{1, 1}, {2, 2}, {3, 3}, {5, 3}, {7, 7}, {9, 9}, {9, 1},
                          {1, 9}, {4, 4}, {6, 6}, {8, 8}, {3, 5}, {4, 6}, {8, 2}};
  for (GLenum b : {GL_REDUCE, GL_CONSTANT_BORDER, GL_REPLICATE_BORDER}) {
    for (const auto& s : sizes) cases.push_back({s[0], s[1], b, GL_RGBA});
    for (GLenum f : {GL_ALPHA, GL_LUMINANCE, GL_LUMINANCE_ALPHA, GL_INTENSITY, GL_RGB})
      cases.push_back({3, 3, b, f});
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(SizesBordersFormats, Filter2DParity, ::testing::ValuesIn(filterCases()),
                         [](const ::testing::TestParamInfo<FilterCase>& i) {
                           return std::to_string(i.param.w) + "x" + std::to_string(i.param.h) +
                                  "_" + borderName(i.param.border) + "_" +
                                  formatName(i.param.format);
                         });

// Separable filters: row x column products, every border mode.
class SeparableParity : public ::testing::TestWithParam<FilterCase> {};
TEST_P(SeparableParity, CopyPixels) {
  SL_REQUIRE_REFERENCE();
  const FilterCase p = GetParam();
  checkParity([p](Outcome& o) {
    putImage(kParityW, kParityH, patternImage(kParityW, kParityH, 41));
    auto row = weights(p.w, 5 + p.w), column = weights(p.h, 9 + p.h);
    for (float& v : column) v *= 2.0f;
    glSeparableFilter2D(GL_SEPARABLE_2D, GL_RGBA, p.w, p.h, GL_RGBA, GL_FLOAT, row.data(),
                        column.data());
    setBorder(GL_SEPARABLE_2D, p.border);
    glEnable(GL_SEPARABLE_2D);
    copyAndRead(o);
    std::vector<float> r(size_t(p.w) * 4), c(size_t(p.h) * 4);
    glGetSeparableFilter(GL_SEPARABLE_2D, GL_RGBA, GL_FLOAT, r.data(), c.data(), nullptr);
    appendFloats(o, r);
    appendFloats(o, c);
  });
}
INSTANTIATE_TEST_SUITE_P(SizesBorders, SeparableParity,
                         ::testing::Values(FilterCase{3, 3, GL_REDUCE, GL_RGBA},
                                           FilterCase{3, 3, GL_CONSTANT_BORDER, GL_RGBA},
                                           FilterCase{3, 3, GL_REPLICATE_BORDER, GL_RGBA},
                                           FilterCase{5, 1, GL_REDUCE, GL_RGBA},
                                           FilterCase{5, 1, GL_CONSTANT_BORDER, GL_RGBA},
                                           FilterCase{1, 5, GL_REPLICATE_BORDER, GL_RGBA},
                                           FilterCase{9, 9, GL_REDUCE, GL_RGBA},
                                           FilterCase{9, 9, GL_CONSTANT_BORDER, GL_RGBA},
                                           FilterCase{9, 9, GL_REPLICATE_BORDER, GL_RGBA},
                                           FilterCase{4, 2, GL_REPLICATE_BORDER, GL_RGBA}),
                         [](const ::testing::TestParamInfo<FilterCase>& i) {
                           return std::to_string(i.param.w) + "x" + std::to_string(i.param.h) +
                                  "_" + borderName(i.param.border);
                         });

// Small images: a 1x1 image and kernels larger than the image, every border mode.
struct SmallCase {
  int srcW, srcH, fw, fh;
  GLenum border;
};
class SmallImageParity : public ::testing::TestWithParam<SmallCase> {};
TEST_P(SmallImageParity, CopyPixels) {
  SL_REQUIRE_REFERENCE();
  const SmallCase p = GetParam();
  checkParity([p](Outcome& o) {
    putImage(kParityW, kParityH, patternImage(kParityW, kParityH, 51));
    const auto f = weights(p.fw * p.fh, 3);
    glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, p.fw, p.fh, GL_RGBA, GL_FLOAT, f.data());
    setBorder(GL_CONVOLUTION_2D, p.border);
    glEnable(GL_CONVOLUTION_2D);
    copyAndRead(o, p.srcW, p.srcH);
  });
}
INSTANTIATE_TEST_SUITE_P(
    OneByOneAndLargeKernels, SmallImageParity,
    ::testing::Values(SmallCase{1, 1, 3, 3, GL_REDUCE}, SmallCase{1, 1, 3, 3, GL_CONSTANT_BORDER},
                      SmallCase{1, 1, 3, 3, GL_REPLICATE_BORDER}, SmallCase{1, 1, 1, 1, GL_REDUCE},
                      SmallCase{4, 3, 5, 5, GL_REDUCE}, SmallCase{4, 3, 5, 5, GL_CONSTANT_BORDER},
                      SmallCase{4, 3, 5, 5, GL_REPLICATE_BORDER},
                      SmallCase{2, 2, 9, 9, GL_REPLICATE_BORDER}),
    [](const ::testing::TestParamInfo<SmallCase>& i) {
      const auto& p = i.param;
      return std::to_string(p.srcW) + "x" + std::to_string(p.srcH) + "_kernel" +
             std::to_string(p.fw) + "x" + std::to_string(p.fh) + "_" + borderName(p.border);
    });

// Filter scale/bias (at definition, 3.6.3) and post-convolution scale/bias (3.6.5).
class ScaleBiasParity : public ::testing::TestWithParam<int> {};
TEST_P(ScaleBiasParity, CopyPixels) {
  SL_REQUIRE_REFERENCE();
  const int k = GetParam();
  checkParity([k](Outcome& o) {
    putImage(kParityW, kParityH, patternImage(kParityW, kParityH, 61 + k));
    const float scale[3][4] = {{2, 0.5f, 1, -1}, {0.25f, 0.25f, 0.25f, 0.25f}, {1, 1, 1, 1}};
    const float bias[3][4] = {{0, 0.01f, -0.02f, 0.1f}, {0.05f, 0, 0, 0}, {0, 0, 0, 0}};
    if (k < 3) {
      glConvolutionParameterfv(GL_CONVOLUTION_2D, GL_CONVOLUTION_FILTER_SCALE, scale[k]);
      glConvolutionParameterfv(GL_CONVOLUTION_2D, GL_CONVOLUTION_FILTER_BIAS, bias[k]);
    }
    const auto f = weights(9, 70 + k);
    glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, f.data());
    setBorder(GL_CONVOLUTION_2D, GL_REPLICATE_BORDER);
    if (k >= 2) {
      const float ps[4] = {1.5f, 0.5f, 2.0f, 1.0f}, pb[4] = {-0.1f, 0.2f, 0.0f, 0.3f};
      const GLenum sp[4] = {GL_POST_CONVOLUTION_RED_SCALE, GL_POST_CONVOLUTION_GREEN_SCALE,
                            GL_POST_CONVOLUTION_BLUE_SCALE, GL_POST_CONVOLUTION_ALPHA_SCALE};
      const GLenum bp[4] = {GL_POST_CONVOLUTION_RED_BIAS, GL_POST_CONVOLUTION_GREEN_BIAS,
                            GL_POST_CONVOLUTION_BLUE_BIAS, GL_POST_CONVOLUTION_ALPHA_BIAS};
      for (int c = 0; c < 4; ++c) {
        glPixelTransferf(sp[c], ps[c] * (k == 4 ? -1.0f : 1.0f));
        glPixelTransferf(bp[c], pb[c] + (k == 4 ? 1.0f : 0.0f));
      }
    }
    if (k != 3) glEnable(GL_CONVOLUTION_2D);  // k == 3: post-conv scale/bias without a filter
    copyAndRead(o);
    std::vector<float> back(9 * 4);
    glGetConvolutionFilter(GL_CONVOLUTION_2D, GL_RGBA, GL_FLOAT, back.data());
    appendFloats(o, back);
  });
}
INSTANTIATE_TEST_SUITE_P(FilterAndPostConvolution, ScaleBiasParity, ::testing::Range(0, 5));

// The packing kernel of Brabec–Seidel Eq. (1) on glCopyTexSubImage2D.
TEST(BrabecSeidelParity, PackingKernelOnCopyTexSubImage) {
  SL_REQUIRE_REFERENCE();
  checkParity([](Outcome& o) {
    putImage(kParityW, kParityH, patternImage(kParityW, kParityH, 81));
    GLuint tex = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    std::vector<uint8_t> zero(16 * 16 * 4, 0);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 16, 16, 0, GL_RGBA, GL_UNSIGNED_BYTE, zero.data());
    // Rows bottom-up: R from (0,0), G from (1,0), B from (0,1), A from (1,1).
    float kernel[9 * 4] = {};
    kernel[(0 * 3 + 0) * 4 + 0] = 1;
    kernel[(0 * 3 + 1) * 4 + 1] = 1;
    kernel[(1 * 3 + 0) * 4 + 2] = 1;
    kernel[(1 * 3 + 1) * 4 + 3] = 1;
    glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, kernel);
    glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, GL_REPLICATE_BORDER);
    glEnable(GL_CONVOLUTION_2D);
    glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 2, 1, 0, 0, kParityW, kParityH);
    resetImaging();
    std::vector<uint8_t> back(16 * 16 * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, back.data());
    appendBytes(o, back);
    glDeleteTextures(1, &tex);
  });
}

}  // namespace
}  // namespace sl::imaging::testing

namespace sl::imaging::testing {
namespace {

// One-dimensional filters (3.6.5: GL_CONVOLUTION_1D applies only to the one-dimensional
// texture commands) of widths 1 to 9 under the three border modes, on glTexImage1D (client
// bytes) and glCopyTexImage1D (framebuffer row); the RGBA8 texture read back with
// glGetTexImage (no pixel transfer, 6.1.4) and its width (REDUCE: W - Wf + 1).
struct Filter1DCase {
  int width;
  GLenum border;
  bool copy;
};
std::vector<Filter1DCase> filter1DCases() {
  std::vector<Filter1DCase> cases;
  for (int w : {1, 3, 5, 7, 9})
    for (GLenum b : {GLenum(GL_REDUCE), GLenum(GL_CONSTANT_BORDER), GLenum(GL_REPLICATE_BORDER)})
      for (bool copy : {false, true})
        // glCopyTexImage1D under REDUCE is departure G (departures_test.cpp).
        if (!(copy && b == GL_REDUCE)) cases.push_back({w, b, copy});
  return cases;
}
class Filter1DParity : public ::testing::TestWithParam<Filter1DCase> {};
TEST_P(Filter1DParity, TextureImage) {
  SL_REQUIRE_REFERENCE();
  const Filter1DCase c = GetParam();
  checkParity([c](Outcome& o) {
    constexpr int kRow = 16;
    const std::vector<uint8_t> row = patternImage(kRow, 1, 131 + unsigned(c.width));
    const std::vector<float> f = weights(c.width, 141 + unsigned(c.width));
    glConvolutionFilter1D(GL_CONVOLUTION_1D, GL_RGBA, c.width, GL_RGBA, GL_FLOAT, f.data());
    glConvolutionParameteri(GL_CONVOLUTION_1D, GL_CONVOLUTION_BORDER_MODE, GLint(c.border));
    const float borderColor[4] = {0.2f, 0.6f, 0.0f, 1.0f};
    glConvolutionParameterfv(GL_CONVOLUTION_1D, GL_CONVOLUTION_BORDER_COLOR, borderColor);
    GLuint tex = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_1D, tex);
    glEnable(GL_CONVOLUTION_1D);
    if (c.copy) {
      putImage(kRow, 1, row);
      glCopyTexImage1D(GL_TEXTURE_1D, 0, GL_RGBA8, 0, 0, kRow, 0);
    } else {
      glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
      glTexImage1D(GL_TEXTURE_1D, 0, GL_RGBA8, kRow, 0, GL_RGBA, GL_UNSIGNED_BYTE, row.data());
    }
    glDisable(GL_CONVOLUTION_1D);
    GLint width = 0;
    glGetTexLevelParameteriv(GL_TEXTURE_1D, 0, GL_TEXTURE_WIDTH, &width);
    o.floats.push_back(float(width));
    std::vector<uint8_t> texels(size_t(std::max(width, 0)) * 4, 0xCD);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    if (width > 0) glGetTexImage(GL_TEXTURE_1D, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
    appendBytes(o, texels);
    glDeleteTextures(1, &tex);
  });
}
INSTANTIATE_TEST_SUITE_P(WidthsBordersPaths, Filter1DParity, ::testing::ValuesIn(filter1DCases()),
                         [](const ::testing::TestParamInfo<Filter1DCase>& info) {
                           const Filter1DCase& c = info.param;
                           return std::string(c.copy ? "CopyTexImage1D_" : "TexImage1D_") +
                                  std::to_string(c.width) +
                                  (c.border == GL_REDUCE            ? "_reduce"
                                   : c.border == GL_CONSTANT_BORDER ? "_constant"
                                                                    : "_replicate");
                         });

}  // namespace
}  // namespace sl::imaging::testing
