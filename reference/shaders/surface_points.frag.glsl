#version 330 core
// surface_points.frag.glsl — attachment 0: world position + (object index + 1);
// 1: shading normal; 2: geometric normal (from dFdx/dFdy). Both face the camera.
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform float uObjectId;
layout(location = 0) out vec4 oPosition;
layout(location = 1) out vec4 oShadingNormal;
layout(location = 2) out vec4 oGeometricNormal;
void main() {
  // @pass surface-points: each pixel's world position, shading and geometric normals for the rays (ours: the reference's GL rasterisation)
  vec3 n = normalize(vWorldNormal);
  if (!gl_FrontFacing) n = -n;
  vec3 g = cross(dFdx(vWorldPosition), dFdy(vWorldPosition));
  float len = length(g);
  g = len > 0.0 ? g / len : n;
  if (dot(g, n) < 0.0) g = -g;
  oPosition = vec4(vWorldPosition, uObjectId);
  oShadingNormal = vec4(n, 1.0);
  oGeometricNormal = vec4(g, 1.0);
  // @end surface-points
}
