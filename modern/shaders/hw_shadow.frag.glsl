// hw_shadow.frag — Everitt, Rege & Cebenoyan 2001: the ARB_shadow comparison as a shader.
// The texgen planes E_po = S·P_light·L^-1 (Eq. 5) arrive as one uniform matrix; the hardware
// 2x2 compare (GL_LINEAR on a depth texture with compare mode) is sampler2DShadow.
#version 330 core
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform sampler2DShadow uShadowMap;
uniform mat4 uWorldToShadowMap;   // S · P_light · L^-1 (Everitt Eq. 5)
uniform bool uReceivesShadow;
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;
#include "lighting.glsl"

// The shadow comparison: 1 = lit. Behind the light (q <= 0) is always shadowed (Everitt,
// "negative projection").
float shadowTest(vec3 world) {
  vec4 coord = uWorldToShadowMap * vec4(world, 1.0);
  if (coord.w <= 0.0) return 0.0;
  return textureProj(uShadowMap, coord);
}

void main() {
  float visibility = uReceivesShadow ? shadowTest(vWorldPosition) : 1.0;
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
}
