// One-dimensional convolution (glspec121 3.6.5 "Convolution"): GL_CONVOLUTION_1D applies only
// to the images of TexImage1D, TexSubImage1D, CopyTexImage1D and CopyTexSubImage1D, and the
// 2D filters never do. Expected texels are computed here from the specification's sums:
//   REDUCE:           C'[i] = sum_n C[i + n] F[n],          width W - Wf + 1
//   CONSTANT_BORDER:  C'[i] = sum_n C[i + n - Cw] F[n],     C outside = the border colour
//   REPLICATE_BORDER: the same, C outside = the nearest edge group (Cw = floor(Wf / 2))
// then the filter scale/bias applied when the filter was defined (3.6.3), and the final
// clamp to [0, 1] of 3.6.5 "Final Conversion" (clamp01 below). Float textures (GL_RGBA32F)
// read back with glGetTexImage, which applies no pixel transfer (6.1.4).
#include <cmath>

#include "imaging/imaging_test_util.h"

namespace sl::imaging::testing {
namespace {

constexpr int kWidth = 8;            // source groups
constexpr int kFilter = 3;           // filter width Wf
constexpr float kTolerance = 1e-6f;  // float sums of three products of values in [0, 1]

// Source group i, component c: distinct values per group and component.
float sourceValue(int i, int c) { return float((i * 29 + c * 53) % 97) / 96.0f; }
std::vector<float> sourceImage(int w = kWidth) {
  std::vector<float> px(size_t(w) * 4);
  for (int i = 0; i < w; ++i)
    for (int c = 0; c < 4; ++c) px[size_t(i) * 4 + c] = sourceValue(i, c);
  return px;
}
// Filter tap n, component c.
float filterValue(int n, int c) {
  const float taps[kFilter][4] = {
      {0.25f, 0.5f, 0.0f, 1.0f}, {0.5f, 0.25f, 1.0f, 0.0f}, {0.125f, 0.25f, 0.0f, 0.5f}};
  return taps[n][c];
}
void loadFilter() {
  std::vector<float> f(kFilter * 4);
  for (int n = 0; n < kFilter; ++n)
    for (int c = 0; c < 4; ++c) f[size_t(n) * 4 + c] = filterValue(n, c);
  glConvolutionFilter1D(GL_CONVOLUTION_1D, GL_RGBA, kFilter, GL_RGBA, GL_FLOAT, f.data());
}

// The specification's sums for the source of sourceImage().
std::vector<float> expected(GLenum border, const float borderColor[4], int w = kWidth) {
  const bool reduce = border == GL_REDUCE;
  const int ow = reduce ? w - kFilter + 1 : w, cw = reduce ? 0 : kFilter / 2;
  std::vector<float> out(size_t(ow) * 4, 0.0f);
  for (int i = 0; i < ow; ++i)
    for (int c = 0; c < 4; ++c) {
      double sum = 0;
      for (int n = 0; n < kFilter; ++n) {
        const int x = i + n - cw;
        double v;
        if (x >= 0 && x < w)
          v = sourceValue(x, c);
        else if (border == GL_CONSTANT_BORDER)
          v = borderColor[c];
        else
          v = sourceValue(std::clamp(x, 0, w - 1), c);
        sum += v * filterValue(n, c);
      }
      out[size_t(i) * 4 + c] = clamp01(float(sum));
    }
  return out;
}

std::vector<float> texture1D(int& width) {
  glGetTexLevelParameteriv(GL_TEXTURE_1D, 0, GL_TEXTURE_WIDTH, &width);
  std::vector<float> texels(size_t(std::max(width, 0)) * 4, -9.0f);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTexImage(GL_TEXTURE_1D, 0, GL_RGBA, GL_FLOAT, texels.data());
  return texels;
}

void expectTexels(const std::vector<float>& got, const std::vector<float>& want, const char* what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (size_t i = 0; i < got.size(); ++i)
    EXPECT_NEAR(got[i], want[i], kTolerance)
        << what << ": group " << i / 4 << " component " << i % 4;
}

class Convolution1D : public ::testing::Test {
 protected:
  void SetUp() override {
    context_ = emulatedContext(16, 4);
    glGenTextures(1, &texture_);
    glBindTexture(GL_TEXTURE_1D, texture_);
    loadFilter();
  }
  void TearDown() override { glDeleteTextures(1, &texture_); }
  std::unique_ptr<GlContext> context_;
  GLuint texture_ = 0;
};

TEST_F(Convolution1D, TexImage1DEveryBorderMode) {
  const float borderColor[4] = {0.5f, 0.0f, 1.0f, 0.25f};
  for (GLenum border :
       {GLenum(GL_REDUCE), GLenum(GL_CONSTANT_BORDER), GLenum(GL_REPLICATE_BORDER)}) {
    glConvolutionParameteri(GL_CONVOLUTION_1D, GL_CONVOLUTION_BORDER_MODE, GLint(border));
    glConvolutionParameterfv(GL_CONVOLUTION_1D, GL_CONVOLUTION_BORDER_COLOR, borderColor);
    glEnable(GL_CONVOLUTION_1D);
    const std::vector<float> src = sourceImage();
    glTexImage1D(GL_TEXTURE_1D, 0, GL_RGBA32F, kWidth, 0, GL_RGBA, GL_FLOAT, src.data());
    int width = 0;
    const std::vector<float> got = texture1D(width);
    EXPECT_EQ(width, border == GL_REDUCE ? kWidth - kFilter + 1 : kWidth);  // REDUCE: W - Wf + 1
    expectTexels(got, expected(border, borderColor),
                 border == GL_REDUCE            ? "REDUCE"
                 : border == GL_CONSTANT_BORDER ? "CONSTANT_BORDER"
                                                : "REPLICATE_BORDER");
  }
  EXPECT_TRUE(drainErrors().empty());
}

TEST_F(Convolution1D, NullDataStillShrinksUnderReduce) {
  glEnable(GL_CONVOLUTION_1D);  // REDUCE is the initial border mode
  glTexImage1D(GL_TEXTURE_1D, 0, GL_RGBA8, kWidth, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  int width = 0;
  glGetTexLevelParameteriv(GL_TEXTURE_1D, 0, GL_TEXTURE_WIDTH, &width);
  EXPECT_EQ(width, kWidth - kFilter + 1);
}

TEST_F(Convolution1D, FilterScaleAndBiasApplyWhenTheFilterIsDefined) {
  const float scale[4] = {2.0f, 1.0f, 0.5f, 1.0f}, bias[4] = {0.0f, 0.125f, 0.0f, -0.25f};
  glConvolutionParameterfv(GL_CONVOLUTION_1D, GL_CONVOLUTION_FILTER_SCALE, scale);
  glConvolutionParameterfv(GL_CONVOLUTION_1D, GL_CONVOLUTION_FILTER_BIAS, bias);
  loadFilter();  // F'[n] = F[n] * scale + bias (3.6.3)
  glEnable(GL_CONVOLUTION_1D);
  const std::vector<float> src = sourceImage();
  glTexImage1D(GL_TEXTURE_1D, 0, GL_RGBA32F, kWidth, 0, GL_RGBA, GL_FLOAT, src.data());
  int width = 0;
  const std::vector<float> got = texture1D(width);
  ASSERT_EQ(width, kWidth - kFilter + 1);
  for (int i = 0; i < width; ++i)
    for (int c = 0; c < 4; ++c) {
      double sum = 0;
      for (int n = 0; n < kFilter; ++n)
        sum += sourceValue(i + n, c) * (filterValue(n, c) * scale[c] + bias[c]);
      EXPECT_NEAR(got[size_t(i) * 4 + c], clamp01(float(sum)), kTolerance) << i << " " << c;
    }
}

TEST_F(Convolution1D, CopyTexImage1DAndSubImagesTakeTheFilter) {
  // The framebuffer row 0: sourceImage() as bytes (so the expected sums use the bytes' values).
  std::vector<uint8_t> row(size_t(kWidth) * 4);
  for (size_t i = 0; i < row.size(); ++i)
    row[i] = uint8_t(std::lround(sourceValue(int(i / 4), int(i % 4)) * 255.0f));
  putImage(kWidth, 1, row);
  glConvolutionParameteri(GL_CONVOLUTION_1D, GL_CONVOLUTION_BORDER_MODE, GL_REPLICATE_BORDER);
  glEnable(GL_CONVOLUTION_1D);
  glCopyTexImage1D(GL_TEXTURE_1D, 0, GL_RGBA32F, 0, 0, kWidth, 0);
  int width = 0;
  std::vector<float> got = texture1D(width);
  ASSERT_EQ(width, kWidth);
  for (int i = 0; i < kWidth; ++i)
    for (int c = 0; c < 4; ++c) {
      double sum = 0;
      for (int n = 0; n < kFilter; ++n)
        sum += row[size_t(std::clamp(i + n - 1, 0, kWidth - 1)) * 4 + size_t(c)] / 255.0 *
               filterValue(n, c);
      EXPECT_NEAR(got[size_t(i) * 4 + c], clamp01(float(sum)), kTolerance)
          << "copy " << i << " " << c;
    }
  // TexSubImage1D and CopyTexSubImage1D into texels 2..5 of a zeroed texture.
  const std::vector<float> zeros(size_t(kWidth) * 4, 0.0f);
  glDisable(GL_CONVOLUTION_1D);
  glTexImage1D(GL_TEXTURE_1D, 0, GL_RGBA32F, kWidth, 0, GL_RGBA, GL_FLOAT, zeros.data());
  glEnable(GL_CONVOLUTION_1D);
  const std::vector<float> src = sourceImage(4);
  glTexSubImage1D(GL_TEXTURE_1D, 0, 2, 4, GL_RGBA, GL_FLOAT, src.data());
  got = texture1D(width);
  const float none[4] = {0, 0, 0, 0};
  const std::vector<float> sub = expected(GL_REPLICATE_BORDER, none, 4);
  for (int i = 0; i < kWidth; ++i)
    for (int c = 0; c < 4; ++c) {
      const float want = i >= 2 && i < 6 ? sub[size_t(i - 2) * 4 + size_t(c)] : 0.0f;
      EXPECT_NEAR(got[size_t(i) * 4 + c], want, kTolerance) << "sub " << i << " " << c;
    }
  glCopyTexSubImage1D(GL_TEXTURE_1D, 0, 0, 0, 0, 2);  // groups 0-1 of row 0, replicated edges
  got = texture1D(width);
  for (int c = 0; c < 4; ++c) {
    const double r0 = row[size_t(c)] / 255.0, r1 = row[4 + size_t(c)] / 255.0;
    EXPECT_NEAR(
        got[size_t(c)],
        clamp01(float(r0 * filterValue(0, c) + r0 * filterValue(1, c) + r1 * filterValue(2, c))),
        kTolerance);
    EXPECT_NEAR(
        got[4 + size_t(c)],
        clamp01(float(r0 * filterValue(0, c) + r1 * filterValue(1, c) + r1 * filterValue(2, c))),
        kTolerance);
  }
  EXPECT_TRUE(drainErrors().empty());
}

TEST_F(Convolution1D, OneDimensionalAndTwoDimensionalFiltersKeepToTheirImages) {
  const std::vector<float> src = sourceImage();
  // The 1D filter leaves TexImage2D alone.
  glEnable(GL_CONVOLUTION_1D);
  GLuint tex2D = 0;
  glGenTextures(1, &tex2D);
  glBindTexture(GL_TEXTURE_2D, tex2D);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kWidth, 1, 0, GL_RGBA, GL_FLOAT, src.data());
  std::vector<float> got(src.size(), -9.0f);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, got.data());
  expectTexels(got, src, "TexImage2D under CONVOLUTION_1D");
  glDeleteTextures(1, &tex2D);
  glDisable(GL_CONVOLUTION_1D);
  // A 2D filter (here a 3x1 that would change every texel) leaves TexImage1D alone.
  std::vector<float> f2(kFilter * 4, 1.0f / 3.0f);
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, kFilter, 1, GL_RGBA, GL_FLOAT, f2.data());
  glEnable(GL_CONVOLUTION_2D);
  glEnable(GL_SEPARABLE_2D);
  glTexImage1D(GL_TEXTURE_1D, 0, GL_RGBA32F, kWidth, 0, GL_RGBA, GL_FLOAT, src.data());
  int width = 0;
  expectTexels(texture1D(width), src, "TexImage1D under CONVOLUTION_2D");
  EXPECT_EQ(width, kWidth);
  EXPECT_TRUE(drainErrors().empty());
}

}  // namespace
}  // namespace sl::imaging::testing
