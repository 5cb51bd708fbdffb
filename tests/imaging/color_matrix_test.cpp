// glMatrixMode(GL_COLOR) and the matrix commands of glspec121 2.10.2 on the colour matrix
// (3.6.3 "Color Matrix Specification": every matrix command acts on the current matrix,
// whichever mode is current). The expected matrices are written out from the formulas of
// 2.10.2 (Rotate, Ortho, Frustum, Scale, Translate, the transpose forms of 1.3) for arguments
// whose results are exact or nearly so, and read back with glGetFloatv(GL_COLOR_MATRIX).
#include <cmath>

#include "imaging/imaging_test_util.h"

namespace sl::imaging::testing {
namespace {

// Column-major, as GL returns it; written here row by row for reading.
std::vector<float> fromRows(std::initializer_list<float> rows) {
  std::vector<float> r(rows), m(16);
  for (int row = 0; row < 4; ++row)
    for (int c = 0; c < 4; ++c) m[size_t(c * 4 + row)] = r[size_t(row * 4 + c)];
  return m;
}

std::vector<float> colorMatrix() {
  std::vector<float> m(16, -99.0f);
  glGetFloatv(GL_COLOR_MATRIX, m.data());
  return m;
}

// The rotation matrices involve cos and sin of 90 and 120 degrees: within a few float steps of
// the exact 0, 1 and -1 (cos 90 degrees evaluates to about 6e-17 in double).
constexpr float kTrigTolerance = 1e-6f;

void expectMatrix(const std::vector<float>& got, const std::vector<float>& want, float tolerance,
                  const char* what) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i)
    EXPECT_NEAR(got[i], want[i], tolerance) << what << ", column " << i / 4 << " row " << i % 4;
}

class ColorMatrixCommands : public ::testing::Test {
 protected:
  void SetUp() override {
    context_ = emulatedContext(4, 4);
    glMatrixMode(GL_COLOR);
    glLoadIdentity();
  }
  std::unique_ptr<GlContext> context_;
};

TEST_F(ColorMatrixCommands, RotateAboutZAndAboutTheDiagonal) {
  glRotatef(90.0f, 0.0f, 0.0f, 1.0f);  // 2.10.2: R = uu^T + cos(I - uu^T) + sin S
  expectMatrix(colorMatrix(), fromRows({0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}),
               kTrigTolerance, "90 degrees about z");
  glLoadIdentity();
  // 120 degrees about (1, 1, 1) (not normalised: Rotate normalises) cycles x -> y -> z.
  glRotated(120.0, 2.0, 2.0, 2.0);
  expectMatrix(colorMatrix(), fromRows({0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1}),
               kTrigTolerance, "120 degrees about the diagonal");
  EXPECT_TRUE(drainErrors().empty());
}

TEST_F(ColorMatrixCommands, OrthoFrustumScaleTranslateMultiply) {
  glOrtho(0.0, 2.0, 0.0, 4.0, -1.0, 1.0);  // 2/(r-l), 2/(t-b), -2/(f-n); -(r+l)/(r-l) ...
  expectMatrix(colorMatrix(), fromRows({1, 0, 0, -1, 0, 0.5f, 0, -1, 0, 0, -1, 0, 0, 0, 0, 1}), 0,
               "ortho");
  glLoadIdentity();
  glFrustum(-1.0, 1.0, -1.0, 1.0, 1.0, 3.0);  // 2n/(r-l) = 1, -(f+n)/(f-n) = -2, -2fn/(f-n) = -3
  expectMatrix(colorMatrix(), fromRows({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -2, -3, 0, 0, -1, 0}), 0,
               "frustum");
  glLoadIdentity();
  glScaled(2.0, 0.5, 4.0);
  glTranslated(1.0, -2.0, 0.25);  // C = S * T: the translation is scaled
  expectMatrix(colorMatrix(), fromRows({2, 0, 0, 2, 0, 0.5f, 0, -1, 0, 0, 4, 1, 0, 0, 0, 1}), 0,
               "scale then translate");
  EXPECT_TRUE(drainErrors().empty());
}

TEST_F(ColorMatrixCommands, TransposeForms) {
  const float rows[16] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};
  glLoadTransposeMatrixf(rows);
  expectMatrix(colorMatrix(), fromRows({1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16}), 0,
               "load transpose");
  const double swap[16] = {0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // rows: R <-> G
  glMultTransposeMatrixd(swap);  // C = C * P: columns 0 and 1 exchange
  expectMatrix(colorMatrix(), fromRows({2, 1, 3, 4, 6, 5, 7, 8, 10, 9, 11, 12, 14, 13, 15, 16}), 0,
               "mult transpose");
  EXPECT_TRUE(drainErrors().empty());
}

TEST_F(ColorMatrixCommands, ErrorsLeaveTheMatrixAlone) {
  glScalef(3.0f, 3.0f, 3.0f);
  const std::vector<float> before = colorMatrix();
  glOrtho(1.0, 1.0, 0.0, 1.0, 0.0, 1.0);  // l = r
  EXPECT_EQ(drainErrors(), std::vector<GLenum>{GL_INVALID_VALUE});
  glFrustum(-1.0, 1.0, -1.0, 1.0, 0.0, 1.0);  // n = 0
  EXPECT_EQ(drainErrors(), std::vector<GLenum>{GL_INVALID_VALUE});
  glFrustum(-1.0, 1.0, -1.0, 1.0, 2.0, 2.0);  // n = f
  EXPECT_EQ(drainErrors(), std::vector<GLenum>{GL_INVALID_VALUE});
  expectMatrix(colorMatrix(), before, 0, "after the errors");
}

TEST_F(ColorMatrixCommands, OtherModesReachTheDriver) {
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glRotatef(90.0f, 0.0f, 0.0f, 1.0f);
  float modelview[16];
  glGetFloatv(GL_MODELVIEW_MATRIX, modelview);
  EXPECT_NEAR(modelview[1], 1.0f, kTrigTolerance);   // column 0, row 1: sin 90
  EXPECT_NEAR(modelview[4], -1.0f, kTrigTolerance);  // column 1, row 0: -sin 90
  expectMatrix(colorMatrix(), fromRows({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}), 0,
               "colour matrix untouched");
}

TEST_F(ColorMatrixCommands, TransposeQueryAndTransformBitKeepTheColorMode) {
  const float rows[16] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};
  glLoadTransposeMatrixf(rows);
  float transposed[16];
  glGetFloatv(GL_TRANSPOSE_COLOR_MATRIX, transposed);  // glspec14 6.1.2: row by row
  for (int i = 0; i < 16; ++i) EXPECT_EQ(transposed[i], rows[i]) << i;
  // GL_TRANSFORM_BIT saves MATRIX_MODE (table 6.7), GL_COLOR included: after the pop, matrix
  // commands act on the colour matrix again.
  glPushAttrib(GL_TRANSFORM_BIT);
  glMatrixMode(GL_MODELVIEW);
  glPopAttrib();
  glLoadIdentity();
  expectMatrix(colorMatrix(), fromRows({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}), 0,
               "identity loaded into the colour matrix after the pop");
  GLint mode = 0;
  glGetIntegerv(GL_MATRIX_MODE, &mode);
  EXPECT_EQ(GLenum(mode), GLenum(GL_COLOR));
  EXPECT_TRUE(drainErrors().empty());
}

TEST_F(ColorMatrixCommands, CopyPixelsThroughARotatedMatrix) {
  // 90 degrees about z: R' = -G (clamped to 0 at the end), G' = R, B' = B, A' = A (3.6.5).
  glMatrixMode(GL_MODELVIEW);
  putImage(1, 1, {200, 100, 50, 255});
  glMatrixMode(GL_COLOR);
  glRotatef(90.0f, 0.0f, 0.0f, 1.0f);
  glMatrixMode(GL_MODELVIEW);
  glWindowPos2i(1, 0);
  glCopyPixels(0, 0, 1, 1, GL_COLOR);
  glMatrixMode(GL_COLOR);
  glLoadIdentity();  // glReadPixels goes through the colour matrix too
  glMatrixMode(GL_MODELVIEW);
  EXPECT_EQ(readRgba8(1, 0, 1, 1), (std::vector<uint8_t>{0, 200, 50, 255}));
}

}  // namespace
}  // namespace sl::imaging::testing
