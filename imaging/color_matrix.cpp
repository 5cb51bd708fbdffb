// imaging/color_matrix.cpp — the color matrix stack (glspec121 3.6.3 "Color Matrix
// Specification": glMatrixMode(GL_COLOR) makes the matrix commands of 2.10.2 act on the top
// of the color matrix stack), the stage of 3.6.5 "Color Matrix Transformation" with its
// post-color-matrix scale and bias, and 6.1.6 "Color Matrix Query" (state.cpp answers it).
#include <cmath>

#include "imaging/internal.h"

namespace sl::imaging::detail {

bool Matrix4::isIdentity() const {
  for (int i = 0; i < 16; ++i)
    if (m[i] != ((i % 5 == 0) ? 1.0f : 0.0f)) return false;
  return true;
}

// (R', G', B', A')^T = diag(scale) * Mc * (R, G, B, A)^T + bias, Mc column-major as GL loads it.
void applyColorMatrix(const Matrix4& mat, const Rgba& scale, const Rgba& bias, Image4& image) {
  float k[16];  // rows of diag(scale) * Mc
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) k[r * 4 + c] = mat.m[c * 4 + r];
  const size_t groups = size_t(image.width) * image.height;
  const bool scaled = scale != Rgba{1, 1, 1, 1};
  parallelRows(image.height, size_t(image.width) * 16, [&](int y0, int y1) {
    float* p = image.px.data() + size_t(y0) * image.width * 4;
    const size_t n = size_t(y1 - y0) * image.width;
    for (size_t g = 0; g < n; ++g, p += 4) {
      const float r = p[0], gr = p[1], b = p[2], a = p[3];
      float o[4];
      for (int row = 0; row < 4; ++row)
        o[row] = k[row * 4 + 0] * r + k[row * 4 + 1] * gr + k[row * 4 + 2] * b + k[row * 4 + 3] * a;
      if (scaled) {
        for (int c = 0; c < 4; ++c) p[c] = o[c] * scale[c] + bias[c];
      } else {
        for (int c = 0; c < 4; ++c) p[c] = o[c] + bias[c];
      }
    }
  });
  (void)groups;
}

namespace {

Matrix4& top(State& s) { return s.transfer.colorMatrixStack.back(); }

Matrix4 multiply(const Matrix4& a, const Matrix4& b) {  // a * b, column-major
  Matrix4 r;
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) {
      float sum = 0.0f;
      for (int k = 0; k < 4; ++k) sum += a.m[k * 4 + row] * b.m[c * 4 + k];
      r.m[c * 4 + row] = sum;
    }
  return r;
}

template <class T>
Matrix4 fromArray(const T* v) {
  Matrix4 m;
  for (int i = 0; i < 16; ++i) m.m[i] = float(v[i]);
  return m;
}

}  // namespace

void emMatrixMode(GLenum mode) {
  State& s = *currentState();
  if (mode == GL_COLOR) {
    s.colorMatrixMode = true;
    return;
  }
  s.driver.MatrixMode(mode);
  // Only a mode the driver accepted leaves GL_COLOR (an invalid enum keeps the current mode).
  GLint now = 0;
  s.driver.GetIntegerv(GL_MATRIX_MODE, &now);
  if (GLenum(now) == mode) s.colorMatrixMode = false;
}

void emLoadIdentity() {
  State& s = *currentState();
  if (!s.colorMatrixMode) return s.driver.LoadIdentity();
  top(s) = Matrix4{};
}

void emLoadMatrixf(const GLfloat* m) {
  State& s = *currentState();
  if (!s.colorMatrixMode) return s.driver.LoadMatrixf(m);
  top(s) = fromArray(m);
}

void emLoadMatrixd(const GLdouble* m) {
  State& s = *currentState();
  if (!s.colorMatrixMode) return s.driver.LoadMatrixd(m);
  top(s) = fromArray(m);
}

void emMultMatrixf(const GLfloat* m) {
  State& s = *currentState();
  if (!s.colorMatrixMode) return s.driver.MultMatrixf(m);
  top(s) = multiply(top(s), fromArray(m));
}

void emMultMatrixd(const GLdouble* m) {
  State& s = *currentState();
  if (!s.colorMatrixMode) return s.driver.MultMatrixd(m);
  top(s) = multiply(top(s), fromArray(m));
}

void emPushMatrix() {
  State& s = *currentState();
  if (!s.colorMatrixMode) return s.driver.PushMatrix();
  auto& stack = s.transfer.colorMatrixStack;
  if (int(stack.size()) >= kMaxColorMatrixStackDepth) {
    recordError(s, GL_STACK_OVERFLOW);  // 2.10.2
    return;
  }
  stack.push_back(stack.back());
}

void emPopMatrix() {
  State& s = *currentState();
  if (!s.colorMatrixMode) return s.driver.PopMatrix();
  auto& stack = s.transfer.colorMatrixStack;
  if (stack.size() <= 1) {
    recordError(s, GL_STACK_UNDERFLOW);
    return;
  }
  stack.pop_back();
}

}  // namespace sl::imaging::detail

namespace sl::imaging::detail {

void emScalef(GLfloat x, GLfloat y, GLfloat z) {
  State& s = *currentState();
  if (!s.colorMatrixMode) return s.driver.Scalef(x, y, z);
  Matrix4 m;
  m.m[0] = x, m.m[5] = y, m.m[10] = z;
  top(s) = multiply(top(s), m);
}

void emTranslatef(GLfloat x, GLfloat y, GLfloat z) {
  State& s = *currentState();
  if (!s.colorMatrixMode) return s.driver.Translatef(x, y, z);
  Matrix4 m;
  m.m[12] = x, m.m[13] = y, m.m[14] = z;
  top(s) = multiply(top(s), m);
}

}  // namespace sl::imaging::detail

namespace sl::imaging::detail {
namespace {

constexpr double kDegreesToRadians = 3.14159265358979323846 / 180.0;
// Rotation about an axis this short is left out, as Mesa does (the specification asks for a
// unit axis and leaves a zero one undefined).
constexpr double kMinimumAxisLength = 1.0e-4;

// The current (color) matrix times m: what every matrix command of 2.10.2 does.
void multiplyTop(State& s, const Matrix4& m) { top(s) = multiply(top(s), m); }

Matrix4 fromRows(const double r[16]) {  // row-major values -> column-major matrix
  Matrix4 m;
  for (int row = 0; row < 4; ++row)
    for (int c = 0; c < 4; ++c) m.m[size_t(c * 4 + row)] = float(r[row * 4 + c]);
  return m;
}

// 2.10.2 Rotate: R = u u^T + cos(theta) (I - u u^T) + sin(theta) S, u the unit axis.
Matrix4 rotation(double degrees, double x, double y, double z) {
  const double length = std::sqrt(x * x + y * y + z * z);
  if (length <= kMinimumAxisLength) return Matrix4{};
  x /= length, y /= length, z /= length;
  const double c = std::cos(degrees * kDegreesToRadians), s = std::sin(degrees * kDegreesToRadians);
  const double u[3] = {x, y, z};
  const double skew[9] = {0, -z, y, z, 0, -x, -y, x, 0};
  double r[16] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r[i * 4 + j] = u[i] * u[j] + c * ((i == j ? 1.0 : 0.0) - u[i] * u[j]) + s * skew[i * 3 + j];
  return fromRows(r);
}

// 2.10.2 Ortho; INVALID_VALUE when l = r, b = t or n = f.
bool orthographic(double l, double r, double b, double t, double n, double f, Matrix4& m) {
  if (l == r || b == t || n == f) return false;
  const double rows[16] = {2 / (r - l),
                           0,
                           0,
                           -(r + l) / (r - l),
                           0,
                           2 / (t - b),
                           0,
                           -(t + b) / (t - b),
                           0,
                           0,
                           -2 / (f - n),
                           -(f + n) / (f - n),
                           0,
                           0,
                           0,
                           1};
  m = fromRows(rows);
  return true;
}

// 2.10.2 Frustum; INVALID_VALUE when n or f is not positive, or l = r, b = t, n = f.
bool perspective(double l, double r, double b, double t, double n, double f, Matrix4& m) {
  if (n <= 0 || f <= 0 || l == r || b == t || n == f) return false;
  const double rows[16] = {2 * n / (r - l),
                           0,
                           (r + l) / (r - l),
                           0,
                           0,
                           2 * n / (t - b),
                           (t + b) / (t - b),
                           0,
                           0,
                           0,
                           -(f + n) / (f - n),
                           -2 * f * n / (f - n),
                           0,
                           0,
                           -1,
                           0};
  m = fromRows(rows);
  return true;
}

template <class T>
Matrix4 transposed(const T* v) {  // 2.10.2 LoadTransposeMatrix: the rows are given
  Matrix4 m;
  for (int row = 0; row < 4; ++row)
    for (int c = 0; c < 4; ++c) m.m[size_t(c * 4 + row)] = float(v[row * 4 + c]);
  return m;
}

}  // namespace

void emScaled(GLdouble x, GLdouble y, GLdouble z) {
  State& s = *currentState();
  if (!s.colorMatrixMode) return s.driver.Scaled(x, y, z);
  emScalef(GLfloat(x), GLfloat(y), GLfloat(z));
}

void emTranslated(GLdouble x, GLdouble y, GLdouble z) {
  State& s = *currentState();
  if (!s.colorMatrixMode) return s.driver.Translated(x, y, z);
  emTranslatef(GLfloat(x), GLfloat(y), GLfloat(z));
}

void emRotatef(GLfloat angle, GLfloat x, GLfloat y, GLfloat z) {
  State& s = *currentState();
  if (!s.colorMatrixMode) return s.driver.Rotatef(angle, x, y, z);
  multiplyTop(s, rotation(angle, x, y, z));
}

void emRotated(GLdouble angle, GLdouble x, GLdouble y, GLdouble z) {
  State& s = *currentState();
  if (!s.colorMatrixMode) return s.driver.Rotated(angle, x, y, z);
  multiplyTop(s, rotation(angle, x, y, z));
}

void emOrtho(GLdouble l, GLdouble r, GLdouble b, GLdouble t, GLdouble n, GLdouble f) {
  State& s = *currentState();
  if (!s.colorMatrixMode) return s.driver.Ortho(l, r, b, t, n, f);
  Matrix4 m;
  if (!orthographic(l, r, b, t, n, f, m)) return recordError(s, GL_INVALID_VALUE);
  multiplyTop(s, m);
}

void emFrustum(GLdouble l, GLdouble r, GLdouble b, GLdouble t, GLdouble n, GLdouble f) {
  State& s = *currentState();
  if (!s.colorMatrixMode) return s.driver.Frustum(l, r, b, t, n, f);
  Matrix4 m;
  if (!perspective(l, r, b, t, n, f, m)) return recordError(s, GL_INVALID_VALUE);
  multiplyTop(s, m);
}

void emLoadTransposeMatrixf(const GLfloat* m) {
  State& s = *currentState();
  if (!s.colorMatrixMode) return s.driver.LoadTransposeMatrixf(m);
  top(s) = transposed(m);
}

void emLoadTransposeMatrixd(const GLdouble* m) {
  State& s = *currentState();
  if (!s.colorMatrixMode) return s.driver.LoadTransposeMatrixd(m);
  top(s) = transposed(m);
}

void emMultTransposeMatrixf(const GLfloat* m) {
  State& s = *currentState();
  if (!s.colorMatrixMode) return s.driver.MultTransposeMatrixf(m);
  multiplyTop(s, transposed(m));
}

void emMultTransposeMatrixd(const GLdouble* m) {
  State& s = *currentState();
  if (!s.colorMatrixMode) return s.driver.MultTransposeMatrixd(m);
  multiplyTop(s, transposed(m));
}

}  // namespace sl::imaging::detail
