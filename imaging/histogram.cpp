// imaging/histogram.cpp — histogram and minmax (glspec121 3.6.3 "Histogram Table
// Specification", "Histogram State and Proxy State", "Minmax Table Specification"; 3.6.5
// "Histogram", "Minmax"; 6.1.9 "Histogram Query", 6.1.10 "Minmax Query"; EXT_histogram
// "Errors").
#include <cmath>
#include <limits>

#include "imaging/internal.h"

namespace sl::imaging::detail {
namespace {

// Histogram and minmax accept the texture formats except 1-4 and INTENSITY* (3.6.3).
bool histogramFormat(GLenum internalformat) {
  const GLenum base = baseInternalFormat(internalformat);
  return base != 0 && base != GL_INTENSITY && internalformat > 4;
}

// Components kept by a histogram/minmax format: R holds luminance.
void keptComponents(GLenum base, bool keep[4]) {
  const FormatComponents f = componentsOf(base);
  keep[0] = f.r || f.l;
  keep[1] = f.g;
  keep[2] = f.b;
  keep[3] = f.a;
}

constexpr int kHistogramComponentBits = 32;  // counters are 32-bit unsigned integers

}  // namespace

// 3.6.5 "Histogram": index = round(clamp(c) * (width - 1)) per component; the components the
// format holds count into their entry (luminance counts R).
void accumulateHistogram(Histogram& h, const Image4& image) {
  if (h.width == 0) return;
  bool keep[4];
  keptComponents(h.format, keep);
  const float scale = float(h.width - 1);
  const float* p = image.px.data();
  const size_t groups = size_t(image.width) * image.height;
  for (size_t g = 0; g < groups; ++g, p += 4) {
    for (int c = 0; c < 4; ++c) {
      if (!keep[c]) continue;
      const float v = p[c] > 0.0f ? (p[c] < 1.0f ? p[c] : 1.0f) : 0.0f;
      ++h.counts[size_t(int(v * scale + 0.5f))][c];
    }
  }
}

// 3.6.5 "Minmax": each kept component replaces the minimum / maximum when smaller / larger.
void accumulateMinmax(Minmax& m, const Image4& image) {
  bool keep[4];
  keptComponents(m.format, keep);
  const float* p = image.px.data();
  const size_t groups = size_t(image.width) * image.height;
  for (size_t g = 0; g < groups; ++g, p += 4) {
    for (int c = 0; c < 4; ++c) {
      if (!keep[c]) continue;
      if (p[c] < m.min[c]) m.min[c] = p[c];
      if (p[c] > m.max[c]) m.max[c] = p[c];
    }
  }
}

// "a minimum table entry set to the maximum representable value and a maximum table entry
// set to the minimum representable value" (3.6.3; 6.1.10 for ResetMinmax and GetMinmax with
// reset TRUE): the largest finite floats of the table's IEEE single type. What the user reads
// back from a reset table: emGetMinmax.
void resetMinmax(Minmax& m) {
  m.min.fill(std::numeric_limits<float>::max());
  m.max.fill(-std::numeric_limits<float>::max());
}

void emHistogram(GLenum target, GLsizei width, GLenum internalformat, GLboolean sink) {
  State& s = *currentState();
  if (target != GL_HISTOGRAM && target != GL_PROXY_HISTOGRAM) {
    recordError(s, GL_INVALID_ENUM);
    return;
  }
  if (width < 0 || (width & (width - 1)) != 0) {
    recordError(s, GL_INVALID_VALUE);
    return;
  }
  if (!histogramFormat(internalformat)) {
    recordError(s, GL_INVALID_ENUM);
    return;
  }
  if (width > kMaxHistogramWidth) {
    if (target == GL_PROXY_HISTOGRAM) {
      s.transfer.proxyHistogram = ProxyTable{0, 0, 0};
    } else {
      recordError(s, GL_TABLE_TOO_LARGE);
    }
    return;
  }
  if (target == GL_PROXY_HISTOGRAM) {
    s.transfer.proxyHistogram =
        ProxyTable{baseInternalFormat(internalformat), internalformat, width};
    return;
  }
  Histogram& h = s.transfer.histogram;
  h.format = baseInternalFormat(internalformat);
  h.internalFormat = internalformat;
  h.width = width;
  h.sink = sink != GL_FALSE;
  h.counts.assign(size_t(width), {0, 0, 0, 0});
}

void emMinmax(GLenum target, GLenum internalformat, GLboolean sink) {
  State& s = *currentState();
  if (target != GL_MINMAX || !histogramFormat(internalformat)) {
    recordError(s, GL_INVALID_ENUM);
    return;
  }
  Minmax& m = s.transfer.minmax;
  m.format = baseInternalFormat(internalformat);
  m.internalFormat = internalformat;
  m.sink = sink != GL_FALSE;
  resetMinmax(m);
}

void emResetHistogram(GLenum target) {
  State& s = *currentState();
  if (target != GL_HISTOGRAM) return recordError(s, GL_INVALID_ENUM);
  for (auto& e : s.transfer.histogram.counts) e = {0, 0, 0, 0};
}

void emResetMinmax(GLenum target) {
  State& s = *currentState();
  if (target != GL_MINMAX) return recordError(s, GL_INVALID_ENUM);
  resetMinmax(s.transfer.minmax);
}

void emGetHistogram(GLenum target, GLboolean reset, GLenum format, GLenum type, void* values) {
  State& s = *currentState();
  if (const GLenum e = targetFormatError(target == GL_HISTOGRAM, format, type); e != GL_NO_ERROR)
    return recordError(s, e);
  Histogram& h = s.transfer.histogram;
  // Counters are returned as counts for every type (EXT_histogram: "the histogram table
  // contains counts"; a normalised conversion would saturate every count above 1); the
  // parity suite shows the reference returns them the same way.
  Image4 image(h.width, 1);
  for (int i = 0; i < h.width; ++i) {
    // Table 6.1: the format's components, the constants 0 (R, G, B) and 1 (A) for the rest.
    const Rgba stored{float(h.counts[i][0]), float(h.counts[i][1]), float(h.counts[i][2]),
                      float(h.counts[i][3])};
    const Rgba v = tableReturnValue(h.format, stored);
    for (int c = 0; c < 4; ++c) image.px[size_t(i) * 4 + c] = v[c];
  }
  if (h.width > 0) {
    // Counts go out unconverted: write them through the float path, then cast per type.
    Image4 asFloat = image;
    if (type == GL_FLOAT) {
      packImage(asFloat, values, format, type, packStore(s.driver), false);
    } else {
      // Pack as float into scratch, then narrow each element to the integer type.
      const PixelStore store = packStore(s.driver);
      PixelStore tight;
      tight.alignment = 1;
      std::vector<float> scratch(size_t(h.width) * 4);
      packImage(asFloat, scratch.data(), format, GL_FLOAT, tight, false);
      int n = 0;
      switch (format) {
        case GL_RGBA:
        case GL_BGRA: n = 4; break;
        case GL_RGB:
        case GL_BGR: n = 3; break;
        case GL_LUMINANCE_ALPHA: n = 2; break;
        default: n = 1; break;
      }
      const size_t size = (type == GL_UNSIGNED_BYTE || type == GL_BYTE)     ? 1
                          : (type == GL_UNSIGNED_SHORT || type == GL_SHORT) ? 2
                                                                            : 4;
      auto* out = static_cast<unsigned char*>(values) + size_t(store.skipPixels) * n * size;
      for (int e = 0; e < h.width * n; ++e) {
        const double v = scratch[size_t(e)];
        switch (type) {
          case GL_UNSIGNED_BYTE: out[e] = uint8_t(v); break;
          case GL_BYTE: reinterpret_cast<int8_t*>(out)[e] = int8_t(v); break;
          case GL_UNSIGNED_SHORT: reinterpret_cast<uint16_t*>(out)[e] = uint16_t(v); break;
          case GL_SHORT: reinterpret_cast<int16_t*>(out)[e] = int16_t(v); break;
          case GL_UNSIGNED_INT: reinterpret_cast<uint32_t*>(out)[e] = uint32_t(v); break;
          case GL_INT: reinterpret_cast<int32_t*>(out)[e] = int32_t(v); break;
          default: break;
        }
      }
    }
  }
  if (reset) emResetHistogram(GL_HISTOGRAM);
}

// 6.1.10 "Minmax Query": "A one-dimensional image of width 2 is returned to values. Pixel
// processing and component mapping are identical to those of GetTexImage." 6.1.4 "Texture
// Queries": the groups take their components from table 6.1 and "are then packed and placed in
// client memory. No pixel transfer operations are performed on this image, but pixel storage
// modes that are applicable to ReadPixels are applied."
// What the user reads (the choice of issue 14 item 6, docs/imaging.md "Minmax"):
//  - type FLOAT: the table's values as they are (table 4.7: c = f). 6.1.4 takes ReadPixels'
//    storage modes, not its "Final Conversion" clamp to [0,1] (4.3.2), and 3.6.5 gives the
//    table "at least the same representable range as a floating point number used to represent
//    colors (section 2.1.1)": an extreme outside [0,1] is what the float query is for.
//  - a reset table (Minmax, ResetMinmax, GetMinmax with reset TRUE) holds "the maximum
//    representable value" as each minimum and "the minimum representable value" as each
//    maximum (3.6.3, 6.1.10). The table is IEEE single, so until a group arrives a FLOAT query
//    reads min = FLT_MAX and max = -FLT_MAX for each component the table holds (table 6.1's
//    constants for the others): min > max says "no group since the reset". Not infinities:
//    2.1.1 requires finite magnitudes and leaves infinities passed to the GL unspecified; a
//    luminance pack (L = R + G + B, 4.3.2) saturates at +-FLT_MAX (pixel_memory.cpp packImage).
//  - other types: 4.3.2's clamp to [0,1], then table 4.7 (a normalised integer holds nothing
//    else): a reset table reads min = the type's largest value, max = 0.
//  - reset TRUE returns the values before the reset, and resets every value "whether returned
//    or not" (6.1.10; EXT_histogram reset only the returned ones).
// The reference (Mesa 7.8.2) departs here (tests/parity/departures_test.cpp, C): it clamps
// FLOAT results to [0,1] as well, so its reset table reads (1, 1, 1, 1) and (0, 0, 0, 0).
void emGetMinmax(GLenum target, GLboolean reset, GLenum format, GLenum type, void* values) {
  State& s = *currentState();
  if (const GLenum e = targetFormatError(target == GL_MINMAX, format, type); e != GL_NO_ERROR)
    return recordError(s, e);
  Minmax& m = s.transfer.minmax;
  // Table 6.1 maps the format's components; absent ones read 0 (R, G, B) or 1 (A).
  const Rgba lo = tableReturnValue(m.format, m.min), hi = tableReturnValue(m.format, m.max);
  Image4 image(2, 1);
  for (int c = 0; c < 4; ++c) {
    image.px[c] = lo[c];
    image.px[4 + c] = hi[c];
  }
  packImage(image, values, format, type, packStore(s.driver), type != GL_FLOAT);
  if (reset) resetMinmax(m);
}

namespace {
bool queryHistogram(State& s, GLenum target, GLenum pname, GLfloat* p) {
  if (target != GL_HISTOGRAM && target != GL_PROXY_HISTOGRAM) {
    recordError(s, GL_INVALID_ENUM);
    return false;
  }
  const bool proxy = target == GL_PROXY_HISTOGRAM;
  const Histogram& h = s.transfer.histogram;
  const GLenum base = proxy ? s.transfer.proxyHistogram.format : h.format;
  const GLenum internalFormat = proxy ? s.transfer.proxyHistogram.internalFormat : h.internalFormat;
  const int width = proxy ? s.transfer.proxyHistogram.width : h.width;
  const FormatComponents f = componentsOf(width > 0 ? base : 0);
  auto bits = [](bool b) { return b ? float(kHistogramComponentBits) : 0.0f; };
  switch (pname) {
    case GL_HISTOGRAM_FORMAT: p[0] = float(internalFormat); return true;
    case GL_HISTOGRAM_WIDTH: p[0] = float(width); return true;
    case GL_HISTOGRAM_RED_SIZE: p[0] = bits(f.r); return true;
    case GL_HISTOGRAM_GREEN_SIZE: p[0] = bits(f.g); return true;
    case GL_HISTOGRAM_BLUE_SIZE: p[0] = bits(f.b); return true;
    case GL_HISTOGRAM_ALPHA_SIZE: p[0] = bits(f.a); return true;
    case GL_HISTOGRAM_LUMINANCE_SIZE: p[0] = bits(f.l); return true;
    case GL_HISTOGRAM_SINK:
      if (proxy) break;  // "pname may be HISTOGRAM_SINK only for target HISTOGRAM"
      p[0] = h.sink ? 1.0f : 0.0f;
      return true;
    default: break;
  }
  recordError(s, GL_INVALID_ENUM);
  return false;
}
bool queryMinmax(State& s, GLenum target, GLenum pname, GLfloat* p) {
  if (target != GL_MINMAX) {
    recordError(s, GL_INVALID_ENUM);
    return false;
  }
  switch (pname) {
    case GL_MINMAX_FORMAT: p[0] = float(s.transfer.minmax.internalFormat); return true;
    case GL_MINMAX_SINK: p[0] = s.transfer.minmax.sink ? 1.0f : 0.0f; return true;
    default: recordError(s, GL_INVALID_ENUM); return false;
  }
}
}  // namespace

void emGetHistogramParameterfv(GLenum target, GLenum pname, GLfloat* p) {
  queryHistogram(*currentState(), target, pname, p);
}
void emGetHistogramParameteriv(GLenum target, GLenum pname, GLint* p) {
  GLfloat f = 0;
  if (queryHistogram(*currentState(), target, pname, &f)) p[0] = GLint(std::lround(f));
}
void emGetMinmaxParameterfv(GLenum target, GLenum pname, GLfloat* p) {
  queryMinmax(*currentState(), target, pname, p);
}
void emGetMinmaxParameteriv(GLenum target, GLenum pname, GLint* p) {
  GLfloat f = 0;
  if (queryMinmax(*currentState(), target, pname, &f)) p[0] = GLint(std::lround(f));
}

}  // namespace sl::imaging::detail
