// imaging/color_table.cpp — color tables (glspec121 3.6.3 "Color Table Specification",
// "Alternate Color Table Specification Commands", "Color Table State and Proxy State"; 3.6.5
// "Color Table Lookup", table 3.13; 6.1.7 "Color Table Query"; SGI_color_table "Errors").
#include <cmath>

#include "imaging/internal.h"

namespace sl::imaging::detail {
namespace {

// Index of a regular table target in TransferState::tables, or -1.
int regularIndex(GLenum target) {
  switch (target) {
    case GL_COLOR_TABLE: return 0;
    case GL_POST_CONVOLUTION_COLOR_TABLE: return 1;
    case GL_POST_COLOR_MATRIX_COLOR_TABLE: return 2;
    default: return -1;
  }
}
int proxyIndex(GLenum target) {
  switch (target) {
    case GL_PROXY_COLOR_TABLE: return 0;
    case GL_PROXY_POST_CONVOLUTION_COLOR_TABLE: return 1;
    case GL_PROXY_POST_COLOR_MATRIX_COLOR_TABLE: return 2;
    default: return -1;
  }
}

bool isPowerOfTwoOrZero(int w) { return w >= 0 && (w & (w - 1)) == 0; }

// 3.6.3: scale, bias, clamp to [0,1], then select the components of the base internal format
// (table 3.15: L and I from R, A from A).
Rgba tableEntry(const Rgba& rgba, const ColorTable& t) {
  Rgba v;
  for (int c = 0; c < 4; ++c) {
    const float x = rgba[c] * t.scale[c] + t.bias[c];
    v[c] = x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f;  // NaN -> 0
  }
  const FormatComponents f = componentsOf(t.format);
  if (f.l || f.i) v[1] = v[2] = v[0];
  if (!f.a && !f.i) v[3] = 0.0f;
  if (f.a && !f.r && !f.l) v[0] = v[1] = v[2] = 0.0f;
  return v;
}

// Argument checks shared by ColorTable and CopyColorTable, in SGI_color_table's order.
// Returns false (having recorded the error or updated the proxy) when nothing is stored.
bool checkTableDefinition(State& s, GLenum target, GLenum internalformat, GLsizei width,
                          int& regular, int& proxy) {
  regular = regularIndex(target);
  proxy = proxyIndex(target);
  if (regular < 0 && proxy < 0) {
    recordError(s, GL_INVALID_ENUM);
    return false;
  }
  if (baseInternalFormat(internalformat) == 0) {
    recordError(s, GL_INVALID_ENUM);
    return false;
  }
  if (!isPowerOfTwoOrZero(width)) {
    recordError(s, GL_INVALID_VALUE);
    return false;
  }
  if (width > kMaxColorTableWidth) {
    if (proxy >= 0) {
      s.transfer.proxies[proxy] = ProxyTable{0, 0, 0};  // 3.6.3: too large -> zero, no error
    } else {
      recordError(s, GL_TABLE_TOO_LARGE);
    }
    return false;
  }
  if (proxy >= 0) {
    auto& p = s.transfer.proxies[proxy];
    p.format = baseInternalFormat(internalformat);
    p.internalFormat = internalformat;
    p.width = width;
    return false;
  }
  return true;
}

void defineTable(State& s, int index, GLenum internalformat, const Image4& image) {
  ColorTable& t = s.transfer.tables[index];
  t.format = baseInternalFormat(internalformat);
  t.internalFormat = internalformat;
  t.width = image.width;
  t.entries.resize(size_t(image.width));
  for (int i = 0; i < image.width; ++i) {
    const float* p = image.px.data() + size_t(i) * 4;
    t.entries[i] = tableEntry({p[0], p[1], p[2], p[3]}, t);
  }
}

void setSubTable(State& s, int index, GLsizei start, const Image4& image) {
  ColorTable& t = s.transfer.tables[index];
  for (int n = 0; n < image.width; ++n) {
    const float* p = image.px.data() + size_t(n) * 4;
    t.entries[size_t(start + n)] = tableEntry({p[0], p[1], p[2], p[3]}, t);
  }
}

}  // namespace

// ---------------------------------------------------------------- lookup (3.6.5)
// "The components to be replaced are converted to indices by clamping to [0,1], multiplying
// by an integer one less than the width of the table, and rounding to the nearest integer."
// Each replaced component uses its own index (table 3.13: L_t for R is looked up with R's
// index, for G with G's, ...). Precomputed per component: which components are replaced and
// the value each index gives.
void applyColorTable(const ColorTable& t, Image4& image) {
  if (t.width == 0) return;  // "If a zero-width table is enabled, no lookup is performed."
  const FormatComponents f = componentsOf(t.format);
  bool replace[4] = {f.r || f.l || f.i, f.g || f.l || f.i, f.b || f.l || f.i, f.a || f.i};
  // lut[c][k]: the value that replaces component c for index k.
  std::vector<float> lut(size_t(t.width) * 4);
  for (int k = 0; k < t.width; ++k) {
    const Rgba& e = t.entries[k];
    const float rgb[3] = {f.l || f.i ? e[0] : e[0], f.l || f.i ? e[0] : e[1],
                          f.l || f.i ? e[0] : e[2]};
    for (int c = 0; c < 3; ++c) lut[size_t(k) * 4 + c] = rgb[c];
    lut[size_t(k) * 4 + 3] = f.i ? e[0] : e[3];
  }
  const float scale = float(t.width - 1);
  const bool all = replace[0] && replace[1] && replace[2] && replace[3];
  const int w = image.width;
  parallelRows(image.height, size_t(w) * 4, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      float* p = image.row(y);
      if (all) {
        for (int i = 0; i < w * 4; ++i) {
          const float v = p[i];
          const float c = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
          p[i] = lut[size_t(int(c * scale + 0.5f)) * 4 + (i & 3)];
        }
      } else {
        for (int i = 0; i < w * 4; ++i) {
          if (!replace[i & 3]) continue;
          const float v = p[i];
          const float c = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
          p[i] = lut[size_t(int(c * scale + 0.5f)) * 4 + (i & 3)];
        }
      }
    }
  });
}

// ---------------------------------------------------------------- entry points
void emColorTable(GLenum target, GLenum internalformat, GLsizei width, GLenum format, GLenum type,
                  const void* data) {
  State& s = *currentState();
  int regular = -1, proxy = -1;
  // Format and type are checked with the other enums, before the width (SGI_color_table).
  if ((regularIndex(target) >= 0 || proxyIndex(target) >= 0) &&
      baseInternalFormat(internalformat) != 0) {
    if (const GLenum e = checkColorFormat(format, type); e != GL_NO_ERROR) {
      recordError(s, e);
      return;
    }
  }
  if (!checkTableDefinition(s, target, internalformat, width, regular, proxy)) return;
  // "taken from memory and processed just as if DrawPixels were called, stopping after the
  // final expansion to RGBA" (no pixel transfer).
  defineTable(s, regular, internalformat,
              unpackImage(data, width, 1, format, type, unpackStore(s.driver)));
}

void emCopyColorTable(GLenum target, GLenum internalformat, GLint x, GLint y, GLsizei width) {
  State& s = *currentState();
  if (proxyIndex(target) >= 0) {  // CopyColorTable takes regular names only
    recordError(s, GL_INVALID_ENUM);
    return;
  }
  int regular = -1, proxy = -1;
  if (!checkTableDefinition(s, target, internalformat, width, regular, proxy)) return;
  defineTable(s, regular, internalformat, readFramebuffer(s, x, y, width, 1));
}

void emColorSubTable(GLenum target, GLsizei start, GLsizei count, GLenum format, GLenum type,
                     const void* data) {
  State& s = *currentState();
  const int index = regularIndex(target);
  if (const GLenum e = targetFormatError(index >= 0, format, type); e != GL_NO_ERROR) {
    recordError(s, e);
    return;
  }
  const ColorTable& t = s.transfer.tables[index];
  if (start < 0 || count < 0 || start + count > t.width) {  // 3.6.3: start + count > width
    recordError(s, GL_INVALID_VALUE);
    return;
  }
  if (count == 0) return;
  setSubTable(s, index, start, unpackImage(data, count, 1, format, type, unpackStore(s.driver)));
}

void emCopyColorSubTable(GLenum target, GLsizei start, GLint x, GLint y, GLsizei count) {
  State& s = *currentState();
  const int index = regularIndex(target);
  if (index < 0) {
    recordError(s, GL_INVALID_ENUM);
    return;
  }
  const ColorTable& t = s.transfer.tables[index];
  if (start < 0 || count < 0 || start + count > t.width) {
    recordError(s, GL_INVALID_VALUE);
    return;
  }
  if (count == 0) return;
  setSubTable(s, index, start, readFramebuffer(s, x, y, count, 1));
}

void emColorTableParameterfv(GLenum target, GLenum pname, const GLfloat* params) {
  State& s = *currentState();
  const int index = regularIndex(target);
  if (index < 0) {
    recordError(s, GL_INVALID_ENUM);
    return;
  }
  ColorTable& t = s.transfer.tables[index];
  Rgba* dst = pname == GL_COLOR_TABLE_SCALE  ? &t.scale
              : pname == GL_COLOR_TABLE_BIAS ? &t.bias
                                             : nullptr;
  if (dst == nullptr) {
    recordError(s, GL_INVALID_ENUM);
    return;
  }
  for (int c = 0; c < 4; ++c) (*dst)[c] = params[c];
}

void emColorTableParameteriv(GLenum target, GLenum pname, const GLint* params) {
  const GLfloat f[4] = {float(params[0]), float(params[1]), float(params[2]), float(params[3])};
  emColorTableParameterfv(target, pname, f);
}

void emGetColorTable(GLenum target, GLenum format, GLenum type, void* data) {
  State& s = *currentState();
  const int index = regularIndex(target);  // proxies have no image: INVALID_ENUM (3.6.3)
  if (const GLenum e = targetFormatError(index >= 0, format, type); e != GL_NO_ERROR) {
    recordError(s, e);
    return;
  }
  const ColorTable& t = s.transfer.tables[index];
  Image4 image(t.width, 1);
  for (int i = 0; i < t.width; ++i) {
    const Rgba v = tableReturnValue(t.format, t.entries[i]);  // table 6.1
    for (int c = 0; c < 4; ++c) image.px[size_t(i) * 4 + c] = v[c];
  }
  packImage(image, data, format, type, packStore(s.driver), true);
}

namespace {
// Returns false (error recorded) when target or pname is not accepted.
bool queryTableParameter(State& s, GLenum target, GLenum pname, GLfloat* params) {
  const int regular = regularIndex(target), proxy = proxyIndex(target);
  if (regular < 0 && proxy < 0) {
    recordError(s, GL_INVALID_ENUM);
    return false;
  }
  GLenum format = 0, internalFormat = 0;
  int width = 0;
  if (regular >= 0) {
    const ColorTable& t = s.transfer.tables[regular];
    format = t.format, internalFormat = t.internalFormat, width = t.width;
    if (pname == GL_COLOR_TABLE_SCALE || pname == GL_COLOR_TABLE_BIAS) {
      const Rgba& v = pname == GL_COLOR_TABLE_SCALE ? t.scale : t.bias;
      for (int c = 0; c < 4; ++c) params[c] = v[c];
      return true;
    }
  } else {
    const ProxyTable& p = s.transfer.proxies[proxy];
    format = p.format, internalFormat = p.internalFormat, width = p.width;
  }
  const FormatComponents f = componentsOf(width > 0 ? format : 0);
  auto bits = [](bool present) { return present ? float(kTableComponentBits) : 0.0f; };
  switch (pname) {
    case GL_COLOR_TABLE_FORMAT: params[0] = float(internalFormat); return true;
    case GL_COLOR_TABLE_WIDTH: params[0] = float(width); return true;
    case GL_COLOR_TABLE_RED_SIZE: params[0] = bits(f.r); return true;
    case GL_COLOR_TABLE_GREEN_SIZE: params[0] = bits(f.g); return true;
    case GL_COLOR_TABLE_BLUE_SIZE: params[0] = bits(f.b); return true;
    case GL_COLOR_TABLE_ALPHA_SIZE: params[0] = bits(f.a); return true;
    case GL_COLOR_TABLE_LUMINANCE_SIZE: params[0] = bits(f.l); return true;
    case GL_COLOR_TABLE_INTENSITY_SIZE: params[0] = bits(f.i); return true;
    default: recordError(s, GL_INVALID_ENUM); return false;  // incl. scale/bias of a proxy
  }
}
}  // namespace

void emGetColorTableParameterfv(GLenum target, GLenum pname, GLfloat* params) {
  queryTableParameter(*currentState(), target, pname, params);
}

void emGetColorTableParameteriv(GLenum target, GLenum pname, GLint* params) {
  GLfloat f[4] = {0, 0, 0, 0};
  const int n = (pname == GL_COLOR_TABLE_SCALE || pname == GL_COLOR_TABLE_BIAS) ? 4 : 1;
  if (!queryTableParameter(*currentState(), target, pname, f)) return;
  for (int c = 0; c < n; ++c) params[c] = GLint(std::lround(f[c]));
}

}  // namespace sl::imaging::detail
