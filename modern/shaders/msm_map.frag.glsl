// msm_map.frag — Moment Shadow Maps (ours, after Peters & Klein 2015, not in shared/papers),
// light pass: the four moments b = (z, z^2, z^3, z^4) of the linear light depth z in [0, 1];
// filtering the map yields their means under the footprint. With uQuantize (16-bit storage) the
// moments are stored through Peters & Klein 2015's affine map q = Q b + o (uQuantization,
// uQuantizationOffset), which spreads them over [0, 1]; the map is linear in b either way, so it
// filters the same.
#version 330 core
in vec3 vWorldPosition;
uniform mat4 uLightView;
uniform float uLightNear;
uniform float uLightFar;
uniform bool uQuantize;
uniform mat4 uQuantization;
uniform vec4 uQuantizationOffset;
layout(location = 0) out vec4 oMoments;

void main() {
  // @pass msm-map: the four moments (z, z^2, z^3, z^4), optionally through the 16-bit quantisation (ours, after Peters & Klein 2015, not in shared/papers)
  float distanceAlongAxis = -(uLightView * vec4(vWorldPosition, 1.0)).z;
  float z = clamp((distanceAlongAxis - uLightNear) / (uLightFar - uLightNear), 0.0, 1.0);
  float z2 = z * z;
  vec4 b = vec4(z, z2, z2 * z, z2 * z2);
  oMoments = uQuantize ? uQuantization * b + uQuantizationOffset : b;
  // @end msm-map
}
