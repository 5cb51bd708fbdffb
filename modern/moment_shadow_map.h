// modern/moment_shadow_map.h — modern.msm: Moment Shadow Maps, Hamburger 4-moment reconstruction
// (ours, after Peters & Klein, "Moment Shadow Mapping", I3D 2015, not in shared/papers), a
// filtered-map baseline next to modern.vsm: four moments of the linear light depth, filtered,
// and the sharpest lower bound on the shadow that is consistent with them.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "core/technique/technique.h"

namespace sl::modern {
Technique momentShadowMapTechnique();

// The moment bias alpha: b' = (1 - alpha) b + alpha u with u = (1/2, 1/3, 1/4, 1/5), the moments
// of the uniform distribution on [0, 1] (ours, default alpha 3e-5, the value the issue names for
// the 16-bit map). u's Hankel matrix is positive definite, so every biased footprint's is too.
// DEVIATION (Peters & Klein 2015, not in shared/papers; public implementations bias towards
// (1/2, 1/2, 1/2, 1/2)): the moment bias points to (1/2, 1/3, 1/4, 1/5), the moments of depths
// uniform on [0, 1], whose Hankel matrix is positive definite; towards the moments of depths 0
// and 1 a footprint of the empty map (depth 1) stays singular and the Cholesky solve divides 0
// by 0
constexpr double kMsmDefaultMomentBias = 3e-5;
constexpr double kMsmBiasMoments[4] = {1.0 / 2, 1.0 / 3, 1.0 / 4, 1.0 / 5};

// Peters & Klein 2015 §4.3's optimised 16-bit quantisation (not in shared/papers): an affine map
// q = Q b + o of the moments b = (z, z^2, z^3, z^4) that spreads them over [0, 1] so that 16-bit
// UNORM storage loses less; the constants as published (cross-checked against two public
// implementations; nothing else taken from them). kMsmQuantization[i] is the row of b_i's
// coefficients: q_j = sum_i b_i kMsmQuantization[i][j] + (j == 0 ? kMsmQuantizationOffset : 0).
constexpr double kMsmQuantization[4][4] = {
    {-2.07224649, 13.7948857237, 0.105877704, 9.7924062118},
    {32.23703778, -59.4683975703, -1.9077466311, -33.7652110555},
    {-68.571074599, 82.0359750338, 9.3496555107, 47.9456096605},
    {39.3703274134, -35.364903257, -6.6543490743, -23.9728048165}};
constexpr double kMsmQuantizationOffset = 0.035955884801;

// The Hamburger 4-moment reconstruction of msm_shadow.frag, mirrored on the CPU (tests): the
// shadow intensity G (1 = in shadow) for a receiver at depth zf from the filtered moments b
// (already dequantised), moment bias alpha. Our derivation (Peters & Klein 2015, Algorithm 2 in
// outline, not in shared/papers): bias; solve B c = (1, zf, zf^2) with the Hankel matrix
// B = [[1, b1, b2], [b1, b2, b3], [b2, b3, b4]] by an LDL^T Cholesky; the roots z2 <= z3 of
// c3 z^2 + c2 z + c1; the 3-point distribution on {zf, z2, z3} with b's first two moments gives
// G = the weight of its points in front of zf.
inline double msmShadowIntensity(std::array<double, 4> b, double zf, double alpha) {
  for (size_t k = 0; k < 4; ++k) b[k] = (1.0 - alpha) * b[k] + alpha * kMsmBiasMoments[k];
  const double d2 = b[1] - b[0] * b[0];
  const double l32 = (b[2] - b[0] * b[1]) / d2;
  const double d3 = b[3] - b[1] * b[1] - l32 * l32 * d2;
  const double y2 = (zf - b[0]) / d2;
  const double y3 = (zf * zf - b[1] - l32 * (zf - b[0])) / d3;
  const double c3 = y3, c2 = y2 - l32 * c3, c1 = 1.0 - b[0] * c2 - b[1] * c3;
  const double p = c2 / c3, q = c1 / c3;
  const double r = std::sqrt(std::max(0.25 * p * p - q, 0.0));
  const double z2 = -0.5 * p - r, z3 = -0.5 * p + r;
  if (zf <= z2) return 0.0;
  if (zf <= z3) return (zf * z3 - b[0] * (zf + z3) + b[1]) / ((z3 - z2) * (zf - z2));
  return 1.0 - (z2 * z3 - b[0] * (z2 + z3) + b[1]) / ((zf - z2) * (zf - z3));
}
}  // namespace sl::modern
