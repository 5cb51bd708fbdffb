// fullscreen_triangle.vert — one triangle covering the viewport, from gl_VertexID alone
// (drawn by FullScreenTriangle with an empty VAO). Used by the image passes of the
// prefiltered shadow maps (Annen et al. 2007 §4.1: "each pass renders a screen-aligned quad").
#version 330 core
void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));  // (0,0) (2,0) (0,2)
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
