// csm_basis.frag — Annen et al. 2007 §4.1: "we evaluate the basis functions (sin(c_k z) and
// cos(c_k z), see Eq. 14) using the current z-values at each texel and store the result ...
// packed into RGBA textures", several at once with multiple render targets.
//
// Layout of the basis array (one RGBA layer per four k): layers 0 .. S-1 hold
// B_(2k-1)(z) = sin(c_k z), layers S .. 2S-1 hold B_(2k)(z) = cos(c_k z), with S = ceil(M/4),
// k = 4 * layer + channel + 1 and c_k = pi (2k - 1) (Eq. 11). Channels with k > M hold 0.
// 8-bit storage (the paper's choice, §5) encodes the bounded basis [-1, 1] as 0.5 + 0.5 v.
//
// TAPS > 1: the horizontal half of §4.1's separable Gaussian is applied here, to the basis
// evaluated at the TAPS depth texels of the row (binomial weights uWeights, borders clamp, as
// separable_gaussian.frag), so that the unblurred basis is never stored and read back; the
// vertical half follows in separable_gaussian.frag. TAPS = 1: the basis itself.
// TAPS, LAYERS (outputs of this pass) and PAIRED (1: this pass writes every layer, so the
// sine and cosine of each k share one rotation) are compile-time defines, so that every loop
// unrolls and every output index is a constant (convolution_shadow_map.cpp compiles one
// program per combination).
#version 330 core
#ifndef TAPS
#define TAPS 1
#endif
#ifndef LAYERS
#define LAYERS 8
#endif
#ifndef PAIRED
#define PAIRED 0
#endif
uniform sampler2D uLinearDepth;  // z(p), linear light-space depth (§4.1)
uniform int uOrder;              // M, the truncation order
uniform int uSinLayers;          // S = ceil(M / 4)
uniform int uFirstLayer;         // layer written by output 0 in this pass
uniform bool uEncodeUnsigned;    // 8-bit unsigned normalised storage
uniform float uWeights[TAPS];    // binomial weights, sum 1 (1 for TAPS = 1)
layout(location = 0) out vec4 oLayers[LAYERS];

const float PI = 3.14159265358979;

void main() {
  // @pass basis: B_i(z) = sin(c_k z), cos(c_k z) of Eq. 14 into MRT layers, with the horizontal Gaussian when blurring (§3.1, §4.1, Fig. 5)
  ivec2 size = textureSize(uLinearDepth, 0);
  ivec2 center = ivec2(gl_FragCoord.xy);
  const int radius = TAPS / 2;
  int firstK = 4 * (uFirstLayer < uSinLayers ? uFirstLayer : uFirstLayer - uSinLayers) + 1;
  vec4 sum[LAYERS];
  for (int i = 0; i < LAYERS; ++i) sum[i] = vec4(0.0);
  for (int t = 0; t < TAPS; ++t) {
    ivec2 texel = clamp(center + ivec2(t - radius, 0), ivec2(0), size - 1);
    float z = texelFetch(uLinearDepth, texel, 0).r;
    // sin(c_k z), cos(c_k z) for c_k = pi (2k - 1): from c_1 z = pi z, rotated by 2 pi z per
    // k (angle addition; float32 error ~1e-7 per step, far below the 8-bit step of 1/127).
    vec2 step = vec2(cos(2.0 * PI * z), sin(2.0 * PI * z));
    vec2 first = vec2(cos(PI * z), sin(PI * z));
#if PAIRED
    // This pass writes all 2S layers (S = LAYERS / 2 = uSinLayers): sin(c_k z) and cos(c_k z)
    // of the same k come from one rotation.
    vec2 pair = first;
    for (int j = 0; j < LAYERS / 2; ++j) {
      vec4 s = vec4(0.0), c = vec4(0.0);
      for (int i = 0; i < 4; ++i) {
        if (4 * j + i + 1 <= uOrder) {  // 0 beyond M
          s[i] = pair.y;
          c[i] = pair.x;
        }
        pair = vec2(pair.x * step.x - pair.y * step.y, pair.y * step.x + pair.x * step.y);
      }
      sum[j] += uWeights[t] * s;
      sum[LAYERS / 2 + j] += uWeights[t] * c;
    }
#else
    vec2 term = firstK == 1 ? first
                            : vec2(cos(PI * float(2 * firstK - 1) * z),
                                   sin(PI * float(2 * firstK - 1) * z));
    for (int i = 0; i < LAYERS; ++i) {
      int layer = uFirstLayer + i;
      bool isSine = layer < uSinLayers;
      if (layer == uSinLayers) term = first;  // the cosines start again at k = 1
      int base = 4 * (isSine ? layer : layer - uSinLayers);
      vec4 v = vec4(0.0);
      for (int c = 0; c < 4; ++c) {
        if (base + c + 1 <= uOrder) v[c] = isSine ? term.y : term.x;  // 0 beyond M
        term = vec2(term.x * step.x - term.y * step.y, term.y * step.x + term.x * step.y);
      }
      sum[i] += uWeights[t] * v;
    }
#endif
  }
  for (int i = 0; i < LAYERS; ++i) oLayers[i] = uEncodeUnsigned ? 0.5 + 0.5 * sum[i] : sum[i];
  // @end basis
}
