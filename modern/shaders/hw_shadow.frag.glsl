// hw_shadow.frag — Everitt, Rege & Cebenoyan 2001: the ARB_shadow comparison as a shader.
// The texgen planes E_po = S·P_light·L^-1 (Eq. 5) arrive as one uniform matrix; the hardware
// 2x2 compare (GL_LINEAR on a depth texture with compare mode) is sampler2DShadow.
#version 330 core
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform sampler2DShadow uShadowMap;
// @pass texgen-planes: the EYE_LINEAR planes E_po = S·P_light·L^-1 as one matrix (Everitt Eq. 5)
// @replaces legacy.hw pass 2 eye-linear texgen planes
// @replaces legacy.woo pass 4 eye-linear texgen planes
// @replaces legacy.second-depth pass 2 eye-linear texgen planes
uniform mat4 uWorldToShadowMap;   // S · P_light · L^-1 (Everitt Eq. 5)
// @end texgen-planes
uniform bool uReceivesShadow;
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;
#include "lighting.glsl"

// The shadow comparison: 1 = lit. Behind the light (q <= 0) is always shadowed (Everitt,
// "negative projection").
// @pass shadow-test: r/q <= depth(s/q, t/q) by sampler2DShadow, GL_LINEAR = 2x2 PCF; behind the light = shadow (Everitt, How It Works, Fig. 5)
// @replaces legacy.hw pass 4 direct light x shadow test
// @replaces legacy.woo pass 6 direct light x shadow test
// @replaces legacy.second-depth pass 4 direct light x shadow test
float shadowTest(vec3 world) {
  vec4 coord = uWorldToShadowMap * vec4(world, 1.0);
  if (coord.w <= 0.0) return 0.0;
  return textureProj(uShadowMap, coord);
}
// @end shadow-test

void main() {
  float visibility = uReceivesShadow ? shadowTest(vWorldPosition) : 1.0;
  // @pass hw-shade: ambient + direct light x comparison in one fragment (Everitt, shading after Fig. 4)
  // @replaces legacy.hw pass 3 ambient
  // @replaces legacy.hw pass 4 direct light x shadow test
  // @replaces legacy.woo pass 5 ambient
  // @replaces legacy.woo pass 6 direct light x shadow test
  // @replaces legacy.second-depth pass 3 ambient
  // @replaces legacy.second-depth pass 4 direct light x shadow test
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  // @end hw-shade
  // @pass hw-visibility: the comparison alone into a second render target (ours: the --mask output)
  // @replaces legacy.hw pass 5 visibility mask
  // @replaces legacy.woo pass 7 visibility mask
  // @replaces legacy.second-depth pass 5 visibility mask
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
  // @end hw-visibility
}
