// esm_shadow.frag — Exponential Shadow Maps (ours, after Annen et al. 2008, not in shared/papers),
// camera pass: for a receiver at linear light depth d and the filtered map E[exp(c z)],
//   visibility = clamp(exp(-c d) * E[exp(c z)], 0, 1).
// Where every z under the footprint is in front of d by much more than 1/c the product is ~0
// (shadow); where they equal d it is 1; a blocker just in front of the receiver (z close to d,
// contact) gives exp(-c (d - z)) ~ 1: ESM's light leak near contacts. A receiver whose own depth
// varies over the footprint (not a plane parallel to the map) weighs its farther texels by
// exp(c (z - d)) > 1, which lights an umbra next to the edge.
#version 330 core
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform sampler2DArray uMap;
uniform mat4 uWorldToShadowMap;
uniform mat4 uLightView;
uniform float uLightNear;
uniform float uLightFar;
uniform float uExponent;  // c
uniform bool uReceivesShadow;
#include "lighting.glsl"
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;

// @pass esm-test: visibility = clamp(exp(-c d) E[exp(c z)], 0, 1) (ours, after Annen et al. 2008, not in shared/papers)
float exponentialTest(float filtered, float d) {
  // exp(-c d) * E first, not exp(c (z - d)) per sample: the filtered value is all we have.
  return clamp(exp(-uExponent * d) * filtered, 0.0, 1.0);
}

float shadowTest(vec3 world) {
  vec4 coord = uWorldToShadowMap * vec4(world, 1.0);
  vec2 p = coord.xy / coord.w;
  // The lookup first, for every pixel of the quad (uniform control flow for texture()'s
  // implicit derivatives), as vsm_shadow.frag.
  float filtered = texture(uMap, vec3(p, 0.0)).x;
  if (coord.w <= 0.0) return 0.0;  // behind the light (as modern.hw)
  if (any(lessThan(p, vec2(0.0))) || any(greaterThan(p, vec2(1.0)))) return 1.0;  // outside
  float distanceAlongAxis = -(uLightView * vec4(world, 1.0)).z;
  float d = clamp((distanceAlongAxis - uLightNear) / (uLightFar - uLightNear), 0.0, 1.0);
  return exponentialTest(filtered, d);
// @end esm-test
}

void main() {
  float visibility = uReceivesShadow ? shadowTest(vWorldPosition) : 1.0;
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
}
