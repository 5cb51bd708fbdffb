// tests/modern/hybrid_agreement.h — where modern.hybrid (Chan 2004 ch. 3) decides a pixel
// otherwise than modern.volumes, and why: every differing pixel gets one class from what
// decided it in the hybrid (its classification pass's "3-decision" buffer) and from two more
// hybrid renders that change one cause each (no polygon offset; a finer map).
#pragma once

#include <array>
#include <string>

#include "core/scene/scene_library.h"
#include "registry/registry.h"

namespace sl::hybrid_agreement {

// The classes, in the order a table prints them.
enum Class {
  kAtSilhouettePixel,  // a silhouette pixel: the volumes decided it, and still differ
  kBackFacing,         // shadowed as back-facing to the light (§3.1 step 2); the volumes: lit
  kBiasLeak,           // the map said lit; without polygon offset a nearest sample says shadow
  kBelowTexel,         // the map agreed wrongly; a map kFinerMapFactor finer is right or unsure
  kMaskMissOther,      // the map agreed wrongly, and neither change helps
  kClassCount
};
inline const char* className(int c) {
  constexpr std::array<const char*, kClassCount> names = {
      "volumes at silhouette pixel", "back-facing forced shadow", "bias leak",
      "below a texel (finer map fixes)", "other mask miss"};
  return names[size_t(c)];
}

// The finer map that separates undersampling (thin features, edges between samples; Chan
// §3.3.1, "small blockers may be poorly represented") from the other mask misses.
constexpr int kFinerMapFactor = 4;

struct Agreement {
  long long pixels = 0;
  long long differing = 0;
  std::array<long long, kClassCount> byClass{};
  double silhouetteFraction = 0;
  double agreeingShare() const {
    return pixels > 0 ? 1.0 - double(differing) / double(pixels) : 0.0;
  }
};

namespace detail {
inline const Image& intermediate(const Frame& f, const std::string& name) {
  for (const PassImage& i : f.intermediates)
    if (i.name == name) return i.image;
  throw std::runtime_error("modern.hybrid frame without the intermediate " + name);
}
inline bool lit(float visibility) { return visibility > 0.5f; }
}  // namespace detail

// Renders modern.hybrid (with `params`, its extra params included) and modern.volumes on
// `scene` and classifies every pixel whose visibility differs.
inline Agreement classifyHybridDifferences(const Scene& scene, RenderParams params) {
  using detail::intermediate;
  using detail::lit;
  const Technique& hybrid = findTechnique("modern.hybrid");
  RenderParams plain = params;
  plain.capturePasses = false;
  plain.extra.clear();
  const Frame volumes = renderTechnique(findTechnique("modern.volumes"), scene, plain);
  params.capturePasses = true;
  const Frame h = renderTechnique(hybrid, scene, params);
  const Image& decision = intermediate(h, "3-decision");
  Agreement a;
  a.pixels = (long long)params.width * params.height;
  a.silhouetteFraction = h.counters.at("silhouette_fraction");
  // The two cause-changing renders, made only when a pixel needs them.
  Frame noBias, finer;
  bool haveNoBias = false, haveFiner = false;
  for (int y = 0; y < params.height; ++y)
    for (int x = 0; x < params.width; ++x) {
      const bool hl = lit(h.visibility.at(x, y)), vl = lit(volumes.visibility.at(x, y));
      if (hl == vl) continue;
      ++a.differing;
      if (decision.at(x, y, 0) > 0.5f) {
        ++a.byClass[kAtSilhouettePixel];
        continue;
      }
      if (decision.at(x, y, 1) > 0.5f) {
        ++a.byClass[kBackFacing];
        continue;
      }
      // The map decided. A map whose answer is right, or which sends the pixel to the
      // volumes, removes the difference.
      const auto fixedBy = [&](const Frame& f) {
        const Image& d = intermediate(f, "3-decision");
        return d.at(x, y, 0) > 0.5f || (d.at(x, y, 1) < 0.5f && lit(d.at(x, y, 2)) == vl);
      };
      if (hl && !vl) {
        if (!haveNoBias) {
          RenderParams p = params;
          p.extra["offset-factor"] = "0";
          p.extra["offset-units"] = "0";
          noBias = renderTechnique(hybrid, scene, p);
          haveNoBias = true;
        }
        // Without the offset, not all four nearest samples say lit: the bias hid the shadow.
        if (intermediate(noBias, "3-decision").at(x, y, 2) < 1.0f) {
          ++a.byClass[kBiasLeak];
          continue;
        }
      }
      if (!haveFiner) {
        RenderParams p = params;
        p.shadowMapTexels *= kFinerMapFactor;
        finer = renderTechnique(hybrid, scene, p);
        haveFiner = true;
      }
      ++a.byClass[fixedBy(finer) ? kBelowTexel : kMaskMissOther];
    }
  return a;
}

}  // namespace sl::hybrid_agreement
