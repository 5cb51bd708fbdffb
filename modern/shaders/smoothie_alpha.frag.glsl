// smoothie_alpha.frag — Chan 2004 §4.2.1 and §4.3 pass 3 (Figure 4-7, "smoothie EDGE" and
// "smoothie CORNER"): the linear alpha of a smoothie pixel in light screen space, remapped by
// Eq. 4.1, a' = a / (1 - b/r), clamped to [0, 1]; composited with minimum blending
// (EXT_blend_minmax) into a buffer cleared to 1. With uRemap false the linear alpha is kept
// (§4.2.1's first approach, Figures 4-4a/b and 4-10 left: fixed-width penumbrae).
#version 330 core
flat in vec2 vRoot;
flat in vec2 vNormal;
flat in int vKind;
in float vLinearDepth;
uniform sampler2D uLinearDepth;  // pass 1: r, the nearest surface seen from the light
uniform float uWidthPixels;      // t in shadow-map pixels
uniform bool uRemap;             // Eq. 4.1 on (default) or Chan's original linear alpha
layout(location = 0) out vec4 oAlpha;

// Eq. 4.1 with the clamp of §4.2.1. When b/r >= 1 (the smoothie lies at or behind the receiver,
// Chan: "If b/r > 1, smoothie pixel is occluded") or a >= 1 - b/r, the result is 1; otherwise
// a < 1 - b/r, so the divisor is positive and the quotient lies in [0, 1): no division by zero,
// no NaN or Inf as b/r -> 1.
// @pass smoothie-alpha: alpha rising across the smoothie, remapped by b / r (Chan 2004 §4.2.1, Eq. 4.1, Fig. 4-4); min blending keeps the smallest
float remapAlpha(float a, float bOverR) {
  float room = 1.0 - bOverR;
  return a >= room ? 1.0 : a / room;
}

void main() {
  vec2 p = gl_FragCoord.xy;
  // Figure 4-7 edge: alpha = dot(wpos - v, n) / t; corner (Figure 4-6): |v - p| / t.
  float a = vKind == 0 ? dot(p - vRoot, vNormal) / uWidthPixels
                       : length(p - vRoot) / uWidthPixels;
  a = clamp(a, 0.0, 1.0);
  float r = texelFetch(uLinearDepth, ivec2(p), 0).r;
  float bOverR = r > 0.0 ? vLinearDepth / r : 0.0;
  // Not remapped (§4.2.1, Figure 4-4b): alpha stays linear, but a smoothie pixel behind the
  // receiver is still discarded (Figure 4-7: "If b/r > 1, smoothie pixel is occluded").
  float linearAlpha = bOverR >= 1.0 ? 1.0 : a;
  oAlpha = vec4(uRemap ? remapAlpha(a, bOverR) : linearAlpha, 0.0, 0.0, 1.0);
// @end smoothie-alpha
}
