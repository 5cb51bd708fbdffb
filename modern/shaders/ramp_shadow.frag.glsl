// ramp_shadow.frag — Brabec & Seidel 2001 §2, second and third passes and footnote 1: the
// camera view encodes each fragment's light-space depth through the same ramp (the texture
// matrix takes camera to light space; the depth bias is subtracted there), the shadow map is
// projected onto the scene, subtractive blending leaves (fragment - map) clamped at 0, and the
// extra copy of footnote 1 scales any value of at least one depth step to 1. Here those passes
// are one fragment shader, which also shades (OpenGL lighting, the mask darkening the direct
// term, §5).
// 'faithful' arithmetic works on the integer codes of the colour buffer (2^bits - 1 = M): the
// subtraction of two codes is exact, the copy multiplies by 1/step and clamps, and the result
// is stored and read back as the legacy alpha channel is (visibility = 1 - alpha).
#version 330 core
in vec3 vWorldPosition;
in vec3 vWorldNormal;
in vec4 vRampCoord;               // texgen.vert: the ramp coordinate of d - bias
in vec4 vShadowCoord[4];          // texgen.vert: [0] = projective map coordinates
uniform vec4 uDepthPlane;         // world position -> d, as in the light pass ('float')
uniform float uBias;              // subtracted from d (§2 depth bias, texture matrix)
uniform sampler1D uRamp;
uniform sampler2D uShadowMap;     // encoded depth, GL_NEAREST, far-plane border
uniform bool uFaithful;
uniform bool uFloatBuffer;        // --precision float: legacy's float colour buffer
uniform float uBufferMax;         // M: 255 (8-bit) or 65535 (12-bit values in 16 bits); 1 float
uniform float uReadScale;         // 1 / M as the driver converts codes to float
uniform float uSaturateScale;     // footnote 1 copy: GL_ALPHA_SCALE = 1 / depth step
uniform bool uReceivesShadow;
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;
#include "lighting.glsl"

// The integer code a fixed-point colour buffer stores; a float buffer stores v itself.
float code(float v) { return uFloatBuffer ? v : roundEven(v * uBufferMax); }

float shadowTerm() {
  // @pass ramp-subtract: the map as a projective texture (§2, third pass)
  // @replaces legacy.ramp 3
  float map = textureProj(uShadowMap, vShadowCoord[0]).r;
  // @end ramp-subtract
  // @pass ramp-float: --param arithmetic=float: light depth minus bias against the map, without the 2001 quantisations
  if (!uFaithful) return dot(uDepthPlane, vec4(vWorldPosition, 1.0)) - uBias > map ? 1.0 : 0.0;
  // @end ramp-float
  // @pass ramp-camera-depth: the fragment's light depth through the same ramp (§2, second pass)
  // @replaces legacy.ramp 2
  float fragment = textureProj(uRamp, vRampCoord).r;
  // @end ramp-camera-depth
  // @pass ramp-subtract: (continued) the fragment's code minus the map's, clamped at 0 as reverse-subtract blending leaves it
  float difference = max(code(fragment) - code(map), 0.0);  // reverse-subtract blending
  // @end ramp-subtract
  // @pass ramp-saturate: the extra copy of footnote 1: one depth step or more becomes 1 (§2)
  // @replaces legacy.ramp 4
  float saturated = clamp(difference * uReadScale * uSaturateScale, 0.0, 1.0);  // footnote 1
  return code(saturated) * uReadScale;  // stored in the colour buffer's alpha, read back
  // @end ramp-saturate
}

void main() {
  float visibility = uReceivesShadow ? 1.0 - shadowTerm() : 1.0;
  // @pass ramp-shade: OpenGL lighting, the direct term x (1 - mask), ambient kept (§5)
  // @replaces legacy.ramp 5
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  // @end ramp-shade
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
}
