// modern/exponential_shadow_map.h — modern.esm: Exponential Shadow Maps (ours, after Annen,
// Mertens, Seidel, Flerackers & Kautz 2008, not in shared/papers), a filtered-map baseline next
// to modern.vsm and modern.csm.
#pragma once

#include <cmath>

#include "core/technique/technique.h"

namespace sl::modern {
Technique exponentialShadowMapTechnique();

// The largest exponent c whose exp(c) (the stored value of depth 1) a storage format holds:
// ln(FLT_MAX) = 88.72 for 32-bit float, ln(65504) = 11.09 for 16-bit float; 0.5 below it.
constexpr double kEsmMaxExponentFloat32 = 88.0;
constexpr double kEsmMaxExponentFloat16 = 10.5;
// The exponent the technique uses: `asked` clamped to the format's limit.
inline double esmEffectiveExponent(double asked, bool float16) {
  return std::fmin(asked, float16 ? kEsmMaxExponentFloat16 : kEsmMaxExponentFloat32);
}
// The test in esm_shadow.frag, mirrored on the CPU (tests): clamp(exp(-c d) E[exp(c z)], 0, 1).
inline double esmVisibility(double exponent, double filtered, double d) {
  return std::fmin(std::fmax(std::exp(-exponent * d) * filtered, 0.0), 1.0);
}
}  // namespace sl::modern
