// Helpers shared by the imaging tests and the parity suite: contexts with the emulation
// installed, drawing and reading RGBA images at the window origin, and a small independent
// model of the specification's formulas (written from glspec121 3.6.5, not from imaging/).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/gl/context.h"
#include "imaging/imaging.h"

namespace sl::imaging::testing {
using namespace sl::gl;

// A Debian OSMesa compatibility context with the emulation installed.
inline std::unique_ptr<GlContext> emulatedContext(int w, int h,
                                                  ColorFormat color = ColorFormat::kRgba8,
                                                  bool accumulation = true) {
  ContextSpec spec;
  spec.width = w;
  spec.height = h;
  spec.color = color;
  spec.accumulation = accumulation;
  auto ctx = GlContext::create(spec);
  EXPECT_EQ(install(*ctx), Mode::kEmulated);
  return ctx;
}

// All pending GL errors, oldest first.
inline std::vector<GLenum> drainErrors() {
  std::vector<GLenum> errors;
  for (int i = 0; i < 8; ++i) {
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR) break;
    errors.push_back(e);
  }
  return errors;
}

// Writes an RGBA8 image with its lower-left corner at window (0,0), bypassing the imaging
// stages (they must be identity or disabled when this is called).
inline void putImage(int w, int h, const std::vector<uint8_t>& rgba, int x = 0, int y = 0) {
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glWindowPos2i(x, y);
  glDrawPixels(w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
}

inline std::vector<uint8_t> readRgba8(int x, int y, int w, int h) {
  std::vector<uint8_t> out(size_t(w) * h * 4, 0xCD);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(x, y, w, h, GL_RGBA, GL_UNSIGNED_BYTE, out.data());
  return out;
}

inline std::vector<float> readRgbaF(int x, int y, int w, int h) {
  std::vector<float> out(size_t(w) * h * 4, -7.0f);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(x, y, w, h, GL_RGBA, GL_FLOAT, out.data());
  return out;
}

// A deterministic test image: every channel sweeps values, including 0 and 255.
inline std::vector<uint8_t> patternImage(int w, int h, unsigned seed = 1) {
  std::vector<uint8_t> px(size_t(w) * h * 4);
  uint32_t s = seed * 2654435761u + 12345u;
  for (size_t i = 0; i < px.size(); ++i) {
    s = s * 1664525u + 1013904223u;
    px[i] = uint8_t(s >> 24);
  }
  if (!px.empty()) {
    px[0] = 0;
    px[px.size() - 1] = 255;
  }
  return px;
}

// ---- the specification's formulas, as a reader would apply them by hand ----
inline float clamp01(float v) { return v < 0.0f ? 0.0f : (v > 1.0f ? 1.0f : v); }
// 3.6.5 Color Table Lookup: index = round(clamp(c) * (width - 1)).
inline int tableIndex(float c, int width) {
  return int(std::floor(clamp01(c) * float(width - 1) + 0.5f));
}
// 4.3.2 final conversion of a component to an unsigned byte.
inline uint8_t toByte(float v) { return uint8_t(std::floor(clamp01(v) * 255.0f + 0.5f)); }

}  // namespace sl::imaging::testing
