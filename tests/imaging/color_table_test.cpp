// Color tables: glspec121 3.6.3 "Color Table Specification" (scale, bias, clamp, component
// selection by table 3.15), 3.6.5 "Color Table Lookup" (table 3.13), 6.1.7 queries, proxies
// and errors (SGI_color_table "Errors").
#include "imaging/imaging_test_util.h"
#include "tests/test_names.h"

namespace sl::imaging::testing {
namespace {

constexpr int kW = 16, kH = 8;

struct TableCase {
  GLenum internalFormat;
  int width;
};

class ColorTableFormats : public ::testing::TestWithParam<TableCase> {};

// The table holds distinct values per component: entry k has R = k/(w-1) reversed, G and B
// other permutations, A = a ramp, so every component's lookup is visible.
std::vector<float> tableData(int width) {
  std::vector<float> t(size_t(width) * 4);
  for (int k = 0; k < width; ++k) {
    const float f = width > 1 ? float(k) / float(width - 1) : 0.5f;
    t[k * 4 + 0] = 1.0f - f;
    t[k * 4 + 1] = 0.25f + 0.5f * f;
    t[k * 4 + 2] = f * f;
    t[k * 4 + 3] = 0.5f * f;
  }
  return t;
}

TEST_P(ColorTableFormats, LookupFollowsTable313) {
  const auto [format, width] = GetParam();
  auto ctx = emulatedContext(kW, kH);
  const auto src = patternImage(kW, kH, 7);
  putImage(kW, kH, src);
  const auto t = tableData(width);
  glColorTable(GL_COLOR_TABLE, format, width, GL_RGBA, GL_FLOAT, t.data());
  glEnable(GL_COLOR_TABLE);
  const auto got = readRgba8(0, 0, kW, kH);
  ASSERT_TRUE(drainErrors().empty());
  // Table 3.15 keeps L and I from R, A from A; table 3.13 assigns them to components, each
  // component indexed by its own value.
  for (size_t p = 0; p < src.size(); p += 4) {
    float in[4], want[4];
    for (int c = 0; c < 4; ++c) in[c] = float(src[p + c]) / 255.0f;
    for (int c = 0; c < 4; ++c) want[c] = in[c];
    auto entry = [&](int c, int comp) { return t[size_t(tableIndex(in[c], width)) * 4 + comp]; };
    switch (format) {
      case GL_ALPHA: want[3] = entry(3, 3); break;
      case GL_LUMINANCE:
        for (int c = 0; c < 3; ++c) want[c] = entry(c, 0);
        break;
      case GL_LUMINANCE_ALPHA:
        for (int c = 0; c < 3; ++c) want[c] = entry(c, 0);
        want[3] = entry(3, 3);
        break;
      case GL_INTENSITY:
        for (int c = 0; c < 4; ++c) want[c] = entry(c, 0);
        break;
      case GL_RGB:
        for (int c = 0; c < 3; ++c) want[c] = entry(c, c);
        break;
      default:
        for (int c = 0; c < 4; ++c) want[c] = entry(c, c);
        break;
    }
    for (int c = 0; c < 4; ++c)
      ASSERT_EQ(got[p + c], toByte(want[c])) << "pixel " << p / 4 << " component " << c;
  }
}

INSTANTIATE_TEST_SUITE_P(AllFormats, ColorTableFormats,
                         ::testing::Values(TableCase{GL_ALPHA, 256}, TableCase{GL_LUMINANCE, 16},
                                           TableCase{GL_LUMINANCE_ALPHA, 8},
                                           TableCase{GL_INTENSITY, 32}, TableCase{GL_RGB, 2},
                                           TableCase{GL_RGBA, 256}, TableCase{GL_RGBA, 1},
                                           TableCase{GL_RGBA8, 64}));

// 3.6.3: "scaled by COLOR_TABLE_SCALE, biased by COLOR_TABLE_BIAS, and clamped to [0,1]",
// scale and bias apply to the unclamped data.
TEST(ColorTable, ScaleBiasThenClampAtDefinition) {
  auto ctx = emulatedContext(4, 1);
  const float scale[4] = {2.0f, 0.5f, -1.0f, 1.0f}, bias[4] = {-0.5f, 0.25f, 1.0f, 0.0f};
  glColorTableParameterfv(GL_COLOR_TABLE, GL_COLOR_TABLE_SCALE, scale);
  glColorTableParameterfv(GL_COLOR_TABLE, GL_COLOR_TABLE_BIAS, bias);
  const float data[8] = {1.5f, 0.2f, 0.3f, -0.5f, 0.1f, 2.0f, 1.4f, 0.7f};
  glColorTable(GL_COLOR_TABLE, GL_RGBA, 2, GL_RGBA, GL_FLOAT, data);
  float back[8] = {};
  glGetColorTable(GL_COLOR_TABLE, GL_RGBA, GL_FLOAT, back);
  for (int i = 0; i < 8; ++i)
    EXPECT_FLOAT_EQ(back[i], clamp01(data[i] * scale[i % 4] + bias[i % 4])) << i;
  float q[4] = {};
  glGetColorTableParameterfv(GL_COLOR_TABLE, GL_COLOR_TABLE_SCALE, q);
  EXPECT_EQ(q[0], 2.0f);
  EXPECT_TRUE(drainErrors().empty());
}

TEST(ColorTable, SubTableAndCopyFromFramebuffer) {
  auto ctx = emulatedContext(8, 2);
  std::vector<float> zeros(8 * 4, 0.0f);
  glColorTable(GL_POST_CONVOLUTION_COLOR_TABLE, GL_RGBA, 8, GL_RGBA, GL_FLOAT, zeros.data());
  const float sub[8] = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f, 0.8f};
  glColorSubTable(GL_POST_CONVOLUTION_COLOR_TABLE, 3, 2, GL_RGBA, GL_FLOAT, sub);
  float back[32] = {};
  glGetColorTable(GL_POST_CONVOLUTION_COLOR_TABLE, GL_RGBA, GL_FLOAT, back);
  for (int i = 0; i < 32; ++i) {
    const float want = (i >= 12 && i < 20) ? sub[i - 12] : 0.0f;
    EXPECT_FLOAT_EQ(back[i], want) << i;
  }
  // CopyColorTable takes the row from the framebuffer (no pixel transfer).
  const auto src = patternImage(8, 2, 3);
  putImage(8, 2, src);
  glCopyColorTable(GL_COLOR_TABLE, GL_RGB, 0, 1, 8);
  uint8_t rgb[8 * 3] = {};
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetColorTable(GL_COLOR_TABLE, GL_RGB, GL_UNSIGNED_BYTE, rgb);
  for (int k = 0; k < 8; ++k)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(rgb[k * 3 + c], src[(8 + k) * 4 + c]) << k;
  glCopyColorSubTable(GL_COLOR_TABLE, 6, 0, 0, 2);
  glGetColorTable(GL_COLOR_TABLE, GL_RGB, GL_UNSIGNED_BYTE, rgb);
  EXPECT_EQ(rgb[6 * 3], src[0]);
  EXPECT_EQ(rgb[7 * 3 + 2], src[4 + 2]);
  EXPECT_TRUE(drainErrors().empty());
}

// 6.1.7 / table 6.1: LUMINANCE returns (L, 0, 0, 1), ALPHA (0, 0, 0, A).
TEST(ColorTable, QueryReturnsTable61) {
  auto ctx = emulatedContext(4, 1);
  const float data[8] = {0.2f, 0.4f, 0.6f, 0.8f, 1.0f, 0.0f, 0.5f, 0.25f};
  glColorTable(GL_COLOR_TABLE, GL_LUMINANCE, 2, GL_RGBA, GL_FLOAT, data);
  float back[8] = {};
  glGetColorTable(GL_COLOR_TABLE, GL_RGBA, GL_FLOAT, back);
  const float want[8] = {0.2f, 0, 0, 1, 1.0f, 0, 0, 1};
  for (int i = 0; i < 8; ++i) EXPECT_FLOAT_EQ(back[i], want[i]) << i;
  glColorTable(GL_COLOR_TABLE, GL_ALPHA, 2, GL_RGBA, GL_FLOAT, data);
  glGetColorTable(GL_COLOR_TABLE, GL_RGBA, GL_FLOAT, back);
  const float wantA[8] = {0, 0, 0, 0.8f, 0, 0, 0, 0.25f};
  for (int i = 0; i < 8; ++i) EXPECT_FLOAT_EQ(back[i], wantA[i]) << i;
  GLint v = 0;
  glGetColorTableParameteriv(GL_COLOR_TABLE, GL_COLOR_TABLE_WIDTH, &v);
  EXPECT_EQ(v, 2);
  glGetColorTableParameteriv(GL_COLOR_TABLE, GL_COLOR_TABLE_FORMAT, &v);
  EXPECT_EQ(GLenum(v), GLenum(GL_ALPHA));
  glGetColorTableParameteriv(GL_COLOR_TABLE, GL_COLOR_TABLE_RED_SIZE, &v);
  EXPECT_EQ(v, 0);
  glGetColorTableParameteriv(GL_COLOR_TABLE, GL_COLOR_TABLE_ALPHA_SIZE, &v);
  EXPECT_GT(v, 0);
  EXPECT_TRUE(drainErrors().empty());
}

// 3.6.3 "Color Table State and Proxy State": a proxy that fits takes the state, one that is
// too large is zeroed without an error, and neither touches the real table.
TEST(ColorTable, Proxies) {
  auto ctx = emulatedContext(4, 1);
  glColorTable(GL_PROXY_COLOR_TABLE, GL_RGB, 128, GL_RGBA, GL_FLOAT, nullptr);
  GLint w = -1;
  glGetColorTableParameteriv(GL_PROXY_COLOR_TABLE, GL_COLOR_TABLE_WIDTH, &w);
  EXPECT_EQ(w, 128);
  glColorTable(GL_PROXY_COLOR_TABLE, GL_RGB, 512, GL_RGBA, GL_FLOAT, nullptr);
  glGetColorTableParameteriv(GL_PROXY_COLOR_TABLE, GL_COLOR_TABLE_WIDTH, &w);
  EXPECT_EQ(w, 0);
  EXPECT_TRUE(drainErrors().empty());
  glGetColorTableParameteriv(GL_COLOR_TABLE, GL_COLOR_TABLE_WIDTH, &w);
  EXPECT_EQ(w, 0);
  float dummy[4];
  glGetColorTable(GL_PROXY_COLOR_TABLE, GL_RGBA, GL_FLOAT, dummy);  // proxies have no image
  EXPECT_EQ(drainErrors(), std::vector<GLenum>{GL_INVALID_ENUM});
}

struct ErrorCase {
  const char* name;
  void (*call)();
  GLenum error;
};

class ColorTableErrors : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(ColorTableErrors, RaisesTheSpecificationsError) {
  auto ctx = emulatedContext(4, 1);
  static const float data[512 * 4] = {};
  (void)data;
  GetParam().call();
  EXPECT_EQ(drainErrors(), std::vector<GLenum>{GetParam().error}) << GetParam().name;
}

const float kTableData[512 * 4] = {};

INSTANTIATE_TEST_SUITE_P(
    SgiColorTableErrors, ColorTableErrors,
    ::testing::Values(
        ErrorCase{"bad target",
                  [] { glColorTable(GL_TEXTURE_2D, GL_RGBA, 4, GL_RGBA, GL_FLOAT, kTableData); },
                  GL_INVALID_ENUM},
        ErrorCase{"bad internal format",
                  [] {
                    glColorTable(GL_COLOR_TABLE, GL_DEPTH_COMPONENT, 4, GL_RGBA, GL_FLOAT,
                                 kTableData);
                  },
                  GL_INVALID_ENUM},
        ErrorCase{"width not a power of two",
                  [] { glColorTable(GL_COLOR_TABLE, GL_RGBA, 3, GL_RGBA, GL_FLOAT, kTableData); },
                  GL_INVALID_VALUE},
        ErrorCase{"negative width",
                  [] { glColorTable(GL_COLOR_TABLE, GL_RGBA, -4, GL_RGBA, GL_FLOAT, kTableData); },
                  GL_INVALID_VALUE},
        ErrorCase{"table too large",
                  [] { glColorTable(GL_COLOR_TABLE, GL_RGBA, 512, GL_RGBA, GL_FLOAT, kTableData); },
                  GL_TABLE_TOO_LARGE},
        ErrorCase{"sub-table past the end",
                  [] {
                    glColorTable(GL_COLOR_TABLE, GL_RGBA, 4, GL_RGBA, GL_FLOAT, kTableData);
                    glColorSubTable(GL_COLOR_TABLE, 3, 2, GL_RGBA, GL_FLOAT, kTableData);
                  },
                  GL_INVALID_VALUE},
        ErrorCase{"parameter on a proxy",
                  [] {
                    const float v[4] = {1, 1, 1, 1};
                    glColorTableParameterfv(GL_PROXY_COLOR_TABLE, GL_COLOR_TABLE_SCALE, v);
                  },
                  GL_INVALID_ENUM},
        ErrorCase{"bad parameter name",
                  [] {
                    const float v[4] = {1, 1, 1, 1};
                    glColorTableParameterfv(GL_COLOR_TABLE, GL_COLOR_TABLE_WIDTH, v);
                  },
                  GL_INVALID_ENUM},
        ErrorCase{"copy to a proxy",
                  [] { glCopyColorTable(GL_PROXY_COLOR_TABLE, GL_RGBA, 0, 0, 4); },
                  GL_INVALID_ENUM},
        ErrorCase{"query bad pname",
                  [] {
                    GLint v;
                    glGetColorTableParameteriv(GL_COLOR_TABLE, GL_TEXTURE_WIDTH, &v);
                  },
                  GL_INVALID_ENUM}),
    [](const auto& info) { return testName(info.param.name); });

// GL's error model (2.5): one sticky flag per error; GetError returns and clears one.
TEST(ColorTable, ErrorFlagsAreStickyOncePerCode) {
  auto ctx = emulatedContext(4, 1);
  glColorTable(GL_COLOR_TABLE, GL_RGBA, 3, GL_RGBA, GL_FLOAT, kTableData);
  glColorTable(GL_COLOR_TABLE, GL_RGBA, 5, GL_RGBA, GL_FLOAT, kTableData);
  glColorTable(GL_TEXTURE_2D, GL_RGBA, 4, GL_RGBA, GL_FLOAT, kTableData);
  EXPECT_EQ(drainErrors(), (std::vector<GLenum>{GL_INVALID_VALUE, GL_INVALID_ENUM}));
}

}  // namespace
}  // namespace sl::imaging::testing
