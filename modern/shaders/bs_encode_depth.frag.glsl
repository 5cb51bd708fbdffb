// bs_encode_depth.frag — Brabec & Seidel 2001 §2, Figure 1 (after Heidrich 1999): the light
// pass maps each fragment's depth in light space to a colour. Fixed function did it with
// texture-coordinate generation (s = the depth plane · position) and a 1D linear ramp texture;
// 'faithful' arithmetic looks the same ramp texture up (so the colour is quantised exactly as
// the ramp texel and the 8- or 12-bit colour buffer quantise it), 'float' writes s itself.
// The channels written are chosen with glColorMask, as in §3 (one channel per jittered pass)
// and §4 (all four channels).
#version 330 core
in vec3 vWorldPosition;
uniform vec4 uRampPlane;   // world position -> ramp coordinate s (light depth over [near, far])
uniform sampler1D uRamp;   // the linear ramp, 2^bits texels, GL_NEAREST
uniform bool uFaithful;
layout(location = 0) out vec4 oColor;
void main() {
  float s = dot(uRampPlane, vec4(vWorldPosition, 1.0));
  float encoded = uFaithful ? texture(uRamp, s).r : s;
  oColor = vec4(encoded);
}
