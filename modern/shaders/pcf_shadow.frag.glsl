// pcf_shadow.frag — Brabec & Seidel 2001 §3 (percentage-closer filtering, Figures 3 and 4) and
// §4 (fast PCF, Figure 6), the shadow test of every group of up to four depth samples packed
// in the R, G, B, A channels of a shadow map:
//   1. the fragment's ramp-encoded light depth is replicated over four channels (§3);
//   2. the packed map is projected (§4: offset by (ds/2, dt/2) and by the phase's region);
//      subtractive blending leaves max(fragment - map, 0) per channel;
//   3. glCopyPixels through the colour table: 0 stays 0, anything > 0 becomes 64 (63 in red,
//      footnote 2, so that four shadowed samples sum to 255);
//   4. the colour matrix sums the four channels into alpha (Figure 4): 5 levels per group;
//   5. groups (footprints 3x3 and 4x4: 9 or 16 samples; fast-PCF 4x4: 4 phases) are summed in
//      the accumulation buffer with weight (samples in the group / samples in all).
// 'faithful' arithmetic repeats each quantisation: 8-bit colour table and matrix results and
// the 16-bit signed accumulation buffer of Mesa (GL_ACCUM truncates c·value·32767 to a short;
// GL_RETURN writes acc·value/32767 rounded to the colour buffer's 8 bits). 'float' computes the
// fraction of shadowed samples directly.
#version 330 core
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform vec4 uRampPlane;
uniform float uBias;
uniform sampler1D uRamp;
uniform sampler2D uMaps[4];        // one packed map per group
uniform int uGroupCount;
uniform int uGroupSamples[4];      // channels in use per group (1..4)
uniform vec2 uGroupOffset[4];      // texture-coordinate offset per group, in texels
uniform float uMapTexels;          // side of the map
uniform mat4 uWorldToShadowMap;    // S · P_light · L^-1
uniform bool uFaithful;
uniform bool uReceivesShadow;
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;
#include "lighting.glsl"

const float kTableShadow = 64.0 / 255.0;       // colour table output for a shadowed sample
const float kTableShadowRed = 63.0 / 255.0;    // footnote 2
const float kAccumScale = 32767.0;             // 16-bit signed accumulation buffer

float encode(float s) { return uFaithful ? texture(uRamp, s).r : s; }

float quantize8(float v) { return roundEven(clamp(v, 0.0, 1.0) * 255.0) / 255.0; }

// GLSL 3.30 indexes sampler arrays with constants only.
vec4 lookupMap(int g, vec4 c) {
  if (g == 0) return textureProj(uMaps[0], c);
  if (g == 1) return textureProj(uMaps[1], c);
  if (g == 2) return textureProj(uMaps[2], c);
  return textureProj(uMaps[3], c);
}

// Steps 2-4 for one group: the alpha that the colour matrix leaves (share shadowed in 'float').
float groupShadow(int g, float fragmentDepth, vec4 coord) {
  vec4 c = coord;
  c.xy += uGroupOffset[g] / uMapTexels * c.w;
  vec4 map = lookupMap(g, c);
  vec4 difference = max(vec4(fragmentDepth) - map, vec4(0.0));
  vec4 inUse = vec4(greaterThan(ivec4(uGroupSamples[g]), ivec4(0, 1, 2, 3)));
  vec4 shadowed = vec4(greaterThan(difference, vec4(0.0))) * inUse;
  if (!uFaithful) return dot(shadowed, vec4(1.0)) / float(uGroupSamples[g]);
  vec4 table = shadowed * vec4(kTableShadowRed, kTableShadow, kTableShadow, kTableShadow);
  return quantize8(dot(table, vec4(1.0)));  // colour matrix row: alpha = r + g + b + a
}

void main() {
  float visibility = 1.0;
  if (uReceivesShadow) {
    float fragmentDepth = encode(dot(uRampPlane, vec4(vWorldPosition, 1.0)) - uBias);
    vec4 coord = uWorldToShadowMap * vec4(vWorldPosition, 1.0);
    int total = 0;
    for (int g = 0; g < uGroupCount; ++g) total += uGroupSamples[g];
    float shadow = 0.0;
    if (uGroupCount == 1) {
      shadow = groupShadow(0, fragmentDepth, coord);  // 2x2: alpha is the result (Figure 4)
    } else if (uFaithful) {
      int accumulator = 0;  // GL_ACCUM per group, then GL_RETURN 1.0
      for (int g = 0; g < uGroupCount; ++g) {
        float weight = float(uGroupSamples[g]) / float(total);
        accumulator += int(groupShadow(g, fragmentDepth, coord) * (weight * kAccumScale));
      }
      shadow = quantize8(float(accumulator) * (1.0 / kAccumScale));
    } else {
      for (int g = 0; g < uGroupCount; ++g)
        shadow += groupShadow(g, fragmentDepth, coord) * float(uGroupSamples[g]) / float(total);
    }
    visibility = 1.0 - shadow;
  }
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
}
