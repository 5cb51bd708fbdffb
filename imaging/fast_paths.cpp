// imaging/fast_paths.cpp — the pipeline on 8-bit RGBA spans without float images, for the
// common case of the Brabec–Seidel passes: 8-bit source, 8-bit destination, only
// per-component stages (scale/bias, GL_MAP_COLOR, the color tables) and the color matrix.
//
// Every per-component stage before the color matrix is a function of one input byte, so it
// is evaluated once for the 256 possible values by the very same stage code (pixel_transfer,
// color_table) and kept as a table. The color matrix then sums its non-zero coefficients
// times those values, in the same order and with the same float operations as
// applyColorMatrix, so the bytes written are identical to the general path's.
#include "imaging/internal.h"

namespace sl::imaging::detail {
namespace {

// The final conversion of 4.3.2 / 2.13.9 to a byte.
inline uint8_t toByte(float v) {
  const float c = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
  return uint8_t(c * 255.0f + 0.5f);
}

}  // namespace

bool bytePathApplies(const TransferState& t) {
  return !(t.histogramEnabled || t.minmaxEnabled || t.convolution2DEnabled ||
           t.separable2DEnabled);
}

bool transformBytes(TransferState& t, std::vector<uint8_t>& bytes, int w, int h) {
  if (!bytePathApplies(t)) return false;
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
    parallelRows(h, size_t(w), [&](int y0, int y1) {
      uint8_t* p = bytes.data() + size_t(y0) * w * 4;
      const size_t n = size_t(y1 - y0) * w * 4;
      for (size_t i = 0; i < n; i += 4) {
        p[i + 0] = lut[p[i + 0] * 4 + 0];
        p[i + 1] = lut[p[i + 1] * 4 + 1];
        p[i + 2] = lut[p[i + 2] * 4 + 2];
        p[i + 3] = lut[p[i + 3] * 4 + 3];
      }
    });
    return true;
  }
  // Rows of diag(scale) * Mc as applyColorMatrix forms them; term[r][k][v] = k_rk * L_k(v).
  float k[16];
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) k[r * 4 + c] = m.m[c * 4 + r];
  struct Term {
    int component;
    std::vector<float> product;  // 256 entries
  };
  std::array<std::vector<Term>, 4> rows;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      if (k[r * 4 + c] == 0.0f) continue;  // zero coefficients add nothing
      Term term{c, std::vector<float>(256)};
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
        tableOut.px[size_t(i) * 4 + c] = t.tables[2].width > 1 ? float(i) / float(t.tables[2].width - 1) : 0.0f;
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
  // Flattened terms per output component; a row without terms is a constant byte.
  struct Row {
    int count = 0;
    int component[4] = {0, 0, 0, 0};
    const float* product[4] = {nullptr, nullptr, nullptr, nullptr};
    uint8_t constant = 0;
  };
  Row flat[4];
  for (int r = 0; r < 4; ++r) {
    flat[r].count = int(rows[r].size());
    for (int i = 0; i < flat[r].count; ++i) {
      flat[r].component[i] = rows[r][size_t(i)].component;
      flat[r].product[i] = rows[r][size_t(i)].product.data();
    }
    flat[r].constant = finish(r, 0.0f);
  }
  parallelRows(h, size_t(w) * 4, [&](int y0, int y1) {
    uint8_t* p = bytes.data() + size_t(y0) * w * 4;
    const size_t n = size_t(y1 - y0) * w;
    for (size_t g = 0; g < n; ++g, p += 4) {
      const uint8_t in[4] = {p[0], p[1], p[2], p[3]};
      for (int r = 0; r < 4; ++r) {
        const Row& row = flat[r];
        if (row.count == 0) {
          p[r] = row.constant;
          continue;
        }
        float sum = row.product[0][in[row.component[0]]];
        for (int i = 1; i < row.count; ++i) sum = sum + row.product[i][in[row.component[i]]];
        p[r] = finish(r, sum);
      }
    }
  });
  return true;
}

}  // namespace sl::imaging::detail
