// smoothie_linear_depth.frag — Chan 2004 §4.3 pass 1 (Figure 4-7, "compute linear z"): the
// shadow map also stores depth linearly (distance along the light's axis), because the alpha
// remapping of Eq. 4.1 needs the ratio b/r of distances, which window depth does not give.
#version 330 core
in vec3 vWorldPosition;
uniform mat4 uLightView;
layout(location = 0) out vec4 oLinearDepth;
void main() {
  // @pass blocker-linear-depth: the blockers' linear light depth, for the ratio b / r of the smoothie alpha (Chan 2004 §4.2 step 1, §4.2.1)
  float z = -(uLightView * vec4(vWorldPosition, 1.0)).z;
  oLinearDepth = vec4(z, 0.0, 0.0, 1.0);
  // @end blocker-linear-depth
}
