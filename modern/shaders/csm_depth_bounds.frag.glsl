// csm_depth_bounds.frag — the depth bounds that let modern.csm's classification pass skip the
// Eq. 13 reconstruction (convolution_shadow_map.cpp, computeDepthBounds): a min/max pyramid of
// the linear light depth z(p) (§4.1). Level 0 would be (z, z) and is not drawn; each texel of
// level L holds the least and the greatest z of the texels of level L - 1 that it covers (2x2, and the odd last row or
// column of a map whose size is not a power of two, so that every base texel is inside one
// texel of every level). FROM_DEPTH (1: level 1, reduced straight from the R32F depth map, whose
// z stands for level 0's (z, z)) is a define.
// DILATE 1: the dilated copy of one level: each texel the bounds of its 3x3 neighbourhood in
// that level (borders clamp), so that one texel of level L bounds every depth texel within
// 2^L of any point of its own block (csm_shadow.frag, depthBoundsAround).
#version 330 core
#ifndef FROM_DEPTH
#define FROM_DEPTH 0
#endif
#ifndef DILATE
#define DILATE 0
#endif
// FROM_DEPTH: the linear depth; else this pyramid with BASE_LEVEL = MAX_LEVEL = the level above
// (texelFetch's and textureSize's level 0 is the base level)
uniform sampler2D uSource;
layout(location = 0) out vec2 oBounds;  // (min z, max z)

void main() {
  // @pass csm-depth-bounds: min/max pyramid of z and its 3x3 dilation, for the classification (not in Annen et al. 2007)
  ivec2 target = ivec2(gl_FragCoord.xy);
#if DILATE
  ivec2 size = textureSize(uSource, 0);
  vec2 bounds = vec2(1e30, -1e30);
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      vec2 b = texelFetch(uSource, clamp(target + ivec2(x, y), ivec2(0), size - 1), 0).rg;
      bounds = vec2(min(bounds.x, b.x), max(bounds.y, b.y));
    }
  oBounds = bounds;
#else
  ivec2 sourceSize = textureSize(uSource, 0);
  ivec2 targetSize = max(sourceSize / 2, ivec2(1));
  ivec2 lo = min(2 * target, sourceSize - 1);
  ivec2 hi = min(2 * target + 1, sourceSize - 1);
  if (target.x == targetSize.x - 1) hi.x = sourceSize.x - 1;  // odd size: the last column too
  if (target.y == targetSize.y - 1) hi.y = sourceSize.y - 1;
  vec2 bounds = vec2(1e30, -1e30);
  for (int y = lo.y; y <= hi.y; ++y)
    for (int x = lo.x; x <= hi.x; ++x) {
#if FROM_DEPTH
      vec2 b = texelFetch(uSource, ivec2(x, y), 0).rr;
#else
      vec2 b = texelFetch(uSource, ivec2(x, y), 0).rg;
#endif
      bounds = vec2(min(bounds.x, b.x), max(bounds.y, b.y));
    }
  oBounds = bounds;
#endif
  // @end csm-depth-bounds
}
