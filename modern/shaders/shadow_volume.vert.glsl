// shadow_volume.vert — Everitt & Kilgard 2002, "Practical and Robust Stenciled Shadow Volumes":
// one vertex shader for the scene's surfaces AND for their shadow volumes (Chan 2004 §3.1 step 3
// uses the same z-fail set-up). The light-facing front cap must rasterise at exactly the depth
// of the surface it was copied from, which Everitt–Kilgard obtain with ARB_position_invariant;
// here both are drawn by this shader with `invariant gl_Position`.
//
// aPosition.w = 1: a surface point (scene meshes feed 3 components, GL supplies w = 1);
// aPosition.w = 0: a point at infinity, extruded away from the light (direction p - light).
#version 330 core
layout(location = 0) in vec4 aPosition;
layout(location = 1) in vec3 aNormal;
uniform mat4 uModel;
uniform mat4 uViewProjection;  // camera projection with its far plane at infinity
out vec3 vWorldPosition;
out vec3 vWorldNormal;
invariant gl_Position;
void main() {
  // @pass volume-vertex: volume and cap vertices to an infinite far plane (w = 0 extrudes to infinity; Chan 2004 §2.1.2)
  vec4 world = uModel * aPosition;
  vWorldPosition = world.xyz;
  vWorldNormal = mat3(transpose(inverse(uModel))) * aNormal;
  gl_Position = uViewProjection * world;
  // @end volume-vertex
}
