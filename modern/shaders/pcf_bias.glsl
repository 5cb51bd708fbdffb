// pcf_bias.glsl — the depth biases of the GPU Gems PCF family (--param bias, gems_pcf.cpp),
// included by gems_pcf.frag and bicubic_pcf.frag (their pass markers show the calls; an
// included file is not a file of the program a pass dump lists, so it carries no marker). BIAS_METHOD (a define) selects one:
//   BIAS_CONSTANT: the receiver moves towards the light by uRelativeBias of its distance (the
//     shaders' own DEVIATION), with pass 1's polygon offset: today's behaviour;
//   BIAS_RECEIVER_PLANE: ours, after Isidoro 2006 and Dou et al. 2014 — each lookup compares
//     the depth of the receiver's plane at the lookup, not at the receiver's point;
//   BIAS_NORMAL_OFFSET: ours, after Holbert 2011 — the receiver's point moves along its
//     normal before it is projected into the light.
// Both add to the constant bias (uRelativeBias), which stays the "small constant" of each.
#define BIAS_CONSTANT 0
#define BIAS_RECEIVER_PLANE 1
#define BIAS_NORMAL_OFFSET 2
uniform float uNormalOffsetTexels;    // texel footprints along the normal (bias=normal-offset)
uniform float uFootprintPerDistance;  // a texel footprint / distance to the light: 2 tan(c/2)/n
uniform bool uNormalOffsetByAngle;    // scale the offset by 1 - N.L (normal-offset-scale)

// A Jacobian of (u, v) over the window this close to singular (the receiver edge-on to the
// camera, or to the light) has no usable plane: the slope is taken as 0 there.
const float kSingularJacobian = 1e-30;  // (map units per pixel)^2
// Beyond this a slope (depth per map unit) is a near-singular solve, not a plane: taken as 0.
const float kLargestSlope = 1e30;

// Normal offset (ours, after Holbert 2011): the receiver's point moved along its normal.
// The world position moved along the surface normal (towards the side the camera sees, as
// lighting.glsl shades it) by uNormalOffsetTexels footprints of a map texel at the point's
// distance from the light, times 1 - N.L with uNormalOffsetByAngle. A zero normal moves nothing.
vec3 normalOffsetPosition(vec3 world, vec3 worldNormal) {
  if (dot(worldNormal, worldNormal) == 0.0) return world;  // no normal (degenerate triangles)
  vec3 n = normalize(worldNormal);
  if (!gl_FrontFacing) n = -n;
  vec3 toLight = uLightPosition - world;
  float toLightDistance = length(toLight);
  float footprint = toLightDistance * uFootprintPerDistance;
  float nDotL = clamp(dot(n, toLight / toLightDistance), 0.0, 1.0);
  float scale = uNormalOffsetByAngle ? 1.0 - nDotL : 1.0;
  return world + n * (uNormalOffsetTexels * footprint * scale);
}

// Receiver-plane depth bias (ours, after Isidoro 2006, Dou et al. 2014): the receiver's depth
// plane in map coordinates from screen derivatives; each lookup compares the plane's depth.
// d(depth)/d(u, v) of the receiver's plane: the window derivatives of (u, v, depth) give
// dz/dx = a du/dx + b dv/dx and dz/dy = a du/dy + b dv/dy; (a, b) solves that 2x2 system.
// Call in uniform control flow (derivatives).
vec2 receiverPlaneDepthSlope(vec3 mapCoord) {
  vec3 dx = dFdx(mapCoord);
  vec3 dy = dFdy(mapCoord);
  float det = dx.x * dy.y - dy.x * dx.y;
  if (abs(det) < kSingularJacobian) return vec2(0.0);
  vec2 slope = vec2(dy.y * dx.z - dx.y * dy.z, dx.x * dy.z - dy.x * dx.z) / det;
  return all(lessThan(abs(slope), vec2(kLargestSlope))) ? slope : vec2(0.0);  // no Inf into a compare
}

// The receiver plane's depth at a texel centre displaced by `offset` (map units) from the
// receiver's point: what that texel's single comparison takes.
float receiverPlaneDepth(float depth, vec2 slope, vec2 offset) {
  return depth + dot(slope, offset);
}
