// imaging/convolution_bytes.cpp — the convolution stage of glspec121 3.6.5 on 8-bit RGBA
// sources for 8-bit destinations (glCopyPixels, glCopyTexSubImage2D of an 8-bit framebuffer),
// fast and bit-identical to the general float path (runPipeline on an Image4, then the final
// conversion of 4.3.2).
//
// The general path computes, per output group and component c: stages 1-3 of each source
// byte (one float per byte value), then C = 0.0f + s_1 * w_1c + s_2 * w_2c + ... over the
// taps of kernelTaps() in their order, one float multiply and one float add per term
// (accumulateTaps), then the post-convolution scale/bias C * scale + bias, stages 5-7 and the
// final conversion. The three forms (one file each) give exactly its bytes:
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

#include "imaging/convolution_bytes_internal.h"

namespace sl::imaging::detail::conv_bytes {
namespace {

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

}  // namespace

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

}  // namespace sl::imaging::detail::conv_bytes

namespace sl::imaging::detail {

using namespace conv_bytes;  // the forms (convolution_bytes_internal.h)

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
