// computation_mask.vert — a full-screen triangle from gl_VertexID (no vertex buffer), for the
// computation-mask pass of Chan 2004 §3.2.
#version 330 core
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
}
