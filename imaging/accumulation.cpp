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
// component as 16-bit signed fixed point k / 32767 in [-1, 1] (the precision of the visuals
// the project asks for, core/gl/context.cpp kAccumBits), so results quantise as a real one's.
// Every operation is a table lookup per component: an 8-bit colour has 256 values and a
// 16-bit accumulator 65536, so the arithmetic is done once per value, in double precision.
#include <cmath>
#include <cstring>

#include "imaging/internal.h"

namespace sl::imaging::detail {
namespace {

constexpr double kAccumSteps = 32767.0;  // 16-bit signed fixed point: v = k / 32767
constexpr int32_t kAccumMin = -32767, kAccumMax = 32767;
constexpr size_t kVectorSpeedup = 8;  // the permute path's work per component, against scalar

// "Accumulation buffer values are taken to be signed values in [-1, 1]": values pushed
// outside are undefined by the specification; the emulation saturates them.
int16_t toFixed(double v) {
  if (!(v == v)) return 0;
  const double k = std::nearbyint(v * kAccumSteps);
  return int16_t(std::clamp(k, double(kAccumMin), double(kAccumMax)));
}

struct Box {
  int x0, y0, x1, y1;  // [x0, x1) x [y0, y1) within the buffer
};

void ensureBuffer(State& s) {
  const int w = s.context->spec().width, h = s.context->spec().height;
  if (s.accumWidth == w && s.accumHeight == h) return;
  s.accumWidth = w;
  s.accumHeight = h;
  s.accum.assign(size_t(w) * h * 4, 0);
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

// Applies op(accumulator value, index of the group component in the box) to the box.
template <class Op>
void forEach(State& s, const Box& b, const Op& op) {
  const int w = b.x1 - b.x0;
  parallelRows(b.y1 - b.y0, size_t(w) * 4, [&](int r0, int r1) {
    for (int y = b.y0 + r0; y < b.y0 + r1; ++y) {
      int16_t* a = s.accum.data() + (size_t(y) * s.accumWidth + b.x0) * 4;
      const size_t base = size_t(y - b.y0) * w * 4;
      for (int i = 0; i < w * 4; ++i) a[i] = op(a[i], base + i);
    }
  });
}

// ACCUM / LOAD: A <- keep * A + value * C. For 8-bit colour, value * C is tabled per byte.
void accumulateColor(State& s, const Box& b, float value, bool keep) {
  const int w = b.x1 - b.x0, h = b.y1 - b.y0;
  if (framebufferType(s) == GL_UNSIGNED_BYTE) {
    std::vector<uint8_t>& bytes = s.scratchIn;  // reused across calls
    bytes.resize(size_t(w) * h * 4);            // every byte is overwritten by the read
    {
      ClientTransfers tight(s);
      s.driver.ReadPixels(b.x0, b.y0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
    }
    // value * C in accumulator steps, rounded once per byte value; the accumulator is an
    // integer, so A + round(value * C) is the rounded sum.
    int32_t scaled[256];
    for (int v = 0; v < 256; ++v)
      scaled[v] = int32_t(std::lround(double(value) * (v / 255.0) * kAccumSteps));
    // Where every value * C fits the accumulator (|value| <= 1), whole rows go through byte
    // permutes of the table (byte_maps.cpp); the rest of each row, or every row, through it
    // one component at a time.
    int16_t words[256];
    bool fits = true;
    for (int v = 0; v < 256; ++v) {
      fits = fits && scaled[v] >= kAccumMin && scaled[v] <= kAccumMax;
      words[v] = int16_t(std::clamp(scaled[v], kAccumMin, kAccumMax));
    }
    const size_t n = size_t(w) * 4;
    parallelRows(h, fits ? n / kVectorSpeedup : n, [&](int r0, int r1) {
      for (int y = r0; y < r1; ++y) {
        const uint8_t* const color = bytes.data() + size_t(y) * n;
        int16_t* const a = s.accum.data() + (size_t(y + b.y0) * s.accumWidth + b.x0) * 4;
        const size_t done = fits ? accumulateBytes(words, keep, color, a, n) : 0;
        for (size_t i = done; i < n; ++i) {
          const int32_t k = (keep ? int32_t(a[i]) : 0) + scaled[color[i]];
          a[i] = int16_t(std::clamp(k, kAccumMin, kAccumMax));
        }
      }
    });
    return;
  }
  const Image4 color = readFramebuffer(s, b.x0, b.y0, w, h);
  forEach(s, b, [&](int16_t a, size_t i) {
    return toFixed((keep ? a / kAccumSteps : 0.0) + double(value) * color.px[i]);
  });
}

// RETURN: draws value * A with only the operations 4.2.4 names; everything else that a
// DrawPixels fragment would meet is switched off for the call and restored afterwards.
void returnToColorBuffer(State& s, const Box& b, float value) {
  const int w = b.x1 - b.x0, h = b.y1 - b.y0;
  if (w <= 0 || h <= 0) return;
  const GLenum type = framebufferType(s);
  std::vector<uint8_t>& bytes = s.scratchOut;  // reused across calls
  std::vector<uint16_t> shorts;
  std::vector<float> floats;
  const void* data = nullptr;
  auto clamp01 = [](double v) { return v > 0.0 ? (v < 1.0 ? v : 1.0) : 0.0; };
  auto rows = [&](auto&& write) {
    parallelRows(h, size_t(w) * 4, [&](int r0, int r1) {
      for (int y = r0; y < r1; ++y) {
        const int16_t* a = s.accum.data() + (size_t(y + b.y0) * s.accumWidth + b.x0) * 4;
        for (int i = 0; i < w * 4; ++i) write(size_t(y) * w * 4 + i, a[i]);
      }
    });
  };
  if (type == GL_UNSIGNED_BYTE) {
    // One table over all 65535 accumulator values: the final conversion of value * A.
    std::vector<uint8_t>& lut = s.returnTable;
    // Bitwise comparison: -0 and 0, or two NaNs, are not assumed to build the same table.
    if (!s.returnTableValid || std::memcmp(&s.returnTableValue, &value, sizeof value) != 0) {
      lut.assign(65536, 0);
      const double step = double(value) / kAccumSteps;  // value * k / 32767, one multiply each
      for (int k = kAccumMin; k <= kAccumMax; ++k)
        lut[size_t(k + 32768)] = uint8_t(clamp01(double(k) * step) * 255.0 + 0.5);
      s.returnTableValue = value;
      s.returnTableValid = true;
      // The float form, 16 components a vector: used only where it gives every one of the
      // table's 65535 entries (it does for most values, 1 included; accumulation_test.cpp).
      s.returnScale = float(double(value) * 255.0 / kAccumSteps);
      std::vector<int16_t> every(size_t(kAccumMax - kAccumMin + 1));
      for (size_t i = 0; i < every.size(); ++i) every[i] = int16_t(kAccumMin + int(i));
      std::vector<uint8_t> converted(every.size());
      const size_t done =
          returnAccumBytes(s.returnScale, every.data(), converted.data(), every.size());
      bool exact = done > 0;
      for (size_t i = 0; i < done && exact; ++i)
        exact = converted[i] == lut[size_t(every[i] + 32768)];
      s.returnVectorExact = exact;
    }
    // Where a blit may write them (write_back.cpp), the bytes go straight into the flipped
    // upload buffer (row y at row h-1-y); else into a buffer for glDrawPixels below.
    const bool blit = blitEqualsReturn(s);
    if (!blit) bytes.resize(size_t(w) * h * 4);
    // Raw pointers: a byte store through a vector's operator[] may alias the vector itself,
    // which would reload its data pointer on every element.
    uint8_t* const dst = blit ? returnRows(s, w, h) : bytes.data();
    const uint8_t* const table = lut.data();
    const size_t n = size_t(w) * 4;
    const bool vector = s.returnVectorExact;
    const float scale = s.returnScale;
    parallelRows(h, vector ? n / kVectorSpeedup : n, [&](int r0, int r1) {
      for (int y = r0; y < r1; ++y) {
        const int16_t* a = s.accum.data() + (size_t(y + b.y0) * s.accumWidth + b.x0) * 4;
        uint8_t* const o = dst + size_t(blit ? h - 1 - y : y) * n;
        const size_t done = vector ? returnAccumBytes(scale, a, o, n) : 0;
        for (size_t i = done; i < n; ++i) o[i] = table[size_t(a[i] + 32768)];
      }
    });
    if (blit) return blitReturnRows(s, b.x0, b.y0, w, h);
    s.writeBack.lastWasBlit = false;
    data = bytes.data();
  } else if (type == GL_UNSIGNED_SHORT) {
    shorts.resize(size_t(w) * h * 4);
    rows([&](size_t i, int16_t a) {
      shorts[i] = uint16_t(clamp01(value * (a / kAccumSteps)) * 65535.0 + 0.5);
    });
    data = shorts.data();
  } else {
    floats.resize(size_t(w) * h * 4);
    rows([&](size_t i, int16_t a) { floats[i] = float(clamp01(value * (a / kAccumSteps))); });
    data = floats.data();
  }
  const GlDispatch& gl = s.driver;
  gl.PushAttrib(GL_ENABLE_BIT | GL_CURRENT_BIT | GL_PIXEL_MODE_BIT);
  for (GLenum cap : {GL_DEPTH_TEST, GL_STENCIL_TEST, GL_ALPHA_TEST, GL_BLEND, GL_COLOR_LOGIC_OP,
                     GL_FOG, GL_TEXTURE_1D, GL_TEXTURE_2D, GL_TEXTURE_3D, GL_TEXTURE_CUBE_MAP})
    gl.Disable(cap);
  gl.PixelZoom(1.0f, 1.0f);
  gl.WindowPos2i(b.x0, b.y0);
  {
    ClientTransfers tight(s);
    gl.DrawPixels(w, h, GL_RGBA, type, data);
  }
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
    int16_t clear[4];
    for (int c = 0; c < 4; ++c) clear[c] = toFixed(s.clearAccum[c]);
    forEach(s, b, [&](int16_t, size_t i) { return clear[i & 3]; });
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
  if (b.x1 <= b.x0 || b.y1 <= b.y0) return;
  switch (op) {
    case GL_ACCUM: accumulateColor(s, b, value, true); return;
    case GL_LOAD: accumulateColor(s, b, value, false); return;
    case GL_MULT: {
      std::vector<int16_t> lut(65536);
      for (int k = kAccumMin; k <= kAccumMax; ++k)
        lut[size_t(k + 32768)] = toFixed(value * (k / kAccumSteps));
      forEach(s, b, [&](int16_t a, size_t) { return lut[size_t(a + 32768)]; });
      return;
    }
    case GL_ADD: {
      const int32_t add = int32_t(std::lround(std::clamp(double(value), -2.0, 2.0) * kAccumSteps));
      forEach(s, b, [&](int16_t a, size_t) {
        return int16_t(std::clamp(int32_t(a) + add, kAccumMin, kAccumMax));
      });
      return;
    }
    case GL_RETURN: returnToColorBuffer(s, b, value); return;
    default: return;
  }
}

}  // namespace sl::imaging::detail
