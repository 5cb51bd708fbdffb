// bs_encode_depth.frag — Brabec & Seidel 2001 §2, Figure 1 (after Heidrich 1999): the light
// pass maps each fragment's depth in light space to a colour. Fixed function did it with
// texture-coordinate generation and a 1D linear ramp texture: d = (-z_eye - near) / (far - near)
// placed on the ramp's texel centres, s = (0.5 + (N - 1) d) / N. 'faithful' arithmetic looks the
// same ramp texture (N = 2^bits texels, GL_NEAREST) up, so the colour is quantised exactly as
// the ramp texel and the 8- or 12-bit colour buffer quantise it; 'float' writes d itself.
// The channels written are chosen with glColorMask, as in §3 (one channel per jittered pass)
// and §4 (all four channels).
#version 330 core
in vec3 vWorldPosition;
in vec4 vRampCoord;          // texgen.vert: (s, ., ., q), s = (0.5 + (N - 1) d) / N
uniform vec4 uDepthPlane;    // world position -> d (light depth over [near, far])
uniform sampler1D uRamp;     // the linear ramp, texel k = k / (N - 1), GL_NEAREST
uniform bool uFaithful;
layout(location = 0) out vec4 oColor;
void main() {
  // @pass encode-depth: light depth through the ramp, as colour in every channel (§2 Fig. 1, §4)
  // @replaces legacy.fast-pcf 1
  // @replaces legacy.pcf 1
  // @replaces legacy.ramp 1
  float d = dot(uDepthPlane, vec4(vWorldPosition, 1.0));
  float encoded = uFaithful ? textureProj(uRamp, vRampCoord).r : d;
  oColor = vec4(encoded);
  // @end encode-depth
}
