// smoothie_shade.frag — Chan 2004 §4.2 step 5 and §4.3 pass 4 (Figure 4-7, "make shadows"):
// at each of the four nearest shadow-map texels, a sample behind the blocker is in umbra (0),
// one behind a smoothie gets the smoothie's alpha, any other is lit (1); the four results are
// interpolated bilinearly (the 2x2 tent of percentage-closer filtering) and looked up in the
// sinusoidal falloff texture (Haines's suggestion, §4.2.1).
#version 330 core
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform sampler2D uBlockerDepth;   // pass 1 depth (window depth, polygon offset), no compare
uniform sampler2D uSmoothieDepth;  // pass 2 depth
uniform sampler2D uSmoothieAlpha;  // pass 3 alpha (minimum blended)
uniform sampler1D uFalloff;        // sinusoidal falloff
uniform float uFalloffTexels;
uniform int uMapTexels;
uniform mat4 uWorldToShadowMap;    // S · P_light · V_light
uniform bool uReceivesShadow;
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;
#include "lighting.glsl"

// §4.2 step 5, cases 1-3, at one texel. Outside the map: lit (as the border of modern.hw).
// @pass smoothie-test: behind the blocker = 0, behind a smoothie = its alpha, else 1, bilinear over 4 texels, then the falloff (Chan 2004 §4.2 step 5, Fig. 4-3)
float texelVisibility(ivec2 t, float depth) {
  if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, ivec2(uMapTexels)))) return 1.0;
  if (depth > texelFetch(uBlockerDepth, t, 0).r) return 0.0;                 // behind a blocker
  if (depth > texelFetch(uSmoothieDepth, t, 0).r) return texelFetch(uSmoothieAlpha, t, 0).r;
  return 1.0;                                                                // illuminated
}

float smoothieVisibility(vec3 world) {
  vec4 coord = uWorldToShadowMap * vec4(world, 1.0);
  if (coord.w <= 0.0) return 0.0;  // behind the light
  vec3 c = coord.xyz / coord.w;
  vec2 st = c.xy * float(uMapTexels) - 0.5;  // texel centres at integers
  ivec2 i0 = ivec2(floor(st));
  vec2 w = st - vec2(i0);
  float v00 = texelVisibility(i0, c.z);
  float v10 = texelVisibility(i0 + ivec2(1, 0), c.z);
  float v01 = texelVisibility(i0 + ivec2(0, 1), c.z);
  float v11 = texelVisibility(i0 + ivec2(1, 1), c.z);
  float v = mix(mix(v00, v10, w.x), mix(v01, v11, w.x), w.y);
  // The falloff texture: texel centres sample s(0) and s(1) exactly at the ends.
  return texture(uFalloff, (v * (uFalloffTexels - 1.0) + 0.5) / uFalloffTexels).r;
// @end smoothie-test
}

void main() {
  float visibility = uReceivesShadow ? smoothieVisibility(vWorldPosition) : 1.0;
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
}
