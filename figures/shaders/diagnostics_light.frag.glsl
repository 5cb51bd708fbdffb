#version 330 core
// diagnostics_light.frag.glsl — Everitt Fig. 2: the light's view. Attachment 0 = linear
// depth, attachment 1 = N.L shading.
in vec3 vNormal;
in vec3 vWorld;
in float vLightZ;
in vec4 vShadowCoord;
uniform vec2 uDepthRange;  // near, far
uniform vec3 uLightPosition;
uniform vec3 uDiffuse;
uniform float uAmbient;
layout(location = 0) out vec4 oDepth;
layout(location = 1) out vec4 oColor;
void main() {
  float d = clamp((vLightZ - uDepthRange.x) / (uDepthRange.y - uDepthRange.x), 0.0, 1.0);
  oDepth = vec4(d, 0.0, 0.0, 1.0);
  vec3 n = normalize(vNormal);
  vec3 l = normalize(uLightPosition - vWorld);
  float lambert = abs(dot(n, l));
  oColor = vec4(uDiffuse * (uAmbient + (1.0 - uAmbient) * lambert), 1.0);
}
