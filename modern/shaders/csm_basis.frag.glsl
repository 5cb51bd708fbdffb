// csm_basis.frag — Annen et al. 2007 §4.1: "we evaluate the basis functions (sin(c_k z) and
// cos(c_k z), see Eq. 14) using the current z-values at each texel and store the result ...
// packed into RGBA textures", several at once with multiple render targets.
//
// Layout of the basis array (one RGBA layer per four k): layers 0 .. S-1 hold
// B_(2k-1)(z) = sin(c_k z), layers S .. 2S-1 hold B_(2k)(z) = cos(c_k z), with S = ceil(M/4),
// k = 4 * layer + channel + 1 and c_k = pi (2k - 1) (Eq. 11). Channels with k > M hold 0.
// 8-bit storage (the paper's choice, §5) encodes the bounded basis [-1, 1] as 0.5 + 0.5 v.
#version 330 core
uniform sampler2D uLinearDepth;  // z(p), linear light-space depth (§4.1)
uniform int uOrder;              // M, the truncation order
uniform int uSinLayers;          // S = ceil(M / 4)
uniform int uFirstLayer;         // layer written by output 0 in this pass
uniform int uLayerCount;         // outputs attached in this pass
uniform bool uEncodeUnsigned;    // 8-bit unsigned normalised storage
layout(location = 0) out vec4 oLayers[8];

const float PI = 3.14159265358979;

vec4 basisLayer(int layer, float z) {
  bool isSine = layer < uSinLayers;
  int base = 4 * (isSine ? layer : layer - uSinLayers);
  vec4 v = vec4(0.0);
  for (int c = 0; c < 4; ++c) {
    int k = base + c + 1;
    if (k > uOrder) break;
    float ck = PI * float(2 * k - 1);  // c_k (Eq. 11)
    v[c] = isSine ? sin(ck * z) : cos(ck * z);
  }
  return uEncodeUnsigned ? 0.5 + 0.5 * v : v;
}

void main() {
  float z = texelFetch(uLinearDepth, ivec2(gl_FragCoord.xy), 0).r;
  for (int i = 0; i < 8; ++i) {
    if (i >= uLayerCount) break;
    oLayers[i] = basisLayer(uFirstLayer + i, z);
  }
}
