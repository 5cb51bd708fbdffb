// imaging/convolution.cpp — convolution filters (glspec121 3.6.3 "Convolution Filter
// Specification", "Alternate Convolution Filter Specification Commands", "Convolution Filter
// State"; 3.6.5 "Convolution", table 3.14, border modes REDUCE, CONSTANT_BORDER and
// REPLICATE_BORDER (HP_convolution_border_modes); 6.1.8 "Convolution Query"; EXT_convolution
// "Errors").
#include <cmath>
#include <functional>

#include "imaging/internal.h"

namespace sl::imaging::detail {
namespace {

ConvolutionFilter* filterFor(State& s, GLenum target) {
  switch (target) {
    case GL_CONVOLUTION_1D: return &s.transfer.conv1D;
    case GL_CONVOLUTION_2D: return &s.transfer.conv2D;
    case GL_SEPARABLE_2D: return &s.transfer.separable2D;
    default: return nullptr;
  }
}

// 3.6.3: scale and bias (no clamping "at any time"), then the components of the base
// internal format (table 3.15: L and I from R, A from A).
std::vector<Rgba> filterImage(const Image4& image, const ConvolutionFilter& f) {
  std::vector<Rgba> out(image.px.size() / 4);
  const FormatComponents fc = componentsOf(f.format);
  for (size_t k = 0; k < out.size(); ++k) {
    Rgba v;
    for (int c = 0; c < 4; ++c) v[c] = image.px[k * 4 + c] * f.scale[c] + f.bias[c];
    if (fc.l || fc.i) v[1] = v[2] = v[0];
    if (fc.i) v[3] = v[0];
    if (!fc.a && !fc.i) v[3] = 0.0f;
    if (fc.a && !fc.r && !fc.l) v[0] = v[1] = v[2] = 0.0f;
    out[k] = v;
  }
  return out;
}

// Which output components are convolved (true) or passed unmodified (false), table 3.14.
void convolvedComponents(GLenum format, bool convolved[4]) {
  const FormatComponents f = componentsOf(format);
  convolved[0] = convolved[1] = convolved[2] = f.r || f.l || f.i;
  convolved[3] = f.a || f.i;
}

// Checks target, internal format, sizes and pixel format in EXT_convolution's order.
bool checkFilter(State& s, GLenum target, GLenum expected, GLenum internalformat, GLsizei width,
                 GLsizei height, bool checkFormat, GLenum format, GLenum type) {
  if (target != expected) {
    recordError(s, GL_INVALID_ENUM);
    return false;
  }
  if (baseInternalFormat(internalformat) == 0 || internalformat <= 4) {
    recordError(s, GL_INVALID_ENUM);
    return false;
  }
  if (width < 0 || width > kMaxConvolutionWidth || height < 0 || height > kMaxConvolutionHeight) {
    recordError(s, GL_INVALID_VALUE);
    return false;
  }
  if (const GLenum e = checkFormat ? checkColorFormat(format, type) : GLenum(GL_NO_ERROR);
      e != GL_NO_ERROR) {
    recordError(s, e);
    return false;
  }
  return true;
}

void defineFilter(ConvolutionFilter& f, GLenum internalformat, const Image4& image) {
  f.format = baseInternalFormat(internalformat);
  f.internalFormat = internalformat;
  f.width = image.width;
  f.height = image.height;
  f.image = filterImage(image, f);
}

}  // namespace

// Dense weights W[m][n] of the filter (2D, or the row x column product for a separable
// filter), with pass-through components as a unit tap at the filter centre, then only the
// non-zero taps. The Brabec–Seidel packing kernel (their Eq. 1) keeps 4 taps of 9.
std::vector<Tap> kernelTaps(const ConvolutionFilter& f, bool separable, int& wf, int& hf) {
  wf = f.width;
  hf = separable ? int(f.column.size()) : f.height;
  bool convolved[4];
  convolvedComponents(f.format, convolved);
  const int cw = wf / 2, ch = hf / 2;
  std::vector<Tap> taps;
  for (int m = 0; m < hf; ++m) {
    for (int n = 0; n < wf; ++n) {
      Tap t{n, m, {0, 0, 0, 0}};
      bool any = false;
      for (int c = 0; c < 4; ++c) {
        if (convolved[c]) {
          t.w[c] = separable ? f.row[n][c] * f.column[m][c] : f.image[size_t(m) * wf + n][c];
        } else {
          // "passed unmodified": the source component under the filter centre.
          t.w[c] = (n == cw && m == ch) ? 1.0f : 0.0f;
        }
        any = any || t.w[c] != 0.0f;
      }
      if (any) taps.push_back(t);
    }
  }
  return taps;
}

std::vector<float> binomialBlur3x3Rgba() {
  constexpr int kTaps = 3, kComponents = 4;
  std::vector<float> k(size_t(kTaps * kTaps * kComponents));
  const float unit = float(1 << kBinomialShift);
  for (int m = 0; m < kTaps; ++m)
    for (int n = 0; n < kTaps; ++n)
      for (int c = 0; c < kComponents; ++c)
        k[size_t((m * kTaps + n) * kComponents + c)] =
            float(kBinomialRow[m] * kBinomialRow[n]) / unit;
  return k;
}

// ---------------------------------------------------------------- the stage (3.6.5)
// C[i', j'] = sum_n sum_m Cs'[i' + n, j' + m] * Cf[n, m]; REDUCE gives (Ws-Wf+1) x (Hs-Hf+1),
// CONSTANT and REPLICATE keep Ws x Hs with Cr[i, j] = C[i - Cw, j - Ch], Cw = floor(Wf/2).
// Computed row by row: each non-zero tap adds a weighted source row to the output row, so
// the inner loop is a contiguous multiply-add over 4-float groups and zero taps cost nothing.
void convolve(const ConvolutionFilter& f, bool separable, Image4& image) {
  int wf = 0, hf = 0;
  const std::vector<Tap> taps = kernelTaps(f, separable, wf, hf);
  const int ws = image.width, hs = image.height;
  if (wf == 0 || hf == 0) {
    // "If either Wf or Hf of a two-dimensional filter is zero, then C[i, j] is always zero."
    std::fill(image.px.begin(), image.px.end(), 0.0f);
    return;
  }
  const Image4* src = &image;
  Image4 padded;
  int ow = ws, oh = hs;
  if (f.borderMode == GL_REDUCE) {
    ow = ws - wf + 1;
    oh = hs - hf + 1;
    if (ow <= 0 || oh <= 0) {  // "the output is simply null, with no error generated"
      image = Image4(std::max(ow, 0), std::max(oh, 0));
      return;
    }
  } else {
    // Surround the source by Cw / Ch columns and rows of border colour or replicated edge.
    const int cw = wf / 2, ch = hf / 2;
    padded = Image4(ws + wf - 1, hs + hf - 1);
    const bool replicate = f.borderMode == GL_REPLICATE_BORDER;
    for (int y = 0; y < padded.height; ++y) {
      const int sy = y - ch;
      float* dst = padded.row(y);
      for (int x = 0; x < padded.width; ++x) {
        const int sx = x - cw;
        const bool inside = sx >= 0 && sx < ws && sy >= 0 && sy < hs;
        if (inside || replicate) {
          const int cx = std::clamp(sx, 0, ws - 1), cy = std::clamp(sy, 0, hs - 1);
          const float* p = image.row(cy) + size_t(cx) * 4;
          for (int c = 0; c < 4; ++c) dst[x * 4 + c] = p[c];
        } else {
          for (int c = 0; c < 4; ++c) dst[x * 4 + c] = f.borderColor[c];
        }
      }
    }
    src = &padded;
  }
  Image4 out(ow, oh);
  parallelRows(oh, size_t(ow) * 4 * (taps.size() + 1), [&](int y0, int y1) {
    for (int j = y0; j < y1; ++j) {
      accumulateTaps(
          taps, [&](int m) { return src->row(j + m); }, ow, out.row(j));
    }
  });
  image = std::move(out);
}

void accumulateTaps(const std::vector<Tap>& taps, const std::function<const float*(int)>& row,
                    int ow, float* o) {
  {
    {
      for (const Tap& t : taps) {
        const float* s = row(t.m) + size_t(t.n) * 4;
        const float w0 = t.w[0], w1 = t.w[1], w2 = t.w[2], w3 = t.w[3];
        // A tap that feeds one component only (each tap of the packing kernel does) touches
        // that component alone; adding 0 * x to the others would change nothing for finite x.
        const int live = (w0 != 0.0f) + (w1 != 0.0f) + (w2 != 0.0f) + (w3 != 0.0f);
        if (live == 1) {
          const int c = w0 != 0.0f ? 0 : w1 != 0.0f ? 1 : w2 != 0.0f ? 2 : 3;
          const float wc = t.w[c];
          for (int i = 0; i < ow; ++i) o[i * 4 + c] += s[i * 4 + c] * wc;
          continue;
        }
        for (int i = 0; i < ow; ++i) {
          o[i * 4 + 0] += s[i * 4 + 0] * w0;
          o[i * 4 + 1] += s[i * 4 + 1] * w1;
          o[i * 4 + 2] += s[i * 4 + 2] * w2;
          o[i * 4 + 3] += s[i * 4 + 3] * w3;
        }
      }
    }
  }
}

// ---------------------------------------------------------------- entry points
void emConvolutionFilter2D(GLenum target, GLenum internalformat, GLsizei width, GLsizei height,
                           GLenum format, GLenum type, const void* data) {
  State& s = *currentState();
  if (!checkFilter(s, target, GL_CONVOLUTION_2D, internalformat, width, height, true, format, type))
    return;
  defineFilter(s.transfer.conv2D, internalformat,
               unpackImage(data, width, height, format, type, unpackStore(s.driver)));
}

void emConvolutionFilter1D(GLenum target, GLenum internalformat, GLsizei width, GLenum format,
                           GLenum type, const void* data) {
  State& s = *currentState();
  if (!checkFilter(s, target, GL_CONVOLUTION_1D, internalformat, width, 1, true, format, type))
    return;
  defineFilter(s.transfer.conv1D, internalformat,
               unpackImage(data, width, 1, format, type, unpackStore(s.driver)));
}

void emSeparableFilter2D(GLenum target, GLenum internalformat, GLsizei width, GLsizei height,
                         GLenum format, GLenum type, const void* row, const void* column) {
  State& s = *currentState();
  if (!checkFilter(s, target, GL_SEPARABLE_2D, internalformat, width, height, true, format, type))
    return;
  ConvolutionFilter& f = s.transfer.separable2D;
  f.format = baseInternalFormat(internalformat);
  f.internalFormat = internalformat;
  f.width = width;
  f.height = height;
  const PixelStore store = unpackStore(s.driver);
  f.row = filterImage(unpackImage(row, width, 1, format, type, store), f);
  f.column = filterImage(unpackImage(column, height, 1, format, type, store), f);
}

void emCopyConvolutionFilter2D(GLenum target, GLenum internalformat, GLint x, GLint y,
                               GLsizei width, GLsizei height) {
  State& s = *currentState();
  if (!checkFilter(s, target, GL_CONVOLUTION_2D, internalformat, width, height, false, 0, 0))
    return;
  defineFilter(s.transfer.conv2D, internalformat, readFramebuffer(s, x, y, width, height));
}

void emCopyConvolutionFilter1D(GLenum target, GLenum internalformat, GLint x, GLint y,
                               GLsizei width) {
  State& s = *currentState();
  if (!checkFilter(s, target, GL_CONVOLUTION_1D, internalformat, width, 1, false, 0, 0)) return;
  defineFilter(s.transfer.conv1D, internalformat, readFramebuffer(s, x, y, width, 1));
}

void emConvolutionParameterfv(GLenum target, GLenum pname, const GLfloat* params) {
  State& s = *currentState();
  ConvolutionFilter* f = filterFor(s, target);
  if (f == nullptr) {
    recordError(s, GL_INVALID_ENUM);
    return;
  }
  switch (pname) {
    case GL_CONVOLUTION_FILTER_SCALE:
      for (int c = 0; c < 4; ++c) f->scale[c] = params[c];
      return;
    case GL_CONVOLUTION_FILTER_BIAS:
      for (int c = 0; c < 4; ++c) f->bias[c] = params[c];
      return;
    case GL_CONVOLUTION_BORDER_COLOR:  // "Floating point color components are not clamped"
      for (int c = 0; c < 4; ++c) f->borderColor[c] = params[c];
      return;
    case GL_CONVOLUTION_BORDER_MODE: {
      const GLenum mode = GLenum(params[0]);
      if (mode != GL_REDUCE && mode != GL_CONSTANT_BORDER && mode != GL_REPLICATE_BORDER) {
        recordError(s, GL_INVALID_ENUM);  // HP_convolution_border_modes "Errors"
        return;
      }
      f->borderMode = mode;
      return;
    }
    default: recordError(s, GL_INVALID_ENUM); return;
  }
}

void emConvolutionParameteriv(GLenum target, GLenum pname, const GLint* params) {
  if (pname == GL_CONVOLUTION_BORDER_COLOR) {
    // "Integer color components are interpreted linearly such that the most positive integer
    // maps to 1.0, and the most negative integer maps to -1.0."
    GLfloat f[4];
    for (int c = 0; c < 4; ++c) f[c] = float((2.0 * double(params[c]) + 1.0) / 4294967295.0);
    emConvolutionParameterfv(target, pname, f);
    return;
  }
  if (pname == GL_CONVOLUTION_BORDER_MODE) {
    const GLfloat f[4] = {float(params[0]), 0, 0, 0};
    emConvolutionParameterfv(target, pname, f);
    return;
  }
  const GLfloat f[4] = {float(params[0]), float(params[1]), float(params[2]), float(params[3])};
  emConvolutionParameterfv(target, pname, f);
}

void emConvolutionParameterf(GLenum target, GLenum pname, GLfloat param) {
  State& s = *currentState();
  if (filterFor(s, target) != nullptr && pname != GL_CONVOLUTION_BORDER_MODE) {
    recordError(s, GL_INVALID_ENUM);  // the scalar form takes the border mode only
    return;
  }
  const GLfloat f[4] = {param, 0, 0, 0};
  emConvolutionParameterfv(target, pname, f);
}

void emConvolutionParameteri(GLenum target, GLenum pname, GLint param) {
  emConvolutionParameterf(target, pname, float(param));
}

namespace {
void packFilter(State& s, const std::vector<Rgba>& values, GLenum baseFormat, int w, int h,
                GLenum format, GLenum type, void* data) {
  Image4 image(w, h);
  for (size_t k = 0; k < values.size() && k < size_t(w) * h; ++k) {
    const Rgba v = tableReturnValue(baseFormat, values[k]);  // table 6.1
    for (int c = 0; c < 4; ++c) image.px[k * 4 + c] = v[c];
  }
  // 6.1.8: "Pixel processing and component mapping are identical to those of GetTexImage";
  // filter values are not clamped to [0,1] when returned as floats.
  packImage(image, data, format, type, packStore(s.driver), type != GL_FLOAT);
}
}  // namespace

void emGetConvolutionFilter(GLenum target, GLenum format, GLenum type, void* data) {
  State& s = *currentState();
  if (const GLenum e = targetFormatError(target == GL_CONVOLUTION_1D || target == GL_CONVOLUTION_2D,
                                         format, type);
      e != GL_NO_ERROR) {
    recordError(s, e);
    return;
  }
  const ConvolutionFilter& f = *filterFor(s, target);
  packFilter(s, f.image, f.format, f.width, f.height, format, type, data);
}

void emGetSeparableFilter(GLenum target, GLenum format, GLenum type, void* row, void* column,
                          void*) {
  State& s = *currentState();
  if (const GLenum e = targetFormatError(target == GL_SEPARABLE_2D, format, type);
      e != GL_NO_ERROR) {
    recordError(s, e);
    return;
  }
  const ConvolutionFilter& f = s.transfer.separable2D;
  packFilter(s, f.row, f.format, f.width, 1, format, type, row);
  packFilter(s, f.column, f.format, f.height, 1, format, type, column);
}

namespace {
bool queryConvolutionParameter(State& s, GLenum target, GLenum pname, GLfloat* params) {
  ConvolutionFilter* f = filterFor(s, target);
  if (f == nullptr) {
    recordError(s, GL_INVALID_ENUM);
    return false;
  }
  const bool oneD = target == GL_CONVOLUTION_1D;
  switch (pname) {
    case GL_CONVOLUTION_BORDER_COLOR:
      for (int c = 0; c < 4; ++c) params[c] = f->borderColor[c];
      return true;
    case GL_CONVOLUTION_FILTER_SCALE:
      for (int c = 0; c < 4; ++c) params[c] = f->scale[c];
      return true;
    case GL_CONVOLUTION_FILTER_BIAS:
      for (int c = 0; c < 4; ++c) params[c] = f->bias[c];
      return true;
    case GL_CONVOLUTION_BORDER_MODE: params[0] = float(f->borderMode); return true;
    case GL_CONVOLUTION_FORMAT: params[0] = float(f->internalFormat); return true;
    case GL_CONVOLUTION_WIDTH: params[0] = float(f->width); return true;
    case GL_MAX_CONVOLUTION_WIDTH: params[0] = float(kMaxConvolutionWidth); return true;
    case GL_CONVOLUTION_HEIGHT:
      if (oneD) break;
      params[0] = float(f->height);
      return true;
    case GL_MAX_CONVOLUTION_HEIGHT:
      if (oneD) break;
      params[0] = float(kMaxConvolutionHeight);
      return true;
    default: break;
  }
  recordError(s, GL_INVALID_ENUM);
  return false;
}
int parameterCount(GLenum pname) {
  return (pname == GL_CONVOLUTION_BORDER_COLOR || pname == GL_CONVOLUTION_FILTER_SCALE ||
          pname == GL_CONVOLUTION_FILTER_BIAS)
             ? 4
             : 1;
}
}  // namespace

void emGetConvolutionParameterfv(GLenum target, GLenum pname, GLfloat* params) {
  queryConvolutionParameter(*currentState(), target, pname, params);
}

void emGetConvolutionParameteriv(GLenum target, GLenum pname, GLint* params) {
  GLfloat f[4] = {0, 0, 0, 0};
  if (!queryConvolutionParameter(*currentState(), target, pname, f)) return;
  for (int c = 0; c < parameterCount(pname); ++c) params[c] = GLint(std::lround(f[c]));
}

}  // namespace sl::imaging::detail
