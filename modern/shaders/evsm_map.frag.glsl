// evsm_map.frag — Exponential Variance Shadow Maps (ours, after Lauritzen & McCool 2008, not in
// shared/papers), light pass: the linear light depth z in [0, 1] is mapped to x = 2 z - 1 in
// [-1, 1] and warped by a positive exponential p = exp(c+ x) and (EVSM4) a negative one
// n = -exp(-c- x); the map stores the moments (p, p^2, n, n^2), so that filtering yields the
// means and mean squares of both warped depths. Both warps increase with z, so the shadow test
// keeps its direction in either. The exponents are clamped on the CPU so that exp(2 c) stays
// within the storage format.
#version 330 core
in vec3 vWorldPosition;
uniform mat4 uLightView;
uniform float uLightNear;
uniform float uLightFar;
uniform float uPositiveExponent;  // c+
uniform float uNegativeExponent;  // c- (0 in EVSM2: n = -1, n^2 = 1, unused)
layout(location = 0) out vec4 oMoments;

void main() {
  // @pass evsm-map: the warps p = exp(c+ x), n = -exp(-c- x) of x = 2 z - 1 and their squares (ours, after Lauritzen & McCool 2008, not in shared/papers)
  float distanceAlongAxis = -(uLightView * vec4(vWorldPosition, 1.0)).z;
  float z = clamp((distanceAlongAxis - uLightNear) / (uLightFar - uLightNear), 0.0, 1.0);
  float x = 2.0 * z - 1.0;
  float p = exp(uPositiveExponent * x);
  float n = -exp(-uNegativeExponent * x);
  oMoments = vec4(p, p * p, n, n * n);
  // @end evsm-map
}
