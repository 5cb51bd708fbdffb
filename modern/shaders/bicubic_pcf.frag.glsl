// bicubic_pcf.frag — 16-sample percentage-closer filtering with bicubic weights: the "bicubic
// (16 samples)" column of Chan 2004, Fig. 4-8 (modern.gems16 --param kernel=bicubic).
// Percentage-closer filtering (Reeves, Salesin, Cook 1987, §3): the results of depth
// comparisons, not the depths, are filtered. Here the filter is the uniform cubic B-spline
// (Mitchell & Netravali 1988, B = 1, C = 0) over the 4x4 texels around the lookup point; its
// per-axis weights w0..w3 are those of Sigg & Hadwiger, "Fast Third-Order Texture Filtering",
// GPU Gems 2 (2005) ch. 20 (w0 = (1-a)^3/6, w1 = (3a^3 - 6a^2 + 4)/6,
// w2 = (-3a^3 + 3a^2 + 3a + 1)/6, w3 = a^3/6, a the lookup's fraction between texel centres).
// Each of the 16 samples is ONE comparison at a texel centre (the map is compared with
// GL_NEAREST in this mode), so the filter is the B-spline's and not a box of bilinear lookups.
// DEVIATION (Chan 2004 §4.4, Fig. 4-8): the thesis says only "a version of percentage closer
// filtering [RSC87] with a bicubic filter", 16 samples; it does not say which cubic or how the
// samples are weighted. We take the B-spline because its weights are non-negative and sum to 1,
// so the filtered value stays a visibility in [0, 1] (Catmull-Rom's negative lobes would not).
// BIAS_METHOD (pcf_bias.glsl, --param bias): the constant bias alone, or with the receiver-plane
// depth bias (ours, after Isidoro 2006, Dou et al. 2014) or the normal offset (ours, after
// Holbert 2011).
#version 330 core
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform sampler2DShadow uShadowMap;  // GL_NEAREST compare: one comparison per sample
uniform mat4 uWorldToShadowMap;      // S * P_light * V_light (Everitt Eq. 5)
uniform vec2 uMapSize;               // the shadow map's width and height in texels
uniform float uRelativeBias;         // bias / distance to the light (gems_pcf.cpp)
uniform bool uReceivesShadow;
#include "lighting.glsl"
#include "pcf_bias.glsl"
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;

// @pass bicubic-weights: the cubic B-spline's weights of the four texels along one axis (Sigg & Hadwiger, GPU Gems 2 ch. 20)
// a: where the lookup point lies between the centres of texels 1 and 2 of the four (0..1).
vec4 bsplineWeights(float a) {
  float a2 = a * a;
  float a3 = a2 * a;
  return vec4(1.0 - 3.0 * a + 3.0 * a2 - a3,  // (1 - a)^3
              3.0 * a3 - 6.0 * a2 + 4.0,
              -3.0 * a3 + 3.0 * a2 + 3.0 * a + 1.0,
              a3) / 6.0;
}
// @end bicubic-weights

// @pass bicubic-region: 16 single comparisons at the centres of the 4x4 texels around the lookup, weighted by the B-spline (Chan 2004 Fig. 4-8; the bias is ours, DEVIATION)
float shadowTest(vec3 world, vec3 worldNormal) {
#if BIAS_METHOD == BIAS_NORMAL_OFFSET
  // DEVIATION (the chapter has no bias): with --param bias=normal-offset the receiver's point
  // moves along its normal by normal-offset-texels texel footprints before it is projected
  // (pcf_bias.glsl: ours, after Holbert 2011).
  world = normalOffsetPosition(world, worldNormal);
#endif
  // DEVIATION (neither Chan nor GPU Gems gives this bias): the receiver moves towards the light
  // along the light ray by uRelativeBias of its distance, as modern.gems16 (gems_pcf.cpp says
  // why; the 4x4 region reaches 2 texels from the lookup point here too).
  vec3 biased = mix(world, uLightPosition, uRelativeBias);
  vec4 coord = uWorldToShadowMap * vec4(biased, 1.0);
#if BIAS_METHOD == BIAS_RECEIVER_PLANE
  vec2 slope = receiverPlaneDepthSlope(coord.xyz / coord.w);  // before the branch below
#endif
  if (coord.w <= 0.0) return 0.0;  // behind the light (as modern.hw)
  vec3 p = coord.xyz / coord.w;
  // Texel i's centre is at (i + 0.5) / size: t counts texel centres, the lookup lies between
  // centres floor(t) and floor(t) + 1, at the fraction a of the way.
  vec2 t = p.xy * uMapSize - 0.5;
  vec2 first = floor(t);
  vec2 a = t - first;
  vec4 wx = bsplineWeights(a.x);
  vec4 wy = bsplineWeights(a.y);
  float sum = 0.0;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      vec2 centre = (first + vec2(float(i - 1), float(j - 1)) + 0.5) / uMapSize;
#if BIAS_METHOD == BIAS_RECEIVER_PLANE
      // DEVIATION (Chan 2004 compares one depth in all 16 comparisons): with --param
      // bias=receiver-plane each comparison takes the receiver plane's depth at its texel centre
      // (pcf_bias.glsl: ours, after Isidoro 2006 and Dou et al. 2014).
      float depth = receiverPlaneDepth(p.z, slope, centre - p.xy);
      sum += wx[i] * wy[j] * texture(uShadowMap, vec3(centre, depth));
#else
      sum += wx[i] * wy[j] * texture(uShadowMap, vec3(centre, p.z));
#endif
    }
  return sum;
}
// @end bicubic-region

void main() {
  float visibility = uReceivesShadow ? shadowTest(vWorldPosition, vWorldNormal) : 1.0;
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
}
