// pcss_light_depth.frag — modern.pcss pass 1 (ours, after Fernando 2005, not in shared/papers):
// the blockers' linear light depth z (distance along the light's axis), the depth in which the
// penumbra formula w_p = (d_receiver - d_blocker) w_light / d_blocker holds.
#version 330 core
in vec3 vWorldPosition;
uniform mat4 uLightView;
layout(location = 0) out vec4 oLinearDepth;
void main() {
  // @pass pcss-linear-depth: the blockers' linear light depth, distance along the light axis (ours, after Fernando 2005: PCSS step 1, the shadow map)
  float z = -(uLightView * vec4(vWorldPosition, 1.0)).z;
  oLinearDepth = vec4(z, 0.0, 0.0, 1.0);
  // @end pcss-linear-depth
}
