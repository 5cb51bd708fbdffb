// imaging/byte_maps.cpp — vector evaluation of the 8-bit path (fast_paths.cpp) when its
// per-component prefix is piecewise constant, as in every Brabec–Seidel pass: the colour
// table of their Section 3 sends 0 to 0 and every other value to 64 (63 in alpha), so each
// component takes two values and an RGBA group one of sixteen.
//
// Every form here is exact: none computes a colour. Each looks up, or classifies each input
// byte by the runs of, a table that the scalar path built with the specification's own
// stage code, and copies that table's output.
//   * stepBytes: each output byte is a function of the same component of the input
//     (identity colour matrix) with a few steps: out = base + sum of the steps at or below
//     the input byte, in byte arithmetic.
//   * classBytes: the colour matrix mixes components, but the input group falls into at most
//     sixteen classes (runs of each component's prefix values, combined); the output group of
//     each class is computed once by the scalar path on a representative group, and every
//     group is a 16-entry byte shuffle (pshufb) of its class index.
//   * tableBytesVbmi: any per-component byte table, by byte permutes over its 256 entries.
//   * accumulateBytesVbmi: GL_ACCUM / GL_LOAD (accumulation.cpp), the 256 value * C steps
//     looked up the same way and added with saturating 16-bit adds.
//   * returnBytesAvx2: GL_RETURN on 8-bit colour (accumulation.cpp), value * A converted in
//     float, 16 components a vector, used only where it reproduced the exact table.
// AVX2 (the maps) and AVX-512 VBMI (the tables) when the processor has them, checked at run
// time (the build targets baseline x86-64); else the caller's scalar loop.
#include <cstring>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define SL_HAVE_X86_VECTORS 1
#endif

#include "imaging/internal.h"

namespace sl::imaging::detail {
namespace {

constexpr size_t kVectorBytes = 32;      // one AVX2 register: eight RGBA8 groups
constexpr size_t kWideVectorBytes = 64;  // one AVX-512 register: sixteen groups

// The four bytes of an RGBA group as one little-endian 32-bit pattern.
uint32_t packGroup(const uint8_t b[4]) {
  return uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
}

#if defined(SL_HAVE_X86_VECTORS)
// x >= threshold, per unsigned byte: max(x, t) == x.
__attribute__((target("avx2"))) inline __m256i atLeast(__m256i x, __m256i threshold) {
  return _mm256_cmpeq_epi8(_mm256_max_epu8(x, threshold), x);
}

template <int Steps>
__attribute__((target("avx2"))) void stepBytesAvx2(const StepMap& map, uint8_t* p, size_t n) {
  const __m256i base = _mm256_set1_epi32(int(packGroup(map.base)));
  __m256i at[Steps], delta[Steps];
  for (int k = 0; k < Steps; ++k) {
    at[k] = _mm256_set1_epi32(int(packGroup(map.at[k])));
    delta[k] = _mm256_set1_epi32(int(packGroup(map.delta[k])));
  }
  for (size_t i = 0; i + kVectorBytes <= n; i += kVectorBytes) {
    const __m256i x = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p + i));
    __m256i out = base;
    for (int k = 0; k < Steps; ++k)
      out = _mm256_add_epi8(out, _mm256_and_si256(atLeast(x, at[k]), delta[k]));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p + i), out);
  }
}

template <int Steps>
__attribute__((target("avx2"))) void classBytesAvx2(const ClassMap& map, uint8_t* p, size_t n) {
  __m256i at[Steps], weight[Steps];
  for (int k = 0; k < Steps; ++k) {
    at[k] = _mm256_set1_epi32(int(packGroup(map.at[k])));
    weight[k] = _mm256_set1_epi32(int(packGroup(map.weight[k])));
  }
  const __m256i constant = _mm256_set1_epi32(int(packGroup(map.constant)));
  const __m256i ones8 = _mm256_set1_epi8(1), ones16 = _mm256_set1_epi16(1);
  // For each component that varies: its 16-entry table, and the shuffle-index bits that keep
  // only its byte of the group (an index with the high bit set gives 0).
  __m256i table[4], others[4];
  int shift[4] = {0, 0, 0, 0};
  int varying = 0;
  for (int r = 0; r < 4; ++r) {
    if (!map.varies[r]) continue;
    table[varying] = _mm256_broadcastsi128_si256(
        _mm_loadu_si128(reinterpret_cast<const __m128i*>(map.table[r])));
    others[varying] = _mm256_set1_epi32(int(0x80808080u & ~(0xffu << (8 * r))));
    shift[varying] = 8 * r;
    ++varying;
  }
  for (size_t i = 0; i + kVectorBytes <= n; i += kVectorBytes) {
    const __m256i x = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p + i));
    // Each byte: its component's class times the component's stride.
    __m256i part = _mm256_setzero_si256();
    for (int k = 0; k < Steps; ++k)
      part = _mm256_add_epi8(part, _mm256_and_si256(atLeast(x, at[k]), weight[k]));
    // The group's class, the sum of its four bytes, in the group's low byte (zeros above):
    // byte pairs summed to 16 bits, then 16-bit pairs to 32.
    const __m256i cls = _mm256_madd_epi16(_mm256_maddubs_epi16(part, ones8), ones16);
    __m256i out = constant;
    for (int r = 0; r < varying; ++r) {
      const __m256i index =
          _mm256_or_si256(_mm256_sll_epi32(cls, _mm_cvtsi32_si128(shift[r])), others[r]);
      out = _mm256_or_si256(out, _mm256_shuffle_epi8(table[r], index));
    }
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p + i), out);
  }
}

// Any per-component byte table, 64 bytes at a time (AVX-512 VBMI): each component's 256
// entries are four registers; two two-register byte permutes give entries 0-127 and
// 128-255, the index's top bit picks one, and a per-position mask keeps the component's bytes.
__attribute__((target("avx512f,avx512bw,avx512vbmi"))) void tableBytesVbmi(const uint8_t* lut,
                                                                           uint8_t* p, size_t n) {
  __m512i quarter[4][4];
  for (int c = 0; c < 4; ++c) {
    alignas(64) uint8_t plane[256];
    for (int v = 0; v < 256; ++v) plane[v] = lut[v * 4 + c];
    for (int q = 0; q < 4; ++q) quarter[c][q] = _mm512_load_si512(plane + 64 * q);
  }
  constexpr __mmask64 kFirstOfGroup = 0x1111111111111111ull;  // byte 0 of every group
  for (size_t i = 0; i + kWideVectorBytes <= n; i += kWideVectorBytes) {
    const __m512i x = _mm512_loadu_si512(p + i);
    const __mmask64 upper = _mm512_movepi8_mask(x);  // index >= 128
    __m512i out = _mm512_setzero_si512();
    for (int c = 0; c < 4; ++c) {
      const __m512i low = _mm512_permutex2var_epi8(quarter[c][0], x, quarter[c][1]);
      const __m512i high = _mm512_permutex2var_epi8(quarter[c][2], x, quarter[c][3]);
      out = _mm512_mask_mov_epi8(out, kFirstOfGroup << c, _mm512_mask_blend_epi8(upper, low, high));
    }
    _mm512_storeu_si512(p + i, out);
  }
}

// The 16-bit words of a 256-entry table at 64 byte indices, as two registers of 32 words in
// the indices' order: the low and high bytes are looked up like tableBytesVbmi, then
// interleaved (within 128-bit lanes) and the lanes put back in order.
struct WordTable {
  __m512i low[4], high[4];  // quarters of the low and high bytes of the 256 entries
};
__attribute__((target("avx512f,avx512bw,avx512vbmi"))) inline __m512i lookupQuarters(
    const __m512i (&quarter)[4], __m512i x, __mmask64 upper) {
  return _mm512_mask_blend_epi8(upper, _mm512_permutex2var_epi8(quarter[0], x, quarter[1]),
                                _mm512_permutex2var_epi8(quarter[2], x, quarter[3]));
}

__attribute__((target("avx512f,avx512bw,avx512vbmi"))) size_t accumulateBytesVbmi(
    const int16_t scaled[256], bool keep, const uint8_t* color, int16_t* accum, size_t n) {
  WordTable table;
  alignas(64) uint8_t low[256], high[256];
  for (int v = 0; v < 256; ++v) {
    const auto word = uint16_t(scaled[v]);
    low[v] = uint8_t(word & 0xff);
    high[v] = uint8_t(word >> 8);
  }
  for (int q = 0; q < 4; ++q) {
    table.low[q] = _mm512_load_si512(low + 64 * q);
    table.high[q] = _mm512_load_si512(high + 64 * q);
  }
  // Lanes 0-1 of the interleaved low half and of the high half, then lanes 2-3 (as qwords).
  const __m512i firstHalf = _mm512_set_epi64(11, 10, 3, 2, 9, 8, 1, 0);
  const __m512i secondHalf = _mm512_set_epi64(15, 14, 7, 6, 13, 12, 5, 4);
  const __m512i floor = _mm512_set1_epi16(-32767);  // kAccumMin: the saturated add gives -32768
  size_t i = 0;
  for (; i + kWideVectorBytes <= n; i += kWideVectorBytes) {
    const __m512i x = _mm512_loadu_si512(color + i);
    const __mmask64 upper = _mm512_movepi8_mask(x);
    const __m512i lo = lookupQuarters(table.low, x, upper);
    const __m512i hi = lookupQuarters(table.high, x, upper);
    const __m512i a = _mm512_unpacklo_epi8(lo, hi), b = _mm512_unpackhi_epi8(lo, hi);
    __m512i s0 = _mm512_permutex2var_epi64(a, firstHalf, b);
    __m512i s1 = _mm512_permutex2var_epi64(a, secondHalf, b);
    if (keep) {
      s0 = _mm512_adds_epi16(_mm512_loadu_si512(accum + i), s0);
      s1 = _mm512_adds_epi16(_mm512_loadu_si512(accum + i + 32), s1);
    }
    _mm512_storeu_si512(accum + i, _mm512_max_epi16(s0, floor));
    _mm512_storeu_si512(accum + i + 32, _mm512_max_epi16(s1, floor));
  }
  return i;
}
#endif

#if defined(SL_HAVE_X86_VECTORS)
// One vector of GL_RETURN's conversion: trunc(clamp(float(k) * scale, 0, 255) + 0.5), k the
// 16-bit accumulator values as 32-bit lanes (separate multiply and add: "avx2", not "fma").
__attribute__((target("avx2"))) inline __m256i returnLanes(__m256i k, __m256 scale) {
  const __m256 t = _mm256_mul_ps(_mm256_cvtepi32_ps(k), scale);
  const __m256 c = _mm256_min_ps(_mm256_max_ps(t, _mm256_setzero_ps()), _mm256_set1_ps(255.0f));
  return _mm256_cvttps_epi32(_mm256_add_ps(c, _mm256_set1_ps(0.5f)));
}

__attribute__((target("avx2"))) size_t returnBytesAvx2(float scale, const int16_t* accum,
                                                       uint8_t* out, size_t n) {
  const __m256 s = _mm256_set1_ps(scale);
  size_t i = 0;
  for (; i + 16 <= n; i += 16) {
    const __m256i k = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(accum + i));
    const __m256i a = returnLanes(_mm256_cvtepi16_epi32(_mm256_castsi256_si128(k)), s);
    const __m256i b = returnLanes(_mm256_cvtepi16_epi32(_mm256_extracti128_si256(k, 1)), s);
    // packs works per 128-bit lane: the permute puts a's and b's halves back in order.
    const __m256i w = _mm256_permute4x64_epi64(_mm256_packs_epi32(a, b), 0xD8);
    const __m128i bytes =
        _mm_packus_epi16(_mm256_castsi256_si128(w), _mm256_extracti128_si256(w, 1));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + i), bytes);
  }
  return i;
}
#endif

bool haveAvx2() {
#if defined(SL_HAVE_X86_VECTORS)
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

}  // namespace

namespace {

// Breakpoints of v -> equal(v - 1, v) over the 256 byte values, at most kMaxByteSteps.
bool findSteps(const std::function<bool(int)>& sameAsPrevious, int& count,
               uint8_t at[kMaxByteSteps]) {
  count = 0;
  for (int v = 1; v < 256; ++v) {
    if (sameAsPrevious(v)) continue;
    if (count == kMaxByteSteps) return false;
    at[count++] = uint8_t(v);
  }
  return true;
}

}  // namespace

bool planStepMap(const uint8_t lut[256 * 4], StepMap& map) {
  map = StepMap{};
  int count[4] = {0, 0, 0, 0};
  uint8_t at[4][kMaxByteSteps] = {};
  for (int c = 0; c < 4; ++c) {
    auto same = [&](int v) { return lut[v * 4 + c] == lut[(v - 1) * 4 + c]; };
    if (!findSteps(same, count[c], at[c])) return false;
    map.steps = std::max(map.steps, count[c]);
    map.base[c] = lut[c];
  }
  // A component with fewer steps pads with "x >= 0" steps that add nothing.
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < count[c]; ++k) {
      map.at[k][c] = at[c][k];
      map.delta[k][c] = uint8_t(lut[at[c][k] * 4 + c] - lut[(at[c][k] - 1) * 4 + c]);  // mod 256
    }
  return true;
}

bool planClassMap(const std::function<bool(int, int)>& sameAsPrevious, const bool matters[4],
                  const std::function<void(uint8_t*, size_t)>& scalar, ClassMap& map) {
  map = ClassMap{};
  int count[4] = {0, 0, 0, 0};
  uint8_t at[4][kMaxByteSteps] = {};
  int classes[4] = {1, 1, 1, 1}, stride[4] = {0, 0, 0, 0};
  int combinations = 1;
  for (int c = 0; c < 4; ++c) {
    if (!matters[c]) continue;
    if (!findSteps([&](int v) { return sameAsPrevious(c, v); }, count[c], at[c])) return false;
    classes[c] = count[c] + 1;
    stride[c] = combinations;
    combinations *= classes[c];
    if (combinations > kMaxClasses) return false;
    map.steps = std::max(map.steps, count[c]);
  }
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < count[c]; ++k) {
      map.at[k][c] = at[c][k];
      map.weight[k][c] = uint8_t(stride[c]);
    }
  // One representative group per class (the first byte of each run), through the scalar path.
  std::vector<uint8_t> groups(size_t(kMaxClasses) * 4, 0);
  for (int i = 0; i < combinations; ++i)
    for (int c = 0; c < 4; ++c) {
      if (!matters[c]) continue;
      const int run = i / stride[c] % classes[c];
      groups[size_t(i) * 4 + c] = run == 0 ? 0 : at[c][run - 1];
    }
  scalar(groups.data(), size_t(combinations));
  for (int r = 0; r < 4; ++r) {
    for (int i = 0; i < kMaxClasses; ++i)
      map.table[r][i] = groups[size_t(i < combinations ? i : 0) * 4 + r];
    map.varies[r] = false;
    for (int i = 1; i < combinations; ++i) map.varies[r] |= map.table[r][i] != map.table[r][0];
    map.constant[r] = map.varies[r] ? 0 : map.table[r][0];
  }
  return true;
}

bool vectorTablesAvailable() {
#if defined(SL_HAVE_X86_VECTORS)
  return __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vbmi");
#else
  return false;
#endif
}

size_t applyByteTable(const uint8_t lut[256 * 4], uint8_t* p, size_t n) {
#if defined(SL_HAVE_X86_VECTORS)
  tableBytesVbmi(lut, p, n);
  return n / kWideVectorBytes * kWideVectorBytes;
#else
  (void)lut, (void)p, (void)n;
  return 0;
#endif
}

size_t accumulateBytes(const int16_t scaled[256], bool keep, const uint8_t* color, int16_t* accum,
                       size_t n) {
#if defined(SL_HAVE_X86_VECTORS)
  if (vectorTablesAvailable()) return accumulateBytesVbmi(scaled, keep, color, accum, n);
#endif
  (void)scaled, (void)keep, (void)color, (void)accum, (void)n;
  return 0;
}

size_t returnAccumBytes(float scale, const int16_t* accum, uint8_t* out, size_t n) {
#if defined(SL_HAVE_X86_VECTORS)
  if (haveAvx2()) return returnBytesAvx2(scale, accum, out, n);
#endif
  (void)scale, (void)accum, (void)out, (void)n;
  return 0;
}

bool vectorMapsAvailable() { return haveAvx2(); }

#if defined(SL_HAVE_X86_VECTORS)
namespace {
// The kernel unrolled for the map's number of steps (1 to kMaxByteSteps).
template <class Map>
using Kernel = void (*)(const Map&, uint8_t*, size_t);
template <class Map>
size_t applyKernel(const Map& map, uint8_t* p, size_t n,
                   const Kernel<Map> (&kernels)[kMaxByteSteps]) {
  kernels[std::clamp(map.steps, 1, kMaxByteSteps) - 1](map, p, n);
  return n / kVectorBytes * kVectorBytes;
}
}  // namespace

size_t applyStepMap(const StepMap& map, uint8_t* p, size_t n) {
  static constexpr Kernel<StepMap> kKernels[kMaxByteSteps] = {&stepBytesAvx2<1>, &stepBytesAvx2<2>,
                                                              &stepBytesAvx2<3>, &stepBytesAvx2<4>};
  return applyKernel(map, p, n, kKernels);
}

size_t applyClassMap(const ClassMap& map, uint8_t* p, size_t n) {
  static constexpr Kernel<ClassMap> kKernels[kMaxByteSteps] = {
      &classBytesAvx2<1>, &classBytesAvx2<2>, &classBytesAvx2<3>, &classBytesAvx2<4>};
  return applyKernel(map, p, n, kKernels);
}
#else
size_t applyStepMap(const StepMap&, uint8_t*, size_t) { return 0; }
size_t applyClassMap(const ClassMap&, uint8_t*, size_t) { return 0; }
#endif

}  // namespace sl::imaging::detail
