#version 330 core
// diagnostics_light_density.frag.glsl — Everitt Fig. 6 right: for each pixel of the light's
// view, where the eye sees its surface point and how densely the eye samples the map there.
// Attachment 0: R, G = the eye's window coordinates of the point, B = its linear light depth,
// A = shadow-map texels per eye pixel (the eye probe's measure, max over the eye's two axes;
// -1 outside the eye's frustum). Attachment 1: R = how much the linear light depth changes
// across one eye pixel there (|d depth / d x_eye| + |d depth / d y_eye|).
in vec3 vNormal;
in vec3 vWorld;
in float vLightZ;
in vec4 vShadowCoord;
uniform vec2 uDepthRange;  // near, far
uniform mat4 uEyeViewProjection;
uniform vec2 uEyeSize;     // the eye image in pixels
uniform float uTexels;     // the shadow map's side
layout(location = 0) out vec4 oEye;
layout(location = 1) out vec4 oSlope;
void main() {
  float d = clamp((vLightZ - uDepthRange.x) / (uDepthRange.y - uDepthRange.x), 0.0, 1.0);
  vec4 clip = uEyeViewProjection * vec4(vWorld, 1.0);
  bool inside = clip.w > 0.0 && all(lessThanEqual(abs(clip.xyz), vec3(clip.w)));
  vec2 eye = (clip.xy / clip.w * 0.5 + 0.5) * uEyeSize;
  vec2 texel = vShadowCoord.xy / vShadowCoord.w * uTexels;
  // Chain rule through the light's pixels: d texel / d eye = (d texel / d light) (d eye /
  // d light)^-1, and the same for the depth.
  mat2 eyePerLight = mat2(dFdx(eye), dFdy(eye));
  mat2 texelsPerLight = mat2(dFdx(texel), dFdy(texel));
  float det = determinant(eyePerLight);
  float texelsPerPixel = -1.0;
  float slope = 0.0;
  if (inside && abs(det) > 0.0) {
    mat2 lightPerEye = inverse(eyePerLight);
    mat2 texelsPerEye = texelsPerLight * lightPerEye;
    texelsPerPixel = max(length(texelsPerEye[0]), length(texelsPerEye[1]));
    vec2 depthPerEye = vec2(dFdx(d), dFdy(d)) * lightPerEye;
    slope = abs(depthPerEye.x) + abs(depthPerEye.y);
  }
  oEye = vec4(eye, d, texelsPerPixel);
  oSlope = vec4(slope, 0.0, 0.0, 1.0);
}
