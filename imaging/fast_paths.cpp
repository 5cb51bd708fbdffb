// imaging/fast_paths.cpp — the pipeline on 8-bit RGBA spans without float images, for the
// common case of the Brabec–Seidel passes: 8-bit source, 8-bit destination, only
// per-component stages (scale/bias, GL_MAP_COLOR, the color tables) and the color matrix.
//
// Every per-component stage before the color matrix is a function of one input byte, so it
// is evaluated once for the 256 possible values by the very same stage code (pixel_transfer,
// color_table) and kept as a table. The color matrix then sums its non-zero coefficients
// times those values, in the same order and with the same float operations as
// applyColorMatrix, so the bytes written are identical to the general path's.
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "imaging/internal.h"

namespace sl::imaging::detail {
namespace {

// The final conversion of 4.3.2 / 2.13.9 to a byte.
inline uint8_t toByte(float v) {
  const float c = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
  return uint8_t(c * 255.0f + 0.5f);
}

// One output component of the color-matrix byte path (transformBytes).
struct RowPlan {
  enum Kind { kConstant, kTable, kFloat } kind = kConstant;
  int count = 0;                                     // non-zero matrix coefficients in the row
  int component[4] = {0, 0, 0, 0};                   // input component of each term
  const float* product[4] = {};                      // 256 products per term
  float coefficient[4] = {0, 0, 0, 0};               // kFloat: the term's matrix coefficient
  std::array<std::array<uint32_t, 256>, 4> index{};  // kTable: byte -> offset into table
  std::vector<uint8_t> table;                        // kTable: final byte per combination
  uint8_t constant = 0;                              // kConstant
  bool plain = false;                                // kFloat: the byte is toByte(sum)
};
constexpr size_t kMaxCombinedTable = 1u << 16;  // entries (bytes) of one combined table
constexpr size_t kChunkGroups = 512;            // RGBA groups per branch-free pass
// The vector maps do a group in about an eighth of the scalar loop's time: the work measure
// that decides whether a second thread pays is divided by this.
constexpr size_t kVectorSpeedup = 8;

// out[g * 4] = table[sum of the terms' offsets for group g]; N terms.
template <int N>
void tableRow(const RowPlan& plan, const uint8_t* in, uint8_t* out, size_t m) {
  const uint8_t* const table = plan.table.data();
  const uint32_t* o[N];
  int c[N];
  for (int i = 0; i < N; ++i) {
    o[i] = plan.index[size_t(i)].data();
    c[i] = plan.component[i];
  }
  for (size_t g = 0; g < m; ++g) {
    const uint8_t* const x = in + g * 4;
    uint32_t k = o[0][x[c[0]]];
    for (int i = 1; i < N; ++i) k += o[i][x[c[i]]];
    out[g * 4] = table[k];
  }
}

// toByte over a span, four floats at a time where SSE2 is there: maxps(v, 0) is v > 0 ? v : 0
// and minps(c, 1) is c < 1 ? c : 1, toByte's own comparisons (NaN and -0 give 0), then the same
// multiply, add and truncation.
void toBytes(const float* v, uint8_t* o, size_t n) {
  size_t i = 0;
#if defined(__SSE2__)
  const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
  const __m128 scale = _mm_set1_ps(255.0f), half = _mm_set1_ps(0.5f);
  auto convert = [&](const float* p) {
    const __m128 c = _mm_min_ps(_mm_max_ps(_mm_loadu_ps(p), zero), one);
    return _mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(c, scale), half));
  };
  for (; i + 16 <= n; i += 16) {
    const __m128i lo = _mm_packs_epi32(convert(v + i), convert(v + i + 4));
    const __m128i hi = _mm_packs_epi32(convert(v + i + 8), convert(v + i + 12));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(o + i), _mm_packus_epi16(lo, hi));
  }
#endif
  for (; i < n; ++i) o[i] = toByte(v[i]);
}

}  // namespace

bool bytePathApplies(const TransferState& t) {
  return !(t.histogramEnabled || t.minmaxEnabled || t.convolution2DEnabled || t.separable2DEnabled);
}

bool transformBytes(TransferState& t, std::vector<uint8_t>& bytes, int w, int h, BytePath path) {
  if (!bytePathApplies(t)) return false;
  // The colour matrix as the only stage: the vector form of color_matrix_groups.cpp, in place,
  // where the processor has AVX-512. Its AVX2 and SSE2 forms (GCC splits the 16-lane vectors,
  // comparisons and byte narrowing partly lane by lane) measured slower than the loops below
  // on RGBA8 (tools/imaging_bench's stage without the matrix vectors, and matrixGroupsToBytes
  // at each MatrixIsa); for client RGB / float groups they still beat the float image.
  if (path == BytePath::kFastest && matrixOnlyPipeline(t) &&
      matrixIsaAvailable(MatrixIsa::kAvx512)) {
    PixelStore tight;
    tight.alignment = 1;
    matrixGroupsToBytes(t, bytes.data(), w, h, GL_RGBA, GL_UNSIGNED_BYTE, tight, bytes.data());
    return true;
  }
  // The per-component prefix on the 256 byte values, by the general stages themselves.
  TransferState prefix = t;
  prefix.colorMatrixStack = {Matrix4{}};
  prefix.postColorMatrixScale = {1, 1, 1, 1};
  prefix.postColorMatrixBias = {0, 0, 0, 0};
  prefix.postColorMatrixTableEnabled = false;
  Image4 values(256, 1);
  for (int v = 0; v < 256; ++v)
    for (int c = 0; c < 4; ++c) values.px[size_t(v) * 4 + c] = float(v) / 255.0f;
  runPipeline(prefix, values, Dimensionality::k2D);
  const Matrix4& m = t.colorMatrixStack.back();
  if (m.isIdentity()) {
    // Everything is per component: one byte table per component.
    TransferState suffix;
    suffix.postColorMatrixScale = t.postColorMatrixScale;
    suffix.postColorMatrixBias = t.postColorMatrixBias;
    suffix.tables[2] = t.tables[2];
    suffix.postColorMatrixTableEnabled = t.postColorMatrixTableEnabled;
    runPipeline(suffix, values, Dimensionality::k2D);
    uint8_t lut[256 * 4];
    for (int i = 0; i < 256 * 4; ++i) lut[i] = toByte(values.px[size_t(i)]);
    // Four tables of 32-bit words, each with its component's byte in place: a group is one
    // 32-bit load, four lookups ORed together and one store.
    std::array<std::array<uint32_t, 256>, 4> words;
    for (int c = 0; c < 4; ++c)
      for (int v = 0; v < 256; ++v)
        words[size_t(c)][size_t(v)] = uint32_t(lut[v * 4 + c]) << (8 * c);
    auto scalar = [&words](uint8_t* p, size_t groups) {
      const uint32_t* const r = words[0].data();
      const uint32_t* const g = words[1].data();
      const uint32_t* const b = words[2].data();
      const uint32_t* const a = words[3].data();
      for (size_t i = 0; i < groups * 4; i += 4) {
        uint32_t x;
        std::memcpy(&x, p + i, 4);  // RGBA bytes, little-endian
        const uint32_t v = r[x & 0xff] | g[(x >> 8) & 0xff] | b[(x >> 16) & 0xff] | a[x >> 24];
        std::memcpy(p + i, &v, 4);
      }
    };
    // A table with few steps per component (the Brabec-Seidel table has one) is evaluated as
    // byte comparisons, 32 bytes at a time (byte_maps.cpp).
    StepMap steps;
    const bool fastest = path == BytePath::kFastest;
    const bool stepped = fastest && vectorMapsAvailable() && planStepMap(lut, steps);
    // Any other table: byte permutes over the 256 entries where the processor has them.
    const bool permuted = fastest && !stepped && vectorTablesAvailable();
    const bool vector = stepped || permuted;
    parallelRows(h, vector ? size_t(w) / kVectorSpeedup : size_t(w), [&](int y0, int y1) {
      uint8_t* p = bytes.data() + size_t(y0) * w * 4;
      const size_t n = size_t(y1 - y0) * w * 4;
      const size_t done = stepped    ? applyStepMap(steps, p, n)
                          : permuted ? applyByteTable(lut, p, n)
                                     : 0;
      scalar(p + done, (n - done) / 4);
    });
    return true;
  }
  // Rows of diag(scale) * Mc as applyColorMatrix forms them; term[r][k][v] = k_rk * L_k(v).
  float k[16];
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) k[r * 4 + c] = m.m[c * 4 + r];
  struct Term {
    int component;
    float coefficient;
    std::vector<float> product;  // 256 entries: coefficient times the prefix value
  };
  std::array<std::vector<Term>, 4> rows;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      if (k[r * 4 + c] == 0.0f) continue;  // zero coefficients add nothing
      Term term{c, k[r * 4 + c], std::vector<float>(256)};
      for (int v = 0; v < 256; ++v) term.product[v] = k[r * 4 + c] * values.px[size_t(v) * 4 + c];
      rows[r].push_back(std::move(term));
    }
  const Rgba scale = t.postColorMatrixScale, bias = t.postColorMatrixBias;
  const bool scaled = scale != Rgba{1, 1, 1, 1};
  const bool table = t.postColorMatrixTableEnabled && t.tables[2].width > 0;
  // The post-color-matrix table as a float -> byte step: index -> final byte.
  Image4 tableOut;
  if (table) {
    tableOut = Image4(t.tables[2].width, 1);
    for (int i = 0; i < tableOut.width; ++i)
      for (int c = 0; c < 4; ++c)
        tableOut.px[size_t(i) * 4 + c] =
            t.tables[2].width > 1 ? float(i) / float(t.tables[2].width - 1) : 0.0f;
    applyColorTable(t.tables[2], tableOut);
  }
  const float tableScale = table ? float(t.tables[2].width - 1) : 0.0f;
  bool replaced[4] = {false, false, false, false};  // table 3.13
  if (table) {
    const FormatComponents f = componentsOf(t.tables[2].format);
    replaced[0] = f.r || f.l || f.i;
    replaced[1] = f.g || f.l || f.i;
    replaced[2] = f.b || f.l || f.i;
    replaced[3] = f.a || f.i;
  }
  // The conversion of a matrix output to its byte: post scale/bias, post-matrix table
  // (replaced components only), final conversion.
  auto finish = [&](int r, float sum) {
    float v = scaled ? sum * scale[r] + bias[r] : sum + bias[r];
    if (replaced[r]) {
      const float c = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
      v = tableOut.px[size_t(int(c * tableScale + 0.5f)) * 4 + r];
    }
    return toByte(v);
  };
  // `finish` before its final conversion, over a span of sums in place.
  auto finishSpan = [&](int r, float* v, size_t m) {
    const float sr = scale[size_t(r)], br = bias[size_t(r)];
    if (scaled) {
      for (size_t g = 0; g < m; ++g) v[g] = v[g] * sr + br;
    } else {
      for (size_t g = 0; g < m; ++g) v[g] = v[g] + br;
    }
    if (!replaced[r]) return;
    for (size_t g = 0; g < m; ++g) {
      const float c = v[g] > 0.0f ? (v[g] < 1.0f ? v[g] : 1.0f) : 0.0f;
      v[g] = tableOut.px[size_t(int(c * tableScale + 0.5f)) * 4 + r];
    }
  };
  // Each output component is a function of at most four input bytes through its terms'
  // products. Where those products take few distinct floats (the Brabec-Seidel table leaves
  // two per component), the whole conversion of a row is one byte table indexed by the
  // distinct-value indices, filled by the very same float sums and `finish` as below, so the
  // bytes are identical; otherwise the floats are summed per pixel.
  std::array<RowPlan, 4> plans;
  for (int r = 0; r < 4; ++r) {
    RowPlan& plan = plans[size_t(r)];
    plan.count = int(rows[r].size());
    const bool plain = !scaled && bias[r] == 0.0f && !replaced[r];
    auto convert = [&](float sum) { return plain ? toByte(sum) : finish(r, sum); };
    if (plan.count == 0) {
      plan.kind = RowPlan::kConstant;
      plan.constant = finish(r, 0.0f);
      continue;
    }
    std::array<std::vector<float>, 4> distinct;
    size_t combos = 1;
    for (int i = 0; i < plan.count; ++i) {
      const Term& term = rows[r][size_t(i)];
      plan.component[i] = term.component;
      plan.product[i] = term.product.data();
      plan.coefficient[i] = term.coefficient;
      // The distinct values by their bits (-0 and NaN payloads stay distinct), through a
      // sort of (bits, byte) pairs: 256 log 256 steps, not 256^2 comparisons.
      std::array<std::pair<uint32_t, int>, 256> keyed;
      for (int v = 0; v < 256; ++v) {
        uint32_t bits;
        std::memcpy(&bits, &term.product[size_t(v)], sizeof bits);
        keyed[size_t(v)] = {bits, v};
      }
      std::sort(keyed.begin(), keyed.end());
      std::array<uint32_t, 256> index{};
      for (size_t k = 0; k < keyed.size(); ++k) {
        if (k == 0 || keyed[k].first != keyed[k - 1].first)
          distinct[i].push_back(term.product[size_t(keyed[k].second)]);
        index[size_t(keyed[k].second)] = uint32_t(distinct[i].size() - 1);
      }
      plan.index[i] = index;
      combos *= distinct[i].size();
    }
    if (combos > kMaxCombinedTable) {
      plan.kind = RowPlan::kFloat;
      plan.plain = plain;
      continue;
    }
    plan.kind = RowPlan::kTable;
    // Strides: term 0 varies slowest. offset_i[v] = index_i(v) * stride_i.
    uint32_t stride = 1;
    std::array<uint32_t, 4> strides{};
    for (int i = plan.count - 1; i >= 0; --i) {
      strides[size_t(i)] = stride;
      stride *= uint32_t(distinct[i].size());
    }
    for (int i = 0; i < plan.count; ++i)
      for (int v = 0; v < 256; ++v) plan.index[i][size_t(v)] *= strides[size_t(i)];
    plan.table.resize(combos);
    for (size_t k = 0; k < combos; ++k) {
      float sum = distinct[0][k / strides[0] % distinct[0].size()];
      for (int i = 1; i < plan.count; ++i)
        sum = sum + distinct[i][k / strides[size_t(i)] % distinct[i].size()];
      plan.table[k] = convert(sum);
    }
  }
  bool planar[4] = {false, false, false, false};  // prefix values a kFloat row reads
  for (const RowPlan& plan : plans)
    if (plan.kind == RowPlan::kFloat)
      for (int i = 0; i < plan.count; ++i) planar[plan.component[i]] = true;
  auto scalar = [&](uint8_t* const p, const size_t n) {
    // Chunks of groups: the inputs are copied aside so that each output component can be
    // written in its own branch-free pass.
    uint8_t in[kChunkGroups * 4];
    float prefix[4][kChunkGroups];  // kFloat rows: the prefix value of each component, planar
    for (size_t g0 = 0; g0 < n; g0 += kChunkGroups) {
      const size_t m = std::min(kChunkGroups, n - g0);
      uint8_t* const q = p + g0 * 4;
      std::memcpy(in, q, m * 4);
      for (int c = 0; c < 4; ++c)
        if (planar[c])
          for (size_t g = 0; g < m; ++g) prefix[c][g] = values.px[size_t(in[g * 4 + c]) * 4 + c];
      for (int r = 0; r < 4; ++r) {
        const RowPlan& plan = plans[size_t(r)];
        switch (plan.kind) {
          case RowPlan::kConstant:
            for (size_t g = 0; g < m; ++g) q[g * 4 + r] = plan.constant;
            break;
          case RowPlan::kTable:
            switch (plan.count) {
              case 1: tableRow<1>(plan, in, q + r, m); break;
              case 2: tableRow<2>(plan, in, q + r, m); break;
              case 3: tableRow<3>(plan, in, q + r, m); break;
              default: tableRow<4>(plan, in, q + r, m); break;
            }
            break;
          case RowPlan::kFloat: {
            // Term by term over the chunk: per group the same products (coefficient times
            // prefix value, as in the product tables) added in the same order as
            // applyColorMatrix, so the multiplies, sums and conversion vectorise.
            float sum[kChunkGroups];
            uint8_t out[kChunkGroups];
            const float k0 = plan.coefficient[0];
            const float* const first = prefix[plan.component[0]];
            for (size_t g = 0; g < m; ++g) sum[g] = k0 * first[g];
            for (int i = 1; i < plan.count; ++i) {
              const float ki = plan.coefficient[i];
              const float* const term = prefix[plan.component[i]];
              for (size_t g = 0; g < m; ++g) sum[g] = sum[g] + ki * term[g];
            }
            if (!plan.plain) finishSpan(r, sum, m);
            toBytes(sum, out, m);
            for (size_t g = 0; g < m; ++g) q[g * 4 + r] = out[g];
            break;
          }
        }
      }
    }
  };
  // Where each component's prefix values fall into few runs and the groups into at most 16
  // classes (Brabec-Seidel's table and sum-into-alpha matrix: 2 x 2 x 2 x 2), every group is
  // a shuffle of its class index into bytes the scalar loop gave one group of each class
  // (byte_maps.cpp).
  bool matters[4] = {false, false, false, false};
  for (int r = 0; r < 4; ++r)
    for (const Term& term : rows[r]) matters[term.component] = true;
  auto samePrefix = [&values](int c, int v) {
    return std::memcmp(&values.px[size_t(v) * 4 + c], &values.px[size_t(v - 1) * 4 + c],
                       sizeof(float)) == 0;  // bitwise: the products are then bitwise equal
  };
  ClassMap classes;
  const bool vector = path == BytePath::kFastest && vectorMapsAvailable() &&
                      planClassMap(samePrefix, matters, scalar, classes);
  parallelRows(h, vector ? size_t(w) / kVectorSpeedup : size_t(w) * 4, [&](int y0, int y1) {
    uint8_t* const p = bytes.data() + size_t(y0) * w * 4;
    const size_t n = size_t(y1 - y0) * w * 4;
    const size_t done = vector ? applyClassMap(classes, p, n) : 0;
    scalar(p + done, (n - done) / 4);
  });
  return true;
}

}  // namespace sl::imaging::detail

namespace sl::imaging::detail {

// Convolution from 8-bit groups: stages 1-3 (per component) give float values per byte
// value; the filter runs over strips of padded float rows built on the fly; stages 4-9 run on
// each output row with the general stage code; the final conversion writes bytes. Same
// floats, same order of operations as the general path (Image4 throughout), so the same
// bytes, without whole-image float buffers. convolveBytes (convolution_bytes.cpp) runs this
// strip form only where its faster forms do not apply (non-finite stage values).
bool convolveBytesApplies(const TransferState& t) {
  if (t.convolution2DEnabled) return t.conv2D.width > 0 && t.conv2D.height > 0;
  if (t.separable2DEnabled) return t.separable2D.width > 0 && !t.separable2D.column.empty();
  return false;
}

bool convolveBytesStrips(TransferState& t, const std::vector<uint8_t>& src, int ws, int hs,
                         std::vector<uint8_t>& out, int& ow, int& oh) {
  const bool separable = !t.convolution2DEnabled;
  const ConvolutionFilter& f = separable ? t.separable2D : t.conv2D;
  // Stages 1-3 on the 256 byte values.
  TransferState prefix;
  prefix.scale = t.scale;
  prefix.bias = t.bias;
  prefix.mapColor = t.mapColor;
  prefix.colorMaps = t.colorMaps;
  prefix.tables[0] = t.tables[0];
  prefix.colorTableEnabled = t.colorTableEnabled;
  Image4 values(256, 1);
  for (int v = 0; v < 256; ++v)
    for (int c = 0; c < 4; ++c) values.px[size_t(v) * 4 + c] = float(v) / 255.0f;
  runPipeline(prefix, values, Dimensionality::k2D);
  // Stages 5-7 (histogram and minmax are taken on the real state below).
  TransferState suffix = t;
  suffix.scale = {1, 1, 1, 1};
  suffix.bias = {0, 0, 0, 0};
  suffix.mapColor = false;
  suffix.colorTableEnabled = false;
  suffix.convolution2DEnabled = suffix.separable2DEnabled = suffix.convolution1DEnabled = false;
  suffix.histogramEnabled = suffix.minmaxEnabled = false;
  const bool postScaleBias =
      !(t.postConvolutionScale == Rgba{1, 1, 1, 1} && t.postConvolutionBias == Rgba{0, 0, 0, 0});

  int wf = 0, hf = 0;
  const std::vector<Tap> taps = kernelTaps(f, separable, wf, hf);
  const bool reduce = f.borderMode == GL_REDUCE;
  ow = reduce ? ws - wf + 1 : ws;
  oh = reduce ? hs - hf + 1 : hs;
  if (ow <= 0 || oh <= 0) {
    ow = oh = 0;
    out.clear();
    return true;
  }
  const int cw = reduce ? 0 : wf / 2, ch = reduce ? 0 : hf / 2;
  const int pw = reduce ? ws : ws + wf - 1;  // padded row width
  const bool replicate = f.borderMode == GL_REPLICATE_BORDER;
  auto padRow = [&](int py, float* dst) {
    const int sy = py - ch;
    if (sy >= 0 && sy < hs) {
      // Inside rows: the source span straight through the stage 1-3 values, then the
      // border columns (the same values the general loop below gives them).
      const uint8_t* const row = src.data() + size_t(sy) * ws * 4;
      const float* const lut = values.px.data();
      const int x0 = reduce ? 0 : cw;
      float* const d = dst + size_t(x0) * 4;
      for (int i = 0; i < ws * 4; i += 4) {
        d[i + 0] = lut[size_t(row[i + 0]) * 4 + 0];
        d[i + 1] = lut[size_t(row[i + 1]) * 4 + 1];
        d[i + 2] = lut[size_t(row[i + 2]) * 4 + 2];
        d[i + 3] = lut[size_t(row[i + 3]) * 4 + 3];
      }
      if (reduce) return;
      for (int x = 0; x < cw; ++x)
        for (int c = 0; c < 4; ++c)
          dst[x * 4 + c] = replicate ? lut[size_t(row[c]) * 4 + c] : f.borderColor[c];
      for (int x = cw + ws; x < pw; ++x)
        for (int c = 0; c < 4; ++c)
          dst[x * 4 + c] =
              replicate ? lut[size_t(row[size_t(ws - 1) * 4 + c]) * 4 + c] : f.borderColor[c];
      return;
    }
    for (int x = 0; x < pw; ++x) {
      const int sx = x - cw;
      const bool inside = sx >= 0 && sx < ws && sy >= 0 && sy < hs;
      if (inside || replicate) {
        const uint8_t* p =
            src.data() +
            (size_t(std::clamp(sy, 0, hs - 1)) * ws + size_t(std::clamp(sx, 0, ws - 1))) * 4;
        for (int c = 0; c < 4; ++c) dst[x * 4 + c] = values.px[size_t(p[c]) * 4 + c];
      } else {
        for (int c = 0; c < 4; ++c) dst[x * 4 + c] = f.borderColor[c];
      }
    }
  };
  out.resize(size_t(ow) * oh * 4);  // every row is written below unless a sink drops it
  const bool counting = t.histogramEnabled || t.minmaxEnabled;
  bool kept = true;
  constexpr int kStripRows = 16;
  // `padded` and `row` are per-thread buffers reused across strips (a strip of a wide image
  // is larger than malloc's mmap threshold, which would map and fault it anew each time).
  auto strip = [&](int j0, int j1, std::vector<float>& padded, Image4& row) {
    const int rows = j1 - j0 + hf - 1;
    padded.resize(size_t(rows) * pw * 4);  // every row is written by padRow
    for (int r = 0; r < rows; ++r) padRow(j0 + r, padded.data() + size_t(r) * pw * 4);
    for (int j = j0; j < j1; ++j) {
      std::fill(row.px.begin(), row.px.end(), 0.0f);
      accumulateTaps(
          taps, [&](int m) { return padded.data() + size_t(j - j0 + m) * pw * 4; }, ow,
          row.px.data());
      if (postScaleBias)
        for (size_t i = 0; i < row.px.size(); ++i)
          row.px[i] = row.px[i] * t.postConvolutionScale[i & 3] + t.postConvolutionBias[i & 3];
      runPipeline(suffix, row, Dimensionality::k2D);
      if (t.histogramEnabled) {
        accumulateHistogram(t.histogram, row);
        if (t.histogram.sink) {
          kept = false;
          continue;
        }
      }
      if (t.minmaxEnabled) {
        accumulateMinmax(t.minmax, row);
        if (t.minmax.sink) {
          kept = false;
          continue;
        }
      }
      toBytes(row.px.data(), out.data() + size_t(j) * ow * 4, row.px.size());
    }
  };
  const int strips = (oh + kStripRows - 1) / kStripRows;
  auto run = [&](int s0, int s1) {
    std::vector<float> padded;
    Image4 row(ow, 1);
    for (int s = s0; s < s1; ++s)
      strip(s * kStripRows, std::min(oh, (s + 1) * kStripRows), padded, row);
  };
  if (counting) {
    run(0, strips);  // the tables are shared: one thread
  } else {
    parallelRows(strips, size_t(kStripRows) * ow * 4 * (taps.size() + 1), run);
  }
  return kept;
}

}  // namespace sl::imaging::detail
