// registry/shadow_error.cpp — the one definition of shadow error (see the header and
// docs/error.md).
#include "registry/shadow_error.h"

#include <cmath>
#include <cstdio>

#include "core/base/errors.h"
#include "reference/reference.h"  // the categories' grey levels and the pixel= params
#include "registry/registry.h"

namespace sl {
namespace {

// The categories are stored as grey levels (reference.h); the nearest level decides.
bool isCategory(float value, float category) {
  constexpr float kHalfStep = 1.0f / 6.0f;  // half the distance between two levels
  return std::fabs(value - category) < kHalfStep;
}

PixelCategories countCategories(const Image& categories) {
  PixelCategories c;
  c.total = (long long)categories.width * categories.height;
  for (int y = 0; y < categories.height; ++y)
    for (int x = 0; x < categories.width; ++x) {
      const float v = categories.at(x, y);
      if (isCategory(v, reference::kCategoryScored))
        ++c.scored;
      else if (isCategory(v, reference::kCategoryFacesAway))
        ++c.facesAway;
      else if (isCategory(v, reference::kCategoryOutsideLight))
        ++c.outsideLight;
      else
        ++c.noReceiver;
    }
  return c;
}

}  // namespace

std::string describeLeftOut(const PixelCategories& c) {
  auto share = [&](long long n) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f%%",
                  c.total > 0 ? 100.0 * double(n) / double(c.total) : 0.0);
    return std::string(text);
  };
  return share(c.total - c.scored) + " of pixels left out (faces away " + share(c.facesAway) +
         ", outside the light " + share(c.outsideLight) + ", no receiver " + share(c.noReceiver) +
         ")";
}

const char* metricName(ErrorMetric metric) {
  return metric == ErrorMetric::kPoint ? "point" : "area";
}

std::string metricDescription(ErrorMetric metric) {
  const std::string scored =
      "scored over the pixels whose centre sees a receiver facing the light inside its frustum "
      "(terminators, the self-shadowed side, outside the light and background left out)";
  if (metric == ErrorMetric::kPoint)
    return "point metric: visibility at the surface point each pixel centre sees against the "
           "ray-traced visibility at that point, " +
           scored;
  return "area (antialiasing) metric: visibility against the ray-traced visibility integrated "
         "over the part of the pixel showing the surface its centre sees, " +
         scored;
}

std::string truthName(bool soft, ErrorMetric metric) {
  return std::string(soft ? "reference.soft" : "reference.hard") + " pixel=" +
         (metric == ErrorMetric::kPoint ? reference::kPixelCentre : reference::kPixelArea);
}

Image scoredBand(const Image& visibility, const Image& scored) {
  Image band = boundaryBand(visibility, kBandRadiusPixels);
  for (size_t i = 0; i < band.data.size(); ++i) band.data[i] *= scored.data[i];
  return band;
}

ShadowTruth truthFromReferenceFrame(Frame frame, ErrorMetric metric, bool soft, std::string name) {
  const Image* categories = nullptr;
  for (const PassImage& i : frame.intermediates)
    if (i.name == reference::kPixelCategoriesPass) categories = &i.image;
  if (categories == nullptr)
    throw InputError(
        "the reference frame has no pixel categories (render it with the passes "
        "captured)");
  ShadowTruth t;
  t.metric = metric;
  t.soft = soft;
  t.name = std::move(name);
  t.visibility = frame.visibility;
  t.counts = countCategories(*categories);
  t.scored = Image(categories->width, categories->height, 1, 0.0f);
  for (size_t i = 0; i < t.scored.data.size(); ++i)
    t.scored.data[i] = isCategory(categories->data[i], reference::kCategoryScored) ? 1.0f : 0.0f;
  t.band = scoredBand(t.visibility, t.scored);
  t.frame = std::move(frame);
  return t;
}

ShadowTruth renderShadowTruth(const Scene& scene, const RenderParams& base, ErrorMetric metric,
                              bool soft, int pixelSamplesPerSide) {
  RenderParams p;
  p.width = base.width;
  p.height = base.height;
  p.backend = base.backend;
  p.capturePasses = true;  // for the pixel categories
  p.extra[reference::kPixelParam] =
      metric == ErrorMetric::kPoint ? reference::kPixelCentre : reference::kPixelArea;
  if (metric == ErrorMetric::kArea && pixelSamplesPerSide > 0)
    p.extra[reference::kPixelSamplesParam] = std::to_string(pixelSamplesPerSide);
  const Technique& t = findTechnique(soft ? "reference.soft" : "reference.hard");
  return truthFromReferenceFrame(renderTechnique(t, scene, p), metric, soft,
                                 truthName(soft, metric));
}

bool isRayTracedReference(const Technique& t) {
  return t.plan.shadowWork == PlanTraits::ShadowWork::kRays;
}

bool haveRayTracedReferences() {
  for (const Technique& t : allTechniques())
    if (isRayTracedReference(t)) return true;
  return false;
}

ShadowError scoreShadow(const Image& mask, const ShadowTruth& truth, double threshold) {
  ShadowError e;
  e.metric = metricName(truth.metric);
  e.truth = truth.name;
  e.counts = truth.counts;
  e.all = compareMasksWithin(mask, truth.visibility, truth.scored, threshold);
  e.band = compareMasksWithin(mask, truth.visibility, truth.band, threshold);
  long long umbra = 0, leaking = 0;
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x) {
      if (truth.scored.at(x, y) <= 0.5f || truth.visibility.at(x, y) != 0.0f ||
          truth.band.at(x, y) > 0.5f)
        continue;
      ++umbra;
      if (mask.at(x, y) > kLeakThreshold) ++leaking;
    }
  e.leakShare = umbra > 0 ? double(leaking) / double(umbra) : 0.0;
  return e;
}

Image errorHeatMap(const Image& mask, const ShadowTruth& truth) {
  Image out = differenceHeatMap(mask, truth.visibility);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      if (truth.scored.at(x, y) <= 0.5f)
        for (int c = 0; c < out.channels; ++c) out.at(x, y, c) = kLeftOutGrey;
  return out;
}

nlohmann::json toJson(const ShadowError& e) {
  return {{"metric", e.metric},
          {"truth", e.truth},
          {"scored_pixels", e.all.pixels},
          {"left_out",
           {{"share", e.counts.leftOutShare()},
            {"faces_away", e.counts.facesAway},
            {"outside_light", e.counts.outsideLight},
            {"no_receiver", e.counts.noReceiver}}},
          {"rmse", e.all.rmse},
          {"max_abs", e.all.maxAbs},
          {"mismatching", e.all.mismatching},
          {"share_above_half", e.all.shareAboveHalf},
          {"band_rmse", e.band.rmse},
          {"band_max_abs", e.band.maxAbs},
          {"band_share_above_half", e.band.shareAboveHalf},
          {"leak_share", e.leakShare}};
}

}  // namespace sl
