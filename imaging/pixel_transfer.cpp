// imaging/pixel_transfer.cpp — the pixel-transfer operations of glspec121 3.6.5 on RGBA
// groups, in the specification's order:
//   1. Arithmetic on Components (RED_SCALE/RED_BIAS ...)
//   2. RGBA to RGBA Lookup (GL_MAP_COLOR)
//   3. Color Table Lookup (GL_COLOR_TABLE)
//   4. Convolution (2D, or separable when 2D is disabled; 1D for 1D images) followed by the
//      post-convolution scale and bias — applied only when a convolution is performed
//      (EXT_convolution: "after convolution, each component of the resulting image is scaled")
//   5. Post Convolution Color Table Lookup
//   6. Color Matrix Transformation with post-color-matrix scale and bias
//   7. Post Color Matrix Color Table Lookup
//   8. Histogram (sink discards the groups; minmax is then not performed)
//   9. Minmax (sink discards the groups)
// Stages that are identity are skipped; every stage works on whole float RGBA images.
#include "imaging/internal.h"

namespace sl::imaging::detail {
namespace {

bool isIdentity(const Rgba& scale, const Rgba& bias) {
  return scale == Rgba{1, 1, 1, 1} && bias == Rgba{0, 0, 0, 0};
}

bool convolutionEnabled(const TransferState& t, Dimensionality dims) {
  return dims == Dimensionality::k2D ? (t.convolution2DEnabled || t.separable2DEnabled)
                                     : t.convolution1DEnabled;
}

// Stage 1 (and the post-convolution scale/bias of stage 4): c * scale + bias.
void scaleBias(const Rgba& scale, const Rgba& bias, Image4& image) {
  parallelRows(image.height, size_t(image.width) * 4, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      float* p = image.row(y);
      for (int i = 0; i < image.width * 4; ++i) p[i] = p[i] * scale[i & 3] + bias[i & 3];
    }
  });
}

// Stage 2: "each component is clamped to [0,1] ... multiplied by an integer one less than the
// size of the corresponding table ... rounding ... the addressed value replaces the element".
void mapColor(const std::array<std::vector<float>, 4>& maps, Image4& image) {
  for (size_t k = 0; k < image.px.size(); ++k) {
    const auto& map = maps[k & 3];
    if (map.empty()) continue;
    const float v = image.px[k];
    const float c = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
    image.px[k] = map[size_t(int(c * float(map.size() - 1) + 0.5f))];
  }
}

bool tableActive(bool enabled, const ColorTable& t) { return enabled && t.width > 0; }

}  // namespace

bool pipelineIsIdentity(const TransferState& t, Dimensionality dims) {
  return isIdentity(t.scale, t.bias) && !t.mapColor &&
         !tableActive(t.colorTableEnabled, t.tables[0]) && !convolutionEnabled(t, dims) &&
         !tableActive(t.postConvolutionTableEnabled, t.tables[1]) &&
         t.colorMatrixStack.back().isIdentity() &&
         isIdentity(t.postColorMatrixScale, t.postColorMatrixBias) &&
         !tableActive(t.postColorMatrixTableEnabled, t.tables[2]) && !t.histogramEnabled &&
         !t.minmaxEnabled;
}

void convolvedSize(const TransferState& t, Dimensionality dims, int& w, int& h) {
  if (!convolutionEnabled(t, dims)) return;
  const ConvolutionFilter& f = dims == Dimensionality::k1D ? t.conv1D
                               : t.convolution2DEnabled    ? t.conv2D
                                                           : t.separable2D;
  if (f.borderMode != GL_REDUCE || f.width == 0) return;
  const int hf = dims == Dimensionality::k1D ? 1 : f.height;
  w = std::max(0, w - f.width + 1);
  if (dims == Dimensionality::k2D) h = std::max(0, h - hf + 1);
}

bool runPipeline(TransferState& t, Image4& image, Dimensionality dims) {
  if (!isIdentity(t.scale, t.bias)) scaleBias(t.scale, t.bias, image);                     // 1
  if (t.mapColor) mapColor(t.colorMaps, image);                                            // 2
  if (tableActive(t.colorTableEnabled, t.tables[0])) applyColorTable(t.tables[0], image);  // 3
  if (convolutionEnabled(t, dims)) {                                                       // 4
    if (dims == Dimensionality::k1D) {
      convolve(t.conv1D, false, image);
    } else if (t.convolution2DEnabled) {
      convolve(t.conv2D, false, image);
    } else {
      convolve(t.separable2D, true, image);
    }
    if (!isIdentity(t.postConvolutionScale, t.postConvolutionBias))
      scaleBias(t.postConvolutionScale, t.postConvolutionBias, image);
  }
  if (tableActive(t.postConvolutionTableEnabled, t.tables[1]))  // 5
    applyColorTable(t.tables[1], image);
  const Matrix4& matrix = t.colorMatrixStack.back();  // 6
  if (!matrix.isIdentity()) {
    applyColorMatrix(matrix, t.postColorMatrixScale, t.postColorMatrixBias, image);
  } else if (!isIdentity(t.postColorMatrixScale, t.postColorMatrixBias)) {
    scaleBias(t.postColorMatrixScale, t.postColorMatrixBias, image);
  }
  if (tableActive(t.postColorMatrixTableEnabled, t.tables[2]))  // 7
    applyColorTable(t.tables[2], image);
  if (t.histogramEnabled) {  // 8
    accumulateHistogram(t.histogram, image);
    if (t.histogram.sink) return false;
  }
  if (t.minmaxEnabled) {  // 9
    accumulateMinmax(t.minmax, image);
    if (t.minmax.sink) return false;
  }
  return true;
}

}  // namespace sl::imaging::detail
