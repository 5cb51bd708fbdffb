// woo_peel.frag — Woo's midpoint shadow map, pass 2 (Everitt, Rege & Cebenoyan 2001,
// "Advantages and Limitations", with depth peeling): a caster fragment survives only when it
// lies behind the first depth layer z1, so the depth test keeps the second layer z2.
// Twin of legacy_gl/woo_shadow_map.cpp peelSecondDepthLayer (ARB_shadow GEQUAL + alpha test).
#version 330 core
in vec3 vWorldPosition;
uniform sampler2DShadow uFirstLayer;  // compare mode GEQUAL, GL_NEAREST
uniform mat4 uWorldToShadowMap;       // S · P_light · L^-1 (Everitt Eq. 5)
uniform float uPeelEpsilon;           // window-depth tolerance of the peel
void main() {
  // @pass peel: keep only caster fragments behind the first layer z1 (Everitt, Woo [9] by depth peeling [2])
  // @replaces legacy.woo 2
  vec4 coord = uWorldToShadowMap * vec4(vWorldPosition, 1.0);
  coord.z -= uPeelEpsilon * coord.w;  // legacy: the texture matrix translates r
  if (textureProj(uFirstLayer, coord) <= 0.5) discard;  // legacy: alpha test GREATER 0.5
  // @end peel
}
