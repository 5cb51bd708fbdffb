// hw_shadow.frag — Everitt, Rege & Cebenoyan 2001: the ARB_shadow comparison as a shader.
// The texgen planes E_po = S·P_light·L^-1 (Eq. 5) arrive as one uniform matrix; the hardware
// 2x2 compare (GL_LINEAR on a depth texture with compare mode) is sampler2DShadow.
#version 330 core
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform sampler2DShadow uShadowMap;
// @pass texgen-planes: the EYE_LINEAR planes E_po = S·P_light·L^-1 as one matrix (Everitt Eq. 5)
// @replaces legacy.hw 2
// @replaces legacy.woo 4
// @replaces legacy.second-depth 2
uniform mat4 uWorldToShadowMap;   // S · P_light · L^-1 (Everitt Eq. 5)
// @end texgen-planes
uniform bool uReceivesShadow;
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;
#include "lighting.glsl"

// The shadow comparison: 1 = lit. Behind the light (q <= 0) is always shadowed (Everitt,
// "negative projection").
// @pass shadow-test: r/q <= depth(s/q, t/q) by sampler2DShadow, GL_LINEAR = 2x2 PCF; behind the light = shadow (Everitt, How It Works, Fig. 5)
// @replaces legacy.hw 4
// @replaces legacy.woo 6
// @replaces legacy.second-depth 4
float shadowTest(vec3 world) {
  vec4 coord = uWorldToShadowMap * vec4(world, 1.0);
  if (coord.w <= 0.0) return 0.0;
  return textureProj(uShadowMap, coord);
}
// @end shadow-test

void main() {
  float visibility = uReceivesShadow ? shadowTest(vWorldPosition) : 1.0;
  // @pass hw-shade: ambient + direct light x comparison in one fragment (Everitt, shading after Fig. 4)
  // @replaces legacy.hw 3
  // @replaces legacy.hw 4
  // @replaces legacy.woo 5
  // @replaces legacy.woo 6
  // @replaces legacy.second-depth 3
  // @replaces legacy.second-depth 4
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  // @end hw-shade
  // @pass hw-visibility: the comparison alone into a second render target (ours: the --mask output)
  // @replaces legacy.hw 5
  // @replaces legacy.woo 7
  // @replaces legacy.second-depth 5
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
  // @end hw-visibility
}
