// evsm_shadow.frag — Exponential Variance Shadow Maps (ours, after Lauritzen & McCool 2008, not
// in shared/papers), camera pass: the receiver's depth d is warped as the map was (x = 2 d - 1,
// p = exp(c+ x), n = -exp(-c- x)); Chebyshev's one-tailed bound (as modern.vsm) is taken on the
// filtered moments of each warp, and the visibility is the smaller of the two bounds (EVSM2:
// the positive warp only). The minimum variance is given in linear-depth units and scaled by the
// square of the warp's slope at the filtered mean, (2 c E[w])^2 (ours): on a lit surface (mean
// at the receiver) it means what modern.vsm's does; behind a far blocker (mean much smaller than
// the receiver's warped depth) it stays small against the gap, where the receiver's own slope
// would let a share 4 c^2 sigma^2 of light through.
// Optional light-bleeding reduction on each bound: p' = clamp((p - amount) / (1 - amount), 0, 1).
#version 330 core
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform sampler2DArray uMap;
uniform mat4 uWorldToShadowMap;
uniform mat4 uLightView;
uniform float uLightNear;
uniform float uLightFar;
uniform float uPositiveExponent;
uniform float uNegativeExponent;
uniform bool uUseNegative;      // EVSM4
uniform float uMinVariance;     // (linear depth)^2, scaled into each warp
uniform float uBleedReduction;  // 0 = off
uniform bool uReceivesShadow;
#include "lighting.glsl"
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;

// @pass evsm-test: Chebyshev's bound on each warp's filtered moments, the smaller one (ours, after Lauritzen & McCool 2008, not in shared/papers)
// Chebyshev's bound for warped receiver depth w from the filtered (E[w], E[w^2]) of a warp of
// exponent c. Everything is first divided by s = max(|w|, |E[w]|), which leaves the bound as it
// is (it is scale-free) and keeps E[w^2] / s^2 and the variance floor within fp32 where
// E[w]^2 or (2 c E[w])^2 alone would overflow (exp(42)^2 * 84^2 > FLT_MAX).
float chebyshev(vec2 moments, float w, float c) {
  if (w <= moments.x) return 1.0;
  float s = max(abs(w), abs(moments.x));
  float mean = moments.x / s;
  float meanSquare = (moments.y / s) / s;
  float slope = 2.0 * c * mean;  // d(warp)/dz at the mean, over s
  float variance = max(meanSquare - mean * mean, uMinVariance * slope * slope);
  float delta = w / s - mean;
  float pMax = variance / (variance + delta * delta);
  if (uBleedReduction > 0.0) pMax = clamp((pMax - uBleedReduction) / (1.0 - uBleedReduction), 0.0, 1.0);
  return pMax;
}

float evsmTest(vec4 moments, float d) {
  float x = 2.0 * d - 1.0;
  float visibility = chebyshev(moments.xy, exp(uPositiveExponent * x), uPositiveExponent);
  if (uUseNegative)
    visibility = min(visibility, chebyshev(moments.zw, -exp(-uNegativeExponent * x), uNegativeExponent));
  return visibility;
}

float shadowTest(vec3 world) {
  vec4 coord = uWorldToShadowMap * vec4(world, 1.0);
  vec2 p = coord.xy / coord.w;
  // The lookup first, for every pixel of the quad (uniform control flow), as vsm_shadow.frag.
  vec4 moments = texture(uMap, vec3(p, 0.0));
  if (coord.w <= 0.0) return 0.0;  // behind the light (as modern.hw)
  if (any(lessThan(p, vec2(0.0))) || any(greaterThan(p, vec2(1.0)))) return 1.0;  // outside
  float distanceAlongAxis = -(uLightView * vec4(world, 1.0)).z;
  float d = clamp((distanceAlongAxis - uLightNear) / (uLightFar - uLightNear), 0.0, 1.0);
  return clamp(evsmTest(moments, d), 0.0, 1.0);
// @end evsm-test
}

void main() {
  float visibility = uReceivesShadow ? shadowTest(vWorldPosition) : 1.0;
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
}
