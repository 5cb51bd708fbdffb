// msm_shadow.frag — Moment Shadow Maps, Hamburger 4-moment reconstruction (ours, after Peters &
// Klein 2015, not in shared/papers), camera pass: from the filtered moments b (dequantised with
// the inverse of the light pass's map) and the receiver depth zf, the shadow intensity G is the
// weight in front of zf of the 3-point distribution on {zf, z2, z3} that has b's moments; the
// visibility is 1 - G. Steps (modern/moment_shadow_map.h mirrors them on the CPU):
//   1. moment bias: b' = (1 - a) b + a (1/2, 1/3, 1/4, 1/5), towards the moments of the uniform
//      distribution on [0, 1], keeps the Hankel matrix definite (DEVIATION: see moment_shadow_map.h);
//   2. Cholesky (LDL^T) solve of [[1, b1, b2], [b1, b2, b3], [b2, b3, b4]] c = (1, zf, zf^2);
//   3. the roots z2 <= z3 of c3 z^2 + c2 z + c1 = 0;
//   4. G = 0 (zf <= z2), the weight of z2 (z2 < zf <= z3), or 1 - the weight of zf (zf > z3).
#version 330 core
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform sampler2DArray uMap;
uniform mat4 uWorldToShadowMap;
uniform mat4 uLightView;
uniform float uLightNear;
uniform float uLightFar;
uniform bool uQuantize;
uniform mat4 uDequantization;  // the inverse of msm_map.frag's uQuantization
uniform vec4 uQuantizationOffset;
uniform float uMomentBias;
uniform bool uReceivesShadow;
#include "lighting.glsl"
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;

// @pass msm-test: Hamburger 4-moment reconstruction: bias, Cholesky, quadratic, 3-point shadow intensity (ours, after Peters & Klein 2015, not in shared/papers)
float hamburgerShadowIntensity(vec4 b, float zf) {
  b = mix(b, vec4(1.0 / 2.0, 1.0 / 3.0, 1.0 / 4.0, 1.0 / 5.0), uMomentBias);  // 1. bias
  float d2 = b.y - b.x * b.x;                                // 2. B = L D L^T
  float l32 = (b.z - b.x * b.y) / d2;
  float d3 = b.w - b.y * b.y - l32 * l32 * d2;
  float y2 = (zf - b.x) / d2;                                //    L y = (1, zf, zf^2), / D
  float y3 = (zf * zf - b.y - l32 * (zf - b.x)) / d3;
  float c3 = y3;                                             //    L^T c = y
  float c2 = y2 - l32 * c3;
  float c1 = 1.0 - b.x * c2 - b.y * c3;
  float p = c2 / c3;                                         // 3. c3 z^2 + c2 z + c1 = 0
  float q = c1 / c3;
  float r = sqrt(max(0.25 * p * p - q, 0.0));
  float z2 = -0.5 * p - r;
  float z3 = -0.5 * p + r;
  if (zf <= z2) return 0.0;                                  // 4. weight in front of zf
  if (zf <= z3) return (zf * z3 - b.x * (zf + z3) + b.y) / ((z3 - z2) * (zf - z2));
  return 1.0 - (z2 * z3 - b.x * (z2 + z3) + b.y) / ((zf - z2) * (zf - z3));
}

float shadowTest(vec3 world) {
  vec4 coord = uWorldToShadowMap * vec4(world, 1.0);
  vec2 p = coord.xy / coord.w;
  // The lookup first, for every pixel of the quad (uniform control flow), as vsm_shadow.frag.
  vec4 stored = texture(uMap, vec3(p, 0.0));
  if (coord.w <= 0.0) return 0.0;  // behind the light (as modern.hw)
  if (any(lessThan(p, vec2(0.0))) || any(greaterThan(p, vec2(1.0)))) return 1.0;  // outside
  vec4 b = uQuantize ? uDequantization * (stored - uQuantizationOffset) : stored;
  float distanceAlongAxis = -(uLightView * vec4(world, 1.0)).z;
  float zf = clamp((distanceAlongAxis - uLightNear) / (uLightFar - uLightNear), 0.0, 1.0);
  float g = hamburgerShadowIntensity(b, zf);
  // A NaN (a degenerate footprint the bias did not cure) counts as lit, never as a NaN pixel.
  return isnan(g) ? 1.0 : clamp(1.0 - g, 0.0, 1.0);
// @end msm-test
}

void main() {
  float visibility = uReceivesShadow ? shadowTest(vWorldPosition) : 1.0;
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
}
