// imaging/accumulation.cpp — the accumulation buffer where the visual has none (EGL pbuffers
// on NVIDIA): glspec121 4.2.4 "The Accumulation Buffer" and glClear/glClearAccum (4.2.3).
//
//   ACCUM  A <- A + value * C      (C read from the read buffer)
//   LOAD   A <- value * C
//   RETURN C <- clamp(value * A, 0, 1), written like a fragment where only the pixel
//          ownership and scissor tests, dithering and the colour mask apply
//   MULT   A <- value * A
//   ADD    A <- A + value
// Operations act on the scissor box when the scissor test is enabled. The buffer keeps each
// component as 16-bit signed fixed point in [-1, 1] (the precision of the visuals the
// project asks for, core/context.cpp kAccumBits), so results quantise as a real one does.
#include <cmath>

#include "imaging/internal.h"

namespace sl::imaging::detail {
namespace {

constexpr float kAccumSteps = 32767.0f;  // 16-bit signed fixed point: v = k / 32767

// "Accumulation buffer values are taken to be signed values in [-1, 1]".
float quantize(float v) {
  if (!(v > -1.0f)) return v != v ? 0.0f : -1.0f;
  if (v >= 1.0f) return 1.0f;
  return std::nearbyint(v * kAccumSteps) / kAccumSteps;
}

struct Box {
  int x0, y0, x1, y1;  // [x0, x1) x [y0, y1) within the buffer
};

void ensureBuffer(State& s) {
  const int w = s.context->spec().width, h = s.context->spec().height;
  if (s.accumWidth == w && s.accumHeight == h) return;
  s.accumWidth = w;
  s.accumHeight = h;
  s.accum.assign(size_t(w) * h * 4, 0.0f);
}

Box region(State& s) {
  Box b{0, 0, s.accumWidth, s.accumHeight};
  if (s.driver.IsEnabled(GL_SCISSOR_TEST)) {
    GLint box[4] = {0, 0, 0, 0};
    s.driver.GetIntegerv(GL_SCISSOR_BOX, box);
    b.x0 = std::clamp(box[0], 0, s.accumWidth);
    b.y0 = std::clamp(box[1], 0, s.accumHeight);
    b.x1 = std::clamp(box[0] + box[2], b.x0, s.accumWidth);
    b.y1 = std::clamp(box[1] + box[3], b.y0, s.accumHeight);
  }
  return b;
}

template <class Op>
void forEach(State& s, const Box& b, const Op& op) {
  const int w = b.x1 - b.x0;
  parallelRows(b.y1 - b.y0, size_t(w) * 4, [&](int r0, int r1) {
    for (int y = b.y0 + r0; y < b.y0 + r1; ++y) {
      float* a = s.accum.data() + (size_t(y) * s.accumWidth + b.x0) * 4;
      for (int i = 0; i < w * 4; ++i) a[i] = quantize(op(a[i], size_t(y - b.y0) * w * 4 + i));
    }
  });
}

// RETURN: draws value * A with only the operations 4.2.4 names; everything else that a
// DrawPixels fragment would meet is switched off for the call and restored afterwards.
void returnToColorBuffer(State& s, const Box& b, float value) {
  const int w = b.x1 - b.x0, h = b.y1 - b.y0;
  if (w <= 0 || h <= 0) return;
  Image4 image(w, h);
  for (int y = 0; y < h; ++y) {
    const float* a = s.accum.data() + (size_t(y + b.y0) * s.accumWidth + b.x0) * 4;
    float* o = image.row(y);
    for (int i = 0; i < w * 4; ++i) o[i] = a[i] * value;
  }
  const GlDispatch& gl = s.driver;
  gl.PushAttrib(GL_ENABLE_BIT | GL_CURRENT_BIT | GL_PIXEL_MODE_BIT);
  for (GLenum cap : {GL_DEPTH_TEST, GL_STENCIL_TEST, GL_ALPHA_TEST, GL_BLEND, GL_COLOR_LOGIC_OP,
                     GL_FOG, GL_TEXTURE_1D, GL_TEXTURE_2D, GL_TEXTURE_3D, GL_TEXTURE_CUBE_MAP})
    gl.Disable(cap);
  gl.PixelZoom(1.0f, 1.0f);
  gl.WindowPos2i(b.x0, b.y0);
  // Final conversion to the buffer's precision, through the driver with identity transfer.
  const GLenum type = s.context->spec().color == ColorFormat::kRgba8    ? GL_UNSIGNED_BYTE
                      : s.context->spec().color == ColorFormat::kRgba16 ? GL_UNSIGNED_SHORT
                                                                        : GL_FLOAT;
  std::vector<unsigned char> bytes;
  std::vector<uint16_t> shorts;
  const void* data = nullptr;
  for (float& v : image.px) v = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
  if (type == GL_UNSIGNED_BYTE) {
    bytes.resize(image.px.size());
    for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = uint8_t(image.px[i] * 255.0f + 0.5f);
    data = bytes.data();
  } else if (type == GL_UNSIGNED_SHORT) {
    shorts.resize(image.px.size());
    for (size_t i = 0; i < shorts.size(); ++i)
      shorts[i] = uint16_t(image.px[i] * 65535.0f + 0.5f);
    data = shorts.data();
  } else {
    data = image.px.data();
  }
  gl.PushClientAttrib(GL_CLIENT_PIXEL_STORE_BIT);
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl.PixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  gl.PixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
  gl.PixelStorei(GL_UNPACK_SKIP_ROWS, 0);
  gl.DrawPixels(w, h, GL_RGBA, type, data);
  gl.PopClientAttrib();
  gl.PopAttrib();
}

}  // namespace

void emClearAccum(GLfloat r, GLfloat g, GLfloat b, GLfloat a) {
  State& s = *currentState();
  const float v[4] = {r, g, b, a};
  for (int c = 0; c < 4; ++c) s.clearAccum[c] = std::clamp(v[c], -1.0f, 1.0f);  // 4.2.3
}

void emClear(GLbitfield mask) {
  State& s = *currentState();
  if ((mask & GL_ACCUM_BUFFER_BIT) != 0) {
    ensureBuffer(s);
    const Box b = region(s);
    const Rgba clear = s.clearAccum;
    forEach(s, b, [&](float, size_t i) { return clear[i & 3]; });
    mask &= ~GLbitfield(GL_ACCUM_BUFFER_BIT);
  }
  if (mask != 0) s.driver.Clear(mask);
}

void emAccum(GLenum op, GLfloat value) {
  State& s = *currentState();
  if (op != GL_ACCUM && op != GL_LOAD && op != GL_RETURN && op != GL_MULT && op != GL_ADD)
    return recordError(s, GL_INVALID_ENUM);
  ensureBuffer(s);
  const Box b = region(s);
  const int w = b.x1 - b.x0, h = b.y1 - b.y0;
  if (w <= 0 || h <= 0) return;
  switch (op) {
    case GL_ACCUM:
    case GL_LOAD: {
      const Image4 color = readFramebuffer(s, b.x0, b.y0, w, h);
      if (op == GL_ACCUM) {
        forEach(s, b, [&](float a, size_t i) { return a + value * color.px[i]; });
      } else {
        forEach(s, b, [&](float, size_t i) { return value * color.px[i]; });
      }
      return;
    }
    case GL_MULT: forEach(s, b, [&](float a, size_t) { return a * value; }); return;
    case GL_ADD: forEach(s, b, [&](float a, size_t) { return a + value; }); return;
    case GL_RETURN: returnToColorBuffer(s, b, value); return;
    default: return;
  }
}

}  // namespace sl::imaging::detail
