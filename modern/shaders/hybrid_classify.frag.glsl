// hybrid_classify.frag — Chan 2004 §3.1 step 2 and Figure 3-3: find the shadow silhouette
// pixels. The hardware 2x2 compare (sampler2DShadow with GL_LINEAR) returns the fraction of the
// four nearest shadow-map samples that are lit; a value strictly between 0 and 1 on a surface
// that faces the light means the four comparisons disagree: a silhouette pixel. Every other
// pixel is final here: lit or shadowed by the shadow map (back faces always in shadow); a
// silhouette pixel is written shadowed until the stencil count says otherwise.
//
// CONSERVATIVE defined (modern.hybrid, classify=conservative, the default): the classifier sends
// every pixel the map is unsure of to the volumes (see the DEVIATION comments below and
// docs/volumes.md, "What decides each pixel").
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
uniform bool uCastsShadow;        // the object has a shadow volume (classify=conservative)
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;
// r: 1 = silhouette pixel (Figure 3-1b, green); g: 1 = shadowed as back-facing to the light;
// b: the centre 2x2 compare (what decided the other pixels). g and b: for the classification of
// the hybrid's differences from the volumes (tests/modern/hybrid_agreement.h).
layout(location = 2) out vec4 oSilhouette;
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
#ifdef CONSERVATIVE
  // DEVIATION (Chan 2004 §3.1 step 2, "pixels that are back-facing with respect to the light
  // are always in shadow"): back-facing is judged by the triangle's plane, as the volumes'
  // light-facing caps judge it, not by the interpolated normal, and only on objects that have a
  // volume (a receiver that casts nothing has none around its far side). Measured at 400x300
  // (tests/modern/hybrid_agreement_test.cpp, docs/volumes.md): with the interpolated normal,
  // triangles still facing the light were forced into shadow where the volumes and the point
  // truth see them lit — 1,373 of the 2,835 pixels Chan's classifier decided otherwise than the
  // volumes over the 16 scenes (bunny 348, trees 367). Lighting still uses the interpolated
  // normal, so the colour there is unchanged (its diffuse term is 0).
  vec3 faceNormal = cross(dFdx(vWorldPosition), dFdy(vWorldPosition));
  if (dot(faceNormal, uEyePosition - vWorldPosition) < 0.0) faceNormal = -faceNormal;
  bool backFacing = uCastsShadow && dot(faceNormal, uLightPosition - vWorldPosition) <= 0.0;
  // DEVIATION (Chan 2004 §3.3.1: an affected pixel's depth "usually lies between the depth
  // values of two adjacent samples"; "usually" is not always): the pixel is unsure, and goes to
  // the volumes, when any of the 4x4 samples around it — the 2x2 compares one texel off
  // diagonally, together covering the 16 nearest texels — disagrees with the centre's. Measured
  // at 400x300: the four nearest samples agreed, wrongly, where the polygon offset hid a
  // contact shadow (1,397 pixels over the 16 scenes; bunny 384, dragon 316) or a shadow edge
  // passed between them (29: trees 25, cubes 4); with the 4x4 test 14 and 1 are left.
  // The four extra compares only where the centre's is already 0 or 1 (ours: the same answer,
  // less sampling).
  bool unsure = v > 0.0 && v < 1.0;
  if (coord.w > 0.0 && !unsure) {
    float vx0 = textureProjOffset(uShadowMap, coord, ivec2(-1, -1));
    float vx1 = textureProjOffset(uShadowMap, coord, ivec2(1, -1));
    float vx2 = textureProjOffset(uShadowMap, coord, ivec2(-1, 1));
    float vx3 = textureProjOffset(uShadowMap, coord, ivec2(1, 1));
    float lo = min(min(min(vx0, vx1), min(vx2, vx3)), v);
    float hi = max(max(max(vx0, vx1), max(vx2, vx3)), v);
    unsure = lo < hi;
  }
  bool lightFacing = !backFacing;
#else
  bool unsure = v > 0.0 && v < 1.0;
  bool backFacing = diffuse <= 0.0;
  bool lightFacing = diffuse > 0.0;
#endif
  bool silhouette = uReceivesShadow && unsure && lightFacing;
  // Non-silhouette pixels: v is exactly 0 or 1 on light-facing surfaces; "pixels that are
  // back-facing with respect to the light are always in shadow" (§3.1 step 2).
  // Silhouette pixels are shaded as shadowed here; step 4 (§3.1: "draw and shade the scene
  // only at pixels with stencil values equal to zero") redraws the lit ones.
  float visibility = !uReceivesShadow ? 1.0 : (lightFacing && !silhouette ? v : 0.0);
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
  oSilhouette = vec4(silhouette ? 1.0 : 0.0, uReceivesShadow && backFacing ? 1.0 : 0.0, v, 1.0);
#ifdef MASK_BIT
  gl_FragStencilRefARB = silhouette ? MASK_BIT : 0;
#endif
  // @end classify
}
