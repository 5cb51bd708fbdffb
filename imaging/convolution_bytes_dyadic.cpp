// imaging/convolution_bytes_dyadic.cpp — form 3 of the 8-bit convolution (convolution_bytes.cpp):
// exact integer sums for dyadic kernels (the binomial blurs), ties summed again in floats.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>

#include "imaging/convolution_bytes_internal.h"

namespace sl::imaging::detail::conv_bytes {

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

bool haveAvx2ForDyadic() {
#if defined(SL_CONVOLUTION_X86)
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

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
// the kernel of the imaging blur stage. Its sums need only adds (x + 2y + z), no multiplies.
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

}  // namespace sl::imaging::detail::conv_bytes
