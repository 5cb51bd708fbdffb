// Every error case of the imaging subset raised by both implementations with the same code
// (glspec121 3.6.3, 2.10.2 stack errors, 4.2.4; SGI_color_table, EXT_convolution,
// HP_convolution_border_modes and EXT_histogram "Errors"). Cases where the reference raises a
// different code are named departures (departures_test.cpp).
#include "parity/parity_util.h"

namespace sl::imaging::testing {
namespace {

const float kData[1024 * 4] = {};

struct ErrorCase {
  const char* name;
  void (*call)();
};

class ErrorParity : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(ErrorParity, SameError) {
  SL_REQUIRE_REFERENCE();
  const auto call = GetParam().call;
  checkParity([call](Outcome& o) {
    drainErrors();
    call();
    o.errors = drainErrors();
    EXPECT_FALSE(o.errors.empty()) << "the case must raise an error";
  });
}

#define SL_ERR(name, ...) \
  ErrorCase { name, [] { __VA_ARGS__; } }

INSTANTIATE_TEST_SUITE_P(
    ImagingErrors, ErrorParity,
    ::testing::Values(
        SL_ERR("ColorTableBadTarget", glColorTable(GL_HISTOGRAM, GL_RGBA, 4, GL_RGBA, GL_FLOAT, kData)),
        SL_ERR("ColorTableBadInternalFormat", glColorTable(GL_COLOR_TABLE, GL_DEPTH_COMPONENT, 4, GL_RGBA, GL_FLOAT, kData)),
        SL_ERR("ColorTableWidthNotPowerOfTwo", glColorTable(GL_COLOR_TABLE, GL_RGBA, 3, GL_RGBA, GL_FLOAT, kData)),
        SL_ERR("ColorTableNegativeWidth", glColorTable(GL_COLOR_TABLE, GL_RGBA, -2, GL_RGBA, GL_FLOAT, kData)),
        SL_ERR("ColorTableTooLarge", glColorTable(GL_COLOR_TABLE, GL_RGBA, 512, GL_RGBA, GL_FLOAT, kData)),
        SL_ERR("PostConvolutionTableTooLarge", glColorTable(GL_POST_CONVOLUTION_COLOR_TABLE, GL_RGB, 1024, GL_RGBA, GL_FLOAT, kData)),
        SL_ERR("ColorSubTablePastEnd", glColorTable(GL_COLOR_TABLE, GL_RGBA, 8, GL_RGBA, GL_FLOAT, kData); glColorSubTable(GL_COLOR_TABLE, 6, 4, GL_RGBA, GL_FLOAT, kData)),
        SL_ERR("ColorSubTableBadTarget", glColorSubTable(GL_PROXY_COLOR_TABLE, 0, 1, GL_RGBA, GL_FLOAT, kData)),
        SL_ERR("CopyColorTableWidthNotPowerOfTwo", glCopyColorTable(GL_COLOR_TABLE, GL_RGBA, 0, 0, 5)),
        SL_ERR("ColorTableParameterBadPname", const float v[4] = {1, 1, 1, 1}; glColorTableParameterfv(GL_COLOR_TABLE, GL_COLOR_TABLE_WIDTH, v)),
        SL_ERR("ColorTableParameterBadTarget", const float v[4] = {1, 1, 1, 1}; glColorTableParameterfv(GL_TEXTURE_2D, GL_COLOR_TABLE_SCALE, v)),
        SL_ERR("GetColorTableProxy", float v[4]; glGetColorTable(GL_PROXY_COLOR_TABLE, GL_RGBA, GL_FLOAT, v)),
        SL_ERR("GetColorTableParameterBadPname", GLint v; glGetColorTableParameteriv(GL_COLOR_TABLE, GL_TEXTURE_WIDTH, &v)),
        SL_ERR("ConvolutionFilter2DBadTarget", glConvolutionFilter2D(GL_CONVOLUTION_1D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, kData)),
        SL_ERR("ConvolutionFilter2DBadInternalFormat", glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_DEPTH_COMPONENT, 3, 3, GL_RGBA, GL_FLOAT, kData)),
        SL_ERR("ConvolutionFilter2DTooWide", glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 10, 3, GL_RGBA, GL_FLOAT, kData)),
        SL_ERR("ConvolutionFilter2DTooHigh", glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 10, GL_RGBA, GL_FLOAT, kData)),
        SL_ERR("ConvolutionFilter2DNegative", glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, -1, 3, GL_RGBA, GL_FLOAT, kData)),
        SL_ERR("ConvolutionFilter1DTooWide", glConvolutionFilter1D(GL_CONVOLUTION_1D, GL_RGBA, 10, GL_RGBA, GL_FLOAT, kData)),
        SL_ERR("ConvolutionFilter1DBadTarget", glConvolutionFilter1D(GL_CONVOLUTION_2D, GL_RGBA, 3, GL_RGBA, GL_FLOAT, kData)),
        SL_ERR("SeparableFilterTooWide", glSeparableFilter2D(GL_SEPARABLE_2D, GL_RGBA, 10, 3, GL_RGBA, GL_FLOAT, kData, kData)),
        SL_ERR("SeparableFilterBadTarget", glSeparableFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, kData, kData)),
        SL_ERR("CopyConvolutionFilter2DTooWide", glCopyConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 0, 0, 10, 3)),
        SL_ERR("ConvolutionParameterBadBorderMode", glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, GL_RGBA)),
        SL_ERR("ConvolutionParameterBadTarget", glConvolutionParameteri(GL_TEXTURE_2D, GL_CONVOLUTION_BORDER_MODE, GL_REDUCE)),
        SL_ERR("ConvolutionParameterBadPname", const float v[4] = {0, 0, 0, 0}; glConvolutionParameterfv(GL_CONVOLUTION_2D, GL_CONVOLUTION_WIDTH, v)),
        SL_ERR("GetConvolutionFilterBadTarget", float v[4]; glGetConvolutionFilter(GL_SEPARABLE_2D, GL_RGBA, GL_FLOAT, v)),
        SL_ERR("GetConvolutionParameterBadPname", GLint v; glGetConvolutionParameteriv(GL_CONVOLUTION_2D, GL_COLOR_TABLE_WIDTH, &v)),
        SL_ERR("GetSeparableFilterBadTarget", float v[4]; glGetSeparableFilter(GL_CONVOLUTION_2D, GL_RGBA, GL_FLOAT, v, v, nullptr)),
        SL_ERR("HistogramBadTarget", glHistogram(GL_MINMAX, 16, GL_RGBA, GL_FALSE)),
        SL_ERR("HistogramWidthNotPowerOfTwo", glHistogram(GL_HISTOGRAM, 12, GL_RGBA, GL_FALSE)),
        SL_ERR("HistogramTooLarge", glHistogram(GL_HISTOGRAM, 1024, GL_RGBA, GL_FALSE)),
        SL_ERR("HistogramIntensityFormat", glHistogram(GL_HISTOGRAM, 16, GL_INTENSITY, GL_FALSE)),
        SL_ERR("ResetHistogramBadTarget", glResetHistogram(GL_MINMAX)),
        SL_ERR("GetHistogramBadTarget", GLuint v[64]; glGetHistogram(GL_PROXY_HISTOGRAM, GL_FALSE, GL_RGBA, GL_UNSIGNED_INT, v)),
        SL_ERR("GetHistogramParameterBadPname", GLint v; glGetHistogramParameteriv(GL_HISTOGRAM, GL_MINMAX_SINK, &v)),
        SL_ERR("MinmaxBadTarget", glMinmax(GL_HISTOGRAM, GL_RGBA, GL_FALSE)),
        SL_ERR("MinmaxIntensityFormat", glMinmax(GL_MINMAX, GL_INTENSITY, GL_FALSE)),
        SL_ERR("ResetMinmaxBadTarget", glResetMinmax(GL_HISTOGRAM)),
        SL_ERR("GetMinmaxParameterBadPname", GLint v; glGetMinmaxParameteriv(GL_MINMAX, GL_HISTOGRAM_WIDTH, &v)),
        SL_ERR("ColorMatrixStackOverflow", glMatrixMode(GL_COLOR); for (int i = 0; i < 4; ++i) glPushMatrix(); glMatrixMode(GL_MODELVIEW)),
        SL_ERR("ColorMatrixStackUnderflow", glMatrixMode(GL_COLOR); glPopMatrix(); glMatrixMode(GL_MODELVIEW)),
        SL_ERR("AccumBadOperation", glAccum(GL_COLOR_TABLE, 1.0f))),
    [](const ::testing::TestParamInfo<ErrorCase>& i) { return std::string(i.param.name); });

}  // namespace
}  // namespace sl::imaging::testing
