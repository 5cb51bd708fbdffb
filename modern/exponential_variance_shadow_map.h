// modern/exponential_variance_shadow_map.h — modern.evsm2 and modern.evsm4: Exponential Variance
// Shadow Maps (ours, after Lauritzen & McCool 2008, not in shared/papers), filtered-map
// baselines next to modern.vsm: the moments of exponentially warped depth, Chebyshev on each.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/technique/technique.h"

namespace sl::modern {
Technique evsm2Technique();  // the positive warp: moments (p, p^2)
Technique evsm4Technique();  // positive and negative warps: (p, p^2, n, n^2)

// The largest warp exponent a storage format holds: the map stores exp(c)^2 = exp(2 c) for
// depth 1 (x = 1), so c <= ln(max) / 2 less a margin for the blur's sums: fp32 (max 3.4e38,
// ln / 2 = 44.4): 42; fp16 (max 65504, ln / 2 = 5.55): 5.54 — the limits the issue names
// (as TheRealMJP/Shadows uses them).
constexpr double kEvsmMaxExponentFloat32 = 42.0;
constexpr double kEvsmMaxExponentFloat16 = 5.54;
inline double evsmEffectiveExponent(double asked, bool float16) {
  return std::min(asked, float16 ? kEvsmMaxExponentFloat16 : kEvsmMaxExponentFloat32);
}

// The positive and negative warps of linear depth z in [0, 1] (x = 2 z - 1), as evsm_map.frag.
inline double evsmPositiveWarp(double c, double z) { return std::exp(c * (2.0 * z - 1.0)); }
inline double evsmNegativeWarp(double c, double z) { return -std::exp(-c * (2.0 * z - 1.0)); }

// Chebyshev's bound of evsm_shadow.frag on one warp, mirrored on the CPU (tests): `mean` and
// `meanSquare` the filtered E[w], E[w^2]; `w` the receiver's warped depth; `c` the exponent;
// `minVariance` in (linear depth)^2, scaled by the warp's slope (2 c E[w])^2.
inline double evsmChebyshev(double mean, double meanSquare, double w, double c, double minVariance,
                            double bleedReduction) {
  if (w <= mean) return 1.0;
  const double s = std::max(std::fabs(w), std::fabs(mean));
  const double m1 = mean / s, m2 = meanSquare / s / s, slope = 2.0 * c * m1;
  const double variance = std::max(m2 - m1 * m1, minVariance * slope * slope);
  const double delta = w / s - m1;
  double p = variance / (variance + delta * delta);
  if (bleedReduction > 0.0) p = std::clamp((p - bleedReduction) / (1.0 - bleedReduction), 0.0, 1.0);
  return p;
}
}  // namespace sl::modern
