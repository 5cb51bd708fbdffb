// imaging/color_matrix_groups.cpp — the color matrix stage (glspec121 3.6.5 "Color Matrix
// Transformation", with its post-color-matrix scale and bias) straight from client groups to
// 8-bit RGBA, when it is the only pixel-transfer stage that is not identity: the dense
// matrices of glColorMatrix-style programs (RGB to luminance, colour rotations, channel mixes).
//
// The general path unpacks to a float RGBA image (3.6.4 "Conversion to floating-point": a byte
// v becomes v / 255; "Final Expansion to RGBA": a missing A is 1), runs applyColorMatrix on it
// and converts each component to a byte (4.3.2 "Final Conversion": clamp to [0, 1], times 255,
// round). This file does the same arithmetic four groups at a time, one group per four lanes of
// a 16-float vector, and writes the bytes without the float image:
//   x     = v / 255.0f (bytes; an IEEE division, as unpackImage does) or the float itself,
//   o_r   = ((k_r0 * x_R + k_r1 * x_G) + k_r2 * x_B) + k_r3 * x_A   (applyColorMatrix's order),
//   o_r   = o_r * scale_r + bias_r, or o_r + bias_r when every scale is 1 (applyColorMatrix),
//   byte  = int((o_r > 0 ? (o_r < 1 ? o_r : 1) : 0) * 255.0f + 0.5f)   (toByte / packImage).
// Every lane computes its component with the same float operations in the same order as the
// general path (all sixteen products, zero coefficients included, so infinities and NaNs in
// float input give the same NaNs), so the bytes are identical: tests/imaging/
// color_matrix_groups_test.cpp compares them on all 2^24 RGB byte groups and random float
// groups at every instruction set this processor has. The vectors are GCC vector extensions,
// compiled three times: AVX-512 and AVX2 behind __builtin_cpu_supports, SSE2 (the x86-64
// baseline) otherwise. The build compiles imaging/ with -ffp-contract=off (CMakeLists.txt): a
// fused multiply-add would round once where the general path rounds twice.
//
// Where the processor has AVX-512 VBMI, a second form (the "planar" section below) does the
// same per-component arithmetic on sixteen groups at a time, one vector per component: no
// per-group broadcasts, byte permutes to unpack the bytes, v / 255 without the division
// (hi and lo below, checked against v / 255.0f on all 256 bytes before use) and a final
// conversion whose clamp is one minimum and the saturation of the packs (its comment says why
// the bytes are the same).
#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "imaging/internal.h"

// The vectors never cross a call (every helper is always_inline), so GCC's note that a
// 64-byte vector is passed differently with and without AVX-512 does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace sl::imaging::detail {
namespace {

constexpr int kLanes = 16;          // floats per vector: four RGBA groups
constexpr float kByteMax = 255.0f;  // table 2.6 / table 4.7: bytes are k / 255

typedef float Floats __attribute__((vector_size(kLanes * sizeof(float))));
typedef int32_t Ints __attribute__((vector_size(kLanes * sizeof(int32_t))));
typedef uint8_t Bytes __attribute__((vector_size(kLanes)));

// The client layouts this path reads (3.6.4 "Unpacking": tight components of one type).
enum Layout { kRgba8, kRgb8, kRgbaF, kRgbF };
// What follows the product: nothing (scale 1, bias 0), + bias (scale 1), * scale + bias.
enum Post { kPlain, kBiased, kScaled };

// Everything the loop reads, replicated per group of four lanes.
struct Plan {
  Floats column[4];  // column[c][4 g + r] = k_rc, the coefficient of input c in output r
  Floats scale, bias;
};

template <Layout L>
constexpr size_t groupBytes() {
  return L == kRgba8 ? 4 : L == kRgb8 ? 3 : L == kRgbaF ? 16 : 12;
}

// Sixteen groups are one block: bytes are read as one vector of sixteen 32-bit words and each
// component picked out of its word by a lane permute, a shift and a mask.
constexpr size_t kBlockGroups = 16;

// Bytes a block reads: the RGB layouts read past the block's last group (a whole word vector,
// or a whole float vector for its last four groups); rowOf runs the end of a row from a padded
// copy where that would pass the end.
template <Layout L>
constexpr size_t blockReadBytes() {
  return L == kRgb8 ? sizeof(Ints) : L == kRgbF ? 12 * 12 + sizeof(Floats) : 16 * groupBytes<L>();
}

// Groups 4q .. 4q + 3 of a block as RGBA floats (3.6.4 "Conversion to floating-point": a
// byte v is v / 255, an IEEE division as in unpackImage; "Final Expansion to RGBA": A = 1).
template <Layout L, int q>
[[gnu::always_inline]] inline Floats loadGroups(const uint8_t* block, const Ints& words) {
  const Floats one = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
  if constexpr (L == kRgba8 || L == kRgb8) {
    // Component c of group g is byte n = 4g + c (RGBA) or 3g + c (RGB) of the block: word n / 4,
    // bits 8 (n % 4) up.
    constexpr int k = L == kRgba8 ? 4 : 3;
    Ints index, shift;
    for (int lane = 0; lane < kLanes; ++lane) {
      const int n = (4 * q + lane / 4) * k + std::min(lane % 4, k - 1);
      index[lane] = n / 4;
      shift[lane] = 8 * (n % 4);
    }
    const Ints bytes = (__builtin_shuffle(words, index) >> shift) & 0xff;
    const Floats x = __builtin_convertvector(bytes, Floats) / kByteMax;
    if constexpr (L == kRgba8) return x;
    return __builtin_shuffle(x, one, Ints{0, 1, 2, 16, 4, 5, 6, 16, 8, 9, 10, 16, 12, 13, 14, 16});
  } else {
    Floats x;
    std::memcpy(&x, block + size_t(4 * q) * groupBytes<L>(), sizeof x);
    if constexpr (L == kRgbaF) return x;
    return __builtin_shuffle(x, one, Ints{0, 1, 2, 16, 3, 4, 5, 16, 6, 7, 8, 16, 9, 10, 11, 16});
  }
}

// Four groups through the matrix, the post-color-matrix scale and bias and the final
// conversion to bytes.
template <Post P>
[[gnu::always_inline]] inline void groups4(const Plan& plan, const Floats x, uint8_t* dst) {
  const Floats r = __builtin_shuffle(x, Ints{0, 0, 0, 0, 4, 4, 4, 4, 8, 8, 8, 8, 12, 12, 12, 12});
  const Floats g = __builtin_shuffle(x, Ints{1, 1, 1, 1, 5, 5, 5, 5, 9, 9, 9, 9, 13, 13, 13, 13});
  const Floats b =
      __builtin_shuffle(x, Ints{2, 2, 2, 2, 6, 6, 6, 6, 10, 10, 10, 10, 14, 14, 14, 14});
  const Floats a =
      __builtin_shuffle(x, Ints{3, 3, 3, 3, 7, 7, 7, 7, 11, 11, 11, 11, 15, 15, 15, 15});
  // Lane 4g + row: k_row0 * R + k_row1 * G + k_row2 * B + k_row3 * A, left to right.
  Floats o = plan.column[0] * r + plan.column[1] * g + plan.column[2] * b + plan.column[3] * a;
  if constexpr (P == kScaled) o = o * plan.scale + plan.bias;
  if constexpr (P == kBiased) o = o + plan.bias;
  const Floats zero = {}, one = zero + 1.0f;
  Floats c = o > zero ? o : zero;  // NaN fails the test: 0, as in toByte
  c = c < one ? c : one;
  const Ints k = __builtin_convertvector(c * kByteMax + 0.5f, Ints);  // in [0, 255]: truncation
  const Bytes out = __builtin_convertvector(k, Bytes);
  std::memcpy(dst, &out, sizeof out);
}

template <Layout L, Post P>
[[gnu::always_inline]] inline void block16(const Plan& plan, const uint8_t* src, uint8_t* dst) {
  Ints words = {};
  if constexpr (L == kRgba8 || L == kRgb8) std::memcpy(&words, src, sizeof words);
  groups4<P>(plan, loadGroups<L, 0>(src, words), dst);
  groups4<P>(plan, loadGroups<L, 1>(src, words), dst + 16);
  groups4<P>(plan, loadGroups<L, 2>(src, words), dst + 32);
  groups4<P>(plan, loadGroups<L, 3>(src, words), dst + 48);
}

template <Layout L, Post P>
[[gnu::always_inline]] inline void rowOf(const Plan& plan, const uint8_t* src, uint8_t* dst,
                                         size_t groups) {
  constexpr size_t in = groupBytes<L>();
  size_t g = 0;
  for (; g * in + blockReadBytes<L>() <= groups * in; g += kBlockGroups)
    block16<L, P>(plan, src + g * in, dst + g * 4);
  // The rest through the same vector code, from a padded copy.
  while (g < groups) {
    const size_t m = std::min(kBlockGroups, groups - g);
    uint8_t tailIn[blockReadBytes<L>()] = {}, tailOut[kBlockGroups * 4];
    std::memcpy(tailIn, src + g * in, m * in);
    block16<L, P>(plan, tailIn, tailOut);
    std::memcpy(dst + g * 4, tailOut, m * 4);
    g += m;
  }
}

template <Layout L>
[[gnu::always_inline]] inline void rowPost(const Plan& plan, Post post, const uint8_t* src,
                                           uint8_t* dst, size_t groups) {
  switch (post) {
    case kPlain: return rowOf<L, kPlain>(plan, src, dst, groups);
    case kBiased: return rowOf<L, kBiased>(plan, src, dst, groups);
    case kScaled: return rowOf<L, kScaled>(plan, src, dst, groups);
  }
}

[[gnu::always_inline]] inline void rowAny(const Plan& plan, Layout layout, Post post,
                                          const uint8_t* src, uint8_t* dst, size_t groups) {
  switch (layout) {
    case kRgba8: return rowPost<kRgba8>(plan, post, src, dst, groups);
    case kRgb8: return rowPost<kRgb8>(plan, post, src, dst, groups);
    case kRgbaF: return rowPost<kRgbaF>(plan, post, src, dst, groups);
    case kRgbF: return rowPost<kRgbF>(plan, post, src, dst, groups);
  }
}

// The same loop compiled for three instruction sets.
__attribute__((target("avx512f,avx512bw,avx512vl"))) void rowAvx512(const Plan& plan, Layout layout,
                                                                    Post post, const uint8_t* src,
                                                                    uint8_t* dst, size_t n) {
  rowAny(plan, layout, post, src, dst, n);
}
__attribute__((target("avx2"))) void rowAvx2(const Plan& plan, Layout layout, Post post,
                                             const uint8_t* src, uint8_t* dst, size_t n) {
  rowAny(plan, layout, post, src, dst, n);
}
void rowSse2(const Plan& plan, Layout layout, Post post, const uint8_t* src, uint8_t* dst,
             size_t n) {
  rowAny(plan, layout, post, src, dst, n);
}

using RowFunction = void (*)(const Plan&, Layout, Post, const uint8_t*, uint8_t*, size_t);

RowFunction rowFunction(MatrixIsa isa) {
  switch (isa) {
    case MatrixIsa::kBest:
      if (matrixIsaAvailable(MatrixIsa::kAvx512)) return rowAvx512;
      if (matrixIsaAvailable(MatrixIsa::kAvx2)) return rowAvx2;
      return rowSse2;
    case MatrixIsa::kAvx512Vbmi:  // its four-groups form (bytes where hi + lo is not exact)
    case MatrixIsa::kAvx512: return rowAvx512;
    case MatrixIsa::kAvx2: return rowAvx2;
    case MatrixIsa::kSse2: return rowSse2;
  }
  return rowSse2;
}

// ---- planar: sixteen groups per block, one 16-float vector per component (AVX-512 VBMI) ----
// x_c holds component c of groups 0 .. 15; output row r is
//   o_r = ((k_r0 * x_R + k_r1 * x_G) + k_r2 * x_B) + k_r3 * x_A,
// each coefficient broadcast from memory: the operations of each output component are the
// ones above, in the same order. For GL_RGB, x_A = 1 and k_r3 * 1 is k_r3 exactly, so the last
// term is k_r3 itself.

// v / 255 for a byte v as fma(v, hi, v * lo): hi is 1/255 with its low kSplitBits mantissa
// bits cleared, so v * hi is exact for v < 256 and the fma is the rounded sum of v * hi and
// v * lo. It is used only where it equals v / 255.0f (unpackImage's IEEE division) for every
// byte, checked once (std::fma rounds once, as vfmadd does); the division otherwise.
constexpr int kSplitBits = 8;  // a byte's significant bits
struct ByteSplit {
  float hi = 0, lo = 0;
  bool exact = false;
};
const ByteSplit& byteSplit() {
  static const ByteSplit split = [] {
    ByteSplit s;
    float hi = 1.0f / kByteMax;
    uint32_t bits = 0;
    std::memcpy(&bits, &hi, sizeof bits);
    bits &= ~((uint32_t(1) << kSplitBits) - 1);
    std::memcpy(&hi, &bits, sizeof hi);
    s.hi = hi;
    s.lo = float(1.0 / double(kByteMax) - double(hi));
    s.exact = true;
    for (int v = 0; v <= int(kByteMax); ++v) {
      const float f = float(v);
      if (std::fma(f, s.hi, f * s.lo) != f / kByteMax) s.exact = false;
    }
    return s;
  }();
  return split;
}

struct PlanarPlan {
  float k[16];  // k[r * 4 + c] = k_rc, the coefficient of input c in output r
  float scale[4], bias[4];
  float hi, lo;  // byteSplit()
};

// Bytes a planar block reads: RGB bytes a whole 64-byte vector (48 used), else its groups.
template <Layout L>
constexpr size_t planarReadBytes() {
  return L == kRgb8 ? sizeof(__m512i) : kBlockGroups * groupBytes<L>();
}

#define SL_PLANAR_TARGET __attribute__((target("avx512f,avx512bw,avx512vl,avx512vbmi")))
constexpr uint64_t kFirstByteOfEachWord = 0x1111111111111111ull;  // byte mask, 64 bytes
constexpr __mmask16 kAllLanes = 0xffff;
// A 64-byte vector of byte indices (the byte permutes' and shuffles' operand).
struct ByteIndex {
  uint8_t b[64];
};
// Byte 4 i + c of each 128-bit lane from byte 4 c + i: R, G, B, A of four groups interleaved.
alignas(64) constexpr ByteIndex kInterleave = [] {
  ByteIndex r{};
  for (int j = 0; j < 64; ++j) r.b[j] = uint8_t(4 * (j % 4) + (j % 16) / 4);
  return r;
}();

// Component c of the block's sixteen groups of n bytes as x = v / 255: byte n g + c moved
// into 32-bit lane g (one byte permute, the lane's other bytes zeroed), converted, split.
template <int n, int c>
SL_PLANAR_TARGET [[gnu::always_inline]] inline __m512 bytePlane(__m512i block, __m512 hi,
                                                                __m512 lo) {
  alignas(64) static constexpr ByteIndex index = [] {
    ByteIndex r{};
    for (int g = 0; g < int(kBlockGroups); ++g) r.b[4 * g] = uint8_t(n * g + c);
    return r;
  }();
  const __m512i v =
      _mm512_maskz_permutexvar_epi8(kFirstByteOfEachWord, _mm512_load_si512(&index), block);
  const __m512 f = __m512(__builtin_convertvector(Ints(v), Floats));
  return _mm512_fmadd_ps(f, hi, _mm512_mul_ps(f, lo));
}

// The block's components: x[c] lane g = component c of group g (x[3] only for RGBA).
template <Layout L>
SL_PLANAR_TARGET [[gnu::always_inline]] inline void planarLoad(const PlanarPlan& p,
                                                               const uint8_t* src, __m512 x[4]) {
  if constexpr (L == kRgba8 || L == kRgb8) {
    const __m512 hi = _mm512_set1_ps(p.hi), lo = _mm512_set1_ps(p.lo);
    const __m512i block = _mm512_loadu_si512(src);
    constexpr int n = L == kRgba8 ? 4 : 3;
    x[0] = bytePlane<n, 0>(block, hi, lo);
    x[1] = bytePlane<n, 1>(block, hi, lo);
    x[2] = bytePlane<n, 2>(block, hi, lo);
    if constexpr (L == kRgba8) x[3] = bytePlane<n, 3>(block, hi, lo);
  } else if constexpr (L == kRgbaF) {  // a 4 x 4 transpose of 4-float groups
    const auto* f = reinterpret_cast<const float*>(src);
    const __m512 v0 = _mm512_loadu_ps(f), v1 = _mm512_loadu_ps(f + 16);
    const __m512 v2 = _mm512_loadu_ps(f + 32), v3 = _mm512_loadu_ps(f + 48);
    const __m512i rg = _mm512_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28, 1, 5, 9, 13, 17, 21, 25, 29);
    const __m512i ba =
        _mm512_setr_epi32(2, 6, 10, 14, 18, 22, 26, 30, 3, 7, 11, 15, 19, 23, 27, 31);
    const __m512 rg0 = _mm512_permutex2var_ps(v0, rg, v1), ba0 = _mm512_permutex2var_ps(v0, ba, v1);
    const __m512 rg1 = _mm512_permutex2var_ps(v2, rg, v3), ba1 = _mm512_permutex2var_ps(v2, ba, v3);
    const __m512i first = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 16, 17, 18, 19, 20, 21, 22, 23);
    const __m512i second =
        _mm512_setr_epi32(8, 9, 10, 11, 12, 13, 14, 15, 24, 25, 26, 27, 28, 29, 30, 31);
    x[0] = _mm512_permutex2var_ps(rg0, first, rg1);
    x[1] = _mm512_permutex2var_ps(rg0, second, rg1);
    x[2] = _mm512_permutex2var_ps(ba0, first, ba1);
    x[3] = _mm512_permutex2var_ps(ba0, second, ba1);
  } else {  // RGB floats: float 3 g + c of the 48, from the first 32, then the last 16
    const auto* f = reinterpret_cast<const float*>(src);
    const __m512 v0 = _mm512_loadu_ps(f), v1 = _mm512_loadu_ps(f + 16),
                 v2 = _mm512_loadu_ps(f + 32);
    const __m512i a[3] = {_mm512_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21, 24, 27, 30, 0, 0, 0, 0, 0),
                          _mm512_setr_epi32(1, 4, 7, 10, 13, 16, 19, 22, 25, 28, 31, 0, 0, 0, 0, 0),
                          _mm512_setr_epi32(2, 5, 8, 11, 14, 17, 20, 23, 26, 29, 0, 0, 0, 0, 0, 0)};
    const __m512i b[3] = {_mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 17, 20, 23, 26, 29),
                          _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 18, 21, 24, 27, 30),
                          _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 16, 19, 22, 25, 28, 31)};
    for (int c = 0; c < 3; ++c)
      x[c] = _mm512_permutex2var_ps(_mm512_permutex2var_ps(v0, a[c], v1), b[c], v2);
  }
}

// Sixteen groups through the matrix, the post-color-matrix scale and bias and the final
// conversion. The conversion is byte = int(min(o * 255 + 0.5, 255.5)) with the packs'
// saturation to [0, 255], which gives toByte's byte for every o: for 0 < o < 1 the operations
// are toByte's (c = o); o >= 1 (+inf too) gives o * 255 >= 255 (rounding is monotonic), so
// 255.5 after the minimum, 255; o <= 0 (-0, -inf) gives at most 0.5, truncated to 0 or a
// negative integer that saturates to 0; NaN passes the minimum (its second operand is
// returned: minps(255.5, NaN) = NaN) and converts to INT_MIN, which saturates to 0, as toByte's
// failed comparison gives 0.
template <Layout L, Post P>
SL_PLANAR_TARGET [[gnu::always_inline]] inline void planarBlock(const PlanarPlan& p,
                                                                const uint8_t* src, uint8_t* dst) {
  __m512 x[4];
  planarLoad<L>(p, src, x);
  constexpr bool rgb = L == kRgb8 || L == kRgbF;
  const __m512 byteMax = _mm512_set1_ps(kByteMax), half = _mm512_set1_ps(0.5f);
  const __m512 limit = _mm512_set1_ps(kByteMax + 0.5f);
  __m512i k[4];
  for (int r = 0; r < 4; ++r) {
    const float* row = p.k + r * 4;
    __m512 o = _mm512_add_ps(_mm512_mul_ps(_mm512_set1_ps(row[0]), x[0]),
                             _mm512_mul_ps(_mm512_set1_ps(row[1]), x[1]));
    o = _mm512_add_ps(o, _mm512_mul_ps(_mm512_set1_ps(row[2]), x[2]));
    if constexpr (rgb)
      o = _mm512_add_ps(o, _mm512_set1_ps(row[3]));
    else
      o = _mm512_add_ps(o, _mm512_mul_ps(_mm512_set1_ps(row[3]), x[3]));
    if constexpr (P == kScaled)
      o = _mm512_add_ps(_mm512_mul_ps(o, _mm512_set1_ps(p.scale[r])), _mm512_set1_ps(p.bias[r]));
    if constexpr (P == kBiased) o = _mm512_add_ps(o, _mm512_set1_ps(p.bias[r]));
    // (The all-lanes masks only keep GCC 12 from warning about its headers' undefined vectors.)
    const __m512 u =
        _mm512_maskz_min_ps(kAllLanes, limit, _mm512_add_ps(_mm512_mul_ps(o, byteMax), half));
    k[r] = _mm512_maskz_cvttps_epi32(kAllLanes, u);
  }
  // Signed saturation to 16 bits, then unsigned to 8: 128-bit lane j holds R, G, B, A of groups
  // 4j .. 4j + 3 in turn; one byte shuffle interleaves them.
  const __m512i bytes =
      _mm512_packus_epi16(_mm512_packs_epi32(k[0], k[1]), _mm512_packs_epi32(k[2], k[3]));
  const __m512i interleave = _mm512_load_si512(&kInterleave);
  _mm512_storeu_si512(dst, _mm512_shuffle_epi8(bytes, interleave));
}

template <Layout L, Post P>
SL_PLANAR_TARGET void planarRow(const PlanarPlan& plan, const uint8_t* src, uint8_t* dst,
                                size_t groups) {
  constexpr size_t in = groupBytes<L>();
  size_t g = 0;
  for (; g * in + planarReadBytes<L>() <= groups * in; g += kBlockGroups)
    planarBlock<L, P>(plan, src + g * in, dst + g * 4);
  while (g < groups) {  // the rest from a padded copy
    const size_t m = std::min(kBlockGroups, groups - g);
    uint8_t tailIn[planarReadBytes<L>()] = {}, tailOut[kBlockGroups * 4];
    std::memcpy(tailIn, src + g * in, m * in);
    planarBlock<L, P>(plan, tailIn, tailOut);
    std::memcpy(dst + g * 4, tailOut, m * 4);
    g += m;
  }
}
#undef SL_PLANAR_TARGET

using PlanarRowFunction = void (*)(const PlanarPlan&, const uint8_t*, uint8_t*, size_t);

template <Layout L>
PlanarRowFunction planarRowPost(Post post) {
  switch (post) {
    case kPlain: return planarRow<L, kPlain>;
    case kBiased: return planarRow<L, kBiased>;
    case kScaled: return planarRow<L, kScaled>;
  }
  return planarRow<L, kScaled>;
}

PlanarRowFunction planarRowFunction(Layout layout, Post post) {
  switch (layout) {
    case kRgba8: return planarRowPost<kRgba8>(post);
    case kRgb8: return planarRowPost<kRgb8>(post);
    case kRgbaF: return planarRowPost<kRgbaF>(post);
    case kRgbF: return planarRowPost<kRgbF>(post);
  }
  return planarRowPost<kRgbaF>(post);
}

bool identity(const Rgba& scale, const Rgba& bias) {
  return scale == Rgba{1, 1, 1, 1} && bias == Rgba{0, 0, 0, 0};
}

// Client bytes between rows (3.6.4 "Unpacking": row length or width, rounded up to the
// alignment when a component is smaller than it).
size_t clientRowBytes(int w, size_t groupSize, size_t componentSize, const PixelStore& store) {
  const size_t bytes = size_t(store.rowLength > 0 ? store.rowLength : w) * groupSize;
  const size_t a = size_t(store.alignment);
  if (componentSize >= a) return bytes;
  return (bytes + a - 1) / a * a;
}

}  // namespace

bool matrixIsaAvailable(MatrixIsa isa) {
  switch (isa) {
    case MatrixIsa::kAvx512Vbmi:
      return matrixIsaAvailable(MatrixIsa::kAvx512) && __builtin_cpu_supports("avx512vbmi");
    case MatrixIsa::kAvx512:
      return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
             __builtin_cpu_supports("avx512vl");
    case MatrixIsa::kAvx2: return __builtin_cpu_supports("avx2");
    case MatrixIsa::kSse2:
    case MatrixIsa::kBest: return true;
  }
  return false;
}

bool matrixOnlyPipeline(const TransferState& t) {
  return identity(t.scale, t.bias) && !t.mapColor &&
         !(t.colorTableEnabled && t.tables[0].width > 0) && !t.convolution2DEnabled &&
         !t.separable2DEnabled && !(t.postConvolutionTableEnabled && t.tables[1].width > 0) &&
         !t.colorMatrixStack.back().isIdentity() &&
         !(t.postColorMatrixTableEnabled && t.tables[2].width > 0) && !t.histogramEnabled &&
         !t.minmaxEnabled;
}

bool matrixGroupsApply(const TransferState& t, GLenum format, GLenum type) {
  return matrixOnlyPipeline(t) && (format == GL_RGBA || format == GL_RGB) &&
         (type == GL_UNSIGNED_BYTE || type == GL_FLOAT);
}

void matrixGroupsToBytes(const TransferState& t, const void* data, int w, int h, GLenum format,
                         GLenum type, const PixelStore& store, uint8_t* out, MatrixIsa isa) {
  if (w <= 0 || h <= 0) return;
  const bool rgba = format == GL_RGBA, bytes = type == GL_UNSIGNED_BYTE;
  const Layout layout = bytes ? (rgba ? kRgba8 : kRgb8) : (rgba ? kRgbaF : kRgbF);
  const size_t componentSize = bytes ? 1 : sizeof(float);
  const size_t groupSize = (rgba ? 4 : 3) * componentSize;
  const size_t stride = clientRowBytes(w, groupSize, componentSize, store);
  const auto* base = static_cast<const uint8_t*>(data) + size_t(store.skipRows) * stride +
                     size_t(store.skipPixels) * groupSize;
  // Rows of diag(scale) * Mc as applyColorMatrix forms them: k_rc = Mc[c * 4 + r].
  const Matrix4& m = t.colorMatrixStack.back();
  Plan plan;
  for (int c = 0; c < 4; ++c)
    for (int lane = 0; lane < kLanes; ++lane) plan.column[c][lane] = m.m[size_t(c * 4 + lane % 4)];
  for (int lane = 0; lane < kLanes; ++lane) {
    plan.scale[lane] = t.postColorMatrixScale[size_t(lane % 4)];
    plan.bias[lane] = t.postColorMatrixBias[size_t(lane % 4)];
  }
  const bool scaled = t.postColorMatrixScale != Rgba{1, 1, 1, 1};
  const Post post = scaled ? kScaled : t.postColorMatrixBias != Rgba{0, 0, 0, 0} ? kBiased : kPlain;
  const RowFunction row = rowFunction(isa);
  // The planar form where asked for (or the best) and available; for bytes only where hi + lo
  // is v / 255 exactly.
  const bool planar = (isa == MatrixIsa::kAvx512Vbmi || isa == MatrixIsa::kBest) &&
                      matrixIsaAvailable(MatrixIsa::kAvx512Vbmi) && (!bytes || byteSplit().exact);
  PlanarPlan planarPlan{};
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) planarPlan.k[r * 4 + c] = m.m[size_t(c * 4 + r)];
    planarPlan.scale[r] = t.postColorMatrixScale[size_t(r)];
    planarPlan.bias[r] = t.postColorMatrixBias[size_t(r)];
  }
  planarPlan.hi = byteSplit().hi;
  planarPlan.lo = byteSplit().lo;
  const PlanarRowFunction planarRowOf = planarRowFunction(layout, post);
  auto rows = [&](const uint8_t* src, uint8_t* dst, size_t groups) {
    if (planar)
      planarRowOf(planarPlan, src, dst, groups);
    else
      row(plan, layout, post, src, dst, groups);
  };
  auto span = [&](int y0, int y1) {
    if (stride == size_t(w) * groupSize) {  // tight rows: one span
      rows(base + size_t(y0) * stride, out + size_t(y0) * w * 4, size_t(y1 - y0) * size_t(w));
      return;
    }
    for (int y = y0; y < y1; ++y)
      rows(base + size_t(y) * stride, out + size_t(y) * w * 4, size_t(w));
  };
  // The planar form runs on one core: with it, imaging_bench's dense-matrix stage rows were
  // faster on one core than split over two at every size (both builds timed alternately on
  // the shared 2-core machine): the thread starts and the wait for the second core cost more
  // than the half of the work they take off. The four-groups forms keep the split.
  // A group costs about as much as two of the scalar loops' components (the work measure).
  constexpr size_t kWorkPerGroup = 2;
  if (planar)
    span(0, h);
  else
    parallelRows(h, size_t(w) * kWorkPerGroup, span);
}

}  // namespace sl::imaging::detail
