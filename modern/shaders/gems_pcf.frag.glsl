// gems_pcf.frag — Bunnell & Pellacini, GPU Gems ch. 11 "Shadow Map Antialiasing".
// §11.3: offset_lookup is a projected lookup of the depth texture with compare mode and
// GL_LINEAR — the hardware's own 2x2 percentage-closer filter (Fig. 11-3) — moved by an offset
// in texels (texmapscale = 1 / map size, multiplied by w so the offset survives the divide).
// SAMPLES 16: the 4x4-texel region, offsets -1.5, -0.5, 0.5, 1.5 in x and y (§11.3).
// SAMPLES 4:  four of those sixteen, chosen per pixel by the dither of Fig. 11-4 (§11.4).
// SAMPLES 1:  one hardware lookup (Fig. 11-6).
// BIAS_METHOD (pcf_bias.glsl, --param bias): the constant bias alone, or with the receiver-plane
// depth bias (ours, after Isidoro 2006, Dou et al. 2014) or the normal offset (ours, after
// Holbert 2011).
#version 330 core
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform sampler2DShadow uShadowMap;
uniform mat4 uWorldToShadowMap;  // S * P_light * V_light (Everitt Eq. 5)
uniform vec2 uTexmapScale;       // (1/width, 1/height) of the shadow map (§11.3)
uniform float uRelativeBias;     // bias / distance to the light (gems_pcf.cpp)
uniform bool uReceivesShadow;
#include "lighting.glsl"
#include "pcf_bias.glsl"
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;

// bias=receiver-plane: the receiver plane's depth slope (receiverPlaneDepthSlope), set once per
// fragment by shadowTest before any lookup.
#if BIAS_METHOD == BIAS_RECEIVER_PLANE
vec2 receiverSlope = vec2(0.0);
#endif

// §11.3 offset_lookup: a projected, hardware-filtered compare, offset in texel units.
// @pass offset-lookup: a projected lookup through the hardware 2x2 compare, offset in texels (§11.3, Fig. 11-3)
float offsetLookup(vec4 loc, vec2 offset) {
#if BIAS_METHOD == BIAS_RECEIVER_PLANE
  // DEVIATION (GPU Gems §11.3 compares one depth in all 16 lookups): with --param
  // bias=receiver-plane each lookup's hardware 2x2 compare is rebuilt from four single
  // comparisons at its texel centres, weighted bilinearly as the hardware weights them, each
  // against the receiver plane's depth at that centre (pcf_bias.glsl: ours, after Isidoro 2006
  // and Dou et al. 2014).
  vec3 p = loc.xyz / loc.w;
  vec2 t = (p.xy + offset * uTexmapScale) / uTexmapScale - 0.5;  // texel centres counted
  vec2 first = floor(t);
  vec2 f = t - first;
  float sum = 0.0;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      vec2 centre = (first + vec2(float(i), float(j)) + 0.5) * uTexmapScale;
      float weight = (i == 0 ? 1.0 - f.x : f.x) * (j == 0 ? 1.0 - f.y : f.y);
      sum += weight * texture(uShadowMap,
                              vec3(centre, receiverPlaneDepth(p.z, receiverSlope, centre - p.xy)));
    }
  return sum;
#else
  return textureProj(uShadowMap, vec4(loc.xy + offset * uTexmapScale * loc.w, loc.z, loc.w));
#endif
}
// @end offset-lookup

// §11.4: which four of the sixteen samples this pixel takes (Fig. 11-4). The chapter computes
// offset = frac(position.xy * 0.5) > 0.25, i.e. the parity of the pixel's column and row;
// then y ^= x, done in floating point as offset.y += offset.x; if (offset.y > 1.1) offset.y = 0.
// @pass dither: which four of the sixteen offsets this pixel takes, by its column and row parity (§11.4, Fig. 11-4)
vec2 ditherOffset(vec2 windowPosition) {
  vec2 offset = vec2(greaterThan(fract(floor(windowPosition) * 0.5), vec2(0.25)));
  offset.y += offset.x;
  if (offset.y > 1.1) offset.y = 0.0;
  return offset;
}
// @end dither

// @pass gems-region: the 4x4-texel region: 16 lookups (§11.3), 4 dithered (§11.4) or 1 (Fig. 11-6); the bias is ours (DEVIATION)
float shadowTest(vec3 world, vec3 worldNormal) {
#if BIAS_METHOD == BIAS_NORMAL_OFFSET
  // DEVIATION (the chapter has no bias): with --param bias=normal-offset the receiver's point
  // moves along its normal by normal-offset-texels texel footprints before it is projected
  // (pcf_bias.glsl: ours, after Holbert 2011).
  world = normalOffsetPosition(world, worldNormal);
#endif
  // DEVIATION (the chapter has no bias): the receiver moves towards the light along the light
  // ray by uRelativeBias of its distance (gems_pcf.cpp says why); uLightPosition: lighting.glsl.
  vec3 biased = mix(world, uLightPosition, uRelativeBias);
  vec4 coord = uWorldToShadowMap * vec4(biased, 1.0);
#if BIAS_METHOD == BIAS_RECEIVER_PLANE
  receiverSlope = receiverPlaneDepthSlope(coord.xyz / coord.w);  // before the branch below
#endif
  if (coord.w <= 0.0) return 0.0;  // behind the light (as modern.hw)
#if SAMPLES == 16
  float sum = 0.0;
  for (float y = -1.5; y <= 1.5; y += 1.0)
    for (float x = -1.5; x <= 1.5; x += 1.0) sum += offsetLookup(coord, vec2(x, y));
  return sum / 16.0;
#elif SAMPLES == 4
  vec2 offset = ditherOffset(gl_FragCoord.xy);
  return (offsetLookup(coord, offset + vec2(-1.5, 0.5)) +
          offsetLookup(coord, offset + vec2(0.5, 0.5)) +
          offsetLookup(coord, offset + vec2(-1.5, -1.5)) +
          offsetLookup(coord, offset + vec2(0.5, -1.5))) * 0.25;
#else
  return offsetLookup(coord, vec2(0.0));
#endif
}
// @end gems-region

void main() {
  float visibility = uReceivesShadow ? shadowTest(vWorldPosition, vWorldNormal) : 1.0;
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
}
