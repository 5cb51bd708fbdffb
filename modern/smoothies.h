// modern/smoothies.h — modern.smoothies (Chan 2004 thesis ch. 4 / Chan & Durand 2003:
// "Rendering Fake Soft Shadows with Smoothies").
#pragma once

#include "core/technique/technique.h"

namespace sl::modern {

Technique smoothiesTechnique();

// Eq. 4.1 with the clamp of §4.2.1, exactly as smoothie_alpha.frag computes it: a' = a/(1-b/r)
// clamped to [0, 1], returning 1 whenever a >= 1 - b/r (which covers b/r >= 1), so the division
// only happens with a positive divisor. `a` must lie in [0, 1].
float remapSmoothieAlpha(float a, float bOverR);

// What smoothie_alpha.frag writes for a clamped linear alpha `a` in [0, 1]: Eq. 4.1 when `remap`
// (the default, --param remap=on), Chan's original linear alpha otherwise (§4.2.1, Figure
// 4-4b). In both, a smoothie pixel behind the receiver (b/r >= 1) is discarded: 1.
float smoothieAlpha(float a, float bOverR, bool remap);

// The sinusoidal falloff of §4.2.1 (Parker et al. 1998, Haines 2001): s(v) = (1 - cos(pi v))/2,
// s(0) = 0, s(1) = 1, slope 0 at both ends; precomputed into a 1D texture.
float smoothieFalloff(float v);

}  // namespace sl::modern
