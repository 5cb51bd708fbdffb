// pcf_shadow.frag — Brabec & Seidel 2001 §3 (percentage-closer filtering, Figures 3 and 4) and
// §4 (fast PCF, Figure 6): the shadow test of every group of up to four depth samples packed
// in the R, G, B, A channels of a map, then shading (OpenGL lighting, §5):
//   1. the fragment's ramp-encoded light depth is replicated over four channels (§3);
//   2. the packed map is projected (§4: coordinates offset by (ds/2, dt/2), and by one texel
//      per 4x4 phase); subtractive blending leaves max(fragment - map, 0) per channel;
//   3. glCopyPixels through the colour table: a difference of at least one depth step becomes
//      the channel's share of M (64, 64, 64 and 63 in the group's last channel at 8 bits, so
//      that a fully shadowed group sums to M = 255, footnote 2);
//   4. the colour matrix sums the four channels into alpha (Figure 4): 5 levels per group;
//   5. footprints of several groups (3x3: 4+4+1 samples, 4x4: four groups or four §4 phases)
//      are summed in the accumulation buffer with weight (group samples / footprint samples).
// 'faithful' arithmetic repeats each quantisation of the legacy pipeline on integer codes of
// the colour buffer: the pixel-transfer scale and the table index rounding of the imaging
// subset, the float colour-matrix sum stored at the buffer's precision, and the accumulation
// buffer as the legacy context has it (uAccumMode 1: Mesa's 16-bit buffer, GL_ACCUM truncating
// c·value·32767 to a short; 2: the imaging/ emulation rounding A + value·c to 1/32767). The
// visibility is 1 - alpha as read back from the buffer. 'float' counts shadowed samples.
#version 330 core
in vec3 vWorldPosition;
in vec3 vWorldNormal;
in vec3 vShadowWorldPosition;      // texgen.vert: vWorldPosition, moved by --param bias=normal-offset
in vec4 vRampCoord;                // texgen.vert: the ramp coordinate of d - bias
in vec4 vShadowCoord[4];           // texgen.vert: projective coordinates of each group's map,
                                   // the Figure 6 offset folded into the texture matrix
uniform vec4 uDepthPlane;          // world position -> d ('float')
uniform float uBias;
uniform sampler1D uRamp;
uniform sampler2D uMaps[4];        // one packed map per group
uniform int uGroupCount;
uniform int uGroupSamples[4];      // channels in use per group (1..4)
uniform vec4 uGroupShares[4];      // colour-table output per channel, share / M
uniform float uGroupWeight[4];     // accumulation value of the group
uniform float uGroupAccumScale[4]; // Mesa: value * 32767
uniform bool uFaithful;
uniform bool uFloatBuffer;         // --precision float: legacy's float colour buffer
uniform float uBufferMax;          // M of the colour buffer: 255 or 65535 (1 for float)
uniform float uReadScale;          // 1 / M as the driver converts codes to float
uniform float uTableScale;         // GL_*_SCALE before the colour table: 1 / (step * 255)
uniform float uTableLastIndex;     // colour-table width - 1
uniform int uAccumMode;            // 1 Mesa, 2 imaging/ emulation
uniform float uAccumReturnScale;   // Mesa GL_RETURN: 1 / 32767
uniform bool uReceivesShadow;
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;
#include "lighting.glsl"

const float kAccumSteps = 32767.0;  // 16-bit signed accumulation buffer

// The value a fixed-point colour buffer stores: an integer code of M. A float buffer stores
// the value itself, unclamped (ARB_color_buffer_float; legacy clamps where 2001 would, below).
float code(float v) { return uFloatBuffer ? v : roundEven(clamp(v, 0.0, 1.0) * uBufferMax); }
vec4 code(vec4 v) { return uFloatBuffer ? v : roundEven(clamp(v, 0.0, 1.0) * uBufferMax); }

// GLSL 3.30 indexes sampler arrays with constants only.
vec4 lookupMap(int g, vec4 c) {
  if (g == 0) return textureProj(uMaps[0], c);
  if (g == 1) return textureProj(uMaps[1], c);
  if (g == 2) return textureProj(uMaps[2], c);
  return textureProj(uMaps[3], c);
}

vec4 projectedMap(int g) {
  if (g == 0) return lookupMap(0, vShadowCoord[0]);
  if (g == 1) return lookupMap(1, vShadowCoord[1]);
  if (g == 2) return lookupMap(2, vShadowCoord[2]);
  return lookupMap(3, vShadowCoord[3]);
}

vec4 inUse(int g) { return vec4(greaterThan(ivec4(uGroupSamples[g]), ivec4(0, 1, 2, 3))); }

// @pass subtract-and-count: packed map minus fragment depth, colour table, colour matrix sum (§3 Fig. 4, §4 Fig. 6)
// @replaces legacy.fast-pcf 4
// @replaces legacy.fast-pcf 5
// @replaces legacy.pcf 3
// @replaces legacy.pcf 4
// Steps 2-4, faithful: the alpha code the colour matrix leaves for group g.
float groupAlphaCode(int g, float fragmentCode) {
  vec4 difference = max(vec4(fragmentCode) - code(projectedMap(g)), vec4(0.0));
  vec4 scaled = clamp(difference * uReadScale * uTableScale, 0.0, 1.0);
  vec4 index = floor(scaled * uTableLastIndex + 0.5);
  vec4 table = vec4(greaterThan(index, vec4(0.0))) * inUse(g) * uGroupShares[g];
  float alpha = ((table.r + table.g) + table.b) + table.a;  // colour matrix alpha row
  return code(alpha);
}
// @end subtract-and-count

// @pass camera-depth: the fragment's light depth through the ramp, replicated over the channels (§3)
// @replaces legacy.fast-pcf 3 3s 3r
// @replaces legacy.pcf 2 2s 2r
float faithfulShadow() {
  float fragment = textureProj(uRamp, vRampCoord).r;
  float fragmentCode = code(fragment);
// @end camera-depth
  // @pass accumulate: the groups or 4x4 phases summed as the accumulation buffer sums them (§3, §4)
  // @replaces legacy.fast-pcf 6a 6b
  // @replaces legacy.pcf 5a 5b
  if (uGroupCount == 1) return groupAlphaCode(0, fragmentCode) * uReadScale;
  if (uAccumMode == 1) {
    int accumulator = 0;  // GL_LOAD, then GL_ACCUM: (short)(c * value * 32767)
    for (int g = 0; g < uGroupCount; ++g)
      accumulator += int(groupAlphaCode(g, fragmentCode) * uReadScale *
                         uGroupAccumScale[g]);
    return code(float(accumulator) * uAccumReturnScale) * uReadScale;  // GL_RETURN 1.0
  }
  float accumulator = 0.0;  // A <- quantise(A + value * c)
  for (int g = 0; g < uGroupCount; ++g) {
    float c = groupAlphaCode(g, fragmentCode) * uReadScale;
    accumulator = clamp(roundEven((accumulator + uGroupWeight[g] * c) * kAccumSteps) /
                            kAccumSteps, -1.0, 1.0);
  }
  if (uFloatBuffer) return clamp(accumulator, 0.0, 1.0);
  return floor(clamp(accumulator, 0.0, 1.0) * uBufferMax + 0.5) * uReadScale;
  // @end accumulate
}

// @pass float-shadow: --precision float: compare and count without the 2001 quantisations
// @replaces legacy.fast-pcf 4
// @replaces legacy.fast-pcf 5
// @replaces legacy.fast-pcf 6a 6b
// @replaces legacy.pcf 3
// @replaces legacy.pcf 4
// @replaces legacy.pcf 5a 5b
float floatShadow(float d) {
  float shadow = 0.0;
  for (int g = 0; g < uGroupCount; ++g) {
    vec4 shadowed = vec4(greaterThan(vec4(d), projectedMap(g))) * inUse(g);
    shadow += uGroupWeight[g] * dot(shadowed, vec4(1.0)) / float(uGroupSamples[g]);
  }
  return shadow;
}
// @end float-shadow

void main() {
  float visibility = 1.0;
  if (uReceivesShadow) {
    float d = dot(uDepthPlane, vec4(vShadowWorldPosition, 1.0)) - uBias;
    visibility = 1.0 - (uFaithful ? faithfulShadow() : floatShadow(d));
  }
  // @pass shade: OpenGL lighting x (1 - shadow) + ambient (§5)
  // @replaces legacy.fast-pcf 7
  // @replaces legacy.pcf 6
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  // @end shade
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
}
