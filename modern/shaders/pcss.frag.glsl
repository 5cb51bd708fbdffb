// pcss.frag — modern.pcss pass 2, the camera pass: percentage-closer soft shadows, ours, after
// Fernando 2005 (not in shared/papers). Three steps per pixel, in linear light depth z (distance
// along the light's axis, pass 1):
//   (a) findBlockers:   the blocker search over the region of the map through which the light
//                       (radius uLightRadius, world) is seen from the receiver, down to the
//                       nearest depth in the scene (uLightNear); the average depth of the texels
//                       in front of the receiver;
//   (b) penumbraWidth:  w_p = (d_receiver - d_blocker) * w_light / d_blocker, w_light = 2 radius;
//   (c) filterPenumbra: percentage-closer filtering over a region of width w_p at the receiver.
// Each tap compares the texel's depth with the receiver's plane at the texel's centre
// (DEVIATION, pcss.cpp says why), less a bias of uBiasTexels texel footprints.
#version 330 core
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform sampler2D uLightDepth;   // pass 1: linear light depth, kNoSurfaceDepth where no caster
uniform mat4 uWorldToShadowMap;  // S * P_light * V_light (as modern.hw); w = linear light depth
uniform float uTanHalfCone;      // tan(cone / 2): the map spans 2 z tan(cone / 2) at depth z
uniform float uLightNear;        // the light's fitted near plane: no blocker is nearer
uniform float uLightRadius;      // world units (SpotLight::radius, as reference.soft)
uniform float uBiasTexels;       // texel footprints along the light axis
uniform float uMaxRadius;        // largest search / filter radius, map units (side = 1)
uniform float uMaxSlope;         // largest receiver slope dz / d(lateral world distance)
uniform int uSearchCount;
uniform vec2 uSearchTaps[64];  // unit region (pcss.cpp pcssTaps)
uniform int uFilterCount;
uniform vec2 uFilterTaps[64];
uniform bool uReceivesShadow;
#include "lighting.glsl"
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;

const float kNoBlocker = -1.0;

// The receiver as the taps see it: map position, linear depth, the depth's gradient over the
// map (its plane) and the depth bias.
struct Receiver {
  vec2 uv;
  float z;
  vec2 dzduv;
  float bias;
};

// Whether the texel under map position `uv` holds a blocker of `r`, and its depth.
bool blockerAt(Receiver r, vec2 uv, out float depth) {
  ivec2 size = textureSize(uLightDepth, 0);
  ivec2 t = ivec2(floor(uv * vec2(size)));
  if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, size))) return false;  // no caster
  depth = texelFetch(uLightDepth, t, 0).r;
  // DEVIATION (ours, after Fernando 2005, not in shared/papers): the tap compares the texel's
  // depth with the receiver's plane at the texel's centre (pcss.cpp says why).
  vec2 centre = (vec2(t) + 0.5) / vec2(size);
  float receiver = r.z + dot(r.dzduv, centre - r.uv) - r.bias;
  return depth < receiver;
}

// @pass pcss-blocker-search: (a) the average depth of the blockers inside the light's region seen from the receiver (ours, after Fernando 2005: PCSS blocker search)
float findBlockers(Receiver r) {
  // The cone from the receiver to the light disk (radius R) is R (z_r - z) / z_r wide at depth
  // z, and the map spans 2 z tan(cone / 2) there: widest at the nearest depth, uLightNear.
  // DEVIATION (ours, after Fernando 2005, not in shared/papers): the search reaches down to the
  // light's fitted near plane and is clamped to uMaxRadius (pcss.cpp says why).
  float radius = uLightRadius * (r.z - uLightNear) / (r.z * 2.0 * uLightNear * uTanHalfCone);
  radius = clamp(radius, 0.0, uMaxRadius);
  float sum = 0.0;
  int count = 0;
  for (int i = 0; i < uSearchCount; ++i) {
    float depth;
    if (blockerAt(r, r.uv + uSearchTaps[i] * radius, depth)) {
      sum += depth;
      ++count;
    }
  }
  return count == 0 ? kNoBlocker : sum / float(count);
}
// @end pcss-blocker-search

// @pass pcss-penumbra: (b) the penumbra width w_p = (d_receiver - d_blocker) w_light / d_blocker, in world units at the receiver (ours, after Fernando 2005: PCSS penumbra estimate)
float penumbraWidth(float receiverDepth, float blockerDepth) {
  float lightWidth = 2.0 * uLightRadius;
  return max(receiverDepth - blockerDepth, 0.0) * lightWidth / blockerDepth;
}
// @end pcss-penumbra

// @pass pcss-filter: (c) percentage-closer filtering over a region of width w_p at the receiver (ours, after Fernando 2005: PCSS filtering; PCF after Reeves et al. 1987)
float filterPenumbra(Receiver r, float penumbra) {
  // Half the width, in map units at the receiver's depth.
  float radius = clamp(0.5 * penumbra / (2.0 * r.z * uTanHalfCone), 0.0, uMaxRadius);
  float lit = 0.0;
  for (int i = 0; i < uFilterCount; ++i) {
    float depth;
    if (!blockerAt(r, r.uv + uFilterTaps[i] * radius, depth)) lit += 1.0;
  }
  return lit / float(uFilterCount);
}
// @end pcss-filter

void main() {
  vec4 coord = uWorldToShadowMap * vec4(vWorldPosition, 1.0);
  Receiver r;
  r.z = coord.w;
  r.uv = coord.xy / max(coord.w, 1e-30);
  // The receiver's plane: the depth's gradient over the map from the screen derivatives (taken
  // here, in uniform control flow), solving [duv/dx; duv/dy] g = (dz/dx, dz/dy).
  vec2 duvdx = dFdx(r.uv), duvdy = dFdy(r.uv);
  float dzdx = dFdx(r.z), dzdy = dFdy(r.z);
  float det = duvdx.x * duvdy.y - duvdx.y * duvdy.x;
  vec2 g = vec2(0.0);
  if (abs(det) > 1e-20) g = vec2(duvdy.y * dzdx - duvdx.y * dzdy, duvdx.x * dzdy - duvdy.x * dzdx) / det;
  // A slope beyond uMaxSlope (grazing light) is clamped: lateral world distance = map distance
  // times 2 z tan(cone / 2).
  float most = uMaxSlope * 2.0 * r.z * uTanHalfCone;
  float len = length(g);
  if (!(len <= most)) g = len > 0.0 && len < 1e30 ? g * (most / len) : vec2(0.0);
  r.dzduv = g;
  vec2 size = vec2(textureSize(uLightDepth, 0));
  r.bias = uBiasTexels * r.z * 2.0 * uTanHalfCone / size.x;

  float visibility = 1.0;
  if (uReceivesShadow) {
    if (coord.w <= 0.0) {
      visibility = 0.0;  // behind the light (as modern.hw)
    } else {
      float blocker = findBlockers(r);
      if (blocker != kNoBlocker) visibility = filterPenumbra(r, penumbraWidth(r.z, blocker));
    }
  }
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
}
