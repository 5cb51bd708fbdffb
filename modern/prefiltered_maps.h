// modern/prefiltered_maps.h — what Convolution Shadow Maps (Annen et al. 2007) and Variance
// Shadow Maps (Donnelly & Lauritzen 2006) share: a shadow map that is an ordinary filterable
// texture, so that it can be blurred with a separable Gaussian (Annen §4.1) and mip-mapped
// with tri-linear and anisotropic filtering (Annen §4, Table 1). Module-internal header.
//
// The maps are 2D array textures: one layer per RGBA basis texture (CSM) or one RG layer
// (VSM), so that any truncation order M needs one sampler only.
#pragma once

#include <string>
#include <vector>

#include "core/technique/technique.h"
#include "modern/gl_objects.h"
#include "modern/hardware_shadow_map.h"

namespace sl::modern {

// Linear light-space depth (Annen §4.1 "we use linear depth values [BAS03]"):
// d = (distance along the light's view axis - near) / (far - near), in [0, 1] over the fitted
// light frustum. Sets uLightView, uLightNear, uLightFar on `program`.
void setLinearDepthUniforms(const Program& program, const Scene& scene);
// The same with an explicit range (CSM's fitted range, fitShadowingDepthRange).
void setLinearDepthUniforms(const Program& program, const Scene& scene, const DepthRange& range);

// The light depth range fitted to what can shadow and be shadowed (Annen Fig. 6: "when using a
// tightly fitted light frustum a single 8-bit RGBA texture usually faithfully reconstructs the
// shadow test"): near at the nearest caster triangle inside the light frustum, far at the
// farthest receiver triangle inside the casters' cone (the cone from the light through the
// casters' outermost vertex; a receiver outside it has no caster in front of it and is lit
// whatever its depth). Margins of 2% of the span, as lightDepthRange. The scene's range when
// no caster reaches the frustum. `nearestCaster` (optional) receives the nearest caster's
// distance along the light axis without the margin (the range's near plane when none).
DepthRange fitShadowingDepthRange(const Scene& scene, float* nearestCaster = nullptr);

// The separable blur of Annen §4.1: n x n binomial weights (the discrete Gaussian), n in
// {3, 5, 7}; blur = 0 or 1 (a 1x1 kernel) means none, returned as 0. Parsed from
// --param blur=0|1|3|5|7 (InputError otherwise).
// --param blur with the technique's default (csm and vsm: 3).
ParamSpec blurParam(int defaultTaps);
int parseBlurTaps(const RenderParams& params, const ParamSpec& blur);
std::vector<float> binomialWeights(int taps);  // sums to 1

// How the map is sampled in the camera pass.
struct MapFiltering {
  bool mipmaps = true;      // trilinear (GL_LINEAR_MIPMAP_LINEAR) when true
  bool linear = true;       // bilinear magnification/minification within a level
  float anisotropy = 1.0f;  // GL_TEXTURE_MAX_ANISOTROPY (1 = off)
};
// --param filtering=trilinear (default)|anisotropic|bilinear|nearest (anisotropic = tri-linear with
// --param anisotropy, default 16, Table 1; trilinear = anisotropy 1 unless given), clamped
// to what the context offers; 1 when GL_EXT_texture_filter_anisotropic is absent.
MapFiltering parseFiltering(const GlContext& context, const RenderParams& params);
// --param filtering and --param anisotropy, as parseFiltering reads them.
ParamSpec filteringParam();
ParamSpec anisotropyParam();

// A square 2D array texture with `layers` layers of `format`, and a full mip chain when
// `mipmapped`.
struct LayeredMap {
  Texture texture;
  int size = 0;
  int layers = 0;
  GLenum format = GL_RGBA8;
  int levels = 1;
};
LayeredMap makeLayeredMap(int size, int layers, GLenum format, bool mipmapped);

// `slot` reallocated with makeLayeredMap unless it already has this size, layer count, format
// and mip chain; returns it.
const LayeredMap& reuseLayeredMap(LayeredMap& slot, int size, int layers, GLenum format,
                                  bool mipmapped);

// GL objects a prefiltered technique keeps in its context from one frame to the next: the
// light-depth target, the layered map, the blur's scratch map and a framebuffer. Allocating
// them every frame (8 layers of 512^2 for M = 16, and as many again for the blur) cost as
// much as using them on llvmpipe. Owned by the context (GlContext::setLayerState), one per
// `key`; the context deletes the GL names with itself.
struct PrefilterWorkspace {
  RenderTarget depth;
  LayeredMap map;
  LayeredMap scratch;
  Framebuffer fbo;
  // modern.csm's min/max pyramid of the light depth (RG32F, full chain) for the classification
  // that skips Eq. 13 where the series is decided (convolution_shadow_map.cpp).
  Texture depthBounds;
  Texture depthBoundsDilated;  // each level's 3x3 neighbourhood bounds
  int depthBoundsSize = 0;
  int depthBoundsLevels = 0;
  // modern.csm's skip intervals (csmSkipIntervals: lit lo, hi, umbra lo, hi) and the settings
  // they were computed for (M, alpha, offset, scale, skip error): a grid of the series, kept.
  std::vector<double> skipKey;
  std::vector<double> skipIntervals;
  // CPU work that depends on the scene and the view only (the fitted depth range, the
  // planner's minification estimate): kept with the key it was computed for.
  std::vector<double> sceneKey;
  DepthRange fittedRange;
  float nearestCaster = 0.0f;
  double texelsPerPixel = 0.0;
  PrefilterWorkspace() = default;
  PrefilterWorkspace(const PrefilterWorkspace&) = delete;
  PrefilterWorkspace& operator=(const PrefilterWorkspace&) = delete;
  ~PrefilterWorkspace();  // gives the names up: the context is gone when this runs
};
PrefilterWorkspace& prefilterWorkspace(GlContext& context, const std::string& key);

// Every number the fitted range and the minification estimate depend on: camera, light,
// window and map size, and each object's mesh (address and size), transform and flags.
std::vector<double> sceneViewKey(const Scene& scene, const RenderParams& params);

// How many colour attachments one pass may write (GL_MAX_DRAW_BUFFERS, at most 8: the
// shaders declare 8 outputs).
int layersPerPass();

// Binds `fbo` with layers [first, first + count) of mip level `level` of `map` as colour
// attachments 0..count-1, sets the draw buffers and the viewport (that level's size).
void attachLayers(const Framebuffer& fbo, const LayeredMap& map, int first, int count,
                  int level = 0);

// Annen §4.1: separable Gaussian blur of every layer (horizontal into a scratch map, then
// vertical back), `taps` in {3, 5, 7}; encoded 8-bit values blur correctly because the
// encoding is affine.
// (The technique's pass function runs it as its pass: core/technique/passes.h.)
void blurLayers(const LayeredMap& map, int taps);
// The same with a caller-kept scratch map (reallocated by reuseLayeredMap when it does not fit).
void blurLayers(const LayeredMap& map, LayeredMap& scratch, int taps);
// One 1D pass of that blur over every layer: `source` -> `target` (same size and layer count),
// horizontal or vertical, drawn with `fbo`.
enum class BlurDirection { kHorizontal, kVertical };
void blurLayersOneDirection(const LayeredMap& source, const LayeredMap& target, int taps,
                            BlurDirection direction, const Framebuffer& fbo);

// Annen §4.1: "we then build a mip-map ... (auto-mip-map)" and set the sampling state. The
// chain is drawn with MRT, several layers per draw (layered_downsample.frag, a 2x2 box).
void buildMipmapsAndSetFiltering(const LayeredMap& map, const MapFiltering& filtering);
// Its departure from Annen §4.1 (the chain drawn, not auto-generated), for the pass tables of
// the passes that run it (modern.csm pass 4, modern.vsm pass 3; core/technique/pass_table.h).
extern const char* const kDrawnMipChainDeviation;

// worldToShadowMap (S * P_light * V_light, Everitt Eq. 5) lives in modern/hardware_shadow_map.h.

// One layer of a layered map as a 4-channel float image (for --dump-passes), each value
// mapped to value * scale + bias and clamped to [0, 1]; `level` is the mip level read
// (its size is the map's halved `level` times, at least 1).
Image readLayer(const LayeredMap& map, int layer, float scale, float bias, int level = 0);

}  // namespace sl::modern
