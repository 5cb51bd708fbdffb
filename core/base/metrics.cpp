#include "core/base/metrics.h"

#include <algorithm>
#include <cmath>

#include "core/base/errors.h"

namespace sl {
namespace {
MaskDifference compareImpl(const Image& a, const Image& b, const Image* region, double threshold) {
  if (a.width != b.width || a.height != b.height)
    throw InputError("masks differ in size: " + std::to_string(a.width) + "x" +
                     std::to_string(a.height) + " vs " + std::to_string(b.width) + "x" +
                     std::to_string(b.height));
  MaskDifference d;
  double sumSq = 0.0;
  long long above = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (region != nullptr && !(region->at(x, y) > 0.5f)) continue;
      const double diff = std::fabs(double(a.at(x, y)) - double(b.at(x, y)));
      ++d.pixels;
      if (diff > threshold) ++d.mismatching;
      if (diff > 0.5) ++above;
      d.maxAbs = std::max(d.maxAbs, diff);
      sumSq += diff * diff;
    }
  if (d.pixels > 0) {
    d.rmse = std::sqrt(sumSq / double(d.pixels));
    d.shareAboveHalf = double(above) / double(d.pixels);
  }
  return d;
}
}  // namespace

MaskDifference compareMasks(const Image& a, const Image& b, double threshold) {
  return compareImpl(a, b, nullptr, threshold);
}

MaskDifference compareMasksWithin(const Image& a, const Image& b, const Image& region,
                                  double threshold) {
  return compareImpl(a, b, &region, threshold);
}

double meanAbsChange(const Image& a, const Image& b, const Image& region) {
  if (a.width != b.width || a.height != b.height || a.width != region.width ||
      a.height != region.height)
    throw InputError("masks differ in size: " + std::to_string(a.width) + "x" +
                     std::to_string(a.height) + " vs " + std::to_string(b.width) + "x" +
                     std::to_string(b.height) + " (region " + std::to_string(region.width) + "x" +
                     std::to_string(region.height) + ")");
  double sum = 0.0;
  long long pixels = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (!(region.at(x, y) > 0.5f)) continue;
      sum += std::fabs(double(a.at(x, y)) - double(b.at(x, y)));
      ++pixels;
    }
  return pixels > 0 ? sum / double(pixels) : 0.0;
}

Image boundaryBand(const Image& mask, int radius) {
  Image edge(mask.width, mask.height, 1);
  auto lit = [&](int x, int y) { return mask.at(x, y) > 0.5f; };
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x) {
      const bool here = lit(x, y);
      const bool crosses = (x + 1 < mask.width && lit(x + 1, y) != here) ||
                           (y + 1 < mask.height && lit(x, y + 1) != here) ||
                           // a partially lit pixel is itself on the boundary
                           (mask.at(x, y) > 0.0f && mask.at(x, y) < 1.0f);
      if (crosses) edge.at(x, y) = 1.0f;
    }
  Image band(mask.width, mask.height, 1);
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x) {
      if (edge.at(x, y) == 0.0f) continue;
      for (int j = std::max(0, y - radius); j <= std::min(mask.height - 1, y + radius + 1); ++j)
        for (int i = std::max(0, x - radius); i <= std::min(mask.width - 1, x + radius + 1); ++i)
          band.at(i, j) = 1.0f;
    }
  return band;
}

nlohmann::json toJson(const MaskDifference& d) {
  return {{"pixels", d.pixels},
          {"mismatching", d.mismatching},
          {"max_abs", d.maxAbs},
          {"rmse", d.rmse},
          {"share_above_half", d.shareAboveHalf}};
}

}  // namespace sl
