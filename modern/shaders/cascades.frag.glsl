// cascades.frag — modern.cascades pass 3, the camera pass: parallel-split shadow maps, ours,
// after Zhang et al. 2006 (not in shared/papers). Each pixel takes the split its view depth falls
// in (the first whose far distance is not nearer), and compares in that split's map as modern.hw
// does (sampler2DShadow, GL_LINEAR = 2x2 PCF). A point outside its split's crop (a crop drawn in
// to the scene's bounds) reads the next split that holds it.
#version 330 core
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform sampler2DShadow uMap0;  // one map per split; GLSL 3.30 indexes samplers by constants
uniform sampler2DShadow uMap1;
uniform sampler2DShadow uMap2;
uniform sampler2DShadow uMap3;
uniform mat4 uWorldToCascade[4];  // S * crop_i * P_light * V_light
uniform float uSplitFar[4];       // far view depth of each split
uniform int uCascadeCount;
uniform mat4 uCameraView;
uniform bool uReceivesShadow;
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;
layout(location = 2) out vec4 oCascade;  // the split used, as colour (--dump-passes)
#include "lighting.glsl"

// The debug colours are tinted by the shaded colour: kTintFloor of the colour always, the rest
// scaled by the shading, so that the scene stays readable under them.
const float kTintFloor = 0.35;
const vec3 kCascadeColours[4] =
    vec3[4](vec3(1.0, 0.25, 0.25), vec3(0.25, 1.0, 0.25), vec3(0.3, 0.45, 1.0), vec3(1.0, 1.0, 0.2));

// @pass cascade-select: the split of the pixel's view depth, or a farther one whose crop holds the point (ours, after Zhang et al. 2006)
int selectCascade(vec3 world, out vec4 coord) {
  float viewDepth = -(uCameraView * vec4(world, 1.0)).z;
  int first = uCascadeCount - 1;
  for (int i = uCascadeCount - 1; i >= 0; --i)
    if (viewDepth <= uSplitFar[i]) first = i;
  for (int i = first; i < uCascadeCount; ++i) {
    coord = uWorldToCascade[i] * vec4(world, 1.0);
    vec2 uv = coord.xy / coord.w;
    if (coord.w > 0.0 && all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0))))
      return i;
  }
  coord = uWorldToCascade[uCascadeCount - 1] * vec4(world, 1.0);
  return uCascadeCount - 1;  // outside every crop: the last map's border (lit), as modern.hw
}
// @end cascade-select

// @pass cascade-shadow-test: r/q <= depth(s/q, t/q) in the chosen split's map by sampler2DShadow, GL_LINEAR = 2x2 PCF; behind the light = shadow (Everitt, How It Works, Fig. 5)
float shadowTest(int cascade, vec4 coord) {
  if (coord.w <= 0.0) return 0.0;
  vec3 c = coord.xyz / coord.w;
  if (cascade == 0) return textureLod(uMap0, c, 0.0);
  if (cascade == 1) return textureLod(uMap1, c, 0.0);
  if (cascade == 2) return textureLod(uMap2, c, 0.0);
  return textureLod(uMap3, c, 0.0);
}
// @end cascade-shadow-test

void main() {
  vec4 coord;
  int cascade = selectCascade(vWorldPosition, coord);
  float visibility = uReceivesShadow ? shadowTest(cascade, coord) : 1.0;
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
  oCascade = vec4(kCascadeColours[cascade] * (kTintFloor + (1.0 - kTintFloor) * oColor.rgb), 1.0);
}
