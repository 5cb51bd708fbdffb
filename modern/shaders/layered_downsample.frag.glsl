// layered_downsample.frag — one level of the mip chain of Annen et al. 2007 §4.1 ("we then
// build a mip-map of this texture"), for LAYERS layers of a 2D array texture at once (multiple
// render targets): each texel of level L is the mean of its 2x2 texels of level L - 1, the box
// filter glGenerateMipmap uses. The source texture's BASE_LEVEL and MAX_LEVEL are both L - 1
// while level L is drawn (no feedback loop), so lod 0 below is level L - 1. An odd size's
// last row or column is left out of the box (clamped), as a 2x2 box has to.
// LAYERS is a compile-time define (prefiltered_maps.cpp): constant output indices.
#version 330 core
#ifndef LAYERS
#define LAYERS 8
#endif
uniform sampler2DArray uSource;
uniform int uFirstLayer;  // first layer of this pass
layout(location = 0) out vec4 oLayers[LAYERS];

void main() {
  // @pass downsample: one mip level: the mean of 2x2 texels of the level above (Annen et al. 2007 §4.1 "build a mip-map"; drawn, not auto-generated: DEVIATION)
  ivec2 size = textureSize(uSource, 0).xy;
  ivec2 low = min(2 * ivec2(gl_FragCoord.xy), size - 1);
  ivec2 high = min(low + 1, size - 1);
  for (int i = 0; i < LAYERS; ++i) {
    int layer = uFirstLayer + i;
    oLayers[i] = 0.25 * (texelFetch(uSource, ivec3(low.x, low.y, layer), 0) +
                         texelFetch(uSource, ivec3(high.x, low.y, layer), 0) +
                         texelFetch(uSource, ivec3(low.x, high.y, layer), 0) +
                         texelFetch(uSource, ivec3(high.x, high.y, layer), 0));
  // @end downsample
  }
}
