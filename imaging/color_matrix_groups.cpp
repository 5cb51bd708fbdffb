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
#include <algorithm>
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
    case MatrixIsa::kAvx512: return rowAvx512;
    case MatrixIsa::kAvx2: return rowAvx2;
    case MatrixIsa::kSse2: return rowSse2;
  }
  return rowSse2;
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
  // A group costs about as much as two of the scalar loops' components (the work measure).
  constexpr size_t kWorkPerGroup = 2;
  parallelRows(h, size_t(w) * kWorkPerGroup, [&](int y0, int y1) {
    if (stride == size_t(w) * groupSize) {  // tight rows: one span
      row(plan, layout, post, base + size_t(y0) * stride, out + size_t(y0) * w * 4,
          size_t(y1 - y0) * size_t(w));
      return;
    }
    for (int y = y0; y < y1; ++y)
      row(plan, layout, post, base + size_t(y) * stride, out + size_t(y) * w * 4, size_t(w));
  });
}

}  // namespace sl::imaging::detail
