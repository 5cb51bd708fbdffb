// registry/shadow_error.h — the one definition of shadow error (docs/error.md), used by
// `compare`, `bench`, the figures' error cells, the lab's error view and the stability suite.
//
// A score compares a technique's visibility mask (1 = lit, 0 = umbra, before shading) with a
// ray-traced truth over the SCORED pixels only: a receiver's surface point, seen through the
// pixel centre, inside the light's frustum, whose triangle faces the light. The other pixels
// are counted in categories and left out (reference/reference.h kPixelCategoriesPass): where
// the surface faces away from the light (the terminator and the self-shadowed side of a
// caster) the lighting term is 0 whatever the visibility, so neither side's self-shadowing
// decides anything there. The categories come from the pixel centres' surface points, the same
// for every technique; every score prints the share left out.
//
// Two metrics, named in every score:
//   point  the truth is reference.hard (or .soft) --param pixel=centre: the visibility at the
//          very surface point the pixel centre sees. An exact technique (modern.volumes)
//          scores ~0 on it.
//   area   the antialiasing metric: the truth is reference.hard (or .soft) --param pixel=area,
//          the visibility integrated over the part of the pixel that shows the centre's surface
//          (the other sub-pixel samples, across a geometry edge or a terminator, are left out),
//          so a geometry edge is not counted as shadow error.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "core/base/image.h"
#include "core/base/metrics.h"
#include "core/technique/technique.h"

namespace sl {

enum class ErrorMetric { kPoint, kArea };
const char* metricName(ErrorMetric metric);  // "point", "area"
// One line a caption or a table note can quote.
std::string metricDescription(ErrorMetric metric);

// The shadow-boundary band: scored pixels within this many pixels of a place where the truth
// crosses 0.5 (where aliasing and filtering errors live).
constexpr int kBandRadiusPixels = 2;
// A scored pixel of the truth's umbra (outside the band) "leaks" when the technique shows it
// more than this lit.
constexpr float kLeakThreshold = 0.2f;

// How many pixels of a frame fall in each category (the same for every technique of a frame).
struct PixelCategories {
  long long total = 0;
  long long scored = 0;
  long long facesAway = 0;     // terminator / self-shadowed side: left out
  long long outsideLight = 0;  // outside the light's frustum: left out
  long long noReceiver = 0;    // background or a non-receiving object: left out
  double leftOutShare() const { return total > 0 ? double(total - scored) / double(total) : 0.0; }
};
// "31.2% of pixels left out (faces away 2.1%, outside the light 0.0%, no receiver 29.1%)"
std::string describeLeftOut(const PixelCategories& c);

struct ShadowTruth {
  ErrorMetric metric = ErrorMetric::kPoint;
  bool soft = false;
  std::string name;  // "reference.hard pixel=centre"
  Image visibility;  // the truth (1 channel)
  Image scored;      // 1 where a pixel is scored, 0 elsewhere
  Image band;        // the scored pixels within kBandRadiusPixels of the truth's shadow edges
  PixelCategories counts;
  Frame frame;  // the reference's frame (its time and passes)
};

// The truth of `metric` for a scene: renders reference.hard (reference.soft when `soft`) at
// base's size with --param pixel=centre or area. `pixelSamplesPerSide` > 0 sets
// --param pixel-samples (area only; 0: the reference's default). Throws GlError in a build
// without the ray tracer.
ShadowTruth renderShadowTruth(const Scene& scene, const RenderParams& base, ErrorMetric metric,
                              bool soft, int pixelSamplesPerSide = 0);
// The truth from a reference frame already rendered with RenderParams::capturePasses
// (its kPixelCategoriesPass intermediate); InputError when the frame has none.
ShadowTruth truthFromReferenceFrame(Frame frame, ErrorMetric metric, bool soft, std::string name);
// The scored pixels within kBandRadiusPixels of a place where `visibility` crosses 0.5: the
// band a truth's band error is measured on (ShadowTruth::band).
Image scoredBand(const Image& visibility, const Image& scored);
// "reference.hard pixel=centre" and the like; for a references' own params (compare's sides).
std::string truthName(bool soft, ErrorMetric metric);

struct ShadowError {
  std::string metric;  // metricName
  std::string truth;   // ShadowTruth::name
  MaskDifference all;  // over the scored pixels
  MaskDifference band;
  double leakShare = 0.0;  // share of the truth's scored umbra pixels (outside the band) leaking
  PixelCategories counts;
};

// Scores `mask` (channel 0) against `truth`; `threshold`: how much a pixel must differ to count
// as mismatching (compare --threshold). InputError on a size mismatch.
ShadowError scoreShadow(const Image& mask, const ShadowTruth& truth, double threshold = 0.0);

// |mask - truth| as core/base/image.h differenceHeatMap colours it, on the scored pixels; the
// pixels left out are kLeftOutGrey, so a viewer sees what the score does not count.
constexpr float kLeftOutGrey = 0.3f;
Image errorHeatMap(const Image& mask, const ShadowTruth& truth);

// A ray-traced reference (declared by its plan: its shadow work is rays), whose frame can be a
// truth.
bool isRayTracedReference(const Technique& t);
// Whether this build has the ray tracer (reference.hard is registered).
bool haveRayTracedReferences();

// {"metric", "truth", "scored_pixels", "left_out": {"share", "faces_away", "outside_light",
//  "no_receiver"}, "rmse", "max_abs", "mismatching", "share_above_half", "band_rmse",
//  "band_max_abs", "band_share_above_half", "leak_share"}
nlohmann::json toJson(const ShadowError& e);

}  // namespace sl
