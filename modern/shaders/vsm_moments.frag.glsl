// vsm_moments.frag — Variance Shadow Maps (Donnelly & Lauritzen 2006, the comparison of
// Annen et al. 2007 §2 and Fig. 9): the light pass stores the first two moments of the linear
// depth, (d, d^2), so that filtering the map (blur, mip-maps) yields the mean and the mean
// square of the depths under the filter footprint.
#version 330 core
in vec3 vWorldPosition;
uniform mat4 uLightView;
uniform float uLightNear;
uniform float uLightFar;
layout(location = 0) out vec4 oMoments;

void main() {
  // @pass moments: the first two moments (d, d^2) of the linear light depth (Donnelly & Lauritzen 2006, as Annen et al. 2007 §2 describe VSM)
  float distanceAlongAxis = -(uLightView * vec4(vWorldPosition, 1.0)).z;
  float d = clamp((distanceAlongAxis - uLightNear) / (uLightFar - uLightNear), 0.0, 1.0);
  oMoments = vec4(d, d * d, 0.0, 1.0);
  // @end moments
}
