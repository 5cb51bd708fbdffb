// csm_shadow.frag — Annen et al. 2007, the camera pass: "we exchange regular shadow mapping
// with our shadow reconstruction as described by Equation 13", from the filtered (blurred,
// mip-mapped, tri-linear/anisotropic) basis textures:
//
//   s_f(x) = 1/2 + sum_k  w_k (2 / c_k) [ cos(c_k d) [w*sin(c_k z)](p) - sin(c_k d) [w*cos(c_k z)](p) ]
//
// with c_k = pi (2k - 1) (Eq. 11, 13, 14), the ringing attenuation w_k = exp(-alpha (k/M)^2)
// (§3.2.1), d offset by a constant and the result scaled (§3.2.2), then clamped to [0, 1]
// (§4.1: "due to ringing, the resulting shadow value can be outside the [0, 1]-range").
//
// ORDER (M) and ENCODE_UNSIGNED (8-bit storage) are compile-time defines
// (convolution_shadow_map.cpp compiles one program per pair), so that the loop over the M/4
// layers unrolls, every layer index and weight index is a constant, and no per-pixel branch
// decodes the storage: with uniform bounds llvmpipe ran the loop per lane with masks.
#version 330 core
#ifndef ORDER
#define ORDER 16
#endif
#ifndef ENCODE_UNSIGNED
#define ENCODE_UNSIGNED 1
#endif
// CLASSIFY 1: the classification pass (convolution_shadow_map.cpp, classifyInCameraPass). No
// filtered lookups: every pixel that the tests below decide (behind the light, outside the map,
// nearer than every caster, or every depth texel under the filter footprint inside an interval
// where the clamped series is within the skip error of 1 or of 0) is shaded here, the last
// kind with the series at the depths around it (reconstructFromDepth), and its stencil set to
// 0; every other visible pixel gets stencil 1, and the reconstruction pass (CLASSIFY 0, stencil
// test EQUAL 1, depth test LEQUAL) shades it with Eq. 13 from the filtered basis.
#ifndef CLASSIFY
#define CLASSIFY 0
#endif
#if CLASSIFY
#extension GL_ARB_shader_stencil_export : require
#extension GL_ARB_texture_gather : require
#endif
#ifndef DEPTH_BOUNDS_LEVELS
#define DEPTH_BOUNDS_LEVELS 5
#endif
// The finest level built (convolution_shadow_map.cpp, firstDepthBoundsLevel): no box of at
// least the margin's width fits a finer one away from the border.
#ifndef FIRST_DEPTH_BOUNDS_LEVEL
#define FIRST_DEPTH_BOUNDS_LEVEL 1
#endif
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform sampler2DArray uBasis;   // layers 0..S-1: sin(c_k z), S..2S-1: cos(c_k z)
uniform mat4 uWorldToShadowMap;  // S * P_light * V_light
uniform mat4 uLightView;
uniform float uLightNear;
uniform float uLightFar;
uniform float uNearestCaster;    // distance along the light axis of the nearest caster
uniform float uDepthScale;       // the same scale as the stored z (light_linear_depth.frag)
const int kSinLayers = (ORDER + 3) / 4;  // S = ceil(M / 4)
// exp(-alpha (k/M)^2) (2 / c_k) for k = 1..M (§3.2.1 attenuation times Eq. 14's 2 / c_k),
// computed once per frame on the CPU instead of per pixel and term, four k per vec4; 0 beyond M.
uniform vec4 uWeights[kSinLayers];
uniform float uOffset;           // subtracted from d (§3.2.2, Fig. 3c)
uniform float uScale;            // multiplies f (§3.2.2, Fig. 3d)
uniform bool uReceivesShadow;
#if CLASSIFY
uniform sampler2D uDepthBounds;  // the dilated min/max pyramid of z (csm_depth_bounds.frag)
uniform int uDepthMapTexels;     // the depth map's side (level 0)
uniform vec2 uLitInterval;       // t = z - d: the clamped series is >= 1 - skip error on it
uniform vec2 uUmbraInterval;     // ... and <= skip error on this one (empty: lo > hi)
uniform float uFootprintScale;   // footprint radius in texels = scale * rho + margin
uniform float uFootprintMargin;  // bilinear reach (1) + blur radius
uniform sampler2D uLinearDepth;  // z(p) of pass 1 (R32F), for the decided pixels' Eq. 13
#endif
#include "lighting.glsl"
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;

const float PI = 3.14159265358979;

// Eq. 13 with the filtered basis images; d is this point's (offset) linear depth. Called in
// uniform control flow (every pixel, before any branch), so that texture()'s implicit
// derivatives, which choose the mip level and the anisotropic footprint, are defined.
// @pass reconstruct: f(d, z) ~ 1/2 + sum a_i(d) B_i(z) from the filtered basis (Eq. 13, coefficients Eq. 14)
float reconstructShadowTest(vec2 p, float d) {
  float sum = 0.5;  // "we add the constant term 1/2 separately" (§3.1)
  // cos(c_k d), sin(c_k d) for c_k = pi (2k - 1): start at c_1 d = pi d and rotate by 2 pi d
  // per k (the angle-addition formulas), two transcendental calls per pixel instead of 2M.
  // The rotation's float32 error grows by ~1e-7 per step: < 1e-5 after 64 terms.
  vec2 term = vec2(cos(PI * d), sin(PI * d));
  vec2 step = vec2(cos(2.0 * PI * d), sin(2.0 * PI * d));
  for (int layer = 0; layer < kSinLayers; ++layer) {
    vec4 sines = texture(uBasis, vec3(p, float(layer)));
    vec4 cosines = texture(uBasis, vec3(p, float(kSinLayers + layer)));
#if ENCODE_UNSIGNED  // 8-bit storage: v = 2 t - 1
    sines = 2.0 * sines - 1.0;
    cosines = 2.0 * cosines - 1.0;
#endif
    vec4 cosD, sinD;  // cos(c_k d), sin(c_k d) for this layer's four k
    for (int c = 0; c < 4; ++c) {
      cosD[c] = term.x;
      sinD[c] = term.y;
      term = vec2(term.x * step.x - term.y * step.y, term.y * step.x + term.x * step.y);
    }
    // a_(2k-1)(d) = 2/c_k cos(c_k d), a_(2k)(d) = -2/c_k sin(c_k d)  (Eq. 14), attenuated
    // (§3.2.1); the weights of k > M are 0.
    sum += dot(uWeights[layer], cosD * sines - sinD * cosines);
  }
  return sum;
// @end reconstruct
}

#if CLASSIFY
// The least and greatest z of every depth texel that the filtered lookups at p can reach:
// the box of the pixel's footprint (rho texels per pixel, from the derivatives) times
// uFootprintScale plus uFootprintMargin texels, bounded by one texel of the dilated pyramid
// (csm_depth_bounds.frag, DILATE): the finest level L <= DEPTH_BOUNDS_LEVELS - 1, and not
// finer than FIRST_DEPTH_BOUNDS_LEVEL (a coarser level bounds a box as well), whose block
// around the box's centre, with its neighbours, covers the box. Every level is read by every
// pixel, one texelFetch each at a level that is the same for all pixels: Mesa 22.3 llvmpipe's
// texelFetch with a level that differs between the lanes of a quad returned wrong texels
// (isolated pixels on lit ground classified as umbra, brabec 1024x768). A box wider than the
// coarsest level allows: no bounds (vec2(-2, 2), never decided).
// @pass csm-classify: the depth bounds under the footprint decide lit or umbra without Eq. 13 (Eq. 8; DEVIATION)
vec2 depthBoundsAround(vec2 p, float rho) {
  ivec2 size = ivec2(uDepthMapTexels);
  float radius = uFootprintScale * rho + uFootprintMargin;
  vec2 u = p * vec2(size) - 0.5;  // texel-centre coordinates
  ivec2 lo = clamp(ivec2(floor(u - radius)), ivec2(0), size - 1);
  ivec2 hi = clamp(ivec2(floor(u + radius)) + 1, ivec2(0), size - 1);
  vec2 bounds = vec2(-2.0, 2.0);
  for (int level = DEPTH_BOUNDS_LEVELS - 1; level >= FIRST_DEPTH_BOUNDS_LEVEL; --level) {
    ivec2 a = lo >> level, b = hi >> level;
    ivec2 centre = min(a + (b - a) / 2, textureSize(uDepthBounds, level) - 1);
    vec2 levelBounds = texelFetch(uDepthBounds, centre, level).rg;
    if (all(lessThanEqual(b - a, ivec2(2)))) bounds = levelBounds;  // finer levels win
  }
  return bounds;
// @end csm-classify
}

// uScale times the series of Eq. 11 with the attenuation of §3.2.1 (the reconstruction pass's
// weights) at four t at once. sin(c_k t), c_k = pi (2k - 1), by the recurrence
// sin((2k + 1) x) = 2 cos(2x) sin((2k - 1) x) - sin((2k - 3) x), x = pi t: one multiply-add
// per term instead of a rotation; a rounding error at one term reaches a later one at most
// multiplied by the number of terms between them, so the float32 error stays below M^2 eps / 2
// (1.5e-5 at M = 16, 2.5e-4 at M = 64).
vec4 scaledSeries(vec4 t) {
  vec4 current = sin(PI * t);  // sin(x), k = 1
  vec4 twoCos = 2.0 - 4.0 * current * current;  // 2 cos(2x) = 2 (1 - 2 sin^2 x)
  vec4 previous = -current;  // sin(-x), the term before k = 1
  vec4 sum = vec4(0.5);
  for (int layer = 0; layer < kSinLayers; ++layer)
    for (int c = 0; c < 4; ++c) {
      sum += uWeights[layer][c] * current;  // 0 beyond M
      vec4 next = twoCos * current - previous;
      previous = current;
      current = next;
    }
  return uScale * sum;
}

// Eq. 13 at a pixel whose footprint the depth bounds decided, without the 2M filtered lookups:
// Eq. 8 makes the filtered reconstruction the weighted mean of the series at the footprint's
// depths, f(z_i - d); here the mean over the four depth texels around p with the bilinear
// weights of the lookup (one textureGather; borders clamp to the edge), the blur's and the mip
// level's wider weights left out. Where z is the same under the whole footprint (an occluder's
// face seen straight from the light, ground that casts nothing) that is the reconstruction's
// own value; elsewhere both are means of the series over depths inside the interval that
// decided the pixel.
float reconstructFromDepth(vec2 p, float d) {
  vec2 u = p * vec2(uDepthMapTexels) - 0.5;  // texel-centre coordinates
  vec2 w = u - floor(u);
  // (i0, j1), (i1, j1), (i1, j0), (i0, j0) of the bilinear footprint (ARB_texture_gather)
  vec4 z = textureGather(uLinearDepth, p);
  vec4 f = scaledSeries(z - d);
  return mix(mix(f.w, f.z, w.x), mix(f.x, f.y, w.x), w.y);
}
const float kNeedsReconstruction = -1.0;
#endif

// @pass csm-test: d from the receiver, offset and scale of §3.2.2 (Fig. 3 c-d), clamp to [0, 1] (§4.1)
float shadowTest(vec3 world) {
  vec4 coord = uWorldToShadowMap * vec4(world, 1.0);
  vec2 p = coord.xy / coord.w;
  float distanceAlongAxis = -(uLightView * vec4(world, 1.0)).z;
  float d = clamp((distanceAlongAxis - uLightNear) / (uLightFar - uLightNear), 0.0, 1.0);
  // The lookups come first, for every pixel of the quad; the frustum tests only choose the
  // result. (An earlier version passed dFdx(p), dFdy(p) to textureGrad instead: Mesa 22.3
  // llvmpipe's anisotropic path with explicit gradients returned wrong values on a row of
  // isolated pixels, the white dots inside the tree shadows of Fig. 7 (c)-(f); its implicit-
  // derivative path, with the same footprint, does not.)
#if CLASSIFY
  // texels per pixel along the longer screen axis (uniform control flow: before any branch)
  vec2 texels = p * float(uDepthMapTexels);
  float rho = max(length(dFdx(texels)), length(dFdy(texels)));
  if (!(rho < 1e4)) rho = 1e4;  // NaN or huge: the whole map
#else
  float f = reconstructShadowTest(p, d * uDepthScale - uOffset);
#endif
  if (coord.w <= 0.0) return 0.0;  // behind the light (as modern.hw)
  if (any(lessThan(p, vec2(0.0))) || any(greaterThan(p, vec2(1.0)))) return 1.0;  // outside
  // Nearer than the nearest caster (modern::csmDepthRange): nothing is in front, so lit. Not
  // left to the series: d is near 0 there (or clamped to it), and beside texels where nothing
  // blocks (z at the far end) t = z - d + offset reaches 1, the falling edge of the periodic
  // square wave (Eq. 10), which reconstructs 1/2 or less.
  if (distanceAlongAxis < uNearestCaster) return 1.0;
#if CLASSIFY
  // Eq. 8: the filtered basis is a convex combination (blur, mip-map, tri-linear, anisotropic
  // weights are >= 0 and sum to 1) of the basis at the footprint's depths z_i, so Eq. 13 gives
  // the same combination of the series f(z_i - d) (Eq. 11, 13). If every z_i - d lies in
  // the lit interval, every term and so the clamped sum is within the skip error of 1; in the
  // umbra interval, of 0.
  // Such pixels get Eq. 13 without the 2M filtered lookups (reconstructFromDepth): the value
  // the reconstruction pass would give, ringing included, so that a decided pixel and its
  // reconstructed neighbour agree (returning exactly 1 or 0 here drew tiles around
  // every shadow, lit ground 0.008 brighter where decided).
  // DEVIATION (Annen et al. 2007, Eq. 13 from the filtered 8-bit basis): the series of the
  // depths themselves, so without the basis' 8-bit rounding (on ground that casts nothing,
  // squares at M = 16: 0.0013 from the reconstruction, a third of an 8-bit grey level), and
  // weighted by the bilinear weights only (where the depth varies across the blur's or the mip
  // level's wider footprint: within the skip error, as both are means over the interval).
  vec2 t = depthBoundsAround(p, rho) - (d * uDepthScale - uOffset);
  bool lit = t.x >= uLitInterval.x && t.y <= uLitInterval.y;
  bool umbra = t.x >= uUmbraInterval.x && t.y <= uUmbraInterval.y;
  if (!lit && !umbra) return kNeedsReconstruction;
  return clamp(reconstructFromDepth(p, d * uDepthScale - uOffset), 0.0, 1.0);  // §4.1 clamp
#else
  return clamp(uScale * f, 0.0, 1.0);  // §3.2.2 scaling, §4.1 clamp
#endif
// @end csm-test
}

void main() {
  float visibility = uReceivesShadow ? shadowTest(vWorldPosition) : 1.0;
#if CLASSIFY
  gl_FragStencilRefARB = visibility == kNeedsReconstruction ? 1 : 0;
  visibility = max(visibility, 0.0);  // overwritten by the reconstruction pass where stencil 1
#endif
  oColor = vec4(shadeSpotlight(vWorldPosition, vWorldNormal, visibility), 1.0);
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
}
