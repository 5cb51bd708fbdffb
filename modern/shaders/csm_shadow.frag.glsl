// csm_shadow.frag — Annen et al. 2007, the camera pass: "we exchange regular shadow mapping
// with our shadow reconstruction as described by Equation 13", from the filtered (blurred,
// mip-mapped, tri-linear/anisotropic) basis textures:
//
//   s_f(x) = 1/2 + sum_k  w_k (2 / c_k) [ cos(c_k d) [w*sin(c_k z)](p) - sin(c_k d) [w*cos(c_k z)](p) ]
//
// with c_k = pi (2k - 1) (Eq. 11, 13, 14), the ringing attenuation w_k = exp(-alpha (k/M)^2)
// (§3.2.1), d offset by a constant and the result scaled (§3.2.2), then clamped to [0, 1]
// (§4.1: "due to ringing, the resulting shadow value can be outside the [0, 1]-range").
#version 330 core
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform sampler2DArray uBasis;   // layers 0..S-1: sin(c_k z), S..2S-1: cos(c_k z)
uniform mat4 uWorldToShadowMap;  // S * P_light * V_light
uniform mat4 uLightView;
uniform float uLightNear;
uniform float uLightFar;
uniform float uDepthScale;       // the same scale as the stored z (light_linear_depth.frag)
uniform int uOrder;              // M
uniform int uSinLayers;          // S = ceil(M / 4)
uniform float uAlpha;            // attenuation strength (§3.2.1), 0 = plain series
uniform float uOffset;           // subtracted from d (§3.2.2, Fig. 3c)
uniform float uScale;            // multiplies f (§3.2.2, Fig. 3d)
uniform bool uEncodeUnsigned;    // 8-bit storage: v = 2 t - 1
uniform bool uReceivesShadow;
#include "lighting.glsl"
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;

const float PI = 3.14159265358979;

// Eq. 13 with the filtered basis images; d is this point's (offset) linear depth.
// The texture derivatives come from the caller (textureGrad), so that mip-map and anisotropic
// footprints stay defined where the caller branches (outside the light frustum).
float reconstructShadowTest(vec2 p, vec2 dpdx, vec2 dpdy, float d) {
  float sum = 0.5;  // "we add the constant term 1/2 separately" (§3.1)
  for (int layer = 0; layer < uSinLayers; ++layer) {
    vec4 sines = textureGrad(uBasis, vec3(p, float(layer)), dpdx, dpdy);
    vec4 cosines = textureGrad(uBasis, vec3(p, float(uSinLayers + layer)), dpdx, dpdy);
    if (uEncodeUnsigned) {
      sines = 2.0 * sines - 1.0;
      cosines = 2.0 * cosines - 1.0;
    }
    for (int c = 0; c < 4; ++c) {
      int k = 4 * layer + c + 1;
      if (k > uOrder) break;
      float ck = PI * float(2 * k - 1);
      float attenuation = exp(-uAlpha * pow(float(k) / float(uOrder), 2.0));  // §3.2.1
      // a_(2k-1)(d) = 2/c_k cos(c_k d), a_(2k)(d) = -2/c_k sin(c_k d)  (Eq. 14)
      sum += attenuation * (2.0 / ck) * (cos(ck * d) * sines[c] - sin(ck * d) * cosines[c]);
    }
  }
  return sum;
}

float shadowTest(vec3 world) {
  vec4 coord = uWorldToShadowMap * vec4(world, 1.0);
  vec2 p = coord.xy / coord.w;
  vec2 dpdx = dFdx(p);  // before any branch: derivatives need every pixel of the quad
  vec2 dpdy = dFdy(p);
  if (coord.w <= 0.0) return 0.0;  // behind the light (as modern.hw)
  if (any(lessThan(p, vec2(0.0))) || any(greaterThan(p, vec2(1.0)))) return 1.0;  // outside
  float distanceAlongAxis = -(uLightView * vec4(world, 1.0)).z;
  float d = clamp((distanceAlongAxis - uLightNear) / (uLightFar - uLightNear), 0.0, 1.0);
  float f = reconstructShadowTest(p, dpdx, dpdy, d * uDepthScale - uOffset);
  return clamp(uScale * f, 0.0, 1.0);  // §3.2.2 scaling, §4.1 clamp
}

void main() {
  float visibility = uReceivesShadow ? shadowTest(vWorldPosition) : 1.0;
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
}
