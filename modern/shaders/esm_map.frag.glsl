// esm_map.frag — Exponential Shadow Maps (ours, after Annen, Mertens, Seidel, Flerackers &
// Kautz 2008, not in shared/papers), light pass: the map stores exp(c * z) of the linear light
// depth z in [0, 1], so that filtering the map (blur, mip-maps) yields E[exp(c * z)] under the
// filter footprint. c is bounded on the CPU so that exp(c) stays finite in the storage format.
#version 330 core
in vec3 vWorldPosition;
uniform mat4 uLightView;
uniform float uLightNear;
uniform float uLightFar;
uniform float uExponent;  // c
layout(location = 0) out vec4 oWarped;

void main() {
  // @pass esm-map: exp(c z) of the linear light depth z (ours, after Annen et al. 2008, not in shared/papers)
  float distanceAlongAxis = -(uLightView * vec4(vWorldPosition, 1.0)).z;
  float z = clamp((distanceAlongAxis - uLightNear) / (uLightFar - uLightNear), 0.0, 1.0);
  oWarped = vec4(exp(uExponent * z), 0.0, 0.0, 1.0);
  // @end esm-map
}
