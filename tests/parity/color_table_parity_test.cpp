// Parity of color tables (glspec121 3.6.3, 3.6.5 table 3.13, 6.1.7) on all three table
// stages, every internal format and several widths, through glReadPixels(GL_FLOAT) (the
// reference truncates when it packs unsigned bytes: departures_test.cpp).
#include "parity/parity_util.h"

namespace sl::imaging::testing {
namespace {

struct TableParity {
  GLenum target;      // which table stage
  GLenum enable;
  GLenum format;      // internal format
  int width;
};

std::vector<float> tableValues(int width, unsigned seed) {
  std::vector<float> t(size_t(width) * 4);
  uint32_t s = seed;
  for (float& v : t) {
    s = s * 1664525u + 1013904223u;
    v = float(s >> 8) / float(1u << 24);
  }
  return t;
}

class ColorTableParity : public ::testing::TestWithParam<TableParity> {};

TEST_P(ColorTableParity, ReadPixels) {
  SL_REQUIRE_REFERENCE();
  const TableParity p = GetParam();
  checkParity([p](Outcome& o) {
    const bool luminance = p.format == GL_LUMINANCE || p.format == GL_LUMINANCE_ALPHA ||
                           p.format == GL_INTENSITY;
    auto src = luminance ? greyPattern(kParityW, kParityH, 11)
                         : patternImage(kParityW, kParityH, 11);
    if (p.format == GL_INTENSITY)  // the reference indexes A with R too (departure 2)
      for (size_t k = 0; k < src.size(); k += 4) src[k + 3] = src[k];
    putImage(kParityW, kParityH, src);
    const auto t = tableValues(p.width, p.width + p.format);
    glColorTable(p.target, p.format, p.width, GL_RGBA, GL_FLOAT, t.data());
    glEnable(p.enable);
    appendFloats(o, readRgbaF(0, 0, kParityW, kParityH));
    // Table 6.1 returns luminance and intensity in R only; the reference repeats them in G,
    // B (and A for intensity): an additional departure (departures_test.cpp), so R and A are
    // compared separately, and only R for intensity.
    std::vector<float> back(size_t(p.width));
    for (GLenum component : {GL_RED, GL_ALPHA}) {
      if (component == GL_ALPHA && p.format == GL_INTENSITY) continue;
      glGetColorTable(p.target, component, GL_FLOAT, back.data());
      appendFloats(o, back);
    }
    GLint v = 0;
    glGetColorTableParameteriv(p.target, GL_COLOR_TABLE_WIDTH, &v);
    o.floats.push_back(float(v));
    glGetColorTableParameteriv(p.target, GL_COLOR_TABLE_FORMAT, &v);
    o.floats.push_back(float(v));
  });
}

std::vector<TableParity> tableCases() {
  std::vector<TableParity> cases;
  const GLenum stages[3][2] = {{GL_COLOR_TABLE, GL_COLOR_TABLE},
                               {GL_POST_CONVOLUTION_COLOR_TABLE, GL_POST_CONVOLUTION_COLOR_TABLE},
                               {GL_POST_COLOR_MATRIX_COLOR_TABLE, GL_POST_COLOR_MATRIX_COLOR_TABLE}};
  for (const auto& st : stages)
    for (GLenum f : {GL_ALPHA, GL_LUMINANCE, GL_LUMINANCE_ALPHA, GL_INTENSITY, GL_RGB, GL_RGBA})
      for (int w : {2, 16, 256}) cases.push_back({st[0], st[1], f, w});
  return cases;
}

std::string tableName(const ::testing::TestParamInfo<TableParity>& info) {
  const auto& p = info.param;
  const char* stage = p.target == GL_COLOR_TABLE ? "Table"
                      : p.target == GL_POST_CONVOLUTION_COLOR_TABLE ? "PostConv" : "PostMatrix";
  const char* f = p.format == GL_ALPHA ? "Alpha" : p.format == GL_LUMINANCE ? "Luminance"
                  : p.format == GL_LUMINANCE_ALPHA ? "LuminanceAlpha"
                  : p.format == GL_INTENSITY ? "Intensity" : p.format == GL_RGB ? "Rgb" : "Rgba";
  return std::string(stage) + "_" + f + "_" + std::to_string(p.width);
}

INSTANTIATE_TEST_SUITE_P(AllStagesFormatsWidths, ColorTableParity,
                         ::testing::ValuesIn(tableCases()), tableName);

// Table scale and bias with data inside [0,1] (outside it the reference clamps first:
// departure 8, named in departures_test.cpp).
class TableScaleBiasParity : public ::testing::TestWithParam<int> {};
TEST_P(TableScaleBiasParity, ReadPixels) {
  SL_REQUIRE_REFERENCE();
  const int k = GetParam();
  checkParity([k](Outcome& o) {
    putImage(kParityW, kParityH, patternImage(kParityW, kParityH, 5));
    const float scales[4][4] = {{2, 1, 0.5f, 1}, {-1, 1, 1, 3}, {0.25f, 0.5f, 0.75f, 1}, {1, -2, 4, 0}};
    const float biases[4][4] = {{0, 0.1f, 0.2f, 0}, {1, 0, 0, -0.5f}, {0.5f, 0.25f, 0, 0}, {0, 1, -1, 0.3f}};
    glColorTableParameterfv(GL_COLOR_TABLE, GL_COLOR_TABLE_SCALE, scales[k]);
    glColorTableParameterfv(GL_COLOR_TABLE, GL_COLOR_TABLE_BIAS, biases[k]);
    const auto t = tableValues(32, 77 + k);
    glColorTable(GL_COLOR_TABLE, GL_RGBA, 32, GL_RGBA, GL_FLOAT, t.data());
    glEnable(GL_COLOR_TABLE);
    appendFloats(o, readRgbaF(0, 0, kParityW, kParityH));
    std::vector<float> back(32 * 4);
    glGetColorTable(GL_COLOR_TABLE, GL_RGBA, GL_FLOAT, back.data());
    appendFloats(o, back);
  });
}
INSTANTIATE_TEST_SUITE_P(FourSettings, TableScaleBiasParity, ::testing::Range(0, 4));

// Sub-tables (client memory and framebuffer) and 8-bit table data.
class SubTableParity : public ::testing::TestWithParam<int> {};
TEST_P(SubTableParity, ReadPixels) {
  SL_REQUIRE_REFERENCE();
  const int k = GetParam();
  checkParity([k](Outcome& o) {
    const auto src = patternImage(kParityW, kParityH, 9);
    putImage(kParityW, kParityH, src);
    const auto t = tableValues(64, 3);
    glColorTable(GL_COLOR_TABLE, GL_RGBA, 64, GL_RGBA, GL_FLOAT, t.data());
    if (k == 0) {
      const auto sub = patternImage(10, 1, 4);
      glColorSubTable(GL_COLOR_TABLE, 20, 10, GL_RGBA, GL_UNSIGNED_BYTE, sub.data());
    } else if (k == 1) {
      glCopyColorSubTable(GL_COLOR_TABLE, 48, 0, 3, 16);
    } else {
      const auto sub = patternImage(64, 1, 6);
      glColorSubTable(GL_COLOR_TABLE, 0, 64, GL_RGBA, GL_UNSIGNED_BYTE, sub.data());
    }
    glEnable(GL_COLOR_TABLE);
    appendFloats(o, readRgbaF(0, 0, kParityW, kParityH));
    std::vector<float> back(64 * 4);
    glGetColorTable(GL_COLOR_TABLE, GL_RGBA, GL_FLOAT, back.data());
    appendFloats(o, back);
  });
}
INSTANTIATE_TEST_SUITE_P(ClientAndFramebuffer, SubTableParity, ::testing::Range(0, 3));

// The Brabec–Seidel pipeline of their Figure 4: RGBA table (0 or 64, 63 in alpha) and the
// sum-into-alpha color matrix, on glCopyPixels.
TEST(BrabecSeidelParity, TableAndSumIntoAlphaOnCopyPixels) {
  SL_REQUIRE_REFERENCE();
  checkParity([](Outcome& o) {
    putImage(kParityW, kParityH, patternImage(kParityW, kParityH, 21));
    std::vector<uint8_t> table(256 * 4);
    for (int i = 0; i < 256; ++i)
      for (int c = 0; c < 4; ++c) table[i * 4 + c] = i == 0 ? 0 : (c == 3 ? 63 : 64);
    glColorTable(GL_COLOR_TABLE, GL_RGBA, 256, GL_RGBA, GL_UNSIGNED_BYTE, table.data());
    glEnable(GL_COLOR_TABLE);
    const float sum[16] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    glMatrixMode(GL_COLOR);
    glLoadMatrixf(sum);
    glMatrixMode(GL_MODELVIEW);
    glWindowPos2i(0, 0);
    glCopyPixels(0, 0, kParityW / 2, kParityH, GL_COLOR);
    appendBytes(o, readWindow());
  });
}

}  // namespace
}  // namespace sl::imaging::testing
