// separable_gaussian.frag — Annen et al. 2007 §4.1: "we apply a separable Gaussian filter
// kernel on the textures to hide aliasing from discretization". One 1D pass (horizontal or
// vertical, uStep) over up to 8 layers of a 2D array texture at once (multiple render
// targets); the weights are the binomial coefficients, the discrete Gaussian. Borders clamp.
#version 330 core
uniform sampler2DArray uSource;
uniform int uFirstLayer;     // first source layer of this pass
uniform int uLayerCount;     // how many of the 8 outputs are attached
uniform int uTaps;           // 3, 5 or 7
uniform float uWeights[7];   // binomial weights, sum 1
uniform ivec2 uStep;         // (1, 0) horizontal, (0, 1) vertical
layout(location = 0) out vec4 oLayers[8];

void main() {
  ivec2 size = textureSize(uSource, 0).xy;
  ivec2 center = ivec2(gl_FragCoord.xy);
  int radius = uTaps / 2;
  for (int i = 0; i < 8; ++i) {
    if (i >= uLayerCount) break;
    vec4 sum = vec4(0.0);
    for (int t = 0; t < uTaps; ++t) {
      ivec2 p = clamp(center + (t - radius) * uStep, ivec2(0), size - 1);
      sum += uWeights[t] * texelFetch(uSource, ivec3(p, uFirstLayer + i), 0);
    }
    oLayers[i] = sum;
  }
}
