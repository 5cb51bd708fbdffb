// imaging/convolution_bytes.cpp — the convolution stage of glspec121 3.6.5 on 8-bit RGBA
// sources for 8-bit destinations (glCopyPixels, glCopyTexSubImage2D of an 8-bit framebuffer),
// fast and bit-identical to the general float path (runPipeline on an Image4, then the final
// conversion of 4.3.2).
//
// The general path computes, per output group and component c: stages 1-3 of each source
// byte (one float per byte value), then C = 0.0f + s_1 * w_1c + s_2 * w_2c + ... over the
// taps of kernelTaps() in their order, one float multiply and one float add per term
// (accumulateTaps), then the post-convolution scale/bias C * scale + bias, stages 5-7 and the
// final conversion. The three forms here give exactly its bytes:
//   1. byte gather (gatherRows): when every component has at most one non-zero tap — the
//      Brabec-Seidel packing kernel of their Eq. (1) has one per component, weight 1 — and
//      every later stage works per component, output byte c is a function of ONE source byte
//      (or of the border colour). The function is tabulated for the 256 byte values and the
//      border by the very same stage code, so the pass is a byte gather.
//   2. SIMD sums (sumRow*): any other kernel. Padded rows of stage 1-3 floats are converted
//      once into a ring of Hf rows that stays in cache; each output vector is summed over the
//      taps in kernelTaps' order with separate multiply and add instructions (no FMA: the
//      AVX2 code is compiled for "avx2" only, so the compiler cannot contract them), then
//      scaled, biased and converted to bytes in registers when stages 5-9 are identity.
//   3. integer sums (dyadicRows; separableRows where the numerators are an outer product,
//      the binomial blurs, with adds only for the 3x3 one): kernels whose weights are
//      multiples of 2^-D on the plain 8-bit prefix with nothing after the convolution: exact
//      integer sums give every byte but the rounding ties, which are summed again in floats
//      in tap order (the error bound that makes this exact is at form 3 below).
//
// Why terms with a zero weight may be skipped (form 1) or added (form 2) although the general
// path skips some and adds others: the sum starts at +0.0f and a round-to-nearest sum is -0
// only when both addends are -0, so the running sum is never -0; adding +-0 (a finite value
// times a zero weight) to anything but -0 returns it unchanged. Both forms therefore require
// finite stage 1-3 values and a finite border colour; otherwise the strip path of
// fast_paths.cpp (the general stage code on float rows) runs instead.
//
// Separable filters: the general path convolves with the dense product kernel
// row[n] * column[m] (kernelTaps), not a row pass then a column pass (which rounds
// differently), so form 2 runs that same product kernel.
#include <cmath>
#include <cstring>
#include <numeric>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define SL_CONVOLUTION_X86 1
#endif

#include "imaging/internal.h"

namespace sl::imaging::detail {
namespace {

constexpr int kByteValues = 256;                // source byte values 0..255
constexpr int kBorderEntry = kByteValues;       // a component table's entry for the border
constexpr int kTableEntries = kByteValues + 1;  // byte values, then the border colour
constexpr int kGroup = 4;                       // floats (or bytes) per RGBA group
constexpr int kMaxTaps = kMaxConvolutionWidth * kMaxConvolutionHeight;
constexpr float kOneOver255 = 1.0f / 255.0f;           // only to split 1/255 into hi + lo below
constexpr uint32_t kSixteenBitMantissa = 0xFFFFFF00u;  // clears 8 of float's 24 mantissa bits

// The final conversion of 4.3.2 / 2.13.9 to a byte (fast_paths.cpp's toByte).
inline uint8_t toByte(float v) {
  const float c = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
  return uint8_t(c * 255.0f + 0.5f);
}

// toByte over a span; SSE2 four at a time: maxps(v, 0) is v > 0 ? v : 0 (NaN gives 0) and
// minps(c, 1) is c < 1 ? c : 1, toByte's own comparisons, then the same multiply, add and
// truncation.
void rowToBytes(const float* v, uint8_t* o, size_t n) {
  size_t i = 0;
#if defined(__SSE2__)
  const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
  const __m128 scale = _mm_set1_ps(255.0f), half = _mm_set1_ps(0.5f);
  for (; i + 4 <= n; i += 4) {
    const __m128 c = _mm_min_ps(_mm_max_ps(_mm_loadu_ps(v + i), zero), one);
    const __m128i q = _mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(c, scale), half));
    const __m128i w = _mm_packs_epi32(q, q);
    const int bytes = _mm_cvtsi128_si32(_mm_packus_epi16(w, w));
    std::memcpy(o + i, &bytes, 4);
  }
#endif
  for (; i < n; ++i) o[i] = toByte(v[i]);
}

bool finiteValues(const float* v, size_t n) {
  for (size_t i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

// Everything both forms need: the filter geometry, stages 1-3 of the 256 byte values and the
// stages after the convolution.
struct Convolution {
  std::vector<Tap> taps;
  int wf = 0, hf = 0;  // filter size
  int cw = 0, ch = 0;  // Cw, Ch (0 under REDUCE): output (i, j) reads padded (i + n, j + m)
  int ws = 0, hs = 0, ow = 0, oh = 0;
  int pw = 0;  // padded row width in groups
  bool reduce = false, replicate = false;
  Rgba border{};
  Image4 values{kByteValues, 1};  // stages 1-3 of byte value v, component c: px[v * 4 + c]
  TransferState suffix;           // stages 5-7 (stage 4's scale/bias is applied separately)
  bool suffixIdentity = true;
  bool perComponent = true;  // stages 5-7 map each component alone (identity color matrix)
  bool postScaleBias = false;
  Rgba postScale{1, 1, 1, 1}, postBias{0, 0, 0, 0};
};

// Stages 1-3 of the 256 byte values, per component, by the general stage code.
void stageValues(const TransferState& t, Image4& values) {
  TransferState prefix = t;  // (a copy: GCC 12 warns on TransferState's default constructor)
  prefix.convolution1DEnabled = prefix.convolution2DEnabled = prefix.separable2DEnabled = false;
  prefix.postConvolutionTableEnabled = prefix.postColorMatrixTableEnabled = false;
  prefix.colorMatrixStack = {Matrix4{}};
  prefix.postColorMatrixScale = {1, 1, 1, 1};
  prefix.postColorMatrixBias = {0, 0, 0, 0};
  prefix.histogramEnabled = prefix.minmaxEnabled = false;
  for (int v = 0; v < kByteValues; ++v)
    for (int c = 0; c < kGroup; ++c) values.px[size_t(v) * kGroup + c] = float(v) / 255.0f;
  runPipeline(prefix, values, Dimensionality::k2D);
}

Convolution prepare(const TransferState& t, int ws, int hs) {
  Convolution cv;
  const bool separable = !t.convolution2DEnabled;
  const ConvolutionFilter& f = separable ? t.separable2D : t.conv2D;
  cv.taps = kernelTaps(f, separable, cv.wf, cv.hf);
  cv.reduce = f.borderMode == GL_REDUCE;
  cv.replicate = f.borderMode == GL_REPLICATE_BORDER;
  cv.border = f.borderColor;
  cv.ws = ws;
  cv.hs = hs;
  cv.ow = cv.reduce ? ws - cv.wf + 1 : ws;
  cv.oh = cv.reduce ? hs - cv.hf + 1 : hs;
  cv.cw = cv.reduce ? 0 : cv.wf / 2;
  cv.ch = cv.reduce ? 0 : cv.hf / 2;
  cv.pw = cv.reduce ? ws : ws + cv.wf - 1;
  stageValues(t, cv.values);
  // Stages 5-7 only (histogram and minmax are taken on the caller's state).
  TransferState& s = cv.suffix;
  s = t;
  s.scale = {1, 1, 1, 1};
  s.bias = {0, 0, 0, 0};
  s.mapColor = false;
  s.colorTableEnabled = false;
  s.convolution1DEnabled = s.convolution2DEnabled = s.separable2DEnabled = false;
  s.histogramEnabled = s.minmaxEnabled = false;
  cv.suffixIdentity = pipelineIsIdentity(s, Dimensionality::k2D);
  cv.perComponent = s.colorMatrixStack.back().isIdentity();
  cv.postScale = t.postConvolutionScale;
  cv.postBias = t.postConvolutionBias;
  cv.postScaleBias = !(cv.postScale == Rgba{1, 1, 1, 1} && cv.postBias == Rgba{0, 0, 0, 0});
  return cv;
}

// The post-convolution scale/bias (as runPipeline's scaleBias forms it), stages 5-7, then
// histogram and minmax on `counting` (when given), then the final conversion of one row of
// sums. False when a sink took the row (nothing written).
bool finishRow(Convolution& cv, TransferState* counting, Image4& row, uint8_t* out) {
  if (cv.postScaleBias)
    for (size_t i = 0; i < row.px.size(); ++i)
      row.px[i] = row.px[i] * cv.postScale[i & 3] + cv.postBias[i & 3];
  if (!cv.suffixIdentity) runPipeline(cv.suffix, row, Dimensionality::k2D);
  if (counting != nullptr && counting->histogramEnabled) {
    accumulateHistogram(counting->histogram, row);
    if (counting->histogram.sink) return false;
  }
  if (counting != nullptr && counting->minmaxEnabled) {
    accumulateMinmax(counting->minmax, row);
    if (counting->minmax.sink) return false;
  }
  rowToBytes(row.px.data(), out, row.px.size());
  return true;
}

// The instruction set of this call: SSE2 (every x86-64) or AVX2 functions of both forms.
struct RowConversion;
struct RowSums;
struct Kernels {
  // Form 1, identity tables: groups [x, xb) of an output row where component c of group x is
  // byte c of base[c] + 4x; returns the first group not written.
  int (*blend)(const uint8_t* const* base, uint8_t* out, int x, int xb) = nullptr;
  void (*convert)(const RowConversion&, const uint8_t*, float*, int) = nullptr;
  void (*sums)(const RowSums&, float*, uint8_t*) = nullptr;
  void (*bytes)(const RowSums&, float*, uint8_t*) = nullptr;
};

// ---------------------------------------------------------------- form 1: byte gather
// Output byte c of group (x, y) = table[c][source byte c at (x + dx[c], y + dy[c])], the
// coordinates clamped under REPLICATE and table[c][kBorderEntry] outside under CONSTANT.
struct GatherPlan {
  int dx[kGroup] = {}, dy[kGroup] = {};  // n - Cw, m - Ch of the component's tap
  uint8_t table[kGroup][kTableEntries] = {};
  bool identity = true;  // every table maps each byte value to itself
};

// Builds the plan when every component has at most one non-zero tap and stages 5-7 are per
// component. table[c][v] is what the general path gives a group whose only contributing
// source value is v: the sum 0.0f + value * weight (accumulateTaps' operations; a component
// without a tap sums to 0.0f), then finishRow — the same code the sums go through.
bool planGather(Convolution& cv, GatherPlan& plan) {
  if (!cv.perComponent) return false;
  int tapOf[kGroup] = {-1, -1, -1, -1};
  for (size_t i = 0; i < cv.taps.size(); ++i)
    for (int c = 0; c < kGroup; ++c) {
      if (cv.taps[i].w[c] == 0.0f) continue;
      if (tapOf[c] >= 0) return false;
      tapOf[c] = int(i);
    }
  Image4 sums(kTableEntries, 1);
  for (int c = 0; c < kGroup; ++c) {
    const Tap* tap = tapOf[c] >= 0 ? &cv.taps[size_t(tapOf[c])] : nullptr;
    // No tap: a constant table; the centre keeps the (unused) source reads in range.
    plan.dx[c] = tap != nullptr ? tap->n - cv.cw : 0;
    plan.dy[c] = tap != nullptr ? tap->m - cv.ch : 0;
    for (int v = 0; v < kTableEntries; ++v) {
      const float x = v == kBorderEntry ? cv.border[c] : cv.values.px[size_t(v) * kGroup + c];
      float sum = 0.0f;
      if (tap != nullptr) sum += x * tap->w[c];
      sums.px[size_t(v) * kGroup + c] = sum;
    }
  }
  uint8_t bytes[kTableEntries * kGroup];
  finishRow(cv, nullptr, sums, bytes);
  for (int v = 0; v < kTableEntries; ++v)
    for (int c = 0; c < kGroup; ++c) {
      plan.table[c][v] = bytes[v * kGroup + c];
      if (v < kByteValues && bytes[v * kGroup + c] != v) plan.identity = false;
    }
  return true;
}

// Rows [y0, y1) of the gather.
void gatherRows(const Convolution& cv, const GatherPlan& plan, const Kernels& k, const uint8_t* src,
                uint8_t* out, int y0, int y1) {
  const int ws = cv.ws, hs = cv.hs, ow = cv.ow;
  // The interior columns, where every component's source column is inside the image.
  int xa = 0, xb = ow;
  for (int c = 0; c < kGroup; ++c) {
    xa = std::max(xa, -plan.dx[c]);
    xb = std::min(xb, ws - plan.dx[c]);
  }
  for (int y = y0; y < y1; ++y) {
    const uint8_t* rows[kGroup];
    bool borderRow = false;  // some component reads a CONSTANT border row
    for (int c = 0; c < kGroup; ++c) {
      int sy = y + plan.dy[c];
      if (sy < 0 || sy >= hs) {
        borderRow = borderRow || !cv.replicate;
        sy = std::clamp(sy, 0, hs - 1);
      }
      rows[c] = src + size_t(sy) * ws * kGroup;
    }
    uint8_t* const o = out + size_t(y) * ow * kGroup;
    // Any group, with the border rules: the edges, and whole rows that touch a border row.
    auto gatherGroup = [&](int x) {
      for (int c = 0; c < kGroup; ++c) {
        const int sy = y + plan.dy[c], sx = x + plan.dx[c];
        const bool inside = sx >= 0 && sx < ws && sy >= 0 && sy < hs;
        o[x * kGroup + c] =
            inside || cv.replicate
                ? plan.table[c][rows[c][size_t(std::clamp(sx, 0, ws - 1)) * kGroup + c]]
                : plan.table[c][kBorderEntry];
      }
    };
    if (borderRow || xa >= xb) {
      for (int x = 0; x < ow; ++x) gatherGroup(x);
      continue;
    }
    for (int x = 0; x < xa; ++x) gatherGroup(x);
    for (int x = xb; x < ow; ++x) gatherGroup(x);
    const uint8_t* s[kGroup];
    for (int c = 0; c < kGroup; ++c) s[c] = rows[c] + ptrdiff_t(plan.dx[c]) * kGroup + c;
    int x = xa;
    if (plan.identity && k.blend != nullptr) {
      const uint8_t* base[kGroup];
      for (int c = 0; c < kGroup; ++c) base[c] = s[c] - c;
      x = k.blend(base, o, x, xb);
    }
    for (; x < xb; ++x) {
      const size_t i = size_t(x) * kGroup;
      const uint32_t v = uint32_t(plan.table[0][s[0][i]]) | uint32_t(plan.table[1][s[1][i]]) << 8 |
                         uint32_t(plan.table[2][s[2][i]]) << 16 |
                         uint32_t(plan.table[3][s[3][i]]) << 24;
      std::memcpy(o + i, &v, 4);  // RGBA bytes, little-endian
    }
  }
}

// ---------------------------------------------------------------- form 2: SIMD sums
// Stages 1-3 of a source row as floats. Where the stages are at most the stage 1 scale/bias,
// v / 255 is computed as v * hi + v * lo (1/255 = hi + lo, hi with 16 significant bits so that
// v * hi is exact), then * scale + bias; this form is used only after it reproduced the
// table (the general stage code's floats) bit for bit on all 256 byte values.
struct RowConversion {
  bool arithmetic = false;
  float hi = 0.0f, lo = 0.0f;
  bool scaled = false;
  Rgba scale{1, 1, 1, 1}, bias{0, 0, 0, 0};
  const float* table = nullptr;  // Convolution::values.px
};

void convertTable(const RowConversion& rc, const uint8_t* in, float* out, int n) {
  for (int i = 0; i < n; i += kGroup)
    for (int c = 0; c < kGroup; ++c) out[i + c] = rc.table[size_t(in[i + c]) * kGroup + c];
}

// One output row: sources[t] is the first float tap t reads (output group 0).
struct RowSums {
  const float* const* sources;
  const Tap* taps;
  int count;   // taps
  int floats;  // ow * 4
  bool postScaleBias;
  const float* postScale;  // 4 floats
  const float* postBias;
};

#if defined(__SSE2__)
// Identity tables: each output byte IS its source byte, so four groups at a time are the OR of
// each component's source bytes under that component's byte mask.
int blendSse2(const uint8_t* const* sources, uint8_t* out, int x, int xb) {
  const uint8_t* base[kGroup];  // a local copy: the stores through `out` cannot alias it
  std::memcpy(base, sources, sizeof base);
  __m128i mask[kGroup];
  for (int c = 0; c < kGroup; ++c) mask[c] = _mm_set1_epi32(int(0xFFu << (8 * c)));
  for (; x + 4 <= xb; x += 4) {
    __m128i v = _mm_setzero_si128();
    for (int c = 0; c < kGroup; ++c) {
      const __m128i in =
          _mm_loadu_si128(reinterpret_cast<const __m128i*>(base[c] + size_t(x) * kGroup));
      v = _mm_or_si128(v, _mm_and_si128(in, mask[c]));
    }
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + size_t(x) * kGroup), v);
  }
  return x;
}

// Baseline x86-64: four floats (one group) per vector.
void convertSse2(const RowConversion& rc, const uint8_t* in, float* out, int n) {
  const __m128 hi = _mm_set1_ps(rc.hi), lo = _mm_set1_ps(rc.lo);
  const __m128 scale = _mm_loadu_ps(rc.scale.data()), bias = _mm_loadu_ps(rc.bias.data());
  const __m128i zero = _mm_setzero_si128();
  for (int i = 0; i < n; i += kGroup) {
    int word;
    std::memcpy(&word, in + i, 4);
    const __m128i b = _mm_unpacklo_epi16(_mm_unpacklo_epi8(_mm_cvtsi32_si128(word), zero), zero);
    const __m128 f = _mm_cvtepi32_ps(b);
    __m128 v = _mm_add_ps(_mm_mul_ps(f, hi), _mm_mul_ps(f, lo));
    if (rc.scaled) v = _mm_add_ps(_mm_mul_ps(v, scale), bias);
    _mm_storeu_ps(out + i, v);
  }
}

inline void storeBytes4(__m128 v, uint8_t* o) {
  const __m128 c = _mm_min_ps(_mm_max_ps(v, _mm_setzero_ps()), _mm_set1_ps(1.0f));
  const __m128i q =
      _mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(c, _mm_set1_ps(255.0f)), _mm_set1_ps(0.5f)));
  const __m128i w = _mm_packs_epi32(q, q);
  const int bytes = _mm_cvtsi128_si32(_mm_packus_epi16(w, w));
  std::memcpy(o, &bytes, 4);
}

constexpr int kSse2Block = 4;  // vectors summed side by side (independent add chains)

// sums (or bytes, when kBytes: post scale/bias and final conversion in registers) of one row.
template <bool kBytes>
void sumRowSse2(const RowSums& r, float* sums, uint8_t* bytes) {
  __m128 w[kMaxTaps];
  for (int t = 0; t < r.count; ++t) w[t] = _mm_loadu_ps(r.taps[t].w);
  const __m128 scale = _mm_loadu_ps(r.postScale), bias = _mm_loadu_ps(r.postBias);
  auto finish = [&](__m128 acc, int i) {
    if constexpr (kBytes) {
      if (r.postScaleBias) acc = _mm_add_ps(_mm_mul_ps(acc, scale), bias);
      storeBytes4(acc, bytes + i);
    } else {
      _mm_storeu_ps(sums + i, acc);
    }
  };
  int i = 0;
  for (; i + kGroup * kSse2Block <= r.floats; i += kGroup * kSse2Block) {
    __m128 acc[kSse2Block];
    for (int k = 0; k < kSse2Block; ++k) acc[k] = _mm_setzero_ps();
    for (int t = 0; t < r.count; ++t) {
      const float* p = r.sources[t] + i;
      for (int k = 0; k < kSse2Block; ++k)
        acc[k] = _mm_add_ps(acc[k], _mm_mul_ps(_mm_loadu_ps(p + kGroup * k), w[t]));
    }
    for (int k = 0; k < kSse2Block; ++k) finish(acc[k], i + kGroup * k);
  }
  for (; i < r.floats; i += kGroup) {
    __m128 acc = _mm_setzero_ps();
    for (int t = 0; t < r.count; ++t)
      acc = _mm_add_ps(acc, _mm_mul_ps(_mm_loadu_ps(r.sources[t] + i), w[t]));
    finish(acc, i);
  }
}
#endif

#if defined(SL_CONVOLUTION_X86)
#pragma GCC push_options
#pragma GCC target("avx2")  // NOT "fma": the multiply and the add must stay two roundings
// AVX2: eight groups of bytes, or eight floats (two groups), per vector.
int blendAvx2(const uint8_t* const* sources, uint8_t* out, int x, int xb) {
  const uint8_t* base[kGroup];  // a local copy: the stores through `out` cannot alias it
  std::memcpy(base, sources, sizeof base);
  __m256i mask[kGroup];
  for (int c = 0; c < kGroup; ++c) mask[c] = _mm256_set1_epi32(int(0xFFu << (8 * c)));
  for (; x + 8 <= xb; x += 8) {
    __m256i v = _mm256_setzero_si256();
    for (int c = 0; c < kGroup; ++c) {
      const __m256i in =
          _mm256_loadu_si256(reinterpret_cast<const __m256i*>(base[c] + size_t(x) * kGroup));
      v = _mm256_or_si256(v, _mm256_and_si256(in, mask[c]));
    }
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + size_t(x) * kGroup), v);
  }
  return blendSse2(base, out, x, xb);
}

inline __m256 broadcastGroup(const float* p) {  // (p0 p1 p2 p3 p0 p1 p2 p3)
  const __m128 g = _mm_loadu_ps(p);
  return _mm256_insertf128_ps(_mm256_castps128_ps256(g), g, 1);
}

void convertAvx2(const RowConversion& rc, const uint8_t* in, float* out, int n) {
  const __m256 hi = _mm256_set1_ps(rc.hi), lo = _mm256_set1_ps(rc.lo);
  const __m256 scale = broadcastGroup(rc.scale.data());
  const __m256 bias = broadcastGroup(rc.bias.data());
  int i = 0;
  for (; i + 2 * kGroup <= n; i += 2 * kGroup) {
    const __m256 f = _mm256_cvtepi32_ps(
        _mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(in + i))));
    __m256 v = _mm256_add_ps(_mm256_mul_ps(f, hi), _mm256_mul_ps(f, lo));
    if (rc.scaled) v = _mm256_add_ps(_mm256_mul_ps(v, scale), bias);
    _mm256_storeu_ps(out + i, v);
  }
  if (i < n) {  // one group left
    int word;
    std::memcpy(&word, in + i, 4);
    const __m128 f = _mm_cvtepi32_ps(_mm_cvtepu8_epi32(_mm_cvtsi32_si128(word)));
    __m128 v = _mm_add_ps(_mm_mul_ps(f, _mm256_castps256_ps128(hi)),
                          _mm_mul_ps(f, _mm256_castps256_ps128(lo)));
    if (rc.scaled)
      v = _mm_add_ps(_mm_mul_ps(v, _mm256_castps256_ps128(scale)), _mm256_castps256_ps128(bias));
    _mm_storeu_ps(out + i, v);
  }
}

inline void storeBytes8(__m256 v, uint8_t* o) {
  const __m256 c = _mm256_min_ps(_mm256_max_ps(v, _mm256_setzero_ps()), _mm256_set1_ps(1.0f));
  const __m256i q = _mm256_cvttps_epi32(
      _mm256_add_ps(_mm256_mul_ps(c, _mm256_set1_ps(255.0f)), _mm256_set1_ps(0.5f)));
  const __m128i w = _mm_packs_epi32(_mm256_castsi256_si128(q), _mm256_extracti128_si256(q, 1));
  _mm_storel_epi64(reinterpret_cast<__m128i*>(o), _mm_packus_epi16(w, w));
}

constexpr int kAvx2Block = 8;  // vectors summed side by side (independent add chains)

template <bool kBytes>
void sumRowAvx2(const RowSums& r, float* sums, uint8_t* bytes) {
  __m256 w[kMaxTaps];
  for (int t = 0; t < r.count; ++t) w[t] = broadcastGroup(r.taps[t].w);
  const __m256 scale = broadcastGroup(r.postScale);
  const __m256 bias = broadcastGroup(r.postBias);
  int i = 0;
  for (; i + 2 * kGroup * kAvx2Block <= r.floats; i += 2 * kGroup * kAvx2Block) {
    __m256 acc[kAvx2Block];
    for (int k = 0; k < kAvx2Block; ++k) acc[k] = _mm256_setzero_ps();
    for (int t = 0; t < r.count; ++t) {
      const float* p = r.sources[t] + i;
      for (int k = 0; k < kAvx2Block; ++k)
        acc[k] = _mm256_add_ps(acc[k], _mm256_mul_ps(_mm256_loadu_ps(p + 2 * kGroup * k), w[t]));
    }
    for (int k = 0; k < kAvx2Block; ++k) {
      if constexpr (kBytes) {
        if (r.postScaleBias) acc[k] = _mm256_add_ps(_mm256_mul_ps(acc[k], scale), bias);
        storeBytes8(acc[k], bytes + i + 2 * kGroup * k);
      } else {
        _mm256_storeu_ps(sums + i + 2 * kGroup * k, acc[k]);
      }
    }
  }
  for (; i + 2 * kGroup <= r.floats; i += 2 * kGroup) {
    __m256 acc = _mm256_setzero_ps();
    for (int t = 0; t < r.count; ++t)
      acc = _mm256_add_ps(acc, _mm256_mul_ps(_mm256_loadu_ps(r.sources[t] + i), w[t]));
    if constexpr (kBytes) {
      if (r.postScaleBias) acc = _mm256_add_ps(_mm256_mul_ps(acc, scale), bias);
      storeBytes8(acc, bytes + i);
    } else {
      _mm256_storeu_ps(sums + i, acc);
    }
  }
  if (i < r.floats) {  // one group left
    __m128 acc = _mm_setzero_ps();
    for (int t = 0; t < r.count; ++t)
      acc =
          _mm_add_ps(acc, _mm_mul_ps(_mm_loadu_ps(r.sources[t] + i), _mm256_castps256_ps128(w[t])));
    if constexpr (kBytes) {
      if (r.postScaleBias)
        acc = _mm_add_ps(_mm_mul_ps(acc, _mm256_castps256_ps128(scale)),
                         _mm256_castps256_ps128(bias));
      storeBytes4(acc, bytes + i);
    } else {
      _mm_storeu_ps(sums + i, acc);
    }
  }
}
#pragma GCC pop_options
#endif

bool chooseKernels(SimdLevel simd, Kernels& k) {
#if defined(SL_CONVOLUTION_X86)
  if (simd == SimdLevel::kBest && __builtin_cpu_supports("avx2")) {
    k = {blendAvx2, convertAvx2, sumRowAvx2<false>, sumRowAvx2<true>};
    return true;
  }
#endif
#if defined(__SSE2__)
  k = {blendSse2, convertSse2, sumRowSse2<false>, sumRowSse2<true>};
  return true;
#else
  (void)simd;
  return false;
#endif
}

// Chooses the arithmetic conversion when it reproduces the table exactly.
RowConversion chooseConversion(const TransferState& t, const Convolution& cv, const Kernels& k) {
  RowConversion rc;
  rc.table = cv.values.px.data();
  const bool prefixIsScaleBias = !t.mapColor && !(t.colorTableEnabled && t.tables[0].width > 0);
  if (!prefixIsScaleBias) return rc;
  // hi: 1/255 rounded to float, low 8 mantissa bits cleared; lo: the rest, rounded.
  float hi = kOneOver255;
  uint32_t bits;
  std::memcpy(&bits, &hi, 4);
  bits &= kSixteenBitMantissa;
  std::memcpy(&hi, &bits, 4);
  rc.hi = hi;
  rc.lo = float(1.0 / 255.0 - double(hi));
  rc.scaled = !(t.scale == Rgba{1, 1, 1, 1} && t.bias == Rgba{0, 0, 0, 0});
  rc.scale = t.scale;
  rc.bias = t.bias;
  uint8_t ramp[kByteValues * kGroup];
  for (int v = 0; v < kByteValues; ++v)
    for (int c = 0; c < kGroup; ++c) ramp[v * kGroup + c] = uint8_t(v);
  float converted[kByteValues * kGroup];
  k.convert(rc, ramp, converted, kByteValues * kGroup);
  rc.arithmetic = std::memcmp(converted, cv.values.px.data(), sizeof converted) == 0;
  return rc;
}

// Padded row py (3.6.5: Cw / Ch columns and rows of border colour or replicated edge around
// the source; none under REDUCE) as stage 1-3 floats.
void padRow(const Convolution& cv, const RowConversion& rc, const Kernels& k, const uint8_t* src,
            int py, float* dst) {
  const int sy = py - cv.ch;
  if (!cv.reduce && !cv.replicate && (sy < 0 || sy >= cv.hs)) {
    for (int x = 0; x < cv.pw; ++x)
      for (int c = 0; c < kGroup; ++c) dst[x * kGroup + c] = cv.border[c];
    return;
  }
  const uint8_t* row = src + size_t(std::clamp(sy, 0, cv.hs - 1)) * cv.ws * kGroup;
  float* const inside = dst + size_t(cv.cw) * kGroup;
  if (rc.arithmetic) {
    k.convert(rc, row, inside, cv.ws * kGroup);
  } else {
    convertTable(rc, row, inside, cv.ws * kGroup);
  }
  if (cv.reduce) return;
  const float* first = inside;
  const float* last = inside + size_t(cv.ws - 1) * kGroup;
  for (int x = 0; x < cv.cw; ++x)
    for (int c = 0; c < kGroup; ++c) dst[x * kGroup + c] = cv.replicate ? first[c] : cv.border[c];
  for (int x = cv.cw + cv.ws; x < cv.pw; ++x)
    for (int c = 0; c < kGroup; ++c) dst[x * kGroup + c] = cv.replicate ? last[c] : cv.border[c];
}

// Output rows [y0, y1) of form 2: a ring of Hf padded rows, each converted once.
bool sumRows(Convolution& cv, const RowConversion& rc, const Kernels& k, TransferState* counting,
             const uint8_t* src, uint8_t* out, int y0, int y1) {
  const int hf = cv.hf;
  const size_t rowFloats = size_t(cv.pw) * kGroup;
  std::vector<float> ring(size_t(hf) * rowFloats);  // every row is written by padRow
  auto slot = [&](int py) { return ring.data() + size_t(py % hf) * rowFloats; };
  const bool fused = cv.suffixIdentity && counting == nullptr;
  Image4 row = fused ? Image4() : Image4(cv.ow, 1);
  const float* sources[kMaxTaps];
  RowSums r{sources,          cv.taps.data(),      int(cv.taps.size()), cv.ow * kGroup,
            cv.postScaleBias, cv.postScale.data(), cv.postBias.data()};
  bool kept = true;
  for (int py = y0; py < y0 + hf - 1; ++py) padRow(cv, rc, k, src, py, slot(py));
  for (int j = y0; j < y1; ++j) {
    padRow(cv, rc, k, src, j + hf - 1, slot(j + hf - 1));
    for (size_t t = 0; t < cv.taps.size(); ++t)
      sources[t] = slot(j + cv.taps[t].m) + size_t(cv.taps[t].n) * kGroup;
    uint8_t* const o = out + size_t(j) * cv.ow * kGroup;
    if (fused) {
      k.bytes(r, nullptr, o);
      continue;
    }
    RowSums raw = r;
    raw.postScaleBias = false;  // finishRow applies it
    k.sums(raw, row.px.data(), nullptr);
    kept = finishRow(cv, counting, row, o) && kept;
  }
  return kept;
}

// ---------------------------------------------------------------- form 3: integer sums
// Dyadic kernels on the plain 8-bit prefix (the binomial blurs: weights N / 2^D, N >= 0), with
// nothing after the convolution. Stage 1 gives s = float(v / 255), within 2^-25 of v / 255, so
// the general path's float sum F lies within about 1.1e-6 of R = I / (255 * 2^D), where
// I = sum of N * v is an exact integer (17 roundings of at most 2^-24 each for sums <= 1, plus
// the 2^-25 of the stage values, times the weights' sum <= 1). Its byte,
// trunc(F * 255 + 0.5) in float, is then within 3.2e-4 of X = I / 2^D + 0.5; X is a
// multiple of 2^-D >= 2^-kMaxDyadicShift = 3.9e-3, so unless X is an integer (I = 2^(D-1)
// mod 2^D: a rounding tie of the real value) the byte is floor(X) = (I + 2^(D-1)) >> D.
// Ties, a few percent of the components, are summed again as the general path does, in
// floats, in tap order. The integer sums are byte pairs times byte weights (pmaddubsw) into
// 16-bit lanes: pairs of taps whose numerators add up to at most 128 cannot saturate, and
// the total, at most 255 * 2^D, fits an unsigned 16-bit lane.
constexpr int kMaxDyadicShift = 8;      // D: weights are multiples of 1/256 at the finest
constexpr int kMaxPairNumerator = 128;  // 255 * 128 fits pmaddubsw's signed 16-bit result
constexpr int kMaxTapPairs = (kMaxTaps + 1) / 2;
constexpr size_t kDyadicSpeedup = 4;  // integer work per tap against float, for parallelRows

bool haveAvx2ForDyadic() {
#if defined(SL_CONVOLUTION_X86)
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

struct DyadicPlan {
  int shift = 0;                             // D
  uint8_t numerator[kMaxTaps][kGroup] = {};  // N of tap t, component c
  int pairs = 0;                             // taps 2k and 2k + 1 (the last may be alone)
  // Separable numerators (the binomial blurs): N(n, m) = row[n] * column[m] per component,
  // so I = sum over n of row[n] * (sum over m of column[m] * v) — the same exact integer in
  // 2 (Wf + Hf) operations a component instead of Wf * Hf.
  bool separable = false;
  uint16_t row[kMaxConvolutionWidth][kGroup] = {};
  uint16_t column[kMaxConvolutionHeight][kGroup] = {};
};

// Factors the numerators of each component as an outer product of integer vectors.
bool planSeparable(const Convolution& cv, DyadicPlan& plan) {
  int grid[kMaxConvolutionHeight][kMaxConvolutionWidth][kGroup] = {};
  for (size_t t = 0; t < cv.taps.size(); ++t) {
    const Tap& tap = cv.taps[t];
    if (tap.n < 0 || tap.n >= cv.wf || tap.m < 0 || tap.m >= cv.hf) return false;
    for (int c = 0; c < kGroup; ++c) grid[tap.m][tap.n][c] += plan.numerator[t][c];
  }
  for (int c = 0; c < kGroup; ++c) {
    int m0 = -1, n0 = -1;  // the first non-zero numerator
    for (int m = 0; m < cv.hf && m0 < 0; ++m)
      for (int n = 0; n < cv.wf && m0 < 0; ++n)
        if (grid[m][n][c] != 0) m0 = m, n0 = n;
    if (m0 < 0) continue;  // no tap: row and column stay 0
    int g = 0;             // gcd of row m0, so that the column gets the integral factors
    for (int n = 0; n < cv.wf; ++n) g = std::gcd(g, grid[m0][n][c]);
    for (int n = 0; n < cv.wf; ++n) plan.row[n][c] = uint16_t(grid[m0][n][c] / g);
    for (int m = 0; m < cv.hf; ++m) {
      if (grid[m][n0][c] % plan.row[n0][c] != 0) return false;
      plan.column[m][c] = uint16_t(grid[m][n0][c] / plan.row[n0][c]);
    }
    for (int m = 0; m < cv.hf; ++m)
      for (int n = 0; n < cv.wf; ++n)
        if (grid[m][n][c] != int(plan.row[n][c]) * int(plan.column[m][c])) return false;
  }
  return true;
}

bool planDyadic(const Convolution& cv, DyadicPlan& plan) {
  if (!cv.suffixIdentity || cv.postScaleBias || !(cv.reduce || cv.replicate)) return false;
  for (int v = 0; v < kByteValues; ++v)
    for (int c = 0; c < kGroup; ++c)
      if (cv.values.px[size_t(v) * kGroup + c] != float(v) / 255.0f) return false;
  const int taps = int(cv.taps.size());
  if (taps == 0 || taps > kMaxTaps) return false;
  // The smallest D for which every weight is an integer multiple of 2^-D.
  for (plan.shift = 0; plan.shift <= kMaxDyadicShift; ++plan.shift) {
    const float unit = std::ldexp(1.0f, plan.shift);
    bool integral = true;
    for (const Tap& tap : cv.taps)
      for (int c = 0; c < kGroup; ++c) {
        const float n = tap.w[c] * unit;  // exact: a power-of-two scaling
        integral = integral && n == std::floor(n);
      }
    if (integral) break;
  }
  if (plan.shift > kMaxDyadicShift) return false;
  const float unit = std::ldexp(1.0f, plan.shift);
  for (int c = 0; c < kGroup; ++c) {
    int total = 0;
    for (int t = 0; t < taps; ++t) {
      const float n = cv.taps[size_t(t)].w[c] * unit;
      if (n < 0.0f || n > float(kMaxPairNumerator)) return false;
      plan.numerator[t][c] = uint8_t(n);
      total += plan.numerator[t][c];
    }
    if (total > (1 << plan.shift)) return false;  // the sum stays within [0, 1]
    for (int t = 0; t + 1 < taps; t += 2)
      if (plan.numerator[t][c] + plan.numerator[t + 1][c] > kMaxPairNumerator) return false;
  }
  plan.pairs = (taps + 1) / 2;
  plan.separable = planSeparable(cv, plan);
  return true;
}

// The general path's byte for component j of an output row (accumulateTaps' float sum in tap
// order, then the final conversion): the ties, and the groups after the last whole vector.
uint8_t exactByte(const Convolution& cv, const uint8_t* const* sources, size_t j) {
  const int c = int(j % kGroup);
  float sum = 0.0f;
  for (size_t t = 0; t < cv.taps.size(); ++t) {
    const float w = cv.taps[t].w[c];
    if (w == 0.0f) continue;  // adds +-0 to a sum that is never -0: no change (file header)
    sum = sum + cv.values.px[size_t(sources[t][j]) * kGroup + size_t(c)] * w;
  }
  return toByte(sum);
}

#if defined(SL_CONVOLUTION_X86)
// Components [0, n) of one output row from the padded byte rows sources[t] (output group 0);
// returns how many were written (whole vectors of 32).
__attribute__((target("avx2"))) size_t dyadicRowAvx2(const Convolution& cv, const DyadicPlan& plan,
                                                     const uint8_t* const* sources, uint8_t* out,
                                                     size_t n) {
  __m256i weights[kMaxTapPairs];
  for (int k = 0; k < plan.pairs; ++k) {
    const int a = 2 * k, b = 2 * k + 1;
    uint8_t pattern[2 * kGroup];  // (N_a, N_b) per component, as unpack interleaves them
    for (int c = 0; c < kGroup; ++c) {
      pattern[2 * c] = plan.numerator[a][c];
      pattern[2 * c + 1] = b < int(cv.taps.size()) ? plan.numerator[b][c] : 0;
    }
    uint64_t bits;
    std::memcpy(&bits, pattern, sizeof bits);
    weights[k] = _mm256_set1_epi64x(int64_t(bits));
  }
  const __m256i half = _mm256_set1_epi16(int16_t(1 << (plan.shift - 1 < 0 ? 0 : plan.shift - 1)));
  const __m256i fraction = _mm256_set1_epi16(int16_t((1 << plan.shift) - 1));
  const __m128i shift = _mm_cvtsi32_si128(plan.shift);
  const bool unit = plan.shift == 0;  // D = 0: integer weights, no rounding and no ties
  const int taps = int(cv.taps.size());
  size_t i = 0;
  for (; i + 32 <= n; i += 32) {
    __m256i low = _mm256_setzero_si256(), high = _mm256_setzero_si256();
    for (int k = 0; k < plan.pairs; ++k) {
      const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(sources[2 * k] + i));
      const __m256i b =
          2 * k + 1 < taps
              ? _mm256_loadu_si256(reinterpret_cast<const __m256i*>(sources[2 * k + 1] + i))
              : _mm256_setzero_si256();
      low = _mm256_add_epi16(low, _mm256_maddubs_epi16(_mm256_unpacklo_epi8(a, b), weights[k]));
      high = _mm256_add_epi16(high, _mm256_maddubs_epi16(_mm256_unpackhi_epi8(a, b), weights[k]));
    }
    __m256i bytes;
    uint32_t ties = 0;
    if (unit) {
      bytes = _mm256_packus_epi16(low, high);
    } else {
      const __m256i tieLow = _mm256_cmpeq_epi16(_mm256_and_si256(low, fraction), half);
      const __m256i tieHigh = _mm256_cmpeq_epi16(_mm256_and_si256(high, fraction), half);
      ties = uint32_t(_mm256_movemask_epi8(_mm256_packs_epi16(tieLow, tieHigh)));
      low = _mm256_srl_epi16(_mm256_add_epi16(low, half), shift);
      high = _mm256_srl_epi16(_mm256_add_epi16(high, half), shift);
      bytes = _mm256_packus_epi16(low, high);  // unpack and pack are both per lane: in order
    }
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + i), bytes);
    for (; ties != 0; ties &= ties - 1) {
      const size_t j = i + size_t(__builtin_ctz(ties));
      out[j] = exactByte(cv, sources, j);
    }
  }
  return i;
}
#endif

// The general path's byte for component c of output group x of an output row (accumulateTaps'
// float sum in tap order, then the final conversion), read from the unpadded source rows under
// that output row (rows[m]: source row of filter row m, already clamped under REPLICATE;
// REPLICATE clamps the columns the same way, REDUCE never leaves the image): the ties of the
// separable form, which keeps no padded rows. The same sum as exactByte.
uint8_t exactByteAt(const Convolution& cv, const uint8_t* const* rows, int x, int c) {
  float sum = 0.0f;
  const float* const values = cv.values.px.data() + c;
  for (const Tap& tap : cv.taps) {
    const float w = tap.w[c];
    if (w == 0.0f) continue;  // adds +-0 to a sum that is never -0: no change (file header)
    const int sx = std::clamp(x + tap.n - cv.cw, 0, cv.ws - 1);
    sum = sum + values[size_t(rows[tap.m][size_t(sx) * kGroup + size_t(c)]) * kGroup] * w;
  }
  return toByte(sum);
}

// The binomial 3x3 blur: row and column numerators (1, 2, 1) for every component, D = 4 —
// the kernel of issue 20's blur stage. Its sums need only adds (x + 2y + z), no multiplies.
bool isBinomial3x3(const Convolution& cv, const DyadicPlan& plan) {
  if (!plan.separable || cv.wf != 3 || cv.hf != 3 || plan.shift != kBinomialShift) return false;
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < kGroup; ++c)
      if (plan.row[k][c] != kBinomialRow[k] || plan.column[k][c] != kBinomialRow[k]) return false;
  return true;
}

// exactByteAt for the binomial 3x3 blur: its nine taps in kernelTaps' order (filter row m,
// then column n), weights kBinomialRow[m] * kBinomialRow[n] / 16, none zero, unrolled.
uint8_t binomialTie(const Convolution& cv, const uint8_t* const* rows, int x, int c) {
  constexpr float kUnit = 1.0f / float(1 << kBinomialShift);
  const float* const values = cv.values.px.data() + c;
  size_t at[3];
  for (int n = 0; n < 3; ++n)
    at[n] = size_t(std::clamp(x + n - cv.cw, 0, cv.ws - 1)) * kGroup + size_t(c);
  float sum = 0.0f;
  for (int m = 0; m < 3; ++m)
    for (int n = 0; n < 3; ++n)
      sum = sum + values[size_t(rows[m][at[n]]) * kGroup] *
                      (float(kBinomialRow[m] * kBinomialRow[n]) * kUnit);
  return toByte(sum);
}

#if defined(SL_CONVOLUTION_X86)
#pragma GCC push_options
#pragma GCC target("avx2")  // lambdas inside inherit it (a function attribute would not)
// 16 components of weights: weight[lane % 4] (four RGBA groups per vector).
inline __m256i groupWeights(const uint16_t (*w)[kGroup], int k) {
  uint16_t pattern[16];
  for (int l = 0; l < 16; ++l) pattern[l] = w[k][l % kGroup];
  return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(pattern));
}

// Column sums of one output row: column[(x + Cw) * 4 + c] = sum over m of column weight m
// times source row m's component c of group x, for the Ws groups of the (unpadded) source
// rows; the Cw groups on either side repeat the edge group's sums (REPLICATE pads with the
// edge group, whose column sums they are; REDUCE has none). 16-bit lanes: at most 255 * 2^D.
// kBinomial: weights (1, 2, 1), summed as a + c + (b + b).
template <bool kBinomial>
void columnSumsAvx2(const Convolution& cv, const DyadicPlan& plan, const uint8_t* const* rows,
                    uint16_t* column) {
  const int hf = kBinomial ? 3 : cv.hf;
  const size_t n = size_t(cv.ws) * kGroup;
  uint16_t* const dst = column + size_t(cv.cw) * kGroup;
  const uint8_t* r[kMaxConvolutionHeight];  // local copies: the stores cannot alias them
  __m256i w[kMaxConvolutionHeight];
  for (int m = 0; m < hf; ++m) {
    r[m] = rows[m];
    w[m] = groupWeights(plan.column, m);
  }
  auto load = [&](int m, size_t i) {
    return _mm256_cvtepu8_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(r[m] + i)));
  };
  size_t i = 0;
  for (; i + 16 <= n; i += 16) {
    __m256i sum;
    if constexpr (kBinomial) {
      const __m256i b = load(1, i);
      sum = _mm256_add_epi16(_mm256_add_epi16(load(0, i), load(2, i)), _mm256_add_epi16(b, b));
    } else {
      sum = _mm256_setzero_si256();
      for (int m = 0; m < hf; ++m)
        sum = _mm256_add_epi16(sum, _mm256_mullo_epi16(load(m, i), w[m]));
    }
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst + i), sum);
  }
  for (; i < n; ++i) {
    unsigned sum = 0;
    for (int m = 0; m < hf; ++m) sum += unsigned(plan.column[m][i % kGroup]) * r[m][i];
    dst[i] = uint16_t(sum);
  }
  for (int x = 0; x < cv.cw; ++x) std::memcpy(column + size_t(x) * kGroup, dst, kGroup * 2);
  const uint16_t* const last = dst + (size_t(cv.ws) - 1) * kGroup;
  for (int x = cv.cw + cv.ws; x < cv.pw; ++x)
    std::memcpy(column + size_t(x) * kGroup, last, kGroup * 2);
}

// Row sums of the column sums for output row y: I = sum over n of row weight n times
// column[j + 4n], then (I + 2^(D-1)) >> D, and the ties (I = 2^(D-1) mod 2^D) by exactByteAt.
// Components [0, n) = ow * 4 of `out`; every one is written.
template <bool kBinomial>
void rowSumsAvx2(const Convolution& cv, const DyadicPlan& plan, const uint16_t* column,
                 const uint8_t* const* rows, uint8_t* out, size_t n) {
  const int wf = kBinomial ? 3 : cv.wf;
  __m256i w[kMaxConvolutionWidth];
  for (int k = 0; k < wf; ++k) w[k] = groupWeights(plan.row, k);
  const int shift = plan.shift;
  const int halfValue = shift > 0 ? 1 << (shift - 1) : 0;
  const int fractionBits = (1 << shift) - 1;
  const __m256i half = _mm256_set1_epi16(int16_t(halfValue));
  const __m256i fraction = _mm256_set1_epi16(int16_t(fractionBits));
  // D = 0 (integer weights) has no rounding and no ties; its fraction and half are both 0,
  // which would compare equal everywhere, so ties are looked for only when D > 0.
  const __m256i tieBits = shift > 0 ? _mm256_set1_epi16(-1) : _mm256_setzero_si256();
  const __m128i count = _mm_cvtsi32_si128(shift);
  auto sum16 = [&](size_t j) {
    auto at = [&](int k) {
      return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(column + j + size_t(k) * kGroup));
    };
    if constexpr (kBinomial) {
      const __m256i b = at(1);
      return _mm256_add_epi16(_mm256_add_epi16(at(0), at(2)), _mm256_add_epi16(b, b));
    } else {
      __m256i sum = _mm256_setzero_si256();
      for (int k = 0; k < wf; ++k) sum = _mm256_add_epi16(sum, _mm256_mullo_epi16(at(k), w[k]));
      return sum;
    }
  };
  auto tie = [&](size_t j) {
    const int x = int(j / kGroup), c = int(j % kGroup);
    out[j] = kBinomial ? binomialTie(cv, rows, x, c) : exactByteAt(cv, rows, x, c);
  };
  size_t j = 0;
  // The last load reads column[j + 31 + (Wf - 1) * 4] < pw * 4: j + 32 <= n = ow * 4.
  for (; j + 32 <= n; j += 32) {
    __m256i low = sum16(j), high = sum16(j + 16);
    const __m256i tieLow = _mm256_cmpeq_epi16(_mm256_and_si256(low, fraction), half);
    const __m256i tieHigh = _mm256_cmpeq_epi16(_mm256_and_si256(high, fraction), half);
    const __m256i ties = _mm256_and_si256(tieBits, _mm256_or_si256(tieLow, tieHigh));
    low = _mm256_srl_epi16(_mm256_add_epi16(low, half), count);
    high = _mm256_srl_epi16(_mm256_add_epi16(high, half), count);
    // packus works per 128-bit lane: the permute puts the quarters back in order.
    const __m256i bytes = _mm256_permute4x64_epi64(_mm256_packus_epi16(low, high), 0xD8);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + j), bytes);
    if (_mm256_testz_si256(ties, ties)) continue;  // the common case on most images
    uint32_t bits = uint32_t(
        _mm256_movemask_epi8(_mm256_permute4x64_epi64(_mm256_packs_epi16(tieLow, tieHigh), 0xD8)));
    for (; bits != 0; bits &= bits - 1) tie(j + size_t(__builtin_ctz(bits)));
  }
  for (; j < n; ++j) {  // the components after the last whole vector
    unsigned sum = 0;
    for (int k = 0; k < wf; ++k)
      sum += unsigned(plan.row[k][j % kGroup]) * column[j + size_t(k) * kGroup];
    out[j] = uint8_t((sum + unsigned(halfValue)) >> shift);
    if (shift > 0 && int(sum & unsigned(fractionBits)) == halfValue) tie(j);
  }
}
#pragma GCC pop_options
#endif

// Rows [y0, y1) of a separable dyadic kernel straight from the source rows (no padded copy):
// column sums of the Hf rows under each output row into a 16-bit row that stays in L1, then
// row sums of those; the same integer I, rounding and ties as dyadicRows.
void separableRows(const Convolution& cv, const DyadicPlan& plan, const uint8_t* src, uint8_t* out,
                   int y0, int y1) {
#if defined(SL_CONVOLUTION_X86)
  const bool binomial = isBinomial3x3(cv, plan);
  // Every load and store of the two passes stays within the pw * 4 sums (their comments).
  std::vector<uint16_t> column(size_t(cv.pw) * kGroup);
  const uint8_t* rows[kMaxConvolutionHeight];
  const size_t n = size_t(cv.ow) * kGroup;
  for (int y = y0; y < y1; ++y) {
    for (int m = 0; m < cv.hf; ++m)
      rows[m] = src + size_t(std::clamp(y + m - cv.ch, 0, cv.hs - 1)) * size_t(cv.ws) * kGroup;
    uint8_t* const o = out + size_t(y) * n;
    if (binomial) {
      columnSumsAvx2<true>(cv, plan, rows, column.data());
      rowSumsAvx2<true>(cv, plan, column.data(), rows, o, n);
    } else {
      columnSumsAvx2<false>(cv, plan, rows, column.data());
      rowSumsAvx2<false>(cv, plan, column.data(), rows, o, n);
    }
  }
#else
  const uint8_t* rows[kMaxConvolutionHeight];
  for (int y = y0; y < y1; ++y) {
    for (int m = 0; m < cv.hf; ++m)
      rows[m] = src + size_t(std::clamp(y + m - cv.ch, 0, cv.hs - 1)) * size_t(cv.ws) * kGroup;
    for (int i = 0; i < cv.ow * kGroup; ++i)
      out[size_t(y) * cv.ow * kGroup + i] = exactByteAt(cv, rows, i / kGroup, i % kGroup);
  }
#endif
}

// Rows [y0, y1) by integer sums: a ring of Hf padded byte rows (the edge replicated under
// REPLICATE; none under REDUCE).
void dyadicRows(const Convolution& cv, const DyadicPlan& plan, const uint8_t* src, uint8_t* out,
                int y0, int y1) {
  const int hf = cv.hf;
  const size_t rowBytes = size_t(cv.pw) * kGroup;
  std::vector<uint8_t> ring(size_t(hf) * rowBytes + 32);  // + a vector of slack for the loads
  auto slot = [&](int py) { return ring.data() + size_t(py % hf) * rowBytes; };
  auto pad = [&](int py) {
    uint8_t* const dst = slot(py);
    const uint8_t* const row = src + size_t(std::clamp(py - cv.ch, 0, cv.hs - 1)) * cv.ws * kGroup;
    std::memcpy(dst + size_t(cv.cw) * kGroup, row, size_t(cv.ws) * kGroup);
    for (int x = 0; x < cv.cw; ++x) std::memcpy(dst + size_t(x) * kGroup, row, kGroup);
    for (int x = cv.cw + cv.ws; x < cv.pw; ++x)
      std::memcpy(dst + size_t(x) * kGroup, row + size_t(cv.ws - 1) * kGroup, kGroup);
  };
  const uint8_t* sources[kMaxTaps];
  const size_t n = size_t(cv.ow) * kGroup;
  for (int py = y0; py < y0 + hf - 1; ++py) pad(py);
  for (int j = y0; j < y1; ++j) {
    pad(j + hf - 1);
    for (size_t t = 0; t < cv.taps.size(); ++t)
      sources[t] = slot(j + cv.taps[t].m) + size_t(cv.taps[t].n) * kGroup;
    uint8_t* const o = out + size_t(j) * n;
    size_t done = 0;
#if defined(SL_CONVOLUTION_X86)
    done = dyadicRowAvx2(cv, plan, sources, o, n);
#endif
    for (size_t i = done; i < n; ++i) o[i] = exactByte(cv, sources, i);
  }
}

}  // namespace

bool convolveBytes(TransferState& t, const std::vector<uint8_t>& src, int ws, int hs,
                   std::vector<uint8_t>& out, int& ow, int& oh, SimdLevel simd) {
  Convolution cv = prepare(t, ws, hs);
  ow = cv.ow;
  oh = cv.oh;
  if (ow <= 0 || oh <= 0) {  // REDUCE with a filter larger than the image: no output
    ow = oh = 0;
    out.clear();
    return true;
  }
  // The zero-weight argument at the top of the file needs finite values.
  const bool finite = finiteValues(cv.values.px.data(), cv.values.px.size()) &&
                      (cv.reduce || cv.replicate || finiteValues(cv.border.data(), kGroup));
  Kernels kernels;
  if (!finite || !chooseKernels(simd, kernels))
    return convolveBytesStrips(t, src, ws, hs, out, ow, oh);
  out.resize(size_t(ow) * oh * kGroup);  // every byte is written below unless a sink takes it
  const bool counting = t.histogramEnabled || t.minmaxEnabled;
  GatherPlan plan;
  if (!counting && planGather(cv, plan)) {
    // One core: the gather moves bytes at nearly memory speed, and a second thread's start
    // (tens of microseconds on this kind of machine) cost more than it saved when measured.
    gatherRows(cv, plan, kernels, src.data(), out.data(), 0, oh);
    return true;
  }
  DyadicPlan dyadic;
  if (!counting && simd == SimdLevel::kBest && haveAvx2ForDyadic() && planDyadic(cv, dyadic)) {
    if (dyadic.separable) {
      // One core, as the gather: on the shared 2-core machine a second thread waits for a
      // core more often than it halves the work (3x3 blur, 512x512, 30 calls each, load 7.4-7.6:
      // median 0.21-0.28 ms on one core against 0.55-0.85 ms on two, wall clock).
      separableRows(cv, dyadic, src.data(), out.data(), 0, oh);
      return true;
    }
    parallelRows(oh, size_t(ow) * kGroup * (cv.taps.size() + 1) / kDyadicSpeedup,
                 [&](int y0, int y1) { dyadicRows(cv, dyadic, src.data(), out.data(), y0, y1); });
    return true;
  }
  const RowConversion rc = chooseConversion(t, cv, kernels);
  if (counting)
    return sumRows(cv, rc, kernels, &t, src.data(), out.data(), 0, oh);  // shared tables
  parallelRows(oh, size_t(ow) * kGroup * (cv.taps.size() + 1), [&](int y0, int y1) {
    sumRows(cv, rc, kernels, nullptr, src.data(), out.data(), y0, y1);
  });
  return true;
}

}  // namespace sl::imaging::detail
