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
uniform float uNearestCaster;    // distance along the light axis of the nearest caster
uniform float uDepthScale;       // the same scale as the stored z (light_linear_depth.frag)
uniform int uOrder;              // M
uniform int uSinLayers;          // S = ceil(M / 4)
// exp(-alpha (k/M)^2) (2 / c_k) for k = 1..M (§3.2.1 attenuation times Eq. 14's 2 / c_k),
// computed once per frame on the CPU instead of per pixel and term; 0 beyond M.
uniform float uWeights[64];
uniform float uOffset;           // subtracted from d (§3.2.2, Fig. 3c)
uniform float uScale;            // multiplies f (§3.2.2, Fig. 3d)
uniform bool uEncodeUnsigned;    // 8-bit storage: v = 2 t - 1
uniform bool uReceivesShadow;
#include "lighting.glsl"
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;

const float PI = 3.14159265358979;

// Eq. 13 with the filtered basis images; d is this point's (offset) linear depth. Called in
// uniform control flow (every pixel, before any branch), so that texture()'s implicit
// derivatives, which choose the mip level and the anisotropic footprint, are defined.
// @pass reconstruct: f(d, z) ~ 1/2 + sum a_i(d) B_i(z) from the filtered basis (Eq. 13, coefficients Eq. 14)
float reconstructShadowTest(vec2 p, float d) {
  float sum = 0.5;  // "we add the constant term 1/2 separately" (§3.1)
  // cos(c_k d), sin(c_k d) for c_k = pi (2k - 1): start at c_1 d = pi d and rotate by 2 pi d
  // per k (the angle-addition formulas), two transcendental calls per pixel instead of 2M.
  // The rotation's float32 error grows by ~1e-7 per step: < 1e-5 after 64 terms.
  vec2 term = vec2(cos(PI * d), sin(PI * d));
  vec2 step = vec2(cos(2.0 * PI * d), sin(2.0 * PI * d));
  for (int layer = 0; layer < uSinLayers; ++layer) {
    vec4 sines = texture(uBasis, vec3(p, float(layer)));
    vec4 cosines = texture(uBasis, vec3(p, float(uSinLayers + layer)));
    if (uEncodeUnsigned) {
      sines = 2.0 * sines - 1.0;
      cosines = 2.0 * cosines - 1.0;
    }
    vec4 cosD, sinD;  // cos(c_k d), sin(c_k d) for this layer's four k
    for (int c = 0; c < 4; ++c) {
      cosD[c] = term.x;
      sinD[c] = term.y;
      term = vec2(term.x * step.x - term.y * step.y, term.y * step.x + term.x * step.y);
    }
    // a_(2k-1)(d) = 2/c_k cos(c_k d), a_(2k)(d) = -2/c_k sin(c_k d)  (Eq. 14), attenuated
    // (§3.2.1); the weights of k > M are 0.
    vec4 weights = vec4(uWeights[4 * layer], uWeights[4 * layer + 1], uWeights[4 * layer + 2],
                        uWeights[4 * layer + 3]);
    sum += dot(weights, cosD * sines - sinD * cosines);
  }
  return sum;
// @end reconstruct
}

// @pass csm-test: d from the receiver, offset and scale of §3.2.2 (Fig. 3 c-d), clamp to [0, 1] (§4.1)
float shadowTest(vec3 world) {
  vec4 coord = uWorldToShadowMap * vec4(world, 1.0);
  vec2 p = coord.xy / coord.w;
  float distanceAlongAxis = -(uLightView * vec4(world, 1.0)).z;
  float d = clamp((distanceAlongAxis - uLightNear) / (uLightFar - uLightNear), 0.0, 1.0);
  // The lookups come first, for every pixel of the quad; the frustum tests only choose the
  // result. (An earlier version passed dFdx(p), dFdy(p) to textureGrad instead: Mesa 22.3
  // llvmpipe's anisotropic path with explicit gradients returned wrong values on a row of
  // isolated pixels, the white dots inside the tree shadows of Fig. 7 (c)-(f); its implicit-
  // derivative path, with the same footprint, does not.)
  float f = reconstructShadowTest(p, d * uDepthScale - uOffset);
  if (coord.w <= 0.0) return 0.0;  // behind the light (as modern.hw)
  if (any(lessThan(p, vec2(0.0))) || any(greaterThan(p, vec2(1.0)))) return 1.0;  // outside
  // Nearer than the nearest caster (modern::csmDepthRange): nothing is in front, so lit. Not
  // left to the series: d is near 0 there (or clamped to it), and beside texels where nothing
  // blocks (z at the far end) t = z - d + offset reaches 1, the falling edge of the periodic
  // square wave (Eq. 10), which reconstructs 1/2 or less.
  if (distanceAlongAxis < uNearestCaster) return 1.0;
  return clamp(uScale * f, 0.0, 1.0);  // §3.2.2 scaling, §4.1 clamp
// @end csm-test
}

void main() {
  float visibility = uReceivesShadow ? shadowTest(vWorldPosition) : 1.0;
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
}
