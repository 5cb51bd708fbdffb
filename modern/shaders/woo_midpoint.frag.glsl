// woo_midpoint.frag — Woo's midpoint shadow map, pass 3 (Everitt, Rege & Cebenoyan 2001,
// "Advantages and Limitations"): the map's depth is the average of the first and second
// depth layers seen from the light. Drawn over the whole map with the depth test off.
#version 330 core
uniform sampler2D uFirstLayer;   // z1, compare mode off
uniform sampler2D uSecondLayer;  // z2 (1 where nothing lies behind z1)
void main() {
  // @pass midpoint: the map's depth = (z1 + z2) / 2 (Everitt, Advantages and Limitations, Woo [9])
  // @replaces legacy.woo 3
  ivec2 texel = ivec2(gl_FragCoord.xy);
  float z1 = texelFetch(uFirstLayer, texel, 0).r;
  float z2 = texelFetch(uSecondLayer, texel, 0).r;
  gl_FragDepth = 0.5 * (z1 + z2);
  // @end midpoint
}
