// hybrid_classify.frag — Chan 2004 §3.1 step 2 and Figure 3-3: find the shadow silhouette
// pixels. The hardware 2x2 compare (sampler2DShadow with GL_LINEAR) returns the fraction of the
// four nearest shadow-map samples that are lit; a value strictly between 0 and 1 on a surface
// that faces the light means the four comparisons disagree: a silhouette pixel. Every other
// pixel is final here: lit or shadowed by the shadow map (back faces always in shadow); a
// silhouette pixel is written shadowed until the stencil count says otherwise.
#version 330 core
// MASK_BIT defined (modern.hybrid, mask-pass=classify): this pass also writes the computation
// mask of §3.2 as the stencil reference of the visible fragment (GL_ARB_shader_stencil_export).
#ifdef MASK_BIT
#extension GL_ARB_shader_stencil_export : require
#endif
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform sampler2DShadow uShadowMap;
uniform mat4 uWorldToShadowMap;   // S · P_light · V_light
uniform bool uReceivesShadow;
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;
layout(location = 2) out vec4 oSilhouette;  // 1 = silhouette pixel (Figure 3-1b, green)
#include "lighting.glsl"

void main() {
  // @pass classify: silhouette pixel = the hardware 2x2 compare is neither 0 nor 1 (Chan 2004 §3.1 step 2, Fig. 3-3)
  vec3 n = normalize(vWorldNormal);
  vec3 toLight = normalize(uLightPosition - vWorldPosition);
  if (!gl_FrontFacing) n = -n;
  float diffuse = max(dot(n, toLight), 0.0);
  vec4 coord = uWorldToShadowMap * vec4(vWorldPosition, 1.0);
  // Figure 3-3: use the hardware's 2x2 filter, 0 <= v <= 1 (behind the light: shadowed).
  float v = coord.w > 0.0 ? textureProj(uShadowMap, coord) : 0.0;
  bool silhouette = uReceivesShadow && v > 0.0 && v < 1.0 && diffuse > 0.0;
  // Non-silhouette pixels: v is exactly 0 or 1 on light-facing surfaces; "pixels that are
  // back-facing with respect to the light are always in shadow" (§3.1 step 2).
  // Silhouette pixels are shaded as shadowed here; step 4 (§3.1: "draw and shade the scene
  // only at pixels with stencil values equal to zero") redraws the lit ones.
  float visibility = !uReceivesShadow ? 1.0 : (diffuse > 0.0 && !silhouette ? v : 0.0);
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
  oSilhouette = vec4(silhouette ? 1.0 : 0.0, 0.0, 0.0, 1.0);
#ifdef MASK_BIT
  gl_FragStencilRefARB = silhouette ? MASK_BIT : 0;
#endif
  // @end classify
}
