// imaging/pixel_memory.cpp — pixel groups to and from client memory for the emulation.
//
// glspec121 3.6.4 "Unpacking" (row length, skip, alignment), "Conversion to floating-point"
// (table 2.6), "Conversion to RGB", "Final Expansion to RGBA"; 4.3.2 "Conversion to L",
// "Final Conversion" (clamp, table 4.7) and "Placement in Client Memory"; table 6.1 for the
// values returned by the table, filter and histogram queries.
#include <cmath>
#include <cstring>
#include <limits>

#include "imaging/internal.h"

namespace sl::imaging::detail {

int componentCount(GLenum format) {
  switch (format) {
    case GL_RED:
    case GL_GREEN:
    case GL_BLUE:
    case GL_ALPHA:
    case GL_LUMINANCE: return 1;
    case GL_LUMINANCE_ALPHA: return 2;
    case GL_RGB:
    case GL_BGR: return 3;
    case GL_RGBA:
    case GL_BGRA: return 4;
    default: return 0;
  }
}

namespace {

int typeSize(GLenum type) {
  switch (type) {
    case GL_UNSIGNED_BYTE:
    case GL_BYTE: return 1;
    case GL_UNSIGNED_SHORT:
    case GL_SHORT: return 2;
    case GL_UNSIGNED_INT:
    case GL_INT:
    case GL_FLOAT: return 4;
    default: return 0;
  }
}

// Byte distance between rows (3.6.4 "Unpacking", equation for k).
size_t rowStride(int width, GLenum format, GLenum type, const PixelStore& s) {
  const size_t groups = size_t(s.rowLength > 0 ? s.rowLength : width);
  const size_t size = size_t(typeSize(type));
  const size_t bytes = groups * size_t(componentCount(format)) * size;
  const size_t a = size_t(s.alignment);
  if (size >= a) return bytes;
  return (bytes + a - 1) / a * a;
}

// Table 2.6: an element of type `type` to float.
float toFloat(const unsigned char* p, GLenum type) {
  switch (type) {
    case GL_UNSIGNED_BYTE: return float(*p) / 255.0f;
    case GL_BYTE: {
      int8_t v;
      std::memcpy(&v, p, 1);
      return (2.0f * v + 1.0f) / 255.0f;
    }
    case GL_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return float(v) / 65535.0f;
    }
    case GL_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return (2.0f * v + 1.0f) / 65535.0f;
    }
    case GL_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return float(double(v) / 4294967295.0);
    }
    case GL_INT: {
      int32_t v;
      std::memcpy(&v, p, 4);
      return float((2.0 * v + 1.0) / 4294967295.0);
    }
    case GL_FLOAT: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    default: return 0.0f;
  }
}

// Table 4.7: a float to an element of `type`, rounding to nearest.
void fromFloat(float f, unsigned char* p, GLenum type) {
  switch (type) {
    case GL_UNSIGNED_BYTE: {
      *p = uint8_t(std::floor(f * 255.0f + 0.5f));
      return;
    }
    case GL_BYTE: {
      int8_t v = int8_t(std::floor((255.0f * f - 1.0f) * 0.5f + 0.5f));
      std::memcpy(p, &v, 1);
      return;
    }
    case GL_UNSIGNED_SHORT: {
      uint16_t v = uint16_t(std::floor(f * 65535.0f + 0.5f));
      std::memcpy(p, &v, 2);
      return;
    }
    case GL_SHORT: {
      int16_t v = int16_t(std::floor((65535.0f * f - 1.0f) * 0.5f + 0.5f));
      std::memcpy(p, &v, 2);
      return;
    }
    case GL_UNSIGNED_INT: {
      uint32_t v = uint32_t(std::floor(double(f) * 4294967295.0 + 0.5));
      std::memcpy(p, &v, 4);
      return;
    }
    case GL_INT: {
      int32_t v = int32_t(std::floor((4294967295.0 * f - 1.0) * 0.5 + 0.5));
      std::memcpy(p, &v, 4);
      return;
    }
    case GL_FLOAT: {
      std::memcpy(p, &f, 4);
      return;
    }
    default: return;
  }
}

// Where each element of a group of `format` goes in RGBA (-1: luminance, fills R, G, B).
void elementSlots(GLenum format, int slots[4]) {
  switch (format) {
    case GL_RED: slots[0] = 0; return;
    case GL_GREEN: slots[0] = 1; return;
    case GL_BLUE: slots[0] = 2; return;
    case GL_ALPHA: slots[0] = 3; return;
    case GL_LUMINANCE: slots[0] = -1; return;
    case GL_LUMINANCE_ALPHA:
      slots[0] = -1;
      slots[1] = 3;
      return;
    case GL_RGB:
      slots[0] = 0;
      slots[1] = 1;
      slots[2] = 2;
      return;
    case GL_BGR:
      slots[0] = 2;
      slots[1] = 1;
      slots[2] = 0;
      return;
    case GL_RGBA:
      slots[0] = 0;
      slots[1] = 1;
      slots[2] = 2;
      slots[3] = 3;
      return;
    case GL_BGRA:
      slots[0] = 2;
      slots[1] = 1;
      slots[2] = 0;
      slots[3] = 3;
      return;
    default: return;
  }
}

}  // namespace

bool isColorFormat(GLenum format) { return componentCount(format) != 0; }

namespace {
// The packed types of table 3.5 (OpenGL 1.2) with three components (RGB only) and four
// (RGBA, BGRA), 3.6.4 "Packed Pixels", table 3.8; 0 for any other type.
int packedComponents(GLenum type) {
  switch (type) {
    case GL_UNSIGNED_BYTE_3_3_2:
    case GL_UNSIGNED_BYTE_2_3_3_REV:
    case GL_UNSIGNED_SHORT_5_6_5:
    case GL_UNSIGNED_SHORT_5_6_5_REV: return 3;
    case GL_UNSIGNED_SHORT_4_4_4_4:
    case GL_UNSIGNED_SHORT_4_4_4_4_REV:
    case GL_UNSIGNED_SHORT_5_5_5_1:
    case GL_UNSIGNED_SHORT_1_5_5_5_REV:
    case GL_UNSIGNED_INT_8_8_8_8:
    case GL_UNSIGNED_INT_8_8_8_8_REV:
    case GL_UNSIGNED_INT_10_10_10_2:
    case GL_UNSIGNED_INT_2_10_10_10_REV: return 4;
    default: return 0;
  }
}
}  // namespace

GLenum checkColorFormat(GLenum format, GLenum type) {
  if (componentCount(format) == 0) return GL_INVALID_ENUM;
  if (const int packed = packedComponents(type); packed != 0) {
    const bool matches = packed == 3 ? format == GL_RGB : (format == GL_RGBA || format == GL_BGRA);
    if (!matches) return GL_INVALID_OPERATION;  // 3.6.4 "Packed Pixels"
    // DEVIATION (glspec121 3.6.4, table 3.8): the emulation does not unpack packed pixel
    // types; a packed type with a format it fits is refused with INVALID_ENUM.
    return GL_INVALID_ENUM;
  }
  if (typeSize(type) == 0) return GL_INVALID_ENUM;
  return GL_NO_ERROR;
}

PixelStore unpackStore(const GlDispatch& gl) {
  PixelStore s;
  gl.GetIntegerv(GL_UNPACK_ALIGNMENT, &s.alignment);
  gl.GetIntegerv(GL_UNPACK_ROW_LENGTH, &s.rowLength);
  gl.GetIntegerv(GL_UNPACK_SKIP_PIXELS, &s.skipPixels);
  gl.GetIntegerv(GL_UNPACK_SKIP_ROWS, &s.skipRows);
  return s;
}

PixelStore packStore(const GlDispatch& gl) {
  PixelStore s;
  gl.GetIntegerv(GL_PACK_ALIGNMENT, &s.alignment);
  gl.GetIntegerv(GL_PACK_ROW_LENGTH, &s.rowLength);
  gl.GetIntegerv(GL_PACK_SKIP_PIXELS, &s.skipPixels);
  gl.GetIntegerv(GL_PACK_SKIP_ROWS, &s.skipRows);
  return s;
}

Image4 unpackImage(const void* data, int w, int h, GLenum format, GLenum type,
                   const PixelStore& store) {
  Image4 out(w, h);
  if (data == nullptr || w <= 0 || h <= 0) return out;
  const int n = componentCount(format);
  const size_t size = size_t(typeSize(type));
  const size_t stride = rowStride(w, format, type, store);
  const auto* base = static_cast<const unsigned char*>(data) + size_t(store.skipRows) * stride +
                     size_t(store.skipPixels) * size_t(n) * size;
  int slots[4] = {0, 0, 0, 0};
  elementSlots(format, slots);
  // Fast path: RGBA unsigned bytes through a 256-entry table.
  if (format == GL_RGBA && type == GL_UNSIGNED_BYTE) {
    float lut[256];
    for (int i = 0; i < 256; ++i) lut[i] = float(i) / 255.0f;
    parallelRows(h, size_t(w) * 4, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y) {
        const unsigned char* src = base + size_t(y) * stride;
        float* dst = out.row(y);
        for (int i = 0; i < w * 4; ++i) dst[i] = lut[src[i]];
      }
    });
    return out;
  }
  for (int y = 0; y < h; ++y) {
    const unsigned char* src = base + size_t(y) * stride;
    float* dst = out.row(y);
    for (int x = 0; x < w; ++x, dst += 4) {
      // Final expansion to RGBA: missing R, G, B are 0, a missing A is 1.
      dst[0] = dst[1] = dst[2] = 0.0f;
      dst[3] = 1.0f;
      for (int e = 0; e < n; ++e, src += size) {
        const float v = toFloat(src, type);
        if (slots[e] < 0) {
          dst[0] = dst[1] = dst[2] = v;  // conversion to RGB
        } else {
          dst[slots[e]] = v;
        }
      }
    }
  }
  return out;
}

void packImage(const Image4& image, void* data, GLenum format, GLenum type, const PixelStore& store,
               bool clamp) {
  const int w = image.width, h = image.height;
  if (data == nullptr || w <= 0 || h <= 0) return;
  const int n = componentCount(format);
  const size_t size = size_t(typeSize(type));
  const size_t stride = rowStride(w, format, type, store);
  auto* base = static_cast<unsigned char*>(data) + size_t(store.skipRows) * stride +
               size_t(store.skipPixels) * size_t(n) * size;
  auto c01 = [clamp](float v) {
    // Unclamped (GL_FLOAT queries of float state: minmax, filters), a value beyond the float
    // range saturates at +-FLT_MAX instead of reaching the user as an infinity: L = R + G + B
    // of a reset minmax table is 3 x FLT_MAX (histogram.cpp, emGetMinmax).
    constexpr float kMax = std::numeric_limits<float>::max();
    if (!clamp) return v > kMax ? kMax : (v < -kMax ? -kMax : v);
    if (!(v > 0.0f)) return 0.0f;  // also maps NaN to 0: never NaN in a buffer
    return v < 1.0f ? v : 1.0f;
  };
  if (format == GL_RGBA && type == GL_UNSIGNED_BYTE) {
    parallelRows(h, size_t(w) * 4, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y) {
        const float* src = image.row(y);
        unsigned char* dst = base + size_t(y) * stride;
        for (int i = 0; i < w * 4; ++i) dst[i] = uint8_t(c01(src[i]) * 255.0f + 0.5f);
      }
    });
    return;
  }
  int slots[4] = {0, 0, 0, 0};
  elementSlots(format, slots);
  for (int y = 0; y < h; ++y) {
    const float* src = image.row(y);
    unsigned char* dst = base + size_t(y) * stride;
    for (int x = 0; x < w; ++x, src += 4) {
      for (int e = 0; e < n; ++e, dst += size) {
        // 4.3.2 "Conversion to L": L = R + G + B, then the final clamp.
        const float v = slots[e] < 0 ? src[0] + src[1] + src[2] : src[slots[e]];
        fromFloat(c01(v), dst, type);
      }
    }
  }
}

Rgba tableReturnValue(GLenum baseFormat, const Rgba& v) {
  switch (baseFormat) {
    case GL_ALPHA: return {0, 0, 0, v[3]};
    case GL_LUMINANCE: return {v[0], 0, 0, 1};
    case GL_LUMINANCE_ALPHA: return {v[0], 0, 0, v[3]};
    case GL_INTENSITY: return {v[0], 0, 0, 1};
    case GL_RGB: return {v[0], v[1], v[2], 1};
    default: return v;
  }
}

FormatComponents componentsOf(GLenum base) {
  FormatComponents c;
  switch (base) {
    case GL_ALPHA: c.a = true; break;
    case GL_LUMINANCE: c.l = true; break;
    case GL_LUMINANCE_ALPHA: c.l = c.a = true; break;
    case GL_INTENSITY: c.i = true; break;
    case GL_RGB: c.r = c.g = c.b = true; break;
    case GL_RGBA: c.r = c.g = c.b = c.a = true; break;
    default: break;
  }
  return c;
}

GLenum baseInternalFormat(GLenum f) {
  switch (f) {
    case GL_ALPHA:
    case GL_ALPHA4:
    case GL_ALPHA8:
    case GL_ALPHA12:
    case GL_ALPHA16: return GL_ALPHA;
    case 1:
    case GL_LUMINANCE:
    case GL_LUMINANCE4:
    case GL_LUMINANCE8:
    case GL_LUMINANCE12:
    case GL_LUMINANCE16: return GL_LUMINANCE;
    case 2:
    case GL_LUMINANCE_ALPHA:
    case GL_LUMINANCE4_ALPHA4:
    case GL_LUMINANCE6_ALPHA2:
    case GL_LUMINANCE8_ALPHA8:
    case GL_LUMINANCE12_ALPHA4:
    case GL_LUMINANCE12_ALPHA12:
    case GL_LUMINANCE16_ALPHA16: return GL_LUMINANCE_ALPHA;
    case GL_INTENSITY:
    case GL_INTENSITY4:
    case GL_INTENSITY8:
    case GL_INTENSITY12:
    case GL_INTENSITY16: return GL_INTENSITY;
    case 3:
    case GL_RGB:
    case GL_R3_G3_B2:
    case GL_RGB4:
    case GL_RGB5:
    case GL_RGB8:
    case GL_RGB10:
    case GL_RGB12:
    case GL_RGB16: return GL_RGB;
    case 4:
    case GL_RGBA:
    case GL_RGBA2:
    case GL_RGBA4:
    case GL_RGB5_A1:
    case GL_RGBA8:
    case GL_RGB10_A2:
    case GL_RGBA12:
    case GL_RGBA16: return GL_RGBA;
    default: return 0;
  }
}

}  // namespace sl::imaging::detail
