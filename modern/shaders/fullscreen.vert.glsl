// fullscreen.vert — one triangle covering the viewport, from gl_VertexID alone (image passes
// of every modern technique: packing, combining, midpoints).
#version 330 core
out vec2 vTexCoord;
void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  vTexCoord = corner;
  gl_Position = vec4(2.0 * corner - 1.0, 0.0, 1.0);
}
