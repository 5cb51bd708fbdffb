#include "registry/twins.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/base/errors.h"
#include "imaging/imaging.h"
#include "registry/registry.h"

namespace sl::twins {
namespace {

bool registered(const std::string& name) {
  for (const Technique& t : allTechniques())
    if (t.name == name) return true;
  return false;
}

// Why a pair of fixed-function and shader code is not bit-exact when it computes the same
// thing: EYE_LINEAR texgen (planes · (modelview · vertex), per vertex, interpolated) and the
// shader's matrix · world position round differently in the last float bit.
const char* kTexgenRounding =
    "texgen planes (fixed function, per vertex) and the shader's matrix round differently in "
    "the last float bit: bilinear compare weights may then differ by one 8-bit step, and a depth "
    "tie (acne where a surface shadows itself) may flip, which happens only where the legacy "
    "mask itself changes, i.e. on the shadow-boundary band";

std::vector<TwinPair> allPairs() {
  std::vector<TwinPair> p;
  auto add = [&](TwinPair t) { p.push_back(std::move(t)); };
  add({"hw (linear compare)",
       "legacy.hw",
       "modern.hw",
       1,
       Precision::k8,
       {},
       {},
       false,
       kTexgenRounding});
  add({"hw (nearest compare)",
       "legacy.hw",
       "modern.hw",
       1,
       Precision::k8,
       {{"compare", "nearest"}},
       {{"compare", "nearest"}},
       false,
       kTexgenRounding});
  add({"woo",
       "legacy.woo",
       "modern.woo",
       1,
       Precision::k8,
       {},
       {},
       false,
       "same as hw; the midpoint depth is averaged on the host (legacy) and in a shader "
       "(modern), which may round the 24-bit midpoint apart by one unit, a tie only"});
  add({"second-depth",
       "legacy.second-depth",
       "modern.second-depth",
       1,
       Precision::k8,
       {},
       {},
       false,
       "same as hw; without polygon offset the back faces (seen from the light) compare against "
       "their own depth, so their acne ties are many, all on the back faces' noisy boundary"});
  const char* kFaithful =
      "'faithful' arithmetic repeats the legacy quantisation step by step (ramp texel, 8/12-bit "
      "channel, colour table, colour matrix, accumulation) and texgen.vert forms the texture "
      "coordinates as the fixed-function vertex stage does, so the masks are identical but where "
      "a coordinate ties with a texel or ramp-step boundary to float rounding";
  const char* kFaithfulFloat =
      "at --precision float 'faithful' arithmetic follows legacy's float pipeline (float colour "
      "buffer, 2-texel LINEAR ramp, RGBA32F maps; the colour table, colour matrix and 16-bit "
      "accumulation as at 8 bits), so the masks are identical but where a coordinate ties with a "
      "texel boundary to float rounding";
  const char* kFloat =
      "'float' arithmetic drops the 2001 quantisation on the modern side and the legacy side "
      "runs with float colour buffers: what remains is texgen rounding (see hw)";
  add({"ramp faithful 8-bit",
       "legacy.ramp",
       "modern.ramp",
       1,
       Precision::k8,
       {},
       {{"arithmetic", "faithful"}},
       true,
       kFaithful});
  add({"ramp faithful 12-bit",
       "legacy.ramp",
       "modern.ramp",
       1,
       Precision::k12,
       {},
       {{"arithmetic", "faithful"}},
       true,
       kFaithful});
  add({"ramp faithful float",
       "legacy.ramp",
       "modern.ramp",
       1,
       Precision::kFloat,
       {},
       {{"arithmetic", "faithful"}},
       true,
       kFaithfulFloat});
  add({"ramp float",
       "legacy.ramp",
       "modern.ramp",
       1,
       Precision::kFloat,
       {},
       {{"arithmetic", "float"}},
       false,
       kFloat});
  for (int f : {2, 3, 4}) {
    const std::string k = std::to_string(f) + "x" + std::to_string(f);
    add({"pcf " + k + " faithful 8-bit",
         "legacy.pcf",
         "modern.pcf",
         f,
         Precision::k8,
         {},
         {{"arithmetic", "faithful"}},
         true,
         kFaithful});
  }
  add({"pcf 2x2 faithful float",
       "legacy.pcf",
       "modern.pcf",
       2,
       Precision::kFloat,
       {},
       {{"arithmetic", "faithful"}},
       true,
       kFaithfulFloat});
  add({"pcf 2x2 float",
       "legacy.pcf",
       "modern.pcf",
       2,
       Precision::kFloat,
       {},
       {{"arithmetic", "float"}},
       false,
       kFloat});
  for (int f : {2, 4}) {
    const std::string k = std::to_string(f) + "x" + std::to_string(f);
    add({"fast-pcf " + k + " faithful 8-bit",
         "legacy.fast-pcf",
         "modern.fast-pcf",
         f,
         Precision::k8,
         {},
         {{"arithmetic", "faithful"}},
         true,
         kFaithful});
  }
  add({"fast-pcf 2x2 faithful float",
       "legacy.fast-pcf",
       "modern.fast-pcf",
       2,
       Precision::kFloat,
       {},
       {{"arithmetic", "faithful"}},
       true,
       kFaithfulFloat});
  add({"fast-pcf 2x2 float",
       "legacy.fast-pcf",
       "modern.fast-pcf",
       2,
       Precision::kFloat,
       {},
       {{"arithmetic", "float"}},
       false,
       kFloat});
  return p;
}

}  // namespace

std::vector<TwinPair> twinPairs() {
  std::vector<TwinPair> out;
  for (TwinPair& p : allPairs())
    if (registered(p.legacy) && registered(p.modern)) out.push_back(std::move(p));
  return out;
}

std::string legacyTwinOf(const std::string& modern) {
  for (const TwinPair& p : twinPairs())
    if (p.modern == modern) return p.legacy;
  return "";
}

const PassTable* legacyTwinPassesOf(const std::string& modern) {
  const std::string legacy = legacyTwinOf(modern);
  return legacy.empty() ? nullptr : &findTechnique(legacy).passes;
}

std::vector<std::string> missingPairs() {
  std::vector<std::string> out;
  for (const TwinPair& p : allPairs())
    if (!registered(p.legacy) || !registered(p.modern))
      out.push_back(p.label + " (" + (registered(p.legacy) ? p.modern : p.legacy) +
                    " not in this build)");
  return out;
}

const std::vector<std::string>& equivalenceScenes() {
  // analytic (exact answer known), the Brabec–Seidel scene, its dueling-frusta variant, and a
  // loaded mesh that shadows itself (the Stanford bunny, assets/scenes/bunny.json).
  static const std::vector<std::string> kScenes = {"analytic", "brabec", "dueling", "bunny"};
  return kScenes;
}

Agreement judge(const TwinPair& pair, const Image& legacyMask, const Image& modernMask) {
  Agreement a;
  a.all = compareMasks(legacyMask, modernMask, 0.0);
  const Image band = boundaryBand(legacyMask, kBandRadius);
  // Masks come from 8-bit (or 16-bit) buffers read as float: a one-step difference may carry
  // float noise of 1e-7, far below half a 16-bit step.
  constexpr double kReadbackNoise = 1e-6;
  for (int y = 0; y < legacyMask.height; ++y)
    for (int x = 0; x < legacyMask.width; ++x) {
      const double d = std::fabs(double(legacyMask.at(x, y)) - double(modernMask.at(x, y)));
      const bool onBand = band.at(x, y) > 0.5f;
      if (d > kIdentical) {
        ++a.differing;
        if (!onBand) ++a.differingOutsideBand;
      }
      if (d <= kOneStep + kReadbackNoise) continue;
      ++a.beyondOneStep;
      if (!onBand) ++a.beyondOutsideBand;
    }
  a.shareBeyondOneStep = a.all.pixels > 0 ? double(a.beyondOneStep) / double(a.all.pixels) : 0;
  std::ostringstream v;
  if (pair.faithful) {
    const double share = a.all.pixels > 0 ? double(a.differing) / double(a.all.pixels) : 0.0;
    a.withinBound = share <= kMaxFaithfulTieShare && a.differingOutsideBand == 0;
    v << "bound: bit-exact but for ties (<= " << kMaxFaithfulTieShare * 100
      << "% of pixels, all on the boundary band); measured " << a.differing << " differing pixels, "
      << a.differingOutsideBand << " off the band, max " << a.all.maxAbs;
  } else {
    a.withinBound = a.shareBeyondOneStep <= kMaxShareBeyondOneStep && a.beyondOutsideBand == 0;
    v << "bound: <= 1/255 on >= 99.9% of pixels, larger only on the boundary band (radius "
      << kBandRadius << "); measured " << a.beyondOneStep << " pixels beyond 1/255 ("
      << 100.0 * a.shareBeyondOneStep << "%), " << a.beyondOutsideBand
      << " of them off the band, max " << a.all.maxAbs;
  }
  a.verdict = v.str();
  return a;
}

ImageAgreement judgeImages(const Image& legacyColor, const Image& modernColor,
                           const Image& legacyMask, const Image& modernMask) {
  if (legacyColor.width != modernColor.width || legacyColor.height != modernColor.height ||
      legacyMask.width != legacyColor.width || legacyMask.height != legacyColor.height ||
      modernMask.width != legacyColor.width || modernMask.height != legacyColor.height)
    throw InputError("judgeImages: images and masks of different sizes");
  const Image a = toRgb(legacyColor), b = toRgb(modernColor);
  ImageAgreement r;
  r.pixels = (long long)a.width * a.height;
  r.boundPixels = kConeEdgeBandPixelsPerPerimeterPixel * 2LL * (a.width + a.height);
  // Colour is read back from 8-bit buffers as float: allow float noise far below a step.
  constexpr double kReadbackNoise = 1e-6;
  double sum = 0.0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      double d = 0.0;
      for (int c = 0; c < 3; ++c) {
        const double e = std::fabs(double(a.at(x, y, c)) - double(b.at(x, y, c)));
        d = std::max(d, e);
        sum += e * e;
      }
      r.maxAbs = std::max(r.maxAbs, d);
      if (d <= kImageSteps * kOneStep + kReadbackNoise) continue;
      ++r.beyondSteps;
      const double m = std::fabs(double(legacyMask.at(x, y)) - double(modernMask.at(x, y)));
      if (m <= kOneStep + kReadbackNoise) ++r.beyondWhereMasksAgree;
    }
  r.rmse = r.pixels > 0 ? std::sqrt(sum / (3.0 * double(r.pixels))) : 0.0;
  r.withinBound = r.beyondWhereMasksAgree <= r.boundPixels;
  std::ostringstream v;
  v << "image bound: <= " << r.boundPixels << " pixels (the cone-edge band, "
    << kConeEdgeBandPixelsPerPerimeterPixel << " x the window perimeter) beyond " << kImageSteps
    << "/255 where the masks agree; measured " << r.beyondWhereMasksAgree << " (" << r.beyondSteps
    << " beyond " << kImageSteps << "/255 in all), max " << r.maxAbs << ", RMSE " << r.rmse;
  r.verdict = v.str();
  return r;
}

Image colourDifferenceHeatMap(const Image& a, const Image& b) {
  const Image ra = toRgb(a), rb = toRgb(b);
  if (ra.width != rb.width || ra.height != rb.height)
    throw InputError("cannot difference images of different sizes");
  Image largest(ra.width, ra.height, 1), zero(ra.width, ra.height, 1);
  for (int y = 0; y < ra.height; ++y)
    for (int x = 0; x < ra.width; ++x)
      for (int c = 0; c < 3; ++c)
        largest.at(x, y) = std::max(largest.at(x, y), std::fabs(ra.at(x, y, c) - rb.at(x, y, c)));
  constexpr float kReadbackNoise = 1e-6f;
  for (float& d : largest.data)
    if (d <= float(kImageSteps * kOneStep) + kReadbackNoise) d = 0.0f;  // within the bound's steps
  return differenceHeatMap(largest, zero, kImageDiffFullScale);
}

RenderParams paramsFor(const TwinPair& pair, bool legacySide, int width, int height,
                       int shadowMapTexels, Backend backend) {
  RenderParams p;
  p.width = width;
  p.height = height;
  p.shadowMapTexels = shadowMapTexels;
  p.filter = pair.filter;
  p.precision = pair.precision;
  p.backend = backend;
  p.extra = legacySide ? pair.legacyExtra : pair.modernExtra;
  return p;
}

std::string unavailablePrecision(const TwinPair& pair, const RenderParams& legacyParams) {
  const Technique& legacy = findTechnique(pair.legacy);
  if (!legacy.needs.colorFromPrecision || pair.precision == Precision::k8) return "";
  constexpr int kBits12 = 16;  // 12-bit values live in a 16-bit buffer
  constexpr int kBitsFloat = 32;
  const int needed = pair.precision == Precision::k12 ? kBits12 : kBitsFloat;
  auto context = GlContext::create(contextFor(legacy, legacyParams));
  const int bits = context->caps().redBits;
  if (bits >= needed) return "";
  return std::string(backendName(legacyParams.backend)) + " gives the legacy context " +
         std::to_string(bits) + "-bit colour, not the " + std::to_string(needed) +
         " bits that precision " + precisionName(pair.precision) + " needs";
}

FrameTimes frameMilliseconds(const Technique& technique, const Scene& scene,
                             const RenderParams& params, int frames) {
  if (frames < 1) throw InputError("the number of timed frames must be at least 1");
  const SteadyTiming t =
      timeTechnique(technique, scene, params, FrameCounts{kWarmupFrames, frames});
  return {t.frameMs, t.minimumFrameMs};
}

}  // namespace sl::twins
