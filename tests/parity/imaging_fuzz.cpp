// The differential fuzzer of the imaging subset (imaging_fuzz.h).
//
// Generator constraints: each keeps a documented departure of the reference
// (../shared/reference-gl/README.md, tests/parity/departures_test.cpp) from hiding the
// behaviour behind it. The departure stays covered by its own named test.
//   * Grey level (0: free, 1: R = G = B, 2: R = G = B = A) for every colour the sequence
//     makes: LUMINANCE / LUMINANCE_ALPHA tables, histograms and minmax appear only at level >=
//     1 and INTENSITY tables only at level 2, so indexing or counting with R for G, B (and A)
//     gives the specification's answer (departures 2, 6).
//   * Convolution filters hold, for components their format does not have, a unit tap at the
//     centre (and L / I data is repeated into the components that share it), so convolving
//     all four channels as unpacked (departure 3) equals table 3.14; filter scale/bias is 1/0
//     there. glCopyConvolutionFilter2D defines RGBA filters only.
//   * Table data lies in [0, 1] (departure 8); copies of tables and filters start at row 0
//     (departures 4, 9), before any other stage is enabled (the reference runs the copied
//     groups through the enabled stages, histogram included, where 3.6.3 stops after the
//     expansion to RGBA: AdditionalM); table/histogram/minmax read-backs use formats holding only
//     the components the object has (departures 10, B).
//   * With GL_HISTOGRAM_SINK the only pipeline call is glReadPixels, whose pixels are not
//     compared (departure 5); with GL_MINMAX_SINK too (the reference honours it on
//     glReadPixels only: AdditionalI).
//   * glCopyTexImage2D only without tables, colour matrix, convolution, histogram, minmax (the
//     reference runs the pipeline twice there: AdditionalD, AdditionalK); glTexImage2D only
//     without convolution (the reference applies an enabled 1D filter's stage to 2D images,
//     AdditionalJ, and clamps before convolving, AdditionalL).
//   * Accumulation values stay inside [-1, 1] (README: wrap-around); no second scissored
//     GL_LOAD (AdditionalE).
//   * At most one call writes the window (glDrawPixels, glCopyPixels, glAccum(GL_RETURN)), so
//     the emulation on a float colour buffer gives the exact value of every byte compared.
#include "parity/imaging_fuzz.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <sstream>

#include "core/gl/gl.h"
#include "imaging/imaging.h"

namespace sl::imaging::fuzz {
namespace {
using namespace sl::gl;

constexpr int kMinSize = 4;  // image sides: small images, cheap sequences (kWindow at most)

// ---------------------------------------------------------------- generator

struct Rng {
  std::mt19937_64 g;
  explicit Rng(uint64_t seed) : g(seed) {}
  int uni(int lo, int hi) { return lo + int(g() % uint64_t(hi - lo + 1)); }
  float unit() { return float(g() >> 40) / float(1u << 24); }  // [0, 1), 24 bits
  float range(float lo, float hi) { return lo + (hi - lo) * unit(); }
  bool chance(int percent) { return uni(0, 99) < percent; }
  template <class T>
  T pick(std::initializer_list<T> v) {
    return *(v.begin() + uni(0, int(v.size()) - 1));
  }
};

constexpr int kMaxFilter = 9;   // GL_MAX_CONVOLUTION_WIDTH/HEIGHT of the reference
constexpr int kMaxTable = 256;  // the reference's largest color table

GLenum baseOf(GLenum f) {
  switch (f) {
    case GL_ALPHA8: return GL_ALPHA;
    case GL_LUMINANCE8: return GL_LUMINANCE;
    case GL_LUMINANCE8_ALPHA8: return GL_LUMINANCE_ALPHA;
    case GL_INTENSITY8: return GL_INTENSITY;
    case GL_RGB8: return GL_RGB;
    case GL_RGBA8: return GL_RGBA;
    default: return f;
  }
}

struct Gen {
  Rng r;
  int grey = 0;
  Sequence s;
  bool tables = false, matrix = false, convolved = false, sink = false, minmax = false,
       histogram = false;
  std::vector<GLenum> tableFormats[3];  // per target index, the defined formats
  GLenum histFormat = 0, minmaxFormat = 0;
  int histGroup = 0, minmaxGroup = 0, tableGroup[3] = {0, 0, 0};
  int reduceW = 1, reduceH = 1;  // the GL_REDUCE filter's size, 1x1 without one

  explicit Gen(uint64_t seed) : r(seed) {}

  // Four components under the grey level.
  void greyify(float* c) const {
    if (grey >= 1) c[1] = c[2] = c[0];
    if (grey >= 2) c[3] = c[0];
  }
  std::vector<float> color(float lo, float hi) {
    std::vector<float> c = {r.range(lo, hi), r.range(lo, hi), r.range(lo, hi), r.range(lo, hi)};
    greyify(c.data());
    return c;
  }
  std::vector<uint8_t> bytes(int n) {
    std::vector<uint8_t> b(size_t(n) * 4);
    for (size_t p = 0; p < b.size(); p += 4) {
      float c[4];
      for (float& v : c) v = float(r.uni(0, 255));
      // Extremes often: 0 and 255 are where clamping and saturation meet.
      if (r.chance(10)) c[0] = r.pick<float>({0.0f, 255.0f});
      greyify(c);
      for (int k = 0; k < 4; ++k) b[p + k] = uint8_t(c[k]);
    }
    return b;
  }
  // A scale: exact halves and doubles (rounding ties), or arbitrary.
  float scale() {
    return r.chance(30) ? r.pick<float>({0.5f, 1.0f, 2.0f, 0.25f}) : r.range(-0.3f, 1.8f);
  }
  float bias() { return r.chance(40) ? 0.0f : r.range(-0.4f, 0.4f); }

  int group = 0;  // the feature the calls being added belong to (minimise() drops whole ones)
  void add(Call c) {
    c.group = group;
    s.calls.push_back(std::move(c));
  }

  void pixelTransfer(int stage) {
    static const GLenum scales[3][4] = {
        {GL_RED_SCALE, GL_GREEN_SCALE, GL_BLUE_SCALE, GL_ALPHA_SCALE},
        {GL_POST_CONVOLUTION_RED_SCALE, GL_POST_CONVOLUTION_GREEN_SCALE,
         GL_POST_CONVOLUTION_BLUE_SCALE, GL_POST_CONVOLUTION_ALPHA_SCALE},
        {GL_POST_COLOR_MATRIX_RED_SCALE, GL_POST_COLOR_MATRIX_GREEN_SCALE,
         GL_POST_COLOR_MATRIX_BLUE_SCALE, GL_POST_COLOR_MATRIX_ALPHA_SCALE}};
    static const GLenum biases[3][4] = {
        {GL_RED_BIAS, GL_GREEN_BIAS, GL_BLUE_BIAS, GL_ALPHA_BIAS},
        {GL_POST_CONVOLUTION_RED_BIAS, GL_POST_CONVOLUTION_GREEN_BIAS,
         GL_POST_CONVOLUTION_BLUE_BIAS, GL_POST_CONVOLUTION_ALPHA_BIAS},
        {GL_POST_COLOR_MATRIX_RED_BIAS, GL_POST_COLOR_MATRIX_GREEN_BIAS,
         GL_POST_COLOR_MATRIX_BLUE_BIAS, GL_POST_COLOR_MATRIX_ALPHA_BIAS}};
    float sc[4] = {scale(), scale(), scale(), scale()}, bi[4] = {bias(), bias(), bias(), bias()};
    greyify(sc);
    greyify(bi);
    // All four or none: a later group's values replace an earlier one's in every component,
    // so the grey level holds.
    const bool scaled =
        sc[0] != 1.0f || sc[1] != 1.0f || sc[2] != 1.0f || sc[3] != 1.0f || r.chance(10);
    const bool biased = bi[0] != 0.0f || bi[1] != 0.0f || bi[2] != 0.0f || bi[3] != 0.0f;
    for (int k = 0; k < 4; ++k) {
      if (scaled) add({Kind::kPixelTransfer, {scales[stage][k]}, {}, {sc[k]}, {}});
      if (biased) add({Kind::kPixelTransfer, {biases[stage][k]}, {}, {bi[k]}, {}});
    }
  }

  // The table formats the grey level keeps grey: at level 2 only those that replace A
  // together with R, G, B from equal entries.
  GLenum tableFormat() {
    std::vector<GLenum> f = {GL_RGBA, GL_RGBA8};
    if (grey <= 1) f.insert(f.end(), {GL_ALPHA, GL_RGB, GL_ALPHA8, GL_RGB8});
    if (grey == 1) f.insert(f.end(), {GL_LUMINANCE, GL_LUMINANCE8});
    if (grey >= 1) f.insert(f.end(), {GL_LUMINANCE_ALPHA, GL_LUMINANCE8_ALPHA8});
    if (grey >= 2) f.insert(f.end(), {GL_INTENSITY, GL_INTENSITY8});
    return f[size_t(r.uni(0, int(f.size()) - 1))];
  }
  // No stage but pixel transfer enabled yet: the reference runs copied tables and filters
  // through the enabled ones (AdditionalM).
  bool copyable() const { return !tables && !matrix && !convolved && !histogram && !minmax; }

  void colorTable() {
    ++group;
    static const GLenum targets[3] = {GL_COLOR_TABLE, GL_POST_CONVOLUTION_COLOR_TABLE,
                                      GL_POST_COLOR_MATRIX_COLOR_TABLE};
    const int t = r.uni(0, 2);
    const GLenum target = targets[t];
    if (r.chance(40)) {
      auto sc = color(0.0f, 1.5f);
      add({Kind::kColorTableParameter, {target, GL_COLOR_TABLE_SCALE}, {}, sc, {}});
    }
    if (r.chance(30)) {
      auto bi = color(-0.3f, 0.3f);
      add({Kind::kColorTableParameter, {target, GL_COLOR_TABLE_BIAS}, {}, bi, {}});
    }
    const GLenum format = tableFormat();
    int width = 1 << r.uni(0, 8);
    if (r.chance(3)) width = r.pick<int>({3, 6, 2 * kMaxTable});  // errors
    if (r.chance(15) && t == 0 && width <= s.w && copyable()) {   // AdditionalM
      add({Kind::kCopyColorTable, {target, format}, {0, 0, width}, {}, {}});
    } else {
      const GLenum type = r.chance(50) ? GL_FLOAT : GL_UNSIGNED_BYTE;
      std::vector<float> data;
      const bool ramp = r.chance(40);
      for (int k = 0; k < width; ++k) {
        std::vector<float> c = color(0.0f, 1.0f);
        if (ramp) {
          const float v = width > 1 ? float(k) / float(width - 1) : 1.0f;
          c = {v, 1.0f - v, v * v, 1.0f - v * v};
          greyify(c.data());
        }
        if (type == GL_UNSIGNED_BYTE)
          for (float& v : c) v = std::round(v * 255.0f) / 255.0f;
        data.insert(data.end(), c.begin(), c.end());
      }
      add({Kind::kColorTable, {target, format, type}, {width}, data, {}});
    }
    if (width > kMaxTable || (width & (width - 1)) != 0) return;  // an error: nothing defined
    tableFormats[t].push_back(format);
    tableGroup[t] = group;
    add({Kind::kEnable, {target}, {}, {}, {}});
    tables = true;
  }

  void colorMatrix() {
    ++group;
    std::vector<float> m(16);
    const bool permute = r.chance(25);
    for (int c = 0; c < 4; ++c)
      for (int row = 0; row < 4; ++row)
        m[size_t(c) * 4 + row] = permute ? (c == (row + 1) % 4 ? 1.0f : 0.0f)
                                         : (r.chance(30) ? 0.0f : r.range(-0.5f, 1.2f));
    // Grey: the rows that must produce equal components are equal.
    for (int c = 0; c < 4; ++c) {
      if (grey >= 1) m[size_t(c) * 4 + 1] = m[size_t(c) * 4 + 2] = m[size_t(c) * 4];
      if (grey >= 2) m[size_t(c) * 4 + 3] = m[size_t(c) * 4];
    }
    add({Kind::kLoadColorMatrix, {}, {}, m, {}});
    if (r.chance(40)) pixelTransfer(2);
    matrix = true;
  }

  // The filter formats the grey level keeps grey.
  GLenum filterFormat() {
    if (grey >= 2) return r.pick<GLenum>({GL_RGBA, GL_INTENSITY, GL_RGBA8, GL_INTENSITY8});
    std::vector<GLenum> f = {GL_RGBA, GL_RGB, GL_ALPHA, GL_RGBA8, GL_RGB8};
    if (grey >= 1) f.insert(f.end(), {GL_LUMINANCE, GL_LUMINANCE_ALPHA, GL_INTENSITY});
    return f[size_t(r.uni(0, int(f.size()) - 1))];
  }

  // n taps, compatible with the reference (constraints above); centre = the tap of the unit.
  std::vector<float> taps(GLenum format, int n, int centre) {
    std::vector<float> f(size_t(n) * 4);
    const bool box = r.chance(20);  // equal taps: sums of exact fractions, ties
    for (int k = 0; k < n; ++k) {
      float* p = &f[size_t(k) * 4];
      for (int c = 0; c < 4; ++c) p[c] = box ? 1.0f / float(n) : r.range(-0.15f, 0.35f);
      greyify(p);
      const float delta = k == centre ? 1.0f : 0.0f;
      switch (baseOf(format)) {
        case GL_ALPHA: p[0] = p[1] = p[2] = delta; break;
        case GL_LUMINANCE:
          p[1] = p[2] = p[0];
          p[3] = delta;
          break;
        case GL_LUMINANCE_ALPHA: p[1] = p[2] = p[0]; break;
        case GL_INTENSITY: p[1] = p[2] = p[3] = p[0]; break;
        case GL_RGB: p[3] = delta; break;
        default: break;
      }
    }
    return f;
  }

  void convolution() {
    ++group;
    const int kind = r.uni(0, 2);  // 1D, 2D, separable
    const GLenum target = kind == 0   ? GL_CONVOLUTION_1D
                          : kind == 1 ? GL_CONVOLUTION_2D
                                      : GL_SEPARABLE_2D;
    const GLenum format = filterFormat();
    const int fw = r.uni(1, kMaxFilter), fh = kind == 0 ? 1 : r.uni(1, kMaxFilter);
    if (baseOf(format) == GL_RGBA && r.chance(30)) {
      auto sc = color(0.5f, 1.5f);
      add({Kind::kConvolutionScaleBias, {target, GL_CONVOLUTION_FILTER_SCALE}, {}, sc, {}});
      auto bi = color(-0.05f, 0.05f);
      add({Kind::kConvolutionScaleBias, {target, GL_CONVOLUTION_FILTER_BIAS}, {}, bi, {}});
    }
    if (kind == 0) {
      if (r.chance(3)) {  // an error: too wide, nothing defined
        add({Kind::kConvolutionFilter1D,
             {format},
             {fw + kMaxFilter},
             taps(format, fw + kMaxFilter, 0),
             {}});
        return;
      }
      add({Kind::kConvolutionFilter1D, {format}, {fw}, taps(format, fw, fw / 2), {}});
    } else if (kind == 1) {
      if (r.chance(15) && baseOf(format) == GL_RGBA && fw <= s.w && fh <= s.h && copyable())
        add({Kind::kCopyConvolutionFilter2D, {GL_RGBA}, {0, 0, fw, fh}, {}, {}});
      else
        add({Kind::kConvolutionFilter2D,
             {format},
             {fw, fh},
             taps(format, fw * fh, (fh / 2) * fw + fw / 2),
             {}});
    } else {
      auto row = taps(format, fw, fw / 2), col = taps(format, fh, fh / 2);
      row.insert(row.end(), col.begin(), col.end());
      add({Kind::kSeparableFilter2D, {format}, {fw, fh}, row, {}});
    }
    const GLenum mode = r.pick<GLenum>({GL_REDUCE, GL_CONSTANT_BORDER, GL_REPLICATE_BORDER});
    if (mode == GL_REDUCE) {
      reduceW = fw;
      reduceH = fh;
    }
    auto border = color(0.0f, 1.0f);
    add({Kind::kConvolutionBorder, {target, mode}, {}, border, {}});
    add({Kind::kEnable, {target}, {}, {}, {}});
    if (r.chance(50)) pixelTransfer(1);
    convolved = true;
  }

  GLenum countFormat() {
    std::vector<GLenum> f = {GL_RGB, GL_RGBA, GL_ALPHA};
    if (grey >= 1) f.insert(f.end(), {GL_LUMINANCE, GL_LUMINANCE_ALPHA});
    return f[size_t(r.uni(0, int(f.size()) - 1))];
  }

  void histogramOrMinmax() {
    ++group;
    if (r.chance(50)) {
      histFormat = countFormat();
      if (r.chance(3)) {  // an error: not a power of two, nothing defined
        add({Kind::kHistogram, {histFormat}, {5, 0}, {}, {}});
        return;
      }
      const int width = 1 << r.uni(0, 8);
      sink = r.chance(20);
      add({Kind::kHistogram, {histFormat}, {width, sink ? 1 : 0}, {}, {}});
      add({Kind::kEnable, {GL_HISTOGRAM}, {}, {}, {}});
      histogram = true;
      histGroup = group;
    } else {
      minmaxFormat = countFormat();
      const bool minmaxSink = r.chance(30);
      sink = sink || minmaxSink;
      add({Kind::kMinmax, {minmaxFormat}, {minmaxSink ? 1 : 0}, {}, {}});
      add({Kind::kEnable, {GL_MINMAX}, {}, {}, {}});
      minmax = true;
      minmaxGroup = group;
    }
  }

  // A rectangle on the image, at least as large as a GL_REDUCE filter (the reference crashes
  // in glReadPixels when the convolved size would be below 1: a seed found it).
  void rect(int& x, int& y, int& w, int& h) {
    w = reduceW <= s.w ? r.uni(reduceW, s.w) : reduceW;
    h = reduceH <= s.h ? r.uni(reduceH, s.h) : reduceH;
    x = r.uni(0, std::max(0, s.w - w));
    y = r.uni(0, std::max(0, s.h - h));
  }

  void readPixels() {
    ++group;
    int x, y, w, h;
    rect(x, y, w, h);
    add({Kind::kReadPixels,
         {r.chance(50) ? GLenum(GL_FLOAT) : GLenum(GL_UNSIGNED_BYTE)},
         {x, y, w, h},
         {},
         {}});
  }

  void writeOnce() {
    ++group;
    int x, y, w, h;
    rect(x, y, w, h);
    const int choice = r.uni(0, 99);
    if (choice < 35) {
      add({Kind::kCopyPixels,
           {},
           {x, y, w, h, r.uni(0, kWindow - 1), r.uni(0, kWindow - 1)},
           {},
           {}});
    } else if (choice < 65) {
      add({Kind::kDrawPixels,
           {},
           {w, h, r.uni(0, kWindow - 1), r.uni(0, kWindow - 1)},
           {},
           bytes(w * h)});
    } else if (convolved) {  // AdditionalJ, AdditionalL: textures only without convolution
      add({Kind::kDrawPixels,
           {},
           {w, h, r.uni(0, kWindow - 1), r.uni(0, kWindow - 1)},
           {},
           bytes(w * h)});
    } else if (choice < 85 || tables || matrix || histogram || minmax) {  // AdditionalD, K
      add({Kind::kTexImage2D, {}, {w, h}, {}, bytes(w * h)});
    } else {
      add({Kind::kCopyTexImage2D, {}, {x, y, w, h}, {}, {}});
    }
  }

  // Read-backs in formats holding only the components the object has; L as R (departures
  // 6, 10 and B: the reference packs L from its R, G and B counts or entries).
  void countQueries(Kind kind, GLenum format, int reset) {
    switch (format) {
      case GL_LUMINANCE: add({kind, {GL_RED}, {reset}, {}, {}}); break;
      case GL_LUMINANCE_ALPHA:
        add({kind, {GL_RED}, {0}, {}, {}});
        add({kind, {GL_ALPHA}, {reset}, {}, {}});
        break;
      default: add({kind, {format}, {reset}, {}, {}});
    }
  }

  void queries() {
    if (histogram && r.chance(80)) {
      group = histGroup;
      countQueries(Kind::kGetHistogram, histFormat, r.chance(50) ? 1 : 0);
    }
    if (minmax && r.chance(80)) {
      group = minmaxGroup;
      countQueries(Kind::kGetMinmax, minmaxFormat, r.chance(50) ? 1 : 0);
    }
    static const GLenum targets[3] = {GL_COLOR_TABLE, GL_POST_CONVOLUTION_COLOR_TABLE,
                                      GL_POST_COLOR_MATRIX_COLOR_TABLE};
    for (int t = 0; t < 3; ++t) {
      if (tableFormats[t].empty() || !r.chance(50)) continue;
      group = tableGroup[t];
      switch (baseOf(tableFormats[t].back())) {
        case GL_LUMINANCE:
        case GL_LUMINANCE_ALPHA:
          add({Kind::kGetColorTable, {targets[t], GL_RED}, {}, {}, {}});
          add({Kind::kGetColorTable, {targets[t], GL_ALPHA}, {}, {}, {}});
          break;
        case GL_INTENSITY: add({Kind::kGetColorTable, {targets[t], GL_RED}, {}, {}, {}}); break;
        default:
          add({Kind::kGetColorTable, {targets[t], baseOf(tableFormats[t].back())}, {}, {}, {}});
      }
    }
  }

  void accumulation() {
    ++group;
    double bound = 0.0;  // the largest |A| the operations so far can reach
    const int n = r.uni(1, 4);
    int loads = 0;
    if (r.chance(25)) {
      int x, y, w, h;
      rect(x, y, w, h);
      add({Kind::kScissor, {}, {x, y, w, h}, {}, {}});
      add({Kind::kEnable, {GL_SCISSOR_TEST}, {}, {}, {}});
    }
    for (int k = 0; k < n; ++k) {
      const GLenum op = k == 0 ? r.pick<GLenum>({GL_LOAD, GL_ACCUM})
                               : r.pick<GLenum>({GL_LOAD, GL_ACCUM, GL_MULT, GL_ADD});
      if (op == GL_LOAD && loads > 0) continue;  // AdditionalE
      float v = 0.0f;
      const float room = float(1.0 - bound);
      switch (op) {
        case GL_LOAD:
          v = r.chance(30) ? r.pick<float>({1.0f, 0.5f, 0.25f}) : r.range(-1.0f, 1.0f);
          bound = std::fabs(v);
          ++loads;
          break;
        case GL_ACCUM:
          v = r.chance(30) ? std::min(room, 0.25f) : r.range(-room, room);
          bound += std::fabs(v);
          break;
        case GL_MULT:
          v = r.range(-1.0f, 1.0f);
          bound *= std::fabs(v);
          break;
        default:
          v = r.range(-room, room);
          bound += std::fabs(v);
          break;
      }
      add({Kind::kAccum, {op}, {}, {v}, {}});
    }
    const float ret = r.chance(40) ? r.pick<float>({1.0f, 2.0f, 4.0f, 0.5f}) : r.range(0.0f, 3.0f);
    add({Kind::kAccum, {GL_RETURN}, {}, {ret}, {}});
  }

  Sequence run() {
    s.w = r.uni(kMinSize, kWindow);
    s.h = r.uni(kMinSize, kWindow);
    grey = r.uni(0, 2);
    s.image = bytes(s.w * s.h);
    if (r.chance(20)) {
      accumulation();
      return s;
    }
    const int stages = r.uni(1, 5);
    for (int k = 0; k < stages; ++k) {
      switch (r.uni(0, 5)) {
        case 0:
          ++group;
          pixelTransfer(0);
          break;
        case 1: colorTable(); break;
        case 2:
          if (!matrix) colorMatrix();
          break;
        case 3:
          if (!convolved) convolution();
          break;
        default:
          if (!histogram && !minmax) histogramOrMinmax();
          break;
      }
    }
    if (r.chance(15)) {
      ++group;
      int x, y, w, h;
      rect(x, y, w, h);
      add({Kind::kScissor, {}, {x, y, w, h}, {}, {}});
      add({Kind::kEnable, {GL_SCISSOR_TEST}, {}, {}, {}});
    }
    const int reads = sink ? 1 : r.uni(0, 1);
    for (int k = 0; k < reads; ++k) readPixels();
    if (!sink) writeOnce();
    queries();
    return s;
  }
};

// ---------------------------------------------------------------- executor

void resetImaging() {
  for (GLenum cap : {GL_COLOR_TABLE, GL_POST_CONVOLUTION_COLOR_TABLE,
                     GL_POST_COLOR_MATRIX_COLOR_TABLE, GL_CONVOLUTION_1D, GL_CONVOLUTION_2D,
                     GL_SEPARABLE_2D, GL_HISTOGRAM, GL_MINMAX, GL_SCISSOR_TEST})
    glDisable(cap);
  glMatrixMode(GL_COLOR);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  for (GLenum p : {GL_RED_SCALE, GL_GREEN_SCALE, GL_BLUE_SCALE, GL_ALPHA_SCALE,
                   GL_POST_CONVOLUTION_RED_SCALE, GL_POST_CONVOLUTION_GREEN_SCALE,
                   GL_POST_CONVOLUTION_BLUE_SCALE, GL_POST_CONVOLUTION_ALPHA_SCALE,
                   GL_POST_COLOR_MATRIX_RED_SCALE, GL_POST_COLOR_MATRIX_GREEN_SCALE,
                   GL_POST_COLOR_MATRIX_BLUE_SCALE, GL_POST_COLOR_MATRIX_ALPHA_SCALE})
    glPixelTransferf(p, 1.0f);
  for (GLenum p : {GL_RED_BIAS, GL_GREEN_BIAS, GL_BLUE_BIAS, GL_ALPHA_BIAS,
                   GL_POST_CONVOLUTION_RED_BIAS, GL_POST_CONVOLUTION_GREEN_BIAS,
                   GL_POST_CONVOLUTION_BLUE_BIAS, GL_POST_CONVOLUTION_ALPHA_BIAS,
                   GL_POST_COLOR_MATRIX_RED_BIAS, GL_POST_COLOR_MATRIX_GREEN_BIAS,
                   GL_POST_COLOR_MATRIX_BLUE_BIAS, GL_POST_COLOR_MATRIX_ALPHA_BIAS})
    glPixelTransferf(p, 0.0f);
}

std::vector<uint32_t> drain() {
  std::vector<uint32_t> errors;
  for (int i = 0; i < 8; ++i) {
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR) break;
    errors.push_back(e);
  }
  return errors;
}

// Codes of Record::truncatable: which rule a byte's difference may fall under.
constexpr uint8_t kNoTruncation = 0;
constexpr uint8_t kReadTruncation = 1;     // glReadPixels(UNSIGNED_BYTE): the reference truncates
constexpr uint8_t kReturnTruncation = 2;   // written by glAccum(GL_RETURN): accumulation ties
constexpr uint8_t kTextureTruncation = 3;  // texels: the plain rules only

struct Executor {
  const Sequence& s;
  bool exact;
  Record rec;
  bool histogramOn = false, sinkOn = false, convolutionOn = false, histogramSink = false;

  void bytesOut(const std::vector<uint8_t>& b, Origin o, uint8_t trunc) {
    rec.bytes.insert(rec.bytes.end(), b.begin(), b.end());
    rec.byteOrigin.insert(rec.byteOrigin.end(), b.size(), o);
    rec.truncatable.insert(rec.truncatable.end(), b.size(), trunc);
  }
  void exactOut(const std::vector<float>& f, Origin o, uint8_t trunc) {
    rec.exact.insert(rec.exact.end(), f.begin(), f.end());
    rec.byteOrigin.insert(rec.byteOrigin.end(), f.size(), o);
    rec.truncatable.insert(rec.truncatable.end(), f.size(), trunc);
  }
  void floatsOut(const std::vector<float>& f, Origin o) {
    rec.floats.insert(rec.floats.end(), f.begin(), f.end());
    rec.floatOrigin.insert(rec.floatOrigin.end(), f.size(), o);
    rec.floatConvolved.insert(rec.floatConvolved.end(), f.size(), convolutionOn ? 1 : 0);
  }

  // The bound texture's level 0 (its size, then its texels), read with every stage off:
  // glGetTexImage applies the pixel transfer stages itself (3.6.5, 6.1.4), which would
  // compare the read rather than the definition.
  void readTexture() {
    resetImaging();
    GLint tw = 0, th = 0;
    glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &tw);
    glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, &th);
    floatsOut({float(tw), float(th)}, Origin::kTexture);
    const size_t n = size_t(std::max(tw, 0)) * size_t(std::max(th, 0)) * 4;
    if (n == 0) return;
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    if (exact) {
      std::vector<float> t(n, -7.0f);
      glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, t.data());
      exactOut(t, Origin::kTexture, kTextureTruncation);
    } else {
      std::vector<uint8_t> t(n, 0xCD);
      glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, t.data());
      bytesOut(t, Origin::kTexture, kTextureTruncation);
    }
  }

  void call(const Call& c) {
    const auto& e = c.e;
    const auto& i = c.i;
    const auto& f = c.f;
    switch (c.kind) {
      case Kind::kPixelTransfer: glPixelTransferf(e[0], f[0]); break;
      case Kind::kColorTable: {
        std::vector<uint8_t> ub;
        for (float v : f) ub.push_back(uint8_t(std::lround(v * 255.0f)));
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glColorTable(e[0], e[1], i[0], GL_RGBA, e[2],
                     e[2] == GL_FLOAT ? static_cast<const void*>(f.data()) : ub.data());
        break;
      }
      case Kind::kColorTableParameter: glColorTableParameterfv(e[0], e[1], f.data()); break;
      case Kind::kCopyColorTable: glCopyColorTable(e[0], e[1], i[0], i[1], i[2]); break;
      case Kind::kEnable:
      case Kind::kDisable: {
        const bool on = c.kind == Kind::kEnable;
        on ? glEnable(e[0]) : glDisable(e[0]);
        if (e[0] == GL_HISTOGRAM) histogramOn = on;
        if (e[0] == GL_CONVOLUTION_1D || e[0] == GL_CONVOLUTION_2D || e[0] == GL_SEPARABLE_2D)
          convolutionOn = on;
        break;
      }
      case Kind::kLoadColorMatrix:
        glMatrixMode(GL_COLOR);
        glLoadMatrixf(f.data());
        glMatrixMode(GL_MODELVIEW);
        break;
      case Kind::kConvolutionFilter1D:
        glConvolutionFilter1D(GL_CONVOLUTION_1D, e[0], i[0], GL_RGBA, GL_FLOAT, f.data());
        break;
      case Kind::kConvolutionFilter2D:
        glConvolutionFilter2D(GL_CONVOLUTION_2D, e[0], i[0], i[1], GL_RGBA, GL_FLOAT, f.data());
        break;
      case Kind::kSeparableFilter2D:
        glSeparableFilter2D(GL_SEPARABLE_2D, e[0], i[0], i[1], GL_RGBA, GL_FLOAT, f.data(),
                            f.data() + size_t(i[0]) * 4);
        break;
      case Kind::kCopyConvolutionFilter2D:
        glCopyConvolutionFilter2D(GL_CONVOLUTION_2D, e[0], i[0], i[1], i[2], i[3]);
        break;
      case Kind::kConvolutionBorder:
        glConvolutionParameteri(e[0], GL_CONVOLUTION_BORDER_MODE, GLint(e[1]));
        glConvolutionParameterfv(e[0], GL_CONVOLUTION_BORDER_COLOR, f.data());
        break;
      case Kind::kConvolutionScaleBias: glConvolutionParameterfv(e[0], e[1], f.data()); break;
      case Kind::kHistogram:
        glHistogram(GL_HISTOGRAM, i[0], e[0], i[1] ? GL_TRUE : GL_FALSE);
        histogramSink = i[1] != 0;
        break;
      case Kind::kMinmax: glMinmax(GL_MINMAX, e[0], i[0] ? GL_TRUE : GL_FALSE); break;
      case Kind::kScissor: glScissor(i[0], i[1], i[2], i[3]); break;
      case Kind::kAccum: glAccum(e[0], f[0]); break;
      case Kind::kReadPixels: {
        const size_t n = size_t(i[2]) * i[3] * 4;
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        const bool unspecified = histogramOn && histogramSink;  // departure 5
        if (e[0] == GL_FLOAT) {
          std::vector<float> px(n, -7.0f);
          glReadPixels(i[0], i[1], i[2], i[3], GL_RGBA, GL_FLOAT, px.data());
          if (!unspecified) floatsOut(px, Origin::kReadPixels);
        } else if (exact) {
          std::vector<float> px(n, 0xCD / 255.0f);
          glReadPixels(i[0], i[1], i[2], i[3], GL_RGBA, GL_FLOAT, px.data());
          if (!unspecified) exactOut(px, Origin::kReadPixels, kReadTruncation);
        } else {
          std::vector<uint8_t> px(n, 0xCD);
          glReadPixels(i[0], i[1], i[2], i[3], GL_RGBA, GL_UNSIGNED_BYTE, px.data());
          if (!unspecified) bytesOut(px, Origin::kReadPixels, kReadTruncation);
        }
        break;
      }
      case Kind::kCopyPixels:
        glWindowPos2i(i[4], i[5]);
        glCopyPixels(i[0], i[1], i[2], i[3], GL_COLOR);
        break;
      case Kind::kDrawPixels:
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glWindowPos2i(i[2], i[3]);
        glDrawPixels(i[0], i[1], GL_RGBA, GL_UNSIGNED_BYTE, c.b.data());
        break;
      case Kind::kTexImage2D:
      case Kind::kCopyTexImage2D: {
        GLuint tex = 0;
        glGenTextures(1, &tex);
        glBindTexture(GL_TEXTURE_2D, tex);
        const GLint internal = exact ? GL_RGBA32F : GL_RGBA8;
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        if (c.kind == Kind::kTexImage2D)
          glTexImage2D(GL_TEXTURE_2D, 0, internal, i[0], i[1], 0, GL_RGBA, GL_UNSIGNED_BYTE,
                       c.b.data());
        else
          glCopyTexImage2D(GL_TEXTURE_2D, 0, GLenum(internal), i[0], i[1], i[2], i[3], 0);
        readTexture();
        glBindTexture(GL_TEXTURE_2D, 0);
        glDeleteTextures(1, &tex);
        break;
      }
      case Kind::kGetHistogram: {
        GLint width = 0;
        glGetHistogramParameteriv(GL_HISTOGRAM, GL_HISTOGRAM_WIDTH, &width);
        std::vector<float> counts(size_t(std::max(width, 0)) * 4, -7.0f);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glGetHistogram(GL_HISTOGRAM, i[0] ? GL_TRUE : GL_FALSE, e[0], GL_FLOAT, counts.data());
        floatsOut(counts, Origin::kHistogram);
        break;
      }
      case Kind::kGetMinmax: {
        std::vector<float> mm(8, -7.0f);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glGetMinmax(GL_MINMAX, i[0] ? GL_TRUE : GL_FALSE, e[0], GL_FLOAT, mm.data());
        floatsOut(mm, Origin::kMinmax);
        break;
      }
      case Kind::kGetColorTable: {
        GLint width = 0;
        glGetColorTableParameteriv(e[0], GL_COLOR_TABLE_WIDTH, &width);
        std::vector<float> t(size_t(std::max(width, 0)) * 4, -7.0f);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glGetColorTable(e[0], e[1], GL_FLOAT, t.data());
        floatsOut(t, Origin::kColorTable);
        break;
      }
    }
  }

  // The state a sequence may leave behind, back to its initial values (the contexts are
  // reused); tables, filters and histograms are defined by every sequence before it enables
  // or reads them.
  static void resetContext() {
    drain();
    resetImaging();
    const float one[4] = {1, 1, 1, 1}, zero[4] = {0, 0, 0, 0};
    for (GLenum t :
         {GL_COLOR_TABLE, GL_POST_CONVOLUTION_COLOR_TABLE, GL_POST_COLOR_MATRIX_COLOR_TABLE}) {
      glColorTableParameterfv(t, GL_COLOR_TABLE_SCALE, one);
      glColorTableParameterfv(t, GL_COLOR_TABLE_BIAS, zero);
    }
    for (GLenum t : {GL_CONVOLUTION_1D, GL_CONVOLUTION_2D, GL_SEPARABLE_2D}) {
      glConvolutionParameterfv(t, GL_CONVOLUTION_FILTER_SCALE, one);
      glConvolutionParameterfv(t, GL_CONVOLUTION_FILTER_BIAS, zero);
    }
    // glHistogram and glMinmax redefine a table without saying what becomes of its counts and
    // extremes (3.6.3; Mesa keeps the extremes): reset, so no sequence sees an earlier one's.
    glResetHistogram(GL_HISTOGRAM);
    glResetMinmax(GL_MINMAX);
    glBindTexture(GL_TEXTURE_2D, 0);
    glScissor(0, 0, kWindow, kWindow);
    glClearColor(0, 0, 0, 0);
    glClearAccum(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_ACCUM_BUFFER_BIT);
    drain();
  }

  Record run() {
    resetContext();
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glWindowPos2i(0, 0);
    glDrawPixels(s.w, s.h, GL_RGBA, GL_UNSIGNED_BYTE, s.image.data());
    auto setup = drain();
    if (!setup.empty()) rec.errors[-1] = setup;
    for (size_t k = 0; k < s.calls.size(); ++k) {
      call(s.calls[k]);
      auto errs = drain();
      if (!errs.empty()) rec.errors[int(k)] = errs;
    }
    // The window with every stage off.
    resetImaging();
    const bool accum = std::any_of(s.calls.begin(), s.calls.end(), [](const Call& c) {
      return c.kind == Kind::kAccum && c.e[0] == GL_RETURN;
    });
    const uint8_t trunc = accum ? kReturnTruncation : kNoTruncation;
    const size_t n = size_t(kWindow) * kWindow * 4;
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    if (exact) {
      std::vector<float> px(n, -7.0f);
      glReadPixels(0, 0, kWindow, kWindow, GL_RGBA, GL_FLOAT, px.data());
      exactOut(px, Origin::kWindow, trunc);
    } else {
      std::vector<uint8_t> px(n, 0xCD);
      glReadPixels(0, 0, kWindow, kWindow, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
      bytesOut(px, Origin::kWindow, trunc);
    }
    auto tail = drain();
    if (!tail.empty()) rec.errors[int(s.calls.size())] = tail;
    return rec;
  }
};

// ---------------------------------------------------------------- comparison

// Float read-backs: both sides compute in single precision from the same inputs
// (parity_util.h kFloatTolerance); a chain of up to 81 taps, three scale/bias stages and a
// 4x4 matrix adds at most ~100 roundings of 2^-24 relative each on values below 2: 2e-5.
constexpr float kFloatTolerance = 2e-5f;
// A byte is a rounding tie when its exact value times 255 lies this close to k + 0.5: the
// same single-precision error bound as above, in byte units (255 * 2e-5).
constexpr float kTieWindow = 5e-3f;
constexpr float kMesaSaturationStart = 0.99609375f;  // parity_util.h

float clamp01(float v) { return v < 0.0f ? 0.0f : (v > 1.0f ? 1.0f : v); }

// One step of the 16-bit accumulation buffer, in 8-bit units (imaging/accumulation.cpp).
constexpr float kAccumStepInBytes = 255.0f / 32767.0f;

}  // namespace

Sequence generate(uint64_t seed) {
  Gen g(seed);
  Sequence s = g.run();
  s.seed = seed;
  return s;
}

Record execute(const Sequence& s, bool exact) { return Executor{s, exact, {}}.run(); }

Runs runAll(const Sequence& s) {
  // One context per side for the whole process, reset between sequences (Executor::run):
  // the reference allocates a thread-specific key per context made and runs out after about a
  // thousand, and making a context costs more than most sequences.
  struct Contexts {
    std::unique_ptr<GlContext> reference, emulated, exact;
  };
  static Contexts contexts;
  auto make = [](Backend backend, ColorFormat color, Mode mode) {
    ContextSpec spec;
    spec.backend = backend;
    spec.width = kWindow;
    spec.height = kWindow;
    spec.color = color;
    // The Debian contexts have no accumulation buffer: the emulation's is used.
    spec.accumulation = backend == Backend::kReference;
    auto ctx = GlContext::create(spec);
    if (install(*ctx) != mode) throw GlError("imaging fuzz: unexpected imaging mode on a context");
    return ctx;
  };
  if (!contexts.reference) {
    contexts.reference = make(Backend::kReference, ColorFormat::kRgba8, Mode::kNative);
    contexts.emulated = make(Backend::kOsmesa, ColorFormat::kRgba8, Mode::kEmulated);
    contexts.exact = make(Backend::kOsmesa, ColorFormat::kRgba32f, Mode::kEmulated);
  }
  Runs runs;
  contexts.reference->makeCurrent();
  runs.reference = execute(s, false);
  contexts.emulated->makeCurrent();
  runs.emulated = execute(s, false);
  contexts.exact->makeCurrent();
  runs.exact = execute(s, true);
  return runs;
}

Verdict compare(const Sequence& s, const Runs& runs) {
  Verdict v;
  const Record& e = runs.emulated;
  const Record& r = runs.reference;
  auto fail = [&v](const std::string& line) {
    if (v.unexplained.size() < 8) v.unexplained.push_back(line);
    ++v.unexplainedCount;
    // The class: the line up to its first digit after the kind ("byte", "float", ...) and
    // its origin, e.g. "float (origin 4)".
    std::string cls = line.substr(0, line.find(' '));
    const size_t o = line.find("(origin ");
    if (o != std::string::npos) cls += " " + line.substr(o, line.find(')', o) - o + 1);
    v.classes.insert(cls);
  };
  if (e.errors != r.errors) {
    std::ostringstream m;
    m << "GL errors differ:";
    for (const auto* side : {&e, &r}) {
      m << (side == &e ? " emulated {" : " reference {");
      for (const auto& [k, list] : side->errors) {
        m << " call " << k << ":";
        for (uint32_t x : list) m << " 0x" << std::hex << x << std::dec;
      }
      m << " }";
    }
    fail(m.str());
  }
  // Accumulation: each operation rounds or truncates to the 16-bit buffer's step on either
  // side (the buffer's precision and rounding are the implementation's, 4.2.4), up to a step
  // each, and GL_RETURN scales the sum (the reference truncates GL_MULT: seed 10719).
  // The value written is then a tie if it lies within that many steps of k + 0.5.
  int accumOps = 0;
  float returnScale = 1.0f;
  for (const Call& c : s.calls) {
    if (c.kind != Kind::kAccum) continue;
    if (c.e[0] == GL_RETURN)
      returnScale = std::max(returnScale, std::fabs(c.f[0]));
    else
      ++accumOps;
  }
  const float accumWindow = float(accumOps + 1) * kAccumStepInBytes * returnScale;
  if (e.bytes.size() != r.bytes.size()) {
    fail("byte counts differ: emulated " + std::to_string(e.bytes.size()) + ", reference " +
         std::to_string(r.bytes.size()));
  } else {
    const bool haveExact = runs.exact.exact.size() == e.bytes.size();
    for (size_t k = 0; k < e.bytes.size(); ++k) {
      const int a = e.bytes[k], b = r.bytes[k];
      if (a == b) continue;
      const char* name = nullptr;
      if (haveExact) {
        const float x = clamp01(runs.exact.exact[k]);
        const float t = x * 255.0f;
        const bool nearest =
            a == int(std::floor(t + 0.5f)) || std::fabs(t - std::floor(t) - 0.5f) <= kTieWindow;
        if (a == 254 && b == 255 && x >= kMesaSaturationStart && x < 254.5f / 255.0f)
          name = "AdditionalF: saturation band (the reference writes 255)";
        else if (std::abs(a - b) == 1 && std::fabs(t - std::floor(t) - 0.5f) <= kTieWindow)
          name = "rounding tie (either way in single precision)";
        else if (std::abs(a - b) == 1 && e.truncatable[k] == kReturnTruncation &&
                 std::fabs(t - std::floor(t) - 0.5f) <= accumWindow)
          name = "accumulation: a tie within the 16-bit buffer's rounding";
        else if (nearest &&
                 (b == int(std::floor(t)) || b == int(std::floor(t + kTieWindow)) ||
                  b == int(std::floor(t - kTieWindow))) &&
                 e.truncatable[k] == kReadTruncation)
          name = "AdditionalA: glReadPixels(UNSIGNED_BYTE) truncates";
      }
      if (name != nullptr) {
        ++v.explained[name];
        continue;
      }
      std::ostringstream m;
      m << "byte " << k << " (origin " << int(e.byteOrigin[k]) << ", pixel " << k / 4
        << ", component " << k % 4 << "): emulated " << a << ", reference " << b;
      if (haveExact) m << ", exact " << runs.exact.exact[k] * 255.0f << "/255";
      fail(m.str());
    }
  }
  if (e.floats.size() != r.floats.size()) {
    fail("float counts differ: emulated " + std::to_string(e.floats.size()) + ", reference " +
         std::to_string(r.floats.size()));
  } else {
    for (size_t k = 0; k < e.floats.size(); ++k) {
      const float a = e.floats[k], b = r.floats[k];
      if (std::fabs(a - b) <= kFloatTolerance) continue;
      const char* name = nullptr;
      if (e.floatOrigin[k] == Origin::kReadPixels && e.floatConvolved[k] &&
          std::fabs(clamp01(b) - a) <= kFloatTolerance)
        name = "Departure1: float glReadPixels after convolution unclamped";
      else if (e.floatOrigin[k] == Origin::kMinmax && std::fabs(clamp01(a) - b) <= kFloatTolerance)
        name = "AdditionalC: minmax extremes clamped";
      if (name != nullptr) {
        ++v.explained[name];
        continue;
      }
      std::ostringstream m;
      m << "float " << k << " (origin " << int(e.floatOrigin[k]) << "): emulated " << a
        << ", reference " << b;
      fail(m.str());
    }
  }
  return v;
}

// ---------------------------------------------------------------- printing

namespace {

std::string enumName(uint32_t e) {
  switch (e) {
#define N(x) \
  case x: return #x;
    // clang-format off
    N(GL_RED_SCALE) N(GL_GREEN_SCALE) N(GL_BLUE_SCALE)
    N(GL_ALPHA_SCALE) N(GL_RED_BIAS) N(GL_GREEN_BIAS)
    N(GL_BLUE_BIAS) N(GL_ALPHA_BIAS) N(GL_POST_CONVOLUTION_RED_SCALE)
    N(GL_POST_CONVOLUTION_GREEN_SCALE) N(GL_POST_CONVOLUTION_BLUE_SCALE) N(GL_POST_CONVOLUTION_ALPHA_SCALE)
    N(GL_POST_CONVOLUTION_RED_BIAS) N(GL_POST_CONVOLUTION_BLUE_BIAS) N(GL_POST_CONVOLUTION_ALPHA_BIAS)
    N(GL_POST_COLOR_MATRIX_RED_SCALE) N(GL_POST_COLOR_MATRIX_BLUE_SCALE) N(GL_POST_COLOR_MATRIX_ALPHA_SCALE)
    N(GL_POST_COLOR_MATRIX_RED_BIAS) N(GL_POST_COLOR_MATRIX_BLUE_BIAS) N(GL_POST_COLOR_MATRIX_ALPHA_BIAS)
    N(GL_COLOR_TABLE) N(GL_POST_COLOR_MATRIX_COLOR_TABLE) N(GL_COLOR_TABLE_SCALE)
    N(GL_COLOR_TABLE_BIAS) N(GL_CONVOLUTION_1D) N(GL_CONVOLUTION_2D)
    N(GL_SEPARABLE_2D) N(GL_REDUCE) N(GL_REPLICATE_BORDER)
    N(GL_CONVOLUTION_FILTER_SCALE) N(GL_CONVOLUTION_FILTER_BIAS) N(GL_HISTOGRAM)
    N(GL_MINMAX) N(GL_SCISSOR_TEST) N(GL_ALPHA)
    N(GL_RGB) N(GL_RGBA) N(GL_LUMINANCE)
    N(GL_LUMINANCE_ALPHA) N(GL_INTENSITY) N(GL_ALPHA8)
    N(GL_RGB8) N(GL_RGBA8) N(GL_LUMINANCE8)
    N(GL_LUMINANCE8_ALPHA8) N(GL_INTENSITY8) N(GL_RED)
    N(GL_FLOAT) N(GL_UNSIGNED_BYTE) N(GL_LOAD)
    N(GL_ACCUM) N(GL_MULT) N(GL_ADD)
    N(GL_RETURN)
    // clang-format on
#undef N
                                                                default : {
      char buf[16];
      std::snprintf(buf, sizeof buf, "0x%04x", unsigned(e));
      return buf;
    }
  }
}

std::string num(float v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", double(v));
  const bool integral = std::string(buf).find_first_of(".en") == std::string::npos;
  return std::string(buf) + (integral ? ".0f" : "f");
}

std::string floats(const std::vector<float>& f, size_t from = 0, size_t n = std::string::npos) {
  std::string out = "{";
  const size_t end = n == std::string::npos ? f.size() : from + n;
  for (size_t k = from; k < end; ++k) out += (k > from ? ", " : "") + num(f[k]);
  return out + "}";
}

std::string bytesC(const std::vector<uint8_t>& b) {
  std::string out = "{";
  for (size_t k = 0; k < b.size(); ++k) out += (k ? "," : "") + std::to_string(int(b[k]));
  return out + "}";
}

}  // namespace

std::string toC(const Sequence& s) {
  std::ostringstream o;
  o << "// imaging_fuzz seed " << s.seed << ": a " << s.w << "x" << s.h << " image in a " << kWindow
    << "x" << kWindow << " window cleared to 0; `buffer` receives each read\n";
  o << "{\n";
  o << "  static const GLubyte image[] = " << bytesC(s.image) << ";\n";
  o << "  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);\n  glWindowPos2i(0, 0);\n";
  o << "  glDrawPixels(" << s.w << ", " << s.h << ", GL_RGBA, GL_UNSIGNED_BYTE, image);\n";
  int n = 0;
  for (const Call& c : s.calls) {
    const auto& e = c.e;
    const auto& i = c.i;
    const auto& f = c.f;
    const std::string v = "v" + std::to_string(n++);
    o << "  ";
    switch (c.kind) {
      case Kind::kPixelTransfer:
        o << "glPixelTransferf(" << enumName(e[0]) << ", " << num(f[0]) << ");";
        break;
      case Kind::kColorTable:
        if (e[2] == GL_FLOAT) {
          o << "{ static const GLfloat " << v << "[] = " << floats(f) << ";\n    ";
        } else {
          std::vector<uint8_t> ub;
          for (float x : f) ub.push_back(uint8_t(std::lround(x * 255.0f)));
          o << "{ static const GLubyte " << v << "[] = " << bytesC(ub) << ";\n    ";
        }
        o << "glColorTable(" << enumName(e[0]) << ", " << enumName(e[1]) << ", " << i[0]
          << ", GL_RGBA, " << enumName(e[2]) << ", " << v << "); }";
        break;
      case Kind::kColorTableParameter:
        o << "{ const GLfloat " << v << "[4] = " << floats(f) << "; glColorTableParameterfv("
          << enumName(e[0]) << ", " << enumName(e[1]) << ", " << v << "); }";
        break;
      case Kind::kCopyColorTable:
        o << "glCopyColorTable(" << enumName(e[0]) << ", " << enumName(e[1]) << ", " << i[0] << ", "
          << i[1] << ", " << i[2] << ");";
        break;
      case Kind::kEnable: o << "glEnable(" << enumName(e[0]) << ");"; break;
      case Kind::kDisable: o << "glDisable(" << enumName(e[0]) << ");"; break;
      case Kind::kLoadColorMatrix:
        o << "{ const GLfloat " << v << "[16] = " << floats(f)
          << ";\n    glMatrixMode(GL_COLOR); glLoadMatrixf(" << v
          << "); glMatrixMode(GL_MODELVIEW); }";
        break;
      case Kind::kConvolutionFilter1D:
        o << "{ static const GLfloat " << v << "[] = " << floats(f)
          << ";\n    glConvolutionFilter1D(GL_CONVOLUTION_1D, " << enumName(e[0]) << ", " << i[0]
          << ", GL_RGBA, GL_FLOAT, " << v << "); }";
        break;
      case Kind::kConvolutionFilter2D:
        o << "{ static const GLfloat " << v << "[] = " << floats(f)
          << ";\n    glConvolutionFilter2D(GL_CONVOLUTION_2D, " << enumName(e[0]) << ", " << i[0]
          << ", " << i[1] << ", GL_RGBA, GL_FLOAT, " << v << "); }";
        break;
      case Kind::kSeparableFilter2D:
        o << "{ static const GLfloat " << v << "r[] = " << floats(f, 0, size_t(i[0]) * 4)
          << ";\n    static const GLfloat " << v << "c[] = " << floats(f, size_t(i[0]) * 4)
          << ";\n    glSeparableFilter2D(GL_SEPARABLE_2D, " << enumName(e[0]) << ", " << i[0]
          << ", " << i[1] << ", GL_RGBA, GL_FLOAT, " << v << "r, " << v << "c); }";
        break;
      case Kind::kCopyConvolutionFilter2D:
        o << "glCopyConvolutionFilter2D(GL_CONVOLUTION_2D, " << enumName(e[0]) << ", " << i[0]
          << ", " << i[1] << ", " << i[2] << ", " << i[3] << ");";
        break;
      case Kind::kConvolutionBorder:
        o << "{ const GLfloat " << v << "[4] = " << floats(f) << ";\n    glConvolutionParameteri("
          << enumName(e[0]) << ", GL_CONVOLUTION_BORDER_MODE, " << enumName(e[1])
          << ");\n    glConvolutionParameterfv(" << enumName(e[0])
          << ", GL_CONVOLUTION_BORDER_COLOR, " << v << "); }";
        break;
      case Kind::kConvolutionScaleBias:
        o << "{ const GLfloat " << v << "[4] = " << floats(f) << "; glConvolutionParameterfv("
          << enumName(e[0]) << ", " << enumName(e[1]) << ", " << v << "); }";
        break;
      case Kind::kHistogram:
        o << "glHistogram(GL_HISTOGRAM, " << i[0] << ", " << enumName(e[0]) << ", "
          << (i[1] ? "GL_TRUE" : "GL_FALSE") << ");";
        break;
      case Kind::kMinmax:
        o << "glMinmax(GL_MINMAX, " << enumName(e[0]) << ", " << (i[0] ? "GL_TRUE" : "GL_FALSE")
          << ");";
        break;
      case Kind::kScissor:
        o << "glScissor(" << i[0] << ", " << i[1] << ", " << i[2] << ", " << i[3] << ");";
        break;
      case Kind::kAccum: o << "glAccum(" << enumName(e[0]) << ", " << num(f[0]) << ");"; break;
      case Kind::kReadPixels:
        o << "/* read */ glReadPixels(" << i[0] << ", " << i[1] << ", " << i[2] << ", " << i[3]
          << ", GL_RGBA, " << enumName(e[0]) << ", buffer);";
        break;
      case Kind::kCopyPixels:
        o << "glWindowPos2i(" << i[4] << ", " << i[5] << "); glCopyPixels(" << i[0] << ", " << i[1]
          << ", " << i[2] << ", " << i[3] << ", GL_COLOR);";
        break;
      case Kind::kDrawPixels:
        o << "{ static const GLubyte " << v << "[] = " << bytesC(c.b) << ";\n    glWindowPos2i("
          << i[2] << ", " << i[3] << "); glDrawPixels(" << i[0] << ", " << i[1]
          << ", GL_RGBA, GL_UNSIGNED_BYTE, " << v << "); }";
        break;
      case Kind::kTexImage2D:
        o << "{ static const GLubyte " << v << "[] = " << bytesC(c.b)
          << ";\n    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, " << i[0] << ", " << i[1]
          << ", 0, GL_RGBA, GL_UNSIGNED_BYTE, " << v << "); /* read: glGetTexImage */ }";
        break;
      case Kind::kCopyTexImage2D:
        o << "glCopyTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, " << i[0] << ", " << i[1] << ", " << i[2]
          << ", " << i[3] << ", 0); /* read: glGetTexImage */";
        break;
      case Kind::kGetHistogram:
        o << "/* read */ glGetHistogram(GL_HISTOGRAM, " << (i[0] ? "GL_TRUE" : "GL_FALSE") << ", "
          << enumName(e[0]) << ", GL_FLOAT, buffer);";
        break;
      case Kind::kGetMinmax:
        o << "/* read */ glGetMinmax(GL_MINMAX, " << (i[0] ? "GL_TRUE" : "GL_FALSE") << ", "
          << enumName(e[0]) << ", GL_FLOAT, buffer);";
        break;
      case Kind::kGetColorTable:
        o << "/* read */ glGetColorTable(" << enumName(e[0]) << ", " << enumName(e[1])
          << ", GL_FLOAT, buffer);";
        break;
    }
    o << "\n";
  }
  o << "  /* read: the window with every stage off, GL_UNSIGNED_BYTE */\n}\n";
  return o.str();
}

namespace {

// Calls that define an object or a mode a later call relies on: dropped only with their group.
bool defines(Kind k) {
  switch (k) {
    case Kind::kColorTable:
    case Kind::kCopyColorTable:
    case Kind::kConvolutionFilter1D:
    case Kind::kConvolutionFilter2D:
    case Kind::kSeparableFilter2D:
    case Kind::kCopyConvolutionFilter2D:
    case Kind::kConvolutionBorder:
    case Kind::kHistogram:
    case Kind::kMinmax:
    case Kind::kScissor:
    case Kind::kPixelTransfer:  // one of a grey level's four: dropped with its group only
    case Kind::kLoadColorMatrix: return true;
    default: return false;
  }
}

}  // namespace

Sequence minimise(const Sequence& s) {
  Sequence best = s;
  const Verdict first = compare(s, runAll(s));
  if (first.classes.empty()) return best;
  const std::string cls = *first.classes.begin();  // keep this kind of difference
  auto keeps = [&cls](const Sequence& trial) {
    return compare(trial, runAll(trial)).classes.count(cls) != 0;
  };
  // Whole features first, then single calls that define nothing.
  std::set<int> groups;
  for (const Call& c : best.calls) groups.insert(c.group);
  for (int g : groups) {
    Sequence trial = best;
    trial.calls.erase(std::remove_if(trial.calls.begin(), trial.calls.end(),
                                     [g](const Call& c) { return c.group == g; }),
                      trial.calls.end());
    if (trial.calls.size() < best.calls.size() && keeps(trial)) best = trial;
  }
  for (size_t k = best.calls.size(); k-- > 0;) {
    if (defines(best.calls[k].kind)) continue;
    Sequence trial = best;
    trial.calls.erase(trial.calls.begin() + long(k));
    if (keeps(trial)) best = trial;
  }
  return best;
}

}  // namespace sl::imaging::fuzz
