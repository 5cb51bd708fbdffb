// registry/twins.h — the legacy/modern twins (issue 5): which technique pairs exist, the bound
// each pair must meet, how two visibility masks are judged against it, and the timing of a
// pair. Shared by tests/modern/equivalence_test.cpp and the shadowlab-twins program.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/base/metrics.h"
#include "core/technique/technique.h"

namespace sl::twins {

// One legacy technique and its modern twin, rendered with the same parameters.
struct TwinPair {
  std::string label;   // "pcf 2x2 faithful"
  std::string legacy;  // "legacy.pcf"
  std::string modern;  // "modern.pcf"
  int filter = 2;
  Precision precision = Precision::k8;
  std::map<std::string, std::string> legacyExtra;  // --param for the legacy side
  std::map<std::string, std::string> modernExtra;  // --param for the modern side
  bool faithful = false;  // the bound: the faithful one (identical but for rare ties), or the
                          // one-step/boundary-band bound
  std::string why;        // why that bound is the right one
};

// Every pair whose two techniques are registered in this build (a pair whose legacy side is
// not there yet is left out and listed by missingPairs()).
std::vector<TwinPair> twinPairs();
std::vector<std::string> missingPairs();
// The legacy technique a modern one is the twin of ("modern.fast-pcf" -> "legacy.fast-pcf"),
// "" when it has none.
std::string legacyTwinOf(const std::string& modern);
// That twin's pass table (core/technique/pass_table.h; what passes.json names its replaced passes
// from), null when it has none.
const PassTable* legacyTwinPassesOf(const std::string& modern);

// Scenes every pair is checked on: analytic (exact shadow known), brabec (Brabec–Seidel §5, the
// torus shadows itself) and dueling (the same meshes, light facing the camera: self-shadowing
// at grazing angles).
const std::vector<std::string>& equivalenceScenes();

// The 'not bit-exact' bound (issue 5): |legacy - modern| <= one 8-bit step on at least
// 99.9% of pixels, and every larger difference inside the shadow-boundary band of the legacy
// mask (core/base/metrics.h boundaryBand with kBandRadius).
constexpr double kOneStep = 1.0 / 255.0;
constexpr double kMaxShareBeyondOneStep = 0.001;
// One pixel on either side of the boundary: a depth tie flips a pixel only where the legacy
// comparison itself changes between neighbours, i.e. next to a crossing.
constexpr int kBandRadius = 1;
// The 'faithful' bound. Goal: bit-exact (identical 16-bit mask values). Every quantisation is
// repeated, so a pixel can differ only where a texture coordinate or a ramp coordinate lies
// within float rounding (~1e-7) of a texel or ramp-step boundary and the two pipelines round
// it to different sides; such a tie flips one sample of one pixel. Bound: at most one pixel in
// 10^4 differs at all (8 of 320x240), and every differing pixel is on the boundary band.
constexpr double kMaxFaithfulTieShare = 1e-4;
// Identical at 16-bit PNG precision (the --mask format): half a 16-bit step.
constexpr double kIdentical = 0.5 / 65535.0;

struct Agreement {
  MaskDifference all;               // over every pixel
  long long beyondOneStep = 0;      // pixels with |diff| > one 8-bit step
  long long beyondOutsideBand = 0;  // of those, how many lie outside the boundary band
  long long differing = 0;          // pixels that differ at all (> kIdentical)
  long long differingOutsideBand = 0;
  double shareBeyondOneStep = 0.0;
  bool withinBound = false;
  std::string verdict;  // one line: what was measured against what bound
};

Agreement judge(const TwinPair& pair, const Image& legacyMask, const Image& modernMask);

// The images agree too, not only the masks (issue 18 item 5). What may differ:
//  - the spotlight cone's edge: legacy cuts it with a texture projected from the light
//    (legacy_gl/projected_spotlight.h), modern per pixel in the shader, so the pixels within one
//    pixel on either side of the cone's edge may be lit in one and not in the other: a band
//    two pixels wide along a convex curve inside the window, shorter than the window's
//    perimeter, so at most kConeEdgeBandPixelsPerPerimeterPixel * 2 (W + H) pixels;
//  - inside the cone, Gouraud against per-pixel diffuse and specular, and legacy's sums in an
//    8-bit framebuffer: a few 8-bit steps (kImageSteps);
//  - where the masks differ (the mask bound above), the direct light they scale.
// Bound: the pixels whose colour differs by more than kImageSteps 8-bit steps in any channel
// while the masks agree within one step number at most the cone-edge band.
constexpr int kImageSteps = 3;
constexpr int kConeEdgeBandPixelsPerPerimeterPixel = 2;

struct ImageAgreement {
  long long pixels = 0;
  long long beyondSteps = 0;            // max |RGB difference| > kImageSteps / 255
  long long beyondWhereMasksAgree = 0;  // of those, where the masks agree within one step
  long long boundPixels = 0;            // the cone-edge band's size for this window
  double maxAbs = 0.0;                  // largest channel difference
  double rmse = 0.0;                    // over every channel of every pixel
  bool withinBound = false;
  std::string verdict;  // one line: measured against the bound
};
ImageAgreement judgeImages(const Image& legacyColor, const Image& modernColor,
                           const Image& legacyMask, const Image& modernMask);
// The largest channel difference of two colour images as core/base/image.h's heat map, full scale
// kImageDiffFullScale; differences within kImageSteps (rounding, Gouraud) are drawn black, so
// the picture shows what judgeImages counts; a lit/unlit flip is white.
constexpr float kImageDiffFullScale = 16.0f / 255.0f;
Image colourDifferenceHeatMap(const Image& a, const Image& b);

// RenderParams for one side of a pair.
RenderParams paramsFor(const TwinPair& pair, bool legacySide, int width, int height,
                       int shadowMapTexels, Backend backend);

// Why the legacy side of `pair` cannot run at the pair's precision with these parameters, ""
// when it can: EGL pbuffers are 8-bit (core/gl/context.cpp), so legacy 12-bit and float colour
// is not there and the pair is not comparable.
std::string unavailablePrecision(const TwinPair& pair, const RenderParams& legacyParams);

// Frame time (sum of the technique's timed passes) over `frames` frames rendered in one context
// after kWarmupFrames warm-up frames (core/technique/frame_timing.h, registry/registry.h
// timeTechnique): the median, and the minimum (the least disturbed by other processes on a shared
// machine).
struct FrameTimes {
  double median = 0.0;
  double minimum = 0.0;
};
FrameTimes frameMilliseconds(const Technique& technique, const Scene& scene,
                             const RenderParams& params, int frames);

}  // namespace sl::twins
