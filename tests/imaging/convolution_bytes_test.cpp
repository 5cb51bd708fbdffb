// The 8-bit convolution path (imaging/convolution_bytes.cpp: byte gather for one tap per
// component, SIMD sums otherwise) gives exactly the bytes of the general float path:
// runPipeline on an Image4 of the same source (each byte as v / 255), then the final
// conversion of 4.3.2 (round(clamp(c) * 255)). Both instruction sets of the sums are checked
// (AVX2 where this CPU has it, and the SSE2 baseline), on random images, every border mode,
// odd sizes, and the stages before and after the convolution. Exact equality is the
// expectation: the fast path claims the same float operations in the same order.
#include <random>

#include "imaging/imaging_test_util.h"
#include "imaging/internal.h"

namespace sl::imaging::testing {
namespace {

using detail::ConvolutionFilter;
using detail::Dimensionality;
using detail::Image4;
using detail::Rgba;
using detail::SimdLevel;
using detail::TransferState;

struct Size {
  int w, h;
};
// Odd widths and heights (1, 3, 17), a square, and one large enough to run on both cores.
const Size kSizes[] = {{1, 1}, {3, 2}, {17, 5}, {1, 9}, {16, 16}, {33, 17}, {256, 192}};

// The general path: runPipeline on floats, then 4.3.2's conversion of each component.
std::vector<uint8_t> generalPath(TransferState t, const std::vector<uint8_t>& src, int w, int h,
                                 int& ow, int& oh, bool& kept) {
  Image4 image(w, h);
  for (size_t i = 0; i < src.size(); ++i) image.px[i] = float(src[i]) / 255.0f;
  kept = detail::runPipeline(t, image, Dimensionality::k2D);
  ow = image.width;
  oh = image.height;
  std::vector<uint8_t> out(image.px.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = toByte(image.px[i]);
  return out;
}

// Runs both paths on random images of every size and asserts equal bytes.
void expectSameBytes(const TransferState& state, const char* what,
                     const std::vector<Size>& sizes = {std::begin(kSizes), std::end(kSizes)}) {
  unsigned seed = 1;
  for (const Size& size : sizes) {
    const std::vector<uint8_t> src = patternImage(size.w, size.h, seed++);
    int gw = 0, gh = 0;
    bool generalKept = true;
    const std::vector<uint8_t> expected =
        generalPath(state, src, size.w, size.h, gw, gh, generalKept);
    for (SimdLevel simd : {SimdLevel::kBest, SimdLevel::kBaseline}) {
      SCOPED_TRACE(::testing::Message() << what << " " << size.w << "x" << size.h << " simd "
                                        << (simd == SimdLevel::kBest ? "best" : "baseline"));
      TransferState t = state;
      std::vector<uint8_t> out(3, 0xCD);  // not the right size: the path must size it
      int ow = -1, oh = -1;
      const bool kept = detail::convolveBytes(t, src, size.w, size.h, out, ow, oh, simd);
      ASSERT_EQ(kept, generalKept);
      if (gw == 0 || gh == 0) {  // REDUCE by a filter larger than the image: "simply null"
        EXPECT_EQ(size_t(ow) * size_t(oh), 0u);
        EXPECT_TRUE(out.empty());
        continue;
      }
      ASSERT_EQ(ow, gw);
      ASSERT_EQ(oh, gh);
      if (!kept) continue;
      ASSERT_EQ(out.size(), expected.size());
      for (size_t i = 0; i < out.size(); ++i)
        ASSERT_EQ(int(out[i]), int(expected[i]))
            << "group " << i / 4 << " (x " << (i / 4) % size_t(std::max(ow, 1)) << ", y "
            << (i / 4) / size_t(std::max(ow, 1)) << ") component " << i % 4;
    }
  }
}

ConvolutionFilter filter2D(int w, int h, const std::vector<float>& rgba, GLenum border,
                           Rgba borderColor = {0, 0, 0, 0}, GLenum format = GL_RGBA) {
  ConvolutionFilter f;
  f.format = format;
  f.internalFormat = format;
  f.width = w;
  f.height = h;
  f.image.resize(size_t(w) * h);
  for (size_t k = 0; k < f.image.size(); ++k)
    for (int c = 0; c < 4; ++c) f.image[k][c] = rgba[k * 4 + c];
  f.borderMode = border;
  f.borderColor = borderColor;
  return f;
}

TransferState with2D(const ConvolutionFilter& f) {
  TransferState t;
  t.conv2D = f;
  t.convolution2DEnabled = true;
  return t;
}

// Brabec–Seidel Eq. (1): R from (0,0), G from (1,0), B from (0,1), A from (1,1), weight 1.
std::vector<float> packingKernel() {
  std::vector<float> k(9 * 4, 0.0f);
  k[(0 * 3 + 0) * 4 + 0] = 1;
  k[(0 * 3 + 1) * 4 + 1] = 1;
  k[(1 * 3 + 0) * 4 + 2] = 1;
  k[(1 * 3 + 1) * 4 + 3] = 1;
  return k;
}

std::vector<float> randomKernel(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> weight(-0.6f, 0.9f);  // negative weights included
  std::vector<float> k(size_t(w) * h * 4);
  for (float& v : k) v = weight(rng);
  return k;
}

const Rgba kBorderColor = {0.25f, 0.9f, -0.3f, 1.5f};  // unclamped, as the spec allows
const GLenum kBorders[] = {GL_REDUCE, GL_CONSTANT_BORDER, GL_REPLICATE_BORDER};

const char* borderName(GLenum b) {
  return b == GL_REDUCE ? "REDUCE" : b == GL_CONSTANT_BORDER ? "CONSTANT" : "REPLICATE";
}

TEST(ConvolutionBytes, PackingKernelEveryBorderMode) {
  for (GLenum border : kBorders)
    expectSameBytes(with2D(filter2D(3, 3, packingKernel(), border, kBorderColor)),
                    borderName(border));
}

TEST(ConvolutionBytes, PackingKernelWithStagesAroundIt) {
  // Non-identity component tables (the gather's table pass), a post-convolution scale/bias
  // that pushes some values out of [0, 1], and the border colour through all of them.
  for (GLenum border : kBorders) {
    TransferState t = with2D(filter2D(3, 3, packingKernel(), border, kBorderColor));
    t.scale = {0.8f, 1.1f, 1.0f, 0.5f};
    t.bias = {0.05f, -0.1f, 0.0f, 0.2f};
    t.postConvolutionScale = {1.5f, 0.5f, -1.0f, 2.0f};
    t.postConvolutionBias = {-0.2f, 0.1f, 1.0f, 0.0f};
    t.tables[2].format = t.tables[2].internalFormat = GL_RGBA;
    t.tables[2].width = 16;
    for (int i = 0; i < 16; ++i)
      t.tables[2].entries.push_back({float(15 - i) / 15.0f, float(i * i) / 225.0f, 0.5f, 1.0f});
    t.postColorMatrixTableEnabled = true;
    expectSameBytes(t, borderName(border));
  }
}

TEST(ConvolutionBytes, PackingKernelThenColorMatrix) {
  // A color matrix mixes the components: no longer one source byte per output byte, so the
  // SIMD sums run the packing kernel.
  TransferState t = with2D(filter2D(3, 3, packingKernel(), GL_REPLICATE_BORDER));
  t.colorMatrixStack.back().m = {0.5f, 0.1f, 0.0f, 0.25f, 0.5f, 0.9f, 0.0f, 0.25f,
                                 0.0f, 0.0f, 1.0f, 0.25f, 0.0f, 0.0f, 0.0f, 0.25f};
  expectSameBytes(t, "packing kernel + sum-into-alpha-like matrix");
}

TEST(ConvolutionBytes, Blur3x3EveryBorderMode) {
  const std::vector<float> k = detail::binomialBlur3x3Rgba();
  for (GLenum border : kBorders)
    expectSameBytes(with2D(filter2D(3, 3, k, border, kBorderColor)), borderName(border));
}

// Dyadic kernels (weights N / 2^D) on the plain 8-bit prefix take the integer sums
// (convolution_bytes.cpp form 3): bytes from (I + 2^(D-1)) >> D, and the rounding ties
// (I = 2^(D-1) mod 2^D) summed again in floats. The expectation is the float path's bytes.
std::vector<float> outerProduct(const std::vector<int>& a, const std::vector<int>& b, int unit) {
  std::vector<float> k(a.size() * b.size() * 4);
  for (size_t m = 0; m < a.size(); ++m)
    for (size_t n = 0; n < b.size(); ++n)
      for (int c = 0; c < 4; ++c) k[(m * b.size() + n) * 4 + c] = float(a[m] * b[n]) / float(unit);
  return k;
}

TEST(ConvolutionBytes, DyadicBinomialKernelsWithRoundingTies) {
  for (GLenum border : {GLenum(GL_REDUCE), GLenum(GL_REPLICATE_BORDER)}) {
    expectSameBytes(with2D(filter2D(3, 3, outerProduct({1, 2, 1}, {1, 2, 1}, 16), border)),
                    borderName(border));
    expectSameBytes(
        with2D(filter2D(5, 5, outerProduct({1, 4, 6, 4, 1}, {1, 4, 6, 4, 1}, 256), border)),
        borderName(border));
    expectSameBytes(with2D(filter2D(3, 1, outerProduct({1}, {1, 2, 1}, 4), border)),
                    borderName(border));
  }
  // The largest test image really has ties for the 3x3 binomial (I = 8 mod 16), so the float
  // re-summation is exercised, not only the integer bytes.
  const std::vector<uint8_t> src = patternImage(256, 192, 7);
  int ties = 0;
  for (int y = 1; y + 1 < 192; ++y)
    for (int x = 1; x + 1 < 256; ++x)
      for (int c = 0; c < 4; ++c) {
        int sum = 0;
        const int w[9] = {1, 2, 1, 2, 4, 2, 1, 2, 1};
        for (int m = 0; m < 3; ++m)
          for (int n = 0; n < 3; ++n)
            sum +=
                w[m * 3 + n] * src[(size_t(y + m - 1) * 256 + size_t(x + n - 1)) * 4 + size_t(c)];
        ties += sum % 16 == 8;
      }
  EXPECT_GT(ties, 1000);
}

// The binomial 3x3 blur's own form (column sums straight from the source rows, adds only):
// widths around its 32-component vectors (7, 8, 9 groups; 129 and 300: vectors and a tail),
// one and two groups (the edge replication is all there is), heights 1-5, as a 2D filter and
// as the same kernel given separably (glSeparableFilter2D), with the ties these images have.
TEST(ConvolutionBytes, Binomial3x3AtVectorEdgesAndOddSizes) {
  const std::vector<Size> sizes = {{1, 3}, {2, 2},   {7, 3},   {8, 4},
                                   {9, 5}, {129, 7}, {300, 3}, {33, 1}};
  for (GLenum border : {GLenum(GL_REDUCE), GLenum(GL_REPLICATE_BORDER)}) {
    expectSameBytes(with2D(filter2D(3, 3, outerProduct({1, 2, 1}, {1, 2, 1}, 16), border)),
                    borderName(border), sizes);
    TransferState t;
    ConvolutionFilter& f = t.separable2D;
    f.width = 3;
    f.height = 3;
    const float w[3] = {0.25f, 0.5f, 0.25f};  // (1, 2, 1) / 4: the product is (1 2 1)^2 / 16
    for (int n = 0; n < 3; ++n) f.row.push_back({w[n], w[n], w[n], w[n]});
    for (int m = 0; m < 3; ++m) f.column.push_back({w[m], w[m], w[m], w[m]});
    f.borderMode = border;
    t.separable2DEnabled = true;
    expectSameBytes(t, borderName(border), sizes);
  }
}

TEST(ConvolutionBytes, DyadicWeightsDifferentPerComponentAndSumsBelowOne) {
  // R: 3x3 binomial; G: a cross summing to 1 in eighths; B: numerators 3 (not powers of two,
  // so the float products round) summing to 15/16; A: every tap 1/32 (9/32 in all).
  const int r[9] = {1, 2, 1, 2, 4, 2, 1, 2, 1}, g[9] = {0, 1, 0, 1, 4, 1, 0, 1, 0},
            b[9] = {1, 1, 1, 3, 3, 3, 1, 1, 1};
  std::vector<float> k(9 * 4);
  for (int t = 0; t < 9; ++t) {
    k[t * 4 + 0] = float(r[t]) / 16.0f;
    k[t * 4 + 1] = float(g[t]) / 8.0f;
    k[t * 4 + 2] = float(b[t]) / 16.0f;
    k[t * 4 + 3] = 1.0f / 32.0f;
  }
  for (GLenum border : {GLenum(GL_REDUCE), GLenum(GL_REPLICATE_BORDER)})
    expectSameBytes(with2D(filter2D(3, 3, k, border)), borderName(border));
}

TEST(ConvolutionBytes, DyadicSeparableKernelsDifferentPerComponent) {
  // Every component an outer product of integer vectors (the separable integer form: column
  // sums, then row sums), each a different one: R the 3x3 binomial on a 5x3 grid, G a row
  // with a zero in the middle, B a single centre tap, A no tap at all (sums to 0).
  const int r[15] = {0, 1, 2, 1, 0, 0, 2, 4, 2, 0, 0, 1, 2, 1, 0};
  const int g[15] = {1, 0, 0, 0, 1, 2, 0, 0, 0, 2, 1, 0, 0, 0, 1};
  std::vector<float> k(15 * 4, 0.0f);
  for (int t = 0; t < 15; ++t) {
    k[t * 4 + 0] = float(r[t]) / 16.0f;
    k[t * 4 + 1] = float(g[t]) / 8.0f;
    k[t * 4 + 2] = t == 7 ? 1.0f : 0.0f;
  }
  for (GLenum border : {GLenum(GL_REDUCE), GLenum(GL_REPLICATE_BORDER)})
    expectSameBytes(with2D(filter2D(5, 3, k, border)), borderName(border));
}

TEST(ConvolutionBytes, DyadicKernelsOutsideTheIntegerLimits) {
  // A pair of numerators above 128 (pmaddubsw could saturate) and a sum above 1: both must
  // take the float sums, with the same bytes.
  std::vector<float> heavy(9 * 4, 0.0f), over(9 * 4, 0.0f);
  for (int c = 0; c < 4; ++c) {
    heavy[0 * 4 + c] = 127.0f / 256.0f;  // odd numerators: D = 8 is the smallest
    heavy[1 * 4 + c] = 127.0f / 256.0f;
    heavy[4 * 4 + c] = 2.0f / 256.0f;
    for (int t = 0; t < 9; ++t) over[t * 4 + c] = 0.25f;
  }
  expectSameBytes(with2D(filter2D(3, 3, heavy, GL_REPLICATE_BORDER)), "pair above 128");
  expectSameBytes(with2D(filter2D(3, 3, over, GL_REPLICATE_BORDER)), "sum above 1");
}

TEST(ConvolutionBytes, Random5x5And9x9WithNegativeWeights) {
  for (GLenum border : kBorders) {
    expectSameBytes(with2D(filter2D(5, 5, randomKernel(5, 5, 11), border, kBorderColor)),
                    borderName(border));
    expectSameBytes(with2D(filter2D(9, 9, randomKernel(9, 9, 12), border, kBorderColor)),
                    borderName(border));
  }
  // Even and non-square sizes: Cw = floor(Wf / 2) puts the centre right of the middle.
  expectSameBytes(with2D(filter2D(4, 2, randomKernel(4, 2, 13), GL_CONSTANT_BORDER, kBorderColor)),
                  "4x2");
  expectSameBytes(with2D(filter2D(1, 7, randomKernel(1, 7, 14), GL_REPLICATE_BORDER)), "1x7");
}

TEST(ConvolutionBytes, SparseKernelSkipsZeroTaps) {
  // Zero taps and taps feeding one component only (accumulateTaps skips the others).
  std::vector<float> k(5 * 5 * 4, 0.0f);
  k[(0 * 5 + 0) * 4 + 0] = 0.5f;
  k[(0 * 5 + 4) * 4 + 0] = -0.25f;
  k[(2 * 5 + 2) * 4 + 1] = 1.0f;
  k[(4 * 5 + 1) * 4 + 2] = 0.75f;
  k[(3 * 5 + 3) * 4 + 3] = 1.0f;
  k[(3 * 5 + 3) * 4 + 2] = 0.5f;
  for (GLenum border : kBorders)
    expectSameBytes(with2D(filter2D(5, 5, k, border, kBorderColor)), borderName(border));
}

TEST(ConvolutionBytes, SeparableFilter) {
  for (GLenum border : kBorders) {
    TransferState t;
    ConvolutionFilter& f = t.separable2D;
    f.width = 7;
    f.height = 3;
    const std::vector<float> row = randomKernel(7, 1, 21), column = randomKernel(3, 1, 22);
    for (int n = 0; n < 7; ++n)
      f.row.push_back({row[n * 4], row[n * 4 + 1], row[n * 4 + 2], row[n * 4 + 3]});
    for (int m = 0; m < 3; ++m)
      f.column.push_back({column[m * 4], column[m * 4 + 1], column[m * 4 + 2], column[m * 4 + 3]});
    f.borderMode = border;
    f.borderColor = kBorderColor;
    t.separable2DEnabled = true;
    expectSameBytes(t, borderName(border));
  }
}

TEST(ConvolutionBytes, PostConvolutionScaleBias) {
  for (GLenum border : kBorders) {
    TransferState t = with2D(filter2D(3, 3, randomKernel(3, 3, 31), border, kBorderColor));
    t.postConvolutionScale = {1.7f, 0.3f, -0.5f, 2.5f};
    t.postConvolutionBias = {-0.1f, 0.4f, 0.9f, -0.6f};
    expectSameBytes(t, borderName(border));
  }
}

TEST(ConvolutionBytes, ColorTablesBeforeAndAfter) {
  TransferState t =
      with2D(filter2D(3, 3, randomKernel(3, 3, 41), GL_CONSTANT_BORDER, kBorderColor));
  auto table = [](int width, int shift) {
    detail::ColorTable ct;
    ct.format = ct.internalFormat = GL_RGBA;
    ct.width = width;
    for (int i = 0; i < width; ++i)
      ct.entries.push_back({float((i * 7 + shift) % width) / float(width - 1),
                            float((i * 3 + shift) % width) / float(width - 1),
                            1.0f - float(i) / float(width - 1), 0.5f});
    return ct;
  };
  t.tables[0] = table(32, 1);
  t.colorTableEnabled = true;  // before: the table form of stages 1-3
  t.tables[1] = table(64, 5);
  t.postConvolutionTableEnabled = true;
  t.tables[2] = table(16, 2);
  t.tables[2].format = GL_LUMINANCE;
  t.postColorMatrixTableEnabled = true;
  expectSameBytes(t, "tables before and after");
  // Stage 1 scale/bias alone: the arithmetic conversion of the source rows.
  TransferState s = with2D(filter2D(3, 3, randomKernel(3, 3, 42), GL_REPLICATE_BORDER));
  s.scale = {1.25f, 0.5f, -1.0f, 1.0f};
  s.bias = {0.0f, 0.25f, 1.0f, -0.125f};
  expectSameBytes(s, "stage 1 scale/bias");
}

TEST(ConvolutionBytes, PassThroughComponentsOfLuminanceFilter) {
  // Table 3.14: a LUMINANCE filter convolves R, G, B and passes A under the filter centre.
  ConvolutionFilter f =
      filter2D(3, 3, randomKernel(3, 3, 51), GL_REPLICATE_BORDER, {}, GL_LUMINANCE);
  for (Rgba& v : f.image) v[1] = v[2] = v[0], v[3] = 0.0f;  // what filterImage stores
  expectSameBytes(with2D(f), "luminance filter");
}

TEST(ConvolutionBytes, NonFiniteValuesTakeTheGeneralStrips) {
  // An infinite stage-1 scale makes infinite source values: zero-weight terms then matter
  // (Inf * 0 = NaN), so the fast forms step aside; the bytes must still match.
  TransferState t = with2D(filter2D(3, 3, packingKernel(), GL_CONSTANT_BORDER, kBorderColor));
  t.scale = {std::numeric_limits<float>::infinity(), 1.0f, 1.0f, 1.0f};
  expectSameBytes(t, "infinite red scale", {{17, 5}});
}

TEST(ConvolutionBytes, MinmaxAndHistogramSeeTheSameValues) {
  TransferState t = with2D(filter2D(3, 3, randomKernel(3, 3, 61), GL_REPLICATE_BORDER));
  t.minmaxEnabled = true;
  t.minmax.format = GL_RGBA;
  detail::resetMinmax(t.minmax);
  t.histogramEnabled = true;
  t.histogram.format = GL_RGBA;
  t.histogram.width = 32;
  t.histogram.counts.assign(32, {0, 0, 0, 0});
  expectSameBytes(t, "counting", {{33, 17}});
  const std::vector<uint8_t> src = patternImage(33, 17, 9);
  TransferState general = t, fast = t;
  int ow = 0, oh = 0;
  bool kept = true;
  generalPath(general, src, 33, 17, ow, oh, kept);  // (a copy: generalPath takes it by value)
  Image4 image(33, 17);
  for (size_t i = 0; i < src.size(); ++i) image.px[i] = float(src[i]) / 255.0f;
  detail::runPipeline(general, image, Dimensionality::k2D);
  std::vector<uint8_t> out;
  detail::convolveBytes(fast, src, 33, 17, out, ow, oh);
  EXPECT_EQ(fast.minmax.min, general.minmax.min);
  EXPECT_EQ(fast.minmax.max, general.minmax.max);
  EXPECT_EQ(fast.histogram.counts, general.histogram.counts);
  // A sink: nothing written, the general path keeps nothing either.
  t.minmax.sink = true;
  expectSameBytes(t, "minmax sink", {{17, 5}});
}

}  // namespace
}  // namespace sl::imaging::testing
