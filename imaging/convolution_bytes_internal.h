// imaging/convolution_bytes_internal.h — what the files of the 8-bit convolution share
// (convolution_bytes.cpp has the overview and the entry point convolveBytes; the three forms
// are convolution_bytes_gather.cpp, convolution_bytes_sums.cpp, convolution_bytes_dyadic.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define SL_CONVOLUTION_X86 1
#endif

#include "imaging/internal.h"

namespace sl::imaging::detail::conv_bytes {

constexpr int kByteValues = 256;                // source byte values 0..255
constexpr int kBorderEntry = kByteValues;       // a component table's entry for the border
constexpr int kTableEntries = kByteValues + 1;  // byte values, then the border colour
constexpr int kGroup = 4;                       // floats (or bytes) per RGBA group
constexpr int kMaxTaps = kMaxConvolutionWidth * kMaxConvolutionHeight;
constexpr size_t kDyadicSpeedup = 4;  // integer work per tap against float, for parallelRows

// The final conversion of 4.3.2 / 2.13.9 to a byte (fast_paths.cpp's toByte).
inline uint8_t toByte(float v) {
  const float c = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
  return uint8_t(c * 255.0f + 0.5f);
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

// The post-convolution scale/bias (as runPipeline's scaleBias forms it), stages 5-7, then
// histogram and minmax on `counting` (when given), then the final conversion of one row of
// sums. False when a sink took the row (nothing written). (convolution_bytes.cpp)
bool finishRow(Convolution& cv, TransferState* counting, Image4& row, uint8_t* out);

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

// ---- form 1: byte gather (convolution_bytes_gather.cpp)
// Output byte c of group (x, y) = table[c][source byte c at (x + dx[c], y + dy[c])], the
// coordinates clamped under REPLICATE and table[c][kBorderEntry] outside under CONSTANT.
struct GatherPlan {
  int dx[kGroup] = {}, dy[kGroup] = {};  // n - Cw, m - Ch of the component's tap
  uint8_t table[kGroup][kTableEntries] = {};
  bool identity = true;  // every table maps each byte value to itself
};
bool planGather(Convolution& cv, GatherPlan& plan);
void gatherRows(const Convolution& cv, const GatherPlan& plan, const Kernels& k, const uint8_t* src,
                uint8_t* out, int y0, int y1);

// ---- form 2: SIMD sums (convolution_bytes_sums.cpp)
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
bool chooseKernels(SimdLevel simd, Kernels& k);
RowConversion chooseConversion(const TransferState& t, const Convolution& cv, const Kernels& k);
bool sumRows(Convolution& cv, const RowConversion& rc, const Kernels& k, TransferState* counting,
             const uint8_t* src, uint8_t* out, int y0, int y1);

// ---- form 3: integer sums (convolution_bytes_dyadic.cpp)
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
bool haveAvx2ForDyadic();
bool planDyadic(const Convolution& cv, DyadicPlan& plan);
void separableRows(const Convolution& cv, const DyadicPlan& plan, const uint8_t* src, uint8_t* out,
                   int y0, int y1);
void dyadicRows(const Convolution& cv, const DyadicPlan& plan, const uint8_t* src, uint8_t* out,
                int y0, int y1);

}  // namespace sl::imaging::detail::conv_bytes
