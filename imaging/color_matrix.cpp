// imaging/color_matrix.cpp — the color matrix stack (glspec121 3.6.3 "Color Matrix
// Specification": glMatrixMode(GL_COLOR) makes the matrix commands of 2.10.2 act on the top
// of the color matrix stack), the stage of 3.6.5 "Color Matrix Transformation" with its
// post-color-matrix scale and bias, and 6.1.6 "Color Matrix Query" (state.cpp answers it).
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
