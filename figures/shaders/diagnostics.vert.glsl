#version 330 core
// diagnostics.vert.glsl — the figures' light and eye probes (Everitt Figs. 2, 4, 6): world
// position, normal, linear light depth and the shadow-map coordinate.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
uniform mat4 uModel;
uniform mat4 uViewProjection;
uniform mat4 uLightView;
uniform mat4 uLightClip;  // bias * projection * view of the light
out vec3 vNormal;
out vec3 vWorld;
out float vLightZ;        // distance along the light's axis (positive)
out vec4 vShadowCoord;
void main() {
  vec4 world = uModel * vec4(aPosition, 1.0);
  vWorld = world.xyz;
  vNormal = mat3(transpose(inverse(uModel))) * aNormal;
  vLightZ = -(uLightView * world).z;
  vShadowCoord = uLightClip * world;
  gl_Position = uViewProjection * world;
}
