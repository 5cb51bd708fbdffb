// imaging/convolution_bytes_sums.cpp — form 2 of the 8-bit convolution (convolution_bytes.cpp):
// float sums over the taps in kernelTaps' order, SSE2 or AVX2, bit-identical to the general path.
#include <algorithm>
#include <cstring>
#include <vector>

#include "imaging/convolution_bytes_internal.h"

namespace sl::imaging::detail::conv_bytes {

constexpr float kOneOver255 = 1.0f / 255.0f;           // only to split 1/255 into hi + lo below
constexpr uint32_t kSixteenBitMantissa = 0xFFFFFF00u;  // clears 8 of float's 24 mantissa bits

// ---------------------------------------------------------------- form 2: SIMD sums

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

}  // namespace sl::imaging::detail::conv_bytes
