// ramp_shadow.frag — Brabec & Seidel 2001 §2, second and third passes: the camera view encodes
// each fragment's light-space depth through the same ramp (a texture matrix takes camera to
// light space), the shadow map is projected onto the scene, and subtractive blending leaves
// (fragment depth - map depth), clamped at 0, in the mask: 0 = lit, > 0 = shadowed; footnote 1's
// extra copy brings every value > 0 to 1. Here the two passes are one fragment shader, which
// also shades (OpenGL lighting, the mask darkening the direct term, §5).
#version 330 core
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform vec4 uRampPlane;          // as in the light pass
uniform float uBias;              // subtracted from the ramp coordinate (texture matrix)
uniform sampler1D uRamp;
uniform sampler2D uShadowMap;     // encoded depth, GL_NEAREST, projective lookup
uniform mat4 uWorldToShadowMap;   // S · P_light · L^-1
uniform bool uFaithful;
uniform bool uReceivesShadow;
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;
#include "lighting.glsl"

float encode(float s) { return uFaithful ? texture(uRamp, s).r : s; }

void main() {
  float visibility = 1.0;
  if (uReceivesShadow) {
    float fragmentDepth = encode(dot(uRampPlane, vec4(vWorldPosition, 1.0)) - uBias);
    float mapDepth = textureProj(uShadowMap, uWorldToShadowMap * vec4(vWorldPosition, 1.0)).r;
    // Subtractive blending clamps at 0 (glspec121 §4.1.6); in 'faithful' arithmetic both terms
    // are ramp texels of the same colour format, so the difference is exact.
    float shadowed = max(fragmentDepth - mapDepth, 0.0);
    visibility = shadowed > 0.0 ? 0.0 : 1.0;  // footnote 1: any value > 0 -> fully shadowed
  }
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
}
