// smoothie.vert — Chan 2004 §4.2 step 3 / §4.3 passes 2-3: smoothie edges and corners arrive
// already built in the light's clip space (the CPU extends each silhouette edge by t in light
// screen space at the edge's own depth), with the root point and outward normal in shadow-map
// pixels for the alpha of Figures 4-4 and 4-6.
#version 330 core
layout(location = 0) in vec4 aClip;      // light clip space
layout(location = 1) in vec2 aRoot;      // silhouette vertex (or a point on the edge), pixels
layout(location = 2) in vec2 aNormal;    // edge: outward unit normal in light screen space
layout(location = 3) in float aKind;     // 0 = smoothie edge, 1 = smoothie corner
flat out vec2 vRoot;
flat out vec2 vNormal;
flat out int vKind;
out float vLinearDepth;                  // b: distance of the smoothie along the light axis
void main() {
  // @pass smoothie-vertex: smoothie edges and corners from the light, with their root and outward normal (Chan 2004 §4.2 step 3, Fig. 4-2)
  vRoot = aRoot;
  vNormal = aNormal;
  vKind = int(aKind + 0.5);
  vLinearDepth = aClip.w;  // perspective projection: clip w = -z_eye
  gl_Position = aClip;
  // @end smoothie-vertex
}
