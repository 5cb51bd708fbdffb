#version 330 core
// diagnostics_eye.frag.glsl — Everitt Figs. 4 and 6: R = own linear light depth, G = map
// value at the projection (-1 outside), B = shadow-map texels per eye pixel, A = 1.
in vec3 vNormal;
in vec3 vWorld;
in float vLightZ;
in vec4 vShadowCoord;
uniform vec2 uDepthRange;
uniform float uTexels;
uniform sampler2D uLinearDepth;
out vec4 oProbe;
void main() {
  float d = clamp((vLightZ - uDepthRange.x) / (uDepthRange.y - uDepthRange.x), 0.0, 1.0);
  vec2 uv = vShadowCoord.xy / vShadowCoord.w;
  vec2 t = uv * uTexels;
  float texelsPerPixel = max(length(dFdx(t)), length(dFdy(t)));
  bool inside = vShadowCoord.w > 0.0 && all(greaterThanEqual(uv, vec2(0.0))) &&
                all(lessThanEqual(uv, vec2(1.0)));
  float mapValue = inside ? texture(uLinearDepth, uv).r : -1.0;
  oProbe = vec4(d, mapValue, inside ? texelsPerPixel : -1.0, 1.0);
}
