// core/base/metrics.h — how two visibility masks (or a mask and the ray-traced reference) differ.
#pragma once

#include <nlohmann/json.hpp>

#include "core/base/image.h"

namespace sl {

struct MaskDifference {
  long long pixels = 0;
  long long mismatching = 0;  // |a - b| > threshold
  double maxAbs = 0.0;
  double rmse = 0.0;
  double shareAboveHalf = 0.0;  // share of pixels with |a - b| > 0.5
};

// Compares channel 0 of two equally sized images. `threshold` decides what counts as a
// mismatch (0 = any difference at all). Throws InputError on a size mismatch.
MaskDifference compareMasks(const Image& a, const Image& b, double threshold = 0.0);
// Same, restricted to pixels where `region` (channel 0) is > 0.5.
MaskDifference compareMasksWithin(const Image& a, const Image& b, const Image& region,
                                  double threshold = 0.0);

// Mean |a - b| (channel 0) over the pixels where `region` (channel 0) is > 0.5; 0 when the
// region is empty. The bench's temporal-stability metric: a mask against the same technique's
// mask after a small light motion. Throws InputError on a size mismatch.
double meanAbsChange(const Image& a, const Image& b, const Image& region);

// Pixels within `radius` pixels of a place where `mask` crosses 0.5 between neighbours
// (the shadow-boundary band): 1 inside the band, 0 elsewhere.
Image boundaryBand(const Image& mask, int radius);

nlohmann::json toJson(const MaskDifference& d);

}  // namespace sl
