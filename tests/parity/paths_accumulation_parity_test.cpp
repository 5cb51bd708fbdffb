// Parity of every stage at once on each pixel path (glspec121 3.6.4 DrawPixels, 4.3.2
// ReadPixels, 4.3.3 CopyPixels, 3.8.1 TexImage2D / TexSubImage2D, 3.8.2 CopyTexImage2D /
// CopyTexSubImage2D), and of the accumulation buffer (4.2.4; the Debian context has none, so
// imaging/ emulates it, against the reference's real 16-bit one).
#include "parity/parity_util.h"

namespace sl::imaging::testing {
namespace {

std::vector<float> ramp(int width, float lo, float hi, bool reverse) {
  std::vector<float> t(size_t(width) * 4);
  for (int k = 0; k < width; ++k)
    for (int c = 0; c < 4; ++c) {
      const float f = float(k) / float(width - 1);
      const float v = lo + (hi - lo) * (reverse ? 1.0f - f : f);
      t[size_t(k) * 4 + c] = c == 1 ? v * v : v;
    }
  return t;
}

// Every stage of 3.6.5 enabled, with values that keep results away from rounding ties.
// `tablesAndMatrix` false (the copy-to-texture cases) keeps scale, convolution and
// post-convolution bias only and leaves out the three color tables and the color matrix with its
// post-matrix scale and bias: the
// reference applies those twice on glCopyTexImage2D / glCopyTexSubImage2D (an additional
// departure, departures_test.cpp), so the copy-to-texture cases compare the other stages.
void enableEverything(GLenum border, bool tablesAndMatrix = true) {
  glPixelTransferf(GL_RED_SCALE, 0.8f);
  // (The reference also clamps to [0,1] before convolving on the copy-to-texture paths, so
  // those cases keep the stage-1 results inside [0,1].)
  glPixelTransferf(tablesAndMatrix ? GL_GREEN_BIAS : GL_GREEN_SCALE, tablesAndMatrix ? 0.2f : 0.6f);
  const auto t0 = ramp(64, 0.05f, 0.95f, false);
  glColorTable(GL_COLOR_TABLE, GL_RGBA, 64, GL_RGBA, GL_FLOAT, t0.data());
  if (tablesAndMatrix) glEnable(GL_COLOR_TABLE);
  // Weights are whole multiples of 1/255: a sum of (8-bit value / 255) x (k / 255) times 255
  // is a multiple of 1/255 and can never be an exact rounding tie (x.5 would need an even
  // number to equal an odd multiple of 255/2).
  const int k255[9 * 4] = {13, 26, 0,  26, 26,  13, 26,  0,   13, 26, 26, 26,
                           26, 51, 26, 26, 102, 77, 128, 153, 26, 13, 26, 26,
                           13, 26, 13, 0,  26,  26, 13,  0,   13, 0,  0,  0};
  float kernel[9 * 4];
  for (int i = 0; i < 9 * 4; ++i) kernel[i] = float(k255[i]) / 255.0f;
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, kernel);
  glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, GLint(border));
  glEnable(GL_CONVOLUTION_2D);
  if (tablesAndMatrix) glPixelTransferf(GL_POST_CONVOLUTION_BLUE_SCALE, 1.2f);
  glPixelTransferf(GL_POST_CONVOLUTION_ALPHA_BIAS, 0.2f);
  const auto t1 = ramp(32, 0.1f, 0.9f, true);
  glColorTable(GL_POST_CONVOLUTION_COLOR_TABLE, GL_RGB, 32, GL_RGBA, GL_FLOAT, t1.data());
  if (tablesAndMatrix) glEnable(GL_POST_CONVOLUTION_COLOR_TABLE);
  const float m[16] = {0.6f, 0.2f, 0.0f, 0.2f, 0.2f, 0.6f, 0.2f, 0.2f,
                       0.2f, 0.2f, 0.8f, 0.2f, 0.0f, 0.0f, 0.0f, 0.4f};
  glMatrixMode(GL_COLOR);
  if (tablesAndMatrix) glLoadMatrixf(m);
  glMatrixMode(GL_MODELVIEW);
  if (tablesAndMatrix) {
    glPixelTransferf(GL_POST_COLOR_MATRIX_RED_SCALE, 0.8f);
    glPixelTransferf(GL_POST_COLOR_MATRIX_ALPHA_BIAS, 0.2f);
  }
  const auto t2 = ramp(256, 0.0f, 1.0f, false);
  glColorTable(GL_POST_COLOR_MATRIX_COLOR_TABLE, GL_RGBA, 256, GL_RGBA, GL_FLOAT, t2.data());
  if (tablesAndMatrix) glEnable(GL_POST_COLOR_MATRIX_COLOR_TABLE);
  if (!tablesAndMatrix) return;  // the copy-to-texture paths count differently too
  glHistogram(GL_HISTOGRAM, 16, GL_RGBA, GL_FALSE);
  glEnable(GL_HISTOGRAM);
  glMinmax(GL_MINMAX, GL_RGBA, GL_FALSE);
  glEnable(GL_MINMAX);
}

void appendHistogramAndMinmax(Outcome& o) {
  std::vector<GLuint> counts(16 * 4);
  glGetHistogram(GL_HISTOGRAM, GL_TRUE, GL_RGBA, GL_UNSIGNED_INT, counts.data());
  for (GLuint c : counts) o.floats.push_back(float(c));
  float mm[8];
  glGetMinmax(GL_MINMAX, GL_TRUE, GL_RGBA, GL_FLOAT, mm);
  o.floats.insert(o.floats.end(), mm, mm + 8);
}

std::vector<uint8_t> textureBytes(int w, int h) {
  std::vector<uint8_t> back(size_t(w) * h * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, back.data());
  return back;
}

enum class Path {
  kReadPixels,
  kDrawPixels,
  kCopyPixels,
  kCopyTexImage,
  kCopyTexSubImage,
  kTexImage,
  kTexSubImage
};
struct PathCase {
  Path path;
  GLenum border;
};

class AllStagesParity : public ::testing::TestWithParam<PathCase> {};

TEST_P(AllStagesParity, Path) {
  SL_REQUIRE_REFERENCE();
  const PathCase p = GetParam();
  checkParity([p](Outcome& o) {
    const int w = kParityW / 2, h = kParityH;
    const auto src = patternImage(kParityW, kParityH, 151);
    putImage(kParityW, kParityH, src);
    GLuint tex = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    std::vector<uint8_t> zero(16 * 16 * 4, 0);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 16, 16, 0, GL_RGBA, GL_UNSIGNED_BYTE, zero.data());
    const bool copyToTexture = p.path == Path::kCopyTexImage || p.path == Path::kCopyTexSubImage;
    enableEverything(p.border, !copyToTexture);
    switch (p.path) {
      case Path::kReadPixels: appendFloats(o, readRgbaF(0, 0, w, h)); break;
      case Path::kDrawPixels:
        glWindowPos2i(w, 0);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glDrawPixels(w, h, GL_RGBA, GL_UNSIGNED_BYTE, src.data());
        break;
      case Path::kCopyPixels:
        glWindowPos2i(w, 0);
        glCopyPixels(0, 0, w, h, GL_COLOR);
        break;
      case Path::kCopyTexImage: glCopyTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 0, 0, 8, 8, 0); break;
      case Path::kCopyTexSubImage: glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 3, 2, 0, 0, w, h); break;
      case Path::kTexImage:
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 8, 8, 0, GL_RGBA, GL_UNSIGNED_BYTE, src.data());
        break;
      case Path::kTexSubImage:
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTexSubImage2D(GL_TEXTURE_2D, 0, 1, 3, w, h, GL_RGBA, GL_UNSIGNED_BYTE, src.data());
        break;
    }
    if (!copyToTexture) appendHistogramAndMinmax(o);
    resetImaging();
    if (p.path == Path::kCopyTexImage || p.path == Path::kTexImage) {
      GLint tw = 0, th = 0;
      glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &tw);
      glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, &th);
      o.floats.push_back(float(tw));
      o.floats.push_back(float(th));
      appendBytes(o, textureBytes(tw, th));
    } else if (p.path == Path::kCopyTexSubImage || p.path == Path::kTexSubImage) {
      appendBytes(o, textureBytes(16, 16));
    } else {
      appendBytes(o, readWindow());
    }
    glDeleteTextures(1, &tex);
  });
}

std::vector<PathCase> pathCases() {
  std::vector<PathCase> c;
  for (GLenum b : {GL_REPLICATE_BORDER, GL_REDUCE})
    for (Path p : {Path::kReadPixels, Path::kDrawPixels, Path::kCopyPixels, Path::kCopyTexImage,
                   Path::kCopyTexSubImage, Path::kTexImage, Path::kTexSubImage})
      c.push_back({p, b});
  return c;
}

std::string pathName(const ::testing::TestParamInfo<PathCase>& i) {
  const char* names[] = {"ReadPixels",        "DrawPixels", "CopyPixels",   "CopyTexImage2D",
                         "CopyTexSubImage2D", "TexImage2D", "TexSubImage2D"};
  return std::string(names[int(i.param.path)]) +
         (i.param.border == GL_REDUCE ? "_Reduce" : "_Replicate");
}

INSTANTIATE_TEST_SUITE_P(EveryPath, AllStagesParity, ::testing::ValuesIn(pathCases()), pathName);

// The accumulation buffer, every operation with values inside [-1, 1]. Factors are fifths so
// that every exact result lies at least 0.1 step from an 8-bit rounding tie; the 16-bit
// accumulation precision moves results by far less (255 / 32767 of a step).
struct AccumCase {
  const char* name;
  void (*ops)();
};

void drawSecond() { putImage(kParityW, kParityH, patternImage(kParityW, kParityH, 162)); }

class AccumulationParity : public ::testing::TestWithParam<AccumCase> {};
TEST_P(AccumulationParity, Operations) {
  SL_REQUIRE_REFERENCE();
  const auto ops = GetParam().ops;
  checkParity(
      [ops](Outcome& o) {
        putImage(kParityW, kParityH, patternImage(kParityW, kParityH, 161));
        ops();
        appendBytes(o, readWindow());
      },
      /*emulatedAccumulation=*/true);
}

INSTANTIATE_TEST_SUITE_P(
    EveryOperation, AccumulationParity,
    ::testing::Values(
        AccumCase{"LoadReturn",
                  [] {
                    glAccum(GL_LOAD, 1.0f);
                    glClear(GL_COLOR_BUFFER_BIT);
                    glAccum(GL_RETURN, 1.0f);
                  }},
        AccumCase{"LoadFifthReturnTwice",
                  [] {
                    glAccum(GL_LOAD, 0.2f);
                    glAccum(GL_RETURN, 2.0f);
                  }},
        AccumCase{"AccumTwoImages",
                  [] {
                    glAccum(GL_LOAD, 0.4f);
                    drawSecond();
                    glAccum(GL_ACCUM, 0.6f);
                    glAccum(GL_RETURN, 1.0f);
                  }},
        AccumCase{"Mult",
                  [] {
                    glAccum(GL_LOAD, 1.0f);
                    glAccum(GL_MULT, 0.6f);
                    glAccum(GL_RETURN, 1.0f);
                  }},
        AccumCase{"Add",
                  [] {
                    glAccum(GL_LOAD, 0.4f);
                    glAccum(GL_ADD, 0.2f);
                    glAccum(GL_RETURN, 1.0f);
                  }},
        AccumCase{"NegativeAdd",
                  [] {
                    glAccum(GL_LOAD, -0.4f);
                    glAccum(GL_ADD, 0.8f);
                    glAccum(GL_RETURN, 1.0f);
                  }},
        AccumCase{"ReturnClamps",
                  [] {
                    glAccum(GL_LOAD, 0.8f);
                    glAccum(GL_RETURN, 1.6f);
                  }},
        AccumCase{"ClearAccum",
                  [] {
                    glClearAccum(0.2f, -0.4f, 0.6f, 0.8f);
                    glClear(GL_ACCUM_BUFFER_BIT);
                    glAccum(GL_ACCUM, 0.2f);
                    glAccum(GL_RETURN, 1.0f);
                  }},
        // (A scissored GL_LOAD after another GL_LOAD is a departure: departures_test.cpp.)
        AccumCase{"Scissor",
                  [] {
                    glClear(GL_ACCUM_BUFFER_BIT);
                    glEnable(GL_SCISSOR_TEST);
                    glScissor(3, 2, 7, 5);
                    glAccum(GL_ACCUM, 0.6f);
                    glDisable(GL_SCISSOR_TEST);
                    glAccum(GL_RETURN, 1.0f);
                  }},
        AccumCase{"ColorMask",
                  [] {
                    glAccum(GL_LOAD, 0.4f);
                    glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
                    glAccum(GL_RETURN, 1.0f);
                    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
                  }},
        AccumCase{"FourPassAverage",
                  [] {
                    glClear(GL_ACCUM_BUFFER_BIT);
                    for (int i = 0; i < 4; ++i) {
                      putImage(kParityW, kParityH, patternImage(kParityW, kParityH, 170 + i));
                      glAccum(GL_ACCUM, 0.2f);
                    }
                    glAccum(GL_RETURN, 1.0f);
                  }}),
    [](const ::testing::TestParamInfo<AccumCase>& i) { return std::string(i.param.name); });

}  // namespace
}  // namespace sl::imaging::testing
