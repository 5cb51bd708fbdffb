// light_linear_depth.frag — Annen et al. 2007 §4.1, first step: "rendering the depth values
// from the light's point of view", stored as LINEAR depth "to increase the sampling
// precision [BAS03]": d = (distance along the light axis - near) / (far - near), then scaled
// by uDepthScale (CSM keeps z - d + offset inside one period of the square wave, Eq. 10).
#version 330 core
in vec3 vWorldPosition;
uniform mat4 uLightView;
uniform float uLightNear;
uniform float uLightFar;
uniform float uDepthScale;
layout(location = 0) out vec4 oDepth;

void main() {
  // @pass linear-depth: linear light depth d in [0, 1], scaled (Annen et al. 2007 §4.1 "we use linear depth values")
  float distanceAlongAxis = -(uLightView * vec4(vWorldPosition, 1.0)).z;
  float d = clamp((distanceAlongAxis - uLightNear) / (uLightFar - uLightNear), 0.0, 1.0);
  oDepth = vec4(d * uDepthScale, 0.0, 0.0, 1.0);
  // @end linear-depth
}
