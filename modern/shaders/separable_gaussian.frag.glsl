// separable_gaussian.frag — Annen et al. 2007 §4.1: "we apply a separable Gaussian filter
// kernel on the textures to hide aliasing from discretization". One 1D pass (horizontal or
// vertical, uStep) over LAYERS layers of a 2D array texture at once (multiple render
// targets); the weights are the binomial coefficients, the discrete Gaussian. Borders clamp.
//
// TAPS (3, 5 or 7) and LAYERS (1..8) are compile-time defines (prefiltered_maps.cpp compiles
// one program per pair): with constant loop bounds the compiler unrolls both loops and every
// output index is a constant. With uniform bounds and oLayers[i] indexed by a loop variable,
// llvmpipe's blur cost ten times the basis pass that writes the same layers.
#version 330 core
#ifndef TAPS
#define TAPS 3
#endif
#ifndef LAYERS
#define LAYERS 8
#endif
uniform sampler2DArray uSource;
uniform int uFirstLayer;       // first source layer of this pass
uniform float uWeights[TAPS];  // binomial weights, sum 1
uniform ivec2 uStep;           // (1, 0) horizontal, (0, 1) vertical
layout(location = 0) out vec4 oLayers[LAYERS];

void main() {
  // @pass gaussian: one direction of the separable Gaussian (binomial weights) over several layers at once (Annen et al. 2007 §4.1)
  ivec2 size = textureSize(uSource, 0).xy;
  ivec2 center = ivec2(gl_FragCoord.xy);
  const int radius = TAPS / 2;
  ivec2 taps[TAPS];
  for (int t = 0; t < TAPS; ++t) taps[t] = clamp(center + (t - radius) * uStep, ivec2(0), size - 1);
  for (int i = 0; i < LAYERS; ++i) {
    vec4 sum = vec4(0.0);
    for (int t = 0; t < TAPS; ++t)
      sum += uWeights[t] * texelFetch(uSource, ivec3(taps[t], uFirstLayer + i), 0);
    oLayers[i] = sum;
  // @end gaussian
  }
}
