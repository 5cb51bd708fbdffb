// Parity of the color matrix and its stack (glspec121 3.6.3, 3.6.5 "Color Matrix
// Transformation", 6.1.6), post-color-matrix scale/bias, histogram and minmax with and
// without sink (3.6.5, 6.1.9, 6.1.10).
#include "parity/parity_util.h"

namespace sl::imaging::testing {
namespace {

const float kMatrices[][16] = {
    {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1},  // identity
    {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1},  // sum into alpha (B&S Fig. 4)
    {0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 0, 0, 1},  // swizzle R->G->B->R
    {0.299f, 0.299f, 0.299f, 0, 0.587f, 0.587f, 0.587f, 0, 0.114f, 0.114f, 0.114f, 0, 0, 0, 0, 1},
    {-1, 0, 0, 0, 0, -1, 0, 0, 0, 0, -1, 0, 1, 1, 1, 1},  // negate, + alpha
    {0.5f, 0.25f, 0, 0.1f, 0.25f, 0.5f, 0.25f, 0.1f, 0, 0.25f, 0.5f, 0.1f, 0.1f, 0, 0.1f, 0.7f},
};

class ColorMatrixParity : public ::testing::TestWithParam<int> {};
TEST_P(ColorMatrixParity, ReadPixelsAndQuery) {
  SL_REQUIRE_REFERENCE();
  const int k = GetParam();
  checkParity([k](Outcome& o) {
    putImage(kParityW, kParityH, patternImage(kParityW, kParityH, 91 + k));
    glMatrixMode(GL_COLOR);
    glLoadMatrixf(kMatrices[k]);
    GLint mode = 0;
    glGetIntegerv(GL_MATRIX_MODE, &mode);
    o.floats.push_back(float(mode));
    glMatrixMode(GL_MODELVIEW);
    appendFloats(o, readRgbaF(0, 0, kParityW, kParityH));
    float m[16];
    glGetFloatv(GL_COLOR_MATRIX, m);
    o.floats.insert(o.floats.end(), m, m + 16);
  });
}
INSTANTIATE_TEST_SUITE_P(SixMatrices, ColorMatrixParity, ::testing::Range(0, 6));

// Dense colour matrices (every entry non-zero, negative entries and entries above 1) on
// glDrawPixels of GL_RGBA / GL_RGB groups of GL_UNSIGNED_BYTE / GL_FLOAT (the layouts of the
// vector path, imaging/color_matrix_groups.cpp), with and without post-color-matrix scale and
// bias; results below 0 and above 1 are clamped by the final conversion (4.3.2). The float
// groups run from -200/255 to 310/255. Entries and scales are fifths, biases and float inputs
// whole 1/255 steps, so 255 times every exact result is a multiple of 1/25: at least 0.02 of a
// step from a rounding tie. Departure F (ReferenceSaturatesAbove0996) is marked from the exact
// value, computed here in double.
const float kDenseMatrices[][16] = {
    // column-major: R' = 1.4R - 0.2G - 0.4B + 0.2A, ...
    {1.4f, -0.6f, 0.2f, 0.4f, -0.2f, 1.2f, -0.4f, 0.2f, -0.4f, 0.6f, 1.6f, -0.2f, 0.2f, -0.2f, 0.4f,
     0.8f},
    {-0.8f, 0.4f, 1.2f, 0.6f, 2.2f, -1.4f, 0.4f, -0.2f, 0.6f, 1.8f, -0.6f, 0.4f, -0.2f, 0.2f, 0.2f,
     1.2f},
};
class DenseColorMatrixParity : public ::testing::TestWithParam<int> {};
TEST_P(DenseColorMatrixParity, DrawPixelsEveryLayout) {
  SL_REQUIRE_REFERENCE();
  const int layout = GetParam() % 4, k = GetParam() / 4;
  const GLenum format = layout % 2 == 0 ? GL_RGBA : GL_RGB;
  const GLenum type = layout < 2 ? GL_UNSIGNED_BYTE : GL_FLOAT;
  const int n = format == GL_RGBA ? 4 : 3;
  const std::vector<uint8_t> pattern = patternImage(kParityW, kParityH, 131 + GetParam());
  std::vector<uint8_t> bytes(size_t(kParityW) * kParityH * n);
  std::vector<float> floats(bytes.size());
  for (size_t i = 0; i < bytes.size(); ++i) {
    bytes[i] = pattern[i];
    floats[i] = float(2 * int(pattern[i]) - 200) / 255.0f;
  }
  const float scale[4] = {1.2f, 0.8f, 1.4f, 0.6f};
  const float bias[4] = {10.0f / 255.0f, -20.0f / 255.0f, 5.0f / 255.0f, 30.0f / 255.0f};
  const bool scaled = k == 1;
  // The exact value of each written component, for departure F's band.
  std::vector<uint8_t> band(size_t(kParityW) * kParityH * 4);
  for (size_t g = 0; g < band.size() / 4; ++g) {
    double x[4] = {0, 0, 0, 1};
    for (int c = 0; c < n; ++c)
      x[c] = type == GL_FLOAT ? double(2 * int(pattern[g * n + c]) - 200) / 255.0
                              : double(pattern[g * n + c]) / 255.0;
    for (int r = 0; r < 4; ++r) {
      double v = 0;
      for (int c = 0; c < 4; ++c) v += double(kDenseMatrices[k][c * 4 + r]) * x[c];
      if (scaled) v = v * scale[r] + bias[r];
      band[g * 4 + size_t(r)] = inSaturationBand(float(v)) ? 1 : 0;
    }
  }
  checkParity([&](Outcome& o) {
    glMatrixMode(GL_COLOR);
    glLoadMatrixf(kDenseMatrices[k]);
    glMatrixMode(GL_MODELVIEW);
    if (scaled) {
      const GLenum scales[4] = {GL_POST_COLOR_MATRIX_RED_SCALE, GL_POST_COLOR_MATRIX_GREEN_SCALE,
                                GL_POST_COLOR_MATRIX_BLUE_SCALE, GL_POST_COLOR_MATRIX_ALPHA_SCALE};
      const GLenum biases[4] = {GL_POST_COLOR_MATRIX_RED_BIAS, GL_POST_COLOR_MATRIX_GREEN_BIAS,
                                GL_POST_COLOR_MATRIX_BLUE_BIAS, GL_POST_COLOR_MATRIX_ALPHA_BIAS};
      for (int c = 0; c < 4; ++c) {
        glPixelTransferf(scales[c], scale[c]);
        glPixelTransferf(biases[c], bias[c]);
      }
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glWindowPos2i(0, 0);
    const void* data = type == GL_FLOAT ? static_cast<const void*>(floats.data()) : bytes.data();
    glDrawPixels(kParityW, kParityH, format, type, data);
    appendBytes(o, readWindow());
    o.saturationBand = band;
  });
}
INSTANTIATE_TEST_SUITE_P(FourLayoutsTwoMatrices, DenseColorMatrixParity, ::testing::Range(0, 8));

// Dense colour matrix, post-color-matrix scale and bias chosen so that the final conversion
// (4.3.2) clamps below 0 and above 1 in every output component, on the emulation's vector
// paths (imaging/color_matrix_groups.cpp): glDrawPixels of each client layout 13 groups wide
// (16-group blocks and a tail), glTexSubImage2D of each layout into an RGBA8 texture (read
// back with glGetTexImage, which has no pixel transfer, 6.1.4) and glCopyPixels of the RGBA8
// window onto itself. Entries and scales are fifths, biases and float inputs whole 1/255
// steps: 255 times every exact result is a multiple of 1/25, at least 0.02 of a step from a
// rounding tie. Each case also checks, on the exact values computed here in double, that
// it exercises both clamps.
constexpr float kClampScale[4] = {1.4f, 0.6f, 1.2f, 0.8f};
constexpr float kClampBias[4] = {-30.0f / 255.0f, 40.0f / 255.0f, 20.0f / 255.0f, -10.0f / 255.0f};
// Exact results below 0 and above 1 each case must contain: a twentieth of the smallest
// case's 4 x 13 x 5 = 260 components (its byte uploads have 20 and 21 below 0).
constexpr int kMinimumClamped = 13;
enum class DenseCall { kDrawPixels, kTexSubImage, kCopyPixels };
class DenseColorMatrixClampParity : public ::testing::TestWithParam<int> {};
TEST_P(DenseColorMatrixClampParity, ClampsBelowZeroAndAboveOne) {
  SL_REQUIRE_REFERENCE();
  // 0-3: glDrawPixels, 4-7: glTexSubImage2D of the four layouts; 8: glCopyPixels.
  const DenseCall call = GetParam() < 4   ? DenseCall::kDrawPixels
                         : GetParam() < 8 ? DenseCall::kTexSubImage
                                          : DenseCall::kCopyPixels;
  const int layout = call == DenseCall::kCopyPixels ? 0 : GetParam() % 4;
  const GLenum format = layout % 2 == 0 ? GL_RGBA : GL_RGB;
  const GLenum type = layout < 2 ? GL_UNSIGNED_BYTE : GL_FLOAT;
  const int n = format == GL_RGBA ? 4 : 3;
  constexpr int kTexture = 16, kSubW = 13, kSubH = 5, kSubX = 2, kSubY = 3;
  const int w = call == DenseCall::kCopyPixels ? kParityW : kSubW;
  const int h = call == DenseCall::kTexSubImage ? kSubH : kParityH;
  const std::vector<uint8_t> pattern = patternImage(kParityW, kParityH, 171 + GetParam());
  std::vector<uint8_t> bytes(size_t(w) * h * size_t(n));
  std::vector<float> floats(bytes.size());
  for (size_t i = 0; i < bytes.size(); ++i) {
    bytes[i] = pattern[i];
    floats[i] = float(2 * int(pattern[i]) - 200) / 255.0f;
  }
  const float* m = kDenseMatrices[1];
  // The exact value of every written component: departure F's band, and the clamps counted.
  std::vector<double> exact(size_t(w) * h * 4);
  int below = 0, above = 0;
  for (size_t g = 0; g < exact.size() / 4; ++g) {
    double x[4] = {0, 0, 0, 1};
    for (int c = 0; c < n; ++c) {
      const int v = bytes[g * size_t(n) + size_t(c)];
      x[c] = double(type == GL_FLOAT ? 2 * v - 200 : v) / 255.0;
    }
    for (int r = 0; r < 4; ++r) {
      double v = 0;
      for (int c = 0; c < 4; ++c) v += double(m[c * 4 + r]) * x[c];
      v = v * kClampScale[r] + kClampBias[r];
      exact[g * 4 + size_t(r)] = v;
      below += v < 0 ? 1 : 0;
      above += v > 1 ? 1 : 0;
    }
  }
  EXPECT_GE(below, kMinimumClamped);
  EXPECT_GE(above, kMinimumClamped);
  // Window (or texture) bytes of the written groups: departure F's band there, 0 elsewhere.
  const int outW = call == DenseCall::kTexSubImage ? kTexture : kParityW;
  const int outH = call == DenseCall::kTexSubImage ? kTexture : kParityH;
  const int x0 = call == DenseCall::kCopyPixels ? 0 : kSubX;
  const int y0 = call == DenseCall::kTexSubImage ? kSubY : 0;
  std::vector<uint8_t> band(size_t(outW) * outH * 4, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int r = 0; r < 4; ++r)
        band[(size_t(y0 + y) * outW + size_t(x0 + x)) * 4 + size_t(r)] =
            inSaturationBand(float(exact[(size_t(y) * w + size_t(x)) * 4 + size_t(r)])) ? 1 : 0;
  checkParity([&](Outcome& o) {
    GLuint texture = 0;
    if (call == DenseCall::kTexSubImage) {  // made before the matrix: zeros, no transfer
      const std::vector<uint8_t> zero(size_t(kTexture) * kTexture * 4, 0);
      glGenTextures(1, &texture);
      glBindTexture(GL_TEXTURE_2D, texture);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, kTexture, kTexture, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                   zero.data());
    }
    if (call == DenseCall::kCopyPixels) putImage(kParityW, kParityH, pattern);
    glMatrixMode(GL_COLOR);
    glLoadMatrixf(m);
    glMatrixMode(GL_MODELVIEW);
    const GLenum scales[4] = {GL_POST_COLOR_MATRIX_RED_SCALE, GL_POST_COLOR_MATRIX_GREEN_SCALE,
                              GL_POST_COLOR_MATRIX_BLUE_SCALE, GL_POST_COLOR_MATRIX_ALPHA_SCALE};
    const GLenum biases[4] = {GL_POST_COLOR_MATRIX_RED_BIAS, GL_POST_COLOR_MATRIX_GREEN_BIAS,
                              GL_POST_COLOR_MATRIX_BLUE_BIAS, GL_POST_COLOR_MATRIX_ALPHA_BIAS};
    for (int c = 0; c < 4; ++c) {
      glPixelTransferf(scales[c], kClampScale[c]);
      glPixelTransferf(biases[c], kClampBias[c]);
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    const void* data = type == GL_FLOAT ? static_cast<const void*>(floats.data()) : bytes.data();
    switch (call) {
      case DenseCall::kDrawPixels:
        glWindowPos2i(kSubX, 0);
        glDrawPixels(w, h, format, type, data);
        appendBytes(o, readWindow());
        break;
      case DenseCall::kTexSubImage: {
        glTexSubImage2D(GL_TEXTURE_2D, 0, kSubX, kSubY, w, h, format, type, data);
        resetImaging();
        std::vector<uint8_t> texels(size_t(kTexture) * kTexture * 4);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
        appendBytes(o, texels);
        glDeleteTextures(1, &texture);
        break;
      }
      case DenseCall::kCopyPixels:
        glWindowPos2i(0, 0);
        glCopyPixels(0, 0, w, h, GL_COLOR);
        appendBytes(o, readWindow());
        break;
    }
    o.saturationBand = band;
  });
}
INSTANTIATE_TEST_SUITE_P(DrawTexSubImageCopy, DenseColorMatrixClampParity, ::testing::Range(0, 9));

// The stack: push, multiply, pop, depths, overflow past 4 and underflow.
TEST(ColorMatrixStackParity, PushMultiplyPopOverflowUnderflow) {
  SL_REQUIRE_REFERENCE();
  checkParity([](Outcome& o) {
    glMatrixMode(GL_COLOR);
    GLint depth = 0, maxDepth = 0;
    glGetIntegerv(GL_MAX_COLOR_MATRIX_STACK_DEPTH, &maxDepth);
    o.floats.push_back(float(maxDepth));
    glLoadMatrixf(kMatrices[5]);
    for (int i = 0; i < 5; ++i) {
      glPushMatrix();
      glMultMatrixf(kMatrices[2]);
      glGetIntegerv(GL_COLOR_MATRIX_STACK_DEPTH, &depth);
      o.floats.push_back(float(depth));
      const auto e = drainErrors();
      o.errors.insert(o.errors.end(), e.begin(), e.end());
    }
    float m[16];
    glGetFloatv(GL_COLOR_MATRIX, m);
    o.floats.insert(o.floats.end(), m, m + 16);
    for (int i = 0; i < 5; ++i) {
      glPopMatrix();
      const auto e = drainErrors();
      o.errors.insert(o.errors.end(), e.begin(), e.end());
    }
    glGetFloatv(GL_COLOR_MATRIX, m);
    o.floats.insert(o.floats.end(), m, m + 16);
    glMatrixMode(GL_MODELVIEW);
  });
}

// The matrix commands of 2.10.2 on the colour matrix (3.6.3): each command, the matrix read
// back, and a copy through the result. The matrices keep every exact result at least 0.1 step
// from a rounding tie: integer entries or fifths (no halves, whose products of odd bytes are
// exact ties); the rotations' cos 90 degrees is about 1e-8, far below a step.
class ColorMatrixCommandParity : public ::testing::TestWithParam<int> {};
TEST_P(ColorMatrixCommandParity, CommandQueryAndCopy) {
  SL_REQUIRE_REFERENCE();
  const int k = GetParam();
  checkParity([k](Outcome& o) {
    putImage(kParityW, kParityH, patternImage(kParityW, kParityH, 121 + k));
    glMatrixMode(GL_COLOR);
    const float rows[16] = {0.6f, 0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0.2f, 0.4f, 0, 0.4f};
    const double swap[16] = {0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    switch (k) {
      case 0: glRotatef(90.0f, 0.0f, 0.0f, 1.0f); break;
      case 1: glRotated(180.0, 1.0, 0.0, 0.0); break;
      case 2: glOrtho(0.0, 2.0, 0.0, 2.0, -1.0, 1.0); break;
      case 3: glFrustum(-1.0, 1.0, -1.0, 1.0, 1.0, 3.0); break;
      case 4:
        glScaled(0.4, 0.8, 1.0);  // results stay below 0.8: clear of departure F's band
        glTranslated(1.0, -1.0, 0.0);
        break;
      case 5:
        glLoadTransposeMatrixf(rows);
        glMultTransposeMatrixd(swap);
        break;
      case 6:  // errors: l = r, n <= 0, n = f; the matrix stays the identity
        glOrtho(1.0, 1.0, 0.0, 1.0, 0.0, 1.0);
        glFrustum(-1.0, 1.0, -1.0, 1.0, 0.0, 1.0);
        glFrustum(-1.0, 1.0, -1.0, 1.0, 2.0, 2.0);
        break;
      default: break;
    }
    const auto e = drainErrors();
    o.errors.insert(o.errors.end(), e.begin(), e.end());
    float m[16];
    glGetFloatv(GL_COLOR_MATRIX, m);
    o.floats.insert(o.floats.end(), m, m + 16);
    glMatrixMode(GL_MODELVIEW);
    glWindowPos2i(kParityW / 2, 0);
    glCopyPixels(0, 0, kParityW / 2, kParityH, GL_COLOR);
    glMatrixMode(GL_COLOR);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    appendBytes(o, readWindow());
  });
}
INSTANTIATE_TEST_SUITE_P(RotateOrthoFrustumScaleTranslateTranspose, ColorMatrixCommandParity,
                         ::testing::Range(0, 7));

// The transpose query (glspec14 6.1.2) and GL_TRANSFORM_BIT saving GL_COLOR as the matrix
// mode (table 6.7).
TEST(ColorMatrixCommandParity, TransposeQueryAndTransformBit) {
  SL_REQUIRE_REFERENCE();
  checkParity([](Outcome& o) {
    glMatrixMode(GL_COLOR);
    const float m[16] = {0.6f, 0.2f, 0, 0, 0, 1, 0.4f, 0, 0, 0, 1, 0, 0.2f, 0, 0, 1};
    glLoadMatrixf(m);
    float t[16];
    glGetFloatv(GL_TRANSPOSE_COLOR_MATRIX, t);
    o.floats.insert(o.floats.end(), t, t + 16);
    glPushAttrib(GL_TRANSFORM_BIT);
    glMatrixMode(GL_MODELVIEW);
    glPopAttrib();
    GLint mode = 0;
    glGetIntegerv(GL_MATRIX_MODE, &mode);
    o.floats.push_back(float(mode));
    glLoadIdentity();  // the colour matrix, if the pop restored GL_COLOR
    float c[16];
    glGetFloatv(GL_COLOR_MATRIX, c);
    o.floats.insert(o.floats.end(), c, c + 16);
    glMatrixMode(GL_MODELVIEW);
  });
}

// Post-color-matrix scale and bias, with and without a matrix.
class PostMatrixScaleBiasParity : public ::testing::TestWithParam<int> {};
TEST_P(PostMatrixScaleBiasParity, CopyPixels) {
  SL_REQUIRE_REFERENCE();
  const int k = GetParam();
  checkParity([k](Outcome& o) {
    putImage(kParityW, kParityH, patternImage(kParityW, kParityH, 101 + k));
    const GLenum sp[4] = {GL_POST_COLOR_MATRIX_RED_SCALE, GL_POST_COLOR_MATRIX_GREEN_SCALE,
                          GL_POST_COLOR_MATRIX_BLUE_SCALE, GL_POST_COLOR_MATRIX_ALPHA_SCALE};
    const GLenum bp[4] = {GL_POST_COLOR_MATRIX_RED_BIAS, GL_POST_COLOR_MATRIX_GREEN_BIAS,
                          GL_POST_COLOR_MATRIX_BLUE_BIAS, GL_POST_COLOR_MATRIX_ALPHA_BIAS};
    // Scales with denominators of 5 and biases on whole 1/255 steps: no exact rounding ties.
    const float scale[4] = {0.6f, 1.2f, -1.0f, 0.8f}, bias[4] = {0.2f, -0.4f, 1.0f, 0.6f};
    for (int c = 0; c < 4; ++c) {
      glPixelTransferf(sp[c], scale[c]);
      glPixelTransferf(bp[c], bias[c]);
    }
    if (k > 0) {
      glMatrixMode(GL_COLOR);
      glLoadMatrixf(kMatrices[k]);
      glMatrixMode(GL_MODELVIEW);
    }
    glWindowPos2i(kParityW / 2, 0);
    glCopyPixels(0, 0, kParityW / 2, kParityH, GL_COLOR);
    appendBytes(o, readWindow());
  });
}
INSTANTIATE_TEST_SUITE_P(WithAndWithoutMatrix, PostMatrixScaleBiasParity, ::testing::Range(0, 4));

// Pixel-transfer scale and bias (stage 1) alone on CopyPixels.
class TransferScaleBiasParity : public ::testing::TestWithParam<int> {};
TEST_P(TransferScaleBiasParity, CopyPixels) {
  SL_REQUIRE_REFERENCE();
  const int k = GetParam();
  checkParity([k](Outcome& o) {
    putImage(kParityW, kParityH, patternImage(kParityW, kParityH, 111 + k));
    // Scales with denominators of 5 and biases that are whole multiples of 1/255 keep every
    // exact result at least 0.1 step from a rounding tie (ties: RoundingTies below).
    const float scales[3] = {0.6f, 1.2f, -0.4f}, biases[3] = {0.2f, -0.4f, 0.8f};
    glPixelTransferf(GL_RED_SCALE, scales[k]);
    glPixelTransferf(GL_GREEN_BIAS, biases[k]);
    glPixelTransferf(GL_ALPHA_SCALE, scales[(k + 1) % 3]);
    glPixelTransferf(GL_BLUE_BIAS, biases[(k + 2) % 3]);
    glWindowPos2i(kParityW / 2, 0);
    glCopyPixels(0, 0, kParityW / 2, kParityH, GL_COLOR);
    appendBytes(o, readWindow());
  });
}
INSTANTIATE_TEST_SUITE_P(ThreeSettings, TransferScaleBiasParity, ::testing::Range(0, 3));

// The pack formats that return exactly the components a histogram / minmax format holds
// (the reference also returns counts and extremes of components the format lacks, where
// table 6.1 gives the constants 0 and 1: departures_test.cpp).
std::vector<GLenum> storedParts(GLenum format) {
  switch (format) {
    case GL_RGB: return {GL_RGB};
    case GL_ALPHA: return {GL_ALPHA};
    case GL_LUMINANCE: return {GL_RED};
    case GL_LUMINANCE_ALPHA: return {GL_RED, GL_ALPHA};
    default: return {GL_RGBA};
  }
}
int partSize(GLenum part) { return part == GL_RGBA ? 4 : part == GL_RGB ? 3 : 1; }

struct HistogramCase {
  GLenum format;
  int width;
};
class HistogramParity : public ::testing::TestWithParam<HistogramCase> {};
TEST_P(HistogramParity, CountsAfterReadPixels) {
  SL_REQUIRE_REFERENCE();
  const HistogramCase p = GetParam();
  checkParity([p](Outcome& o) {
    // Luminance histograms count R only; grey input keeps the reference's extra G and B
    // counts (departure 6) out of this comparison.
    const bool luminance = p.format == GL_LUMINANCE || p.format == GL_LUMINANCE_ALPHA;
    putImage(
        kParityW, kParityH,
        luminance ? greyPattern(kParityW, kParityH, 121) : patternImage(kParityW, kParityH, 121));
    glHistogram(GL_HISTOGRAM, p.width, p.format, GL_FALSE);
    glEnable(GL_HISTOGRAM);
    appendFloats(o, readRgbaF(0, 0, kParityW, kParityH));
    // Luminance formats are returned as (L, 0, 0, 1) by table 6.1; the reference returns its
    // G and B counts there (departure 6), so only the stored components are read.
    for (GLenum part : storedParts(p.format)) {
      std::vector<GLuint> counts(size_t(p.width) * partSize(part), 0xFFFF);
      glGetHistogram(GL_HISTOGRAM, GL_FALSE, part, GL_UNSIGNED_INT, counts.data());
      for (GLuint c : counts) o.floats.push_back(float(c));
    }
    glResetHistogram(GL_HISTOGRAM);
    std::vector<float> after(size_t(p.width), -1.0f);
    glGetHistogram(GL_HISTOGRAM, GL_FALSE, GL_RED, GL_FLOAT, after.data());  // reset: zero
    appendFloats(o, after);
    GLint v = 0;
    glGetHistogramParameteriv(GL_HISTOGRAM, GL_HISTOGRAM_WIDTH, &v);
    o.floats.push_back(float(v));
    glGetHistogramParameteriv(GL_HISTOGRAM, GL_HISTOGRAM_FORMAT, &v);
    o.floats.push_back(float(v));
  });
}
std::vector<HistogramCase> histogramCases() {
  std::vector<HistogramCase> c;
  for (GLenum f : {GL_RGBA, GL_RGB, GL_ALPHA, GL_LUMINANCE, GL_LUMINANCE_ALPHA})
    for (int w : {2, 16, 256}) c.push_back({f, w});
  return c;
}
INSTANTIATE_TEST_SUITE_P(FormatsAndWidths, HistogramParity, ::testing::ValuesIn(histogramCases()));

class MinmaxParity : public ::testing::TestWithParam<HistogramCase> {};
TEST_P(MinmaxParity, ReadPixelsWithAndWithoutSink) {
  SL_REQUIRE_REFERENCE();
  const HistogramCase p = GetParam();
  const bool sink = p.width != 0;
  checkParity([p, sink](Outcome& o) {
    putImage(kParityW, kParityH, patternImage(kParityW, kParityH, 131));
    glMinmax(GL_MINMAX, p.format, sink ? GL_TRUE : GL_FALSE);
    glEnable(GL_MINMAX);
    // Values stay inside [0,1]: outside it the reference clamps (departures_test.cpp).
    glPixelTransferf(GL_RED_SCALE, 0.75f);
    glPixelTransferf(GL_BLUE_SCALE, 0.8f);
    std::vector<float> px(size_t(kParityW) * kParityH * 4, 0.5f);
    glReadPixels(0, 0, kParityW, kParityH, GL_RGBA, GL_FLOAT, px.data());
    appendFloats(o, px);  // with sink: untouched ("no pixel values are returned")
    for (GLenum part : storedParts(p.format)) {
      float mm[8] = {};
      glGetMinmax(GL_MINMAX, GL_FALSE, part, GL_FLOAT, mm);
      o.floats.insert(o.floats.end(), mm, mm + 2 * partSize(part));
    }
    GLint v = 0;
    glGetMinmaxParameteriv(GL_MINMAX, GL_MINMAX_SINK, &v);
    o.floats.push_back(float(v));
  });
}
std::vector<HistogramCase> minmaxCases() {
  std::vector<HistogramCase> c;
  for (GLenum f : {GL_RGBA, GL_RGB, GL_ALPHA, GL_LUMINANCE, GL_LUMINANCE_ALPHA})
    for (int sink : {0, 1}) c.push_back({f, sink});
  return c;
}
INSTANTIATE_TEST_SUITE_P(FormatsAndSink, MinmaxParity, ::testing::ValuesIn(minmaxCases()));

// Histogram sink on DrawPixels: the groups are discarded, the counts still taken.
TEST(HistogramSinkParity, DrawPixelsDiscardsGroups) {
  SL_REQUIRE_REFERENCE();
  checkParity([](Outcome& o) {
    glClearColor(0.2f, 0.4f, 0.6f, 0.8f);
    glClear(GL_COLOR_BUFFER_BIT);
    glHistogram(GL_HISTOGRAM, 8, GL_RGBA, GL_TRUE);
    glEnable(GL_HISTOGRAM);
    const auto img = patternImage(6, 5, 141);
    glWindowPos2i(3, 2);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glDrawPixels(6, 5, GL_RGBA, GL_UNSIGNED_BYTE, img.data());
    std::vector<GLuint> counts(8 * 4);
    glGetHistogram(GL_HISTOGRAM, GL_FALSE, GL_RGBA, GL_UNSIGNED_INT, counts.data());
    for (GLuint c : counts) o.floats.push_back(float(c));
    appendBytes(o, readWindow());
  });
}

}  // namespace
}  // namespace sl::imaging::testing
