// vsm_shadow.frag — Variance Shadow Maps (Donnelly & Lauritzen 2006), camera pass: from the
// filtered moments M1 = E[z], M2 = E[z^2] the one-tailed Chebyshev inequality bounds the
// fraction of the footprint that is at least as far as the receiver depth d:
//   p_max = sigma^2 / (sigma^2 + (d - M1)^2),  sigma^2 = max(M2 - M1^2, minimum variance),
// and visibility is 1 when d <= M1. p_max is an upper bound that becomes an equality only for
// a planar receiver parallel to a planar occluder, hence the light leaking of Annen Fig. 9(a).
// Optional light-bleeding reduction: p' = clamp((p_max - amount) / (1 - amount), 0, 1).
#version 330 core
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform sampler2DArray uMoments;
uniform mat4 uWorldToShadowMap;
uniform mat4 uLightView;
uniform float uLightNear;
uniform float uLightFar;
uniform float uMinVariance;       // floor on sigma^2 (against self-shadowing of lit surfaces)
uniform float uBleedReduction;    // 0 = off; cuts the tail of p_max below this amount
uniform bool uReceivesShadow;
#include "lighting.glsl"
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;

// @pass chebyshev: the one-tailed Chebyshev bound on the lit fraction from the filtered moments (Donnelly & Lauritzen 2006; light leaking: Annen et al. 2007 Fig. 9)
float chebyshevUpperBound(vec2 moments, float d) {
  if (d <= moments.x) return 1.0;
  float variance = max(moments.y - moments.x * moments.x, uMinVariance);
  float delta = d - moments.x;
  float pMax = variance / (variance + delta * delta);
  if (uBleedReduction > 0.0) pMax = clamp((pMax - uBleedReduction) / (1.0 - uBleedReduction), 0.0, 1.0);
  return pMax;
}

float shadowTest(vec3 world) {
  vec4 coord = uWorldToShadowMap * vec4(world, 1.0);
  vec2 p = coord.xy / coord.w;
  // The lookup first, for every pixel of the quad (uniform control flow: texture()'s implicit
  // derivatives choose the mip level and anisotropic footprint); as csm_shadow.frag, which
  // explains why not textureGrad.
  vec2 moments = texture(uMoments, vec3(p, 0.0)).xy;
  if (coord.w <= 0.0) return 0.0;  // behind the light (as modern.hw)
  if (any(lessThan(p, vec2(0.0))) || any(greaterThan(p, vec2(1.0)))) return 1.0;  // outside
  float distanceAlongAxis = -(uLightView * vec4(world, 1.0)).z;
  float d = clamp((distanceAlongAxis - uLightNear) / (uLightFar - uLightNear), 0.0, 1.0);
  return clamp(chebyshevUpperBound(moments, d), 0.0, 1.0);
// @end chebyshev
}

void main() {
  float visibility = uReceivesShadow ? shadowTest(vWorldPosition) : 1.0;
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
}
