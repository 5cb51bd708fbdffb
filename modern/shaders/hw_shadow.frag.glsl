// hw_shadow.frag — Everitt, Rege & Cebenoyan 2001: the ARB_shadow comparison as a shader.
// The texgen planes E_po = S·P_light·L^-1 (Eq. 5) arrive as one uniform matrix; the hardware
// 2x2 compare (GL_LINEAR on a depth texture with compare mode) is sampler2DShadow.
#version 330 core
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform sampler2DShadow uShadowMap;
uniform mat4 uWorldToShadowMap;   // S · P_light · L^-1 (Everitt Eq. 5)
uniform bool uReceivesShadow;
uniform vec3 uDiffuse;
uniform float uSpecular;
uniform vec3 uLightPosition;
uniform vec3 uLightDirection;
uniform float uSpotCosCutoff;
uniform vec3 uLightColor;
uniform float uAmbient;
uniform vec3 uEyePosition;
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;

// The shadow comparison: 1 = lit. Behind the light (q <= 0) is always shadowed (Everitt,
// "negative projection").
float shadowTest(vec3 world) {
  vec4 coord = uWorldToShadowMap * vec4(world, 1.0);
  if (coord.w <= 0.0) return 0.0;
  return textureProj(uShadowMap, coord);
}

// OpenGL fixed-function lighting with one spotlight (glspec121 §2.13.1), split into the
// ambient term and the direct (diffuse + specular) term that the shadow test modulates.
void main() {
  float visibility = uReceivesShadow ? shadowTest(vWorldPosition) : 1.0;
  vec3 n = normalize(vWorldNormal);
  vec3 toLight = normalize(uLightPosition - vWorldPosition);
  if (!gl_FrontFacing) n = -n;
  float spot = dot(-toLight, normalize(uLightDirection)) >= uSpotCosCutoff ? 1.0 : 0.0;
  float diffuse = max(dot(n, toLight), 0.0);
  vec3 toEye = normalize(uEyePosition - vWorldPosition);
  float specular = diffuse > 0.0 ? pow(max(dot(n, normalize(toLight + toEye)), 0.0), 32.0) : 0.0;
  vec3 direct = spot * uLightColor * (uDiffuse * diffuse + vec3(uSpecular) * specular);
  vec3 ambient = uAmbient * uLightColor * uDiffuse;
  oColor = vec4(ambient + visibility * direct, 1.0);
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
}
