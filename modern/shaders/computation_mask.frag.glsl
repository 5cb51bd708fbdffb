// computation_mask.frag — Chan 2004 §3.2: set up the computation mask from the silhouette
// tags of the classification pass.
//   uMode 0 (EXT_depth_bounds_test, Chan's own set-up): "a pixel shader sets the depth values
//     of all non-silhouette pixels to z = 0; depth values of silhouette pixels are unmodified"
//     (silhouette fragments are discarded, so their depth stays).
//   uMode 1 (no depth bounds test, e.g. llvmpipe): only silhouette fragments survive; the
//     stencil test replaces the mask bit there, to be tested by every later pass.
#version 330 core
uniform sampler2D uSilhouette;
uniform int uMode;
void main() {
  // @pass computation-mask: depth 0 at non-silhouette pixels so later passes are rejected early (Chan 2004 §3.2, §3.4.2 computation masks)
  bool silhouette = texelFetch(uSilhouette, ivec2(gl_FragCoord.xy), 0).r > 0.5;
  if (uMode == 0) {
    if (silhouette) discard;
    gl_FragDepth = 0.0;
  } else {
    if (!silhouette) discard;
    gl_FragDepth = gl_FragCoord.z;
  // @end computation-mask
  }
}
