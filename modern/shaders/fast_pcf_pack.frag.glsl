// fast_pcf_pack.frag — Brabec & Seidel 2001 §4, Eq. (1) and Figure 5: the 3x3 RGBA convolution
// applied while the map is copied into the texture packs four neighbouring depth samples into
// one texel: red from the lower-left, green from the lower-middle, blue from the middle-left and
// alpha from the centre pixel of the 3x3 neighbourhood (the kernel C of Eq. 1). For 4x4
// footprints the kernel samples one of the four 2x2 regions of the 3x3 neighbourhood;
// uRegionOrigin is that region's lower-left pixel relative to the centre ((-1,-1) for Eq. 1).
// Pixels beyond the map's edge are the far plane (GL_CONSTANT_BORDER with colour 1, as the
// legacy convolution sets it).
#version 330 core
uniform sampler2D uEncodedDepth;   // the light pass, encoded depth in all four channels
uniform ivec2 uRegionOrigin;
layout(location = 0) out vec4 oPacked;

// @pass pack: Eq. (1)'s kernel as four texel fetches, R G B A = lower left, lower right, upper left, upper right (§4, Fig. 5)
// @replaces legacy.fast-pcf 2
float sampleAt(ivec2 p, int channel) {
  ivec2 size = textureSize(uEncodedDepth, 0);
  if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, size))) return 1.0;
  return texelFetch(uEncodedDepth, p, 0)[channel];
}

void main() {
  ivec2 o = ivec2(gl_FragCoord.xy) + uRegionOrigin;
  oPacked = vec4(sampleAt(o, 0), sampleAt(o + ivec2(1, 0), 1), sampleAt(o + ivec2(0, 1), 2),
                 sampleAt(o + ivec2(1, 1), 3));
}
// @end pack
