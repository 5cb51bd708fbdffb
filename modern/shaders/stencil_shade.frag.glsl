// stencil_shade.frag — Everitt & Kilgard 2002 / Chan 2004 §3.1 step 4: the final shading pass
// of stencil shadow volumes. The stencil test has already chosen the pixels (count == 0: lit;
// count != 0: in shadow), so the visibility arrives as a constant per draw.
#version 330 core
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform float uVisibility;        // 1 for the lit draw, 0 for the shadowed draw
uniform bool uReceivesShadow;
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;
#include "lighting.glsl"

// Shading: lighting.glsl (fixed-function spotlight, glspec121 §2.13.1).
void main() {
  // @pass stencil-shade: lit where the stencil count is 0, shadowed elsewhere: one draw each (Chan 2004 §2.1.2)
  float visibility = uReceivesShadow ? uVisibility : 1.0;
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
  // @end stencil-shade
}
