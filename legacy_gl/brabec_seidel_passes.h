// legacy_gl/brabec_seidel_passes.h — the passes that Brabec & Seidel 2001 §2-§4 share
// (module-internal). Each function is one pass or one pipeline set-up of the paper; the three
// technique files (ramp_shadow_map.cpp, pcf.cpp, fast_pcf.cpp) read as sequences of them.
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/gl/gl.h"
#include "core/gl/gl_objects.h"
#include "core/scene/scene.h"
#include "core/technique/technique.h"
#include "legacy_gl/fixed_function.h"
#include "legacy_gl/projected_spotlight.h"

namespace sl::legacy::bs {

// How depth is carried in colour channels at one precision (§2, §6).
struct DepthEncoding {
  Precision precision = Precision::k8;
  int rampTexels = 256;               // 1D ramp texture width: 2^bits, or 2 (linear) at float
  bool rampNearest = true;            // NEAREST: the ramp itself quantises depth to its texels
  double channelMax = 255.0;          // M: one channel's largest value in steps (4095 at 12 bits)
  double depthStep = 1.0 / 255;       // smallest depth difference (fraction of the light's range)
  GLenum rampFormat = GL_INTENSITY8;  // INTENSITY: r = g = b = a = depth under GL_REPLACE
  GLenum mapFormat = GL_RGBA8;        // the shadow map texture
  GLenum tableFormat = GL_RGBA8;      // colour table storage (shares of M, §3 footnote 2)
};
DepthEncoding depthEncoding(Precision precision);

// `depth-bias` (in 8-bit steps, 1/255 of the light's depth range, at every precision) ->
// fraction of the range.
// DEVIATION (Brabec–Seidel §2): the paper names no bias. glPolygonOffset moves window z only,
// never texgen values, so the bias is subtracted from the camera pass's ramp coordinate
// through the texture matrix (lightEyeToRamp): a surface counts as shadowed only when it lies
// more than `bias` behind the map.
// 2 steps: 1 for the 8-bit rounding of both sides, up to half a step for the depth slope
// across half a map texel (brabec ground, 256^2..512^2 maps), and half a step of margin so that
// near-tie decisions, which different rasterisers round differently, stay rare (the parity
// suite measured 0.11 % of brabec pixels flipping between Mesa 7.8 and 22 at 1.5 steps).
// Curved surfaces near their terminator still self-shadow: the pipeline has no slope-scaled
// bias (the paper's 8-bit limitation, §6).
constexpr double kDefaultDepthBiasSteps = 2.0;
// The departures above and in brabec_seidel_passes.cpp, as the pass tables declare them
// (core/technique/pass_table.h PassSpec::deviations): the camera passes' bias; the float encoding
// (depthEncoding) of the light and camera passes; the clamp of saturateAlphaByCopy.
inline const std::string kDepthBiasDeviation =
    "DEVIATION (Brabec–Seidel §2): the paper names no bias. glPolygonOffset moves window z "
    "only, never texgen values, so the bias is subtracted from the camera pass's ramp "
    "coordinate through the texture matrix (lightEyeToRamp): a surface counts as shadowed only "
    "when it lies more than `bias` behind the map.";
inline const std::string kFloatChannelsDeviation =
    "DEVIATION (Brabec–Seidel §6): float channels did not exist in 2001; the ramp and the map "
    "use ARB_texture_float formats (osmesa only; the reference is 8-bit only).";
inline const std::string kFloatClampDeviation =
    "DEVIATION (float precision only): a float buffer keeps negative differences (lit points in "
    "front of the map) and scaled values above 1; two full-window quads blended with "
    "EXT_blend_minmax clamp alpha to [0, 1] as the fixed-point buffers of 2001 did by "
    "themselves.";
// --param depth-bias, declared once for legacy.ramp, legacy.pcf and legacy.fast-pcf.
ParamSpec depthBiasParam();
double depthBias(const RenderParams& params, const DepthEncoding& enc);

// The 1D ramp texture of Fig. 1 (texel i = i / (N - 1)), bound to GL_TEXTURE_1D.
struct RampTexture {
  Texture name = makeTexture();
};
void createRampTexture(RampTexture& ramp, const DepthEncoding& enc);

// A square RGBA shadow map texture of the encoding's format, bound to GL_TEXTURE_2D.
struct ShadowMapTexture {
  Texture name = makeTexture();
};
void allocateShadowMap(ShadowMapTexture& map, const DepthEncoding& enc, int texels);

// Which colour channels a pass writes (glColorMask).
using ChannelMask = std::array<bool, 4>;
constexpr ChannelMask kAllChannels = {true, true, true, true};
constexpr ChannelMask kAlphaOnly = {false, false, false, true};
ChannelMask onlyChannel(int c);
const char* channelName(int c);  // "red", "green", "blue", "alpha"

// §2 / §3 Fig. 3: the light pass. Casters from the light with the ramp on light eye z
// (EYE_LINEAR texgen, identity planes; the texture matrix selects z and maps it onto the
// ramp), writing only `channels`. `jitterTexels` shifts the image plane by a fraction of a
// texel (stratified sampling). `clear` clears colour to 1 (the far plane: lit) first.
void renderLightDepth(const Scene& scene, const DepthEncoding& enc, const RampTexture& ramp,
                      int texels, glm::vec2 jitterTexels, ChannelMask channels, bool clear);

// §2: the framebuffer copy of the light pass into the shadow map (glCopyTexSubImage2D).
void copyLightPassToMap(const ShadowMapTexture& map, int texels);

// §4 Eq. (1) / Fig. 5: the same copy with GL_CONVOLUTION_2D enabled and the packing kernel
// that takes its four channels from the 2x2 block whose upper-right texel is (x + ox, y + oy),
// ox, oy in {0, 1} (Eq. (1) itself is ox = oy = 0: red from the lower-left neighbour).
void copyLightPassToMapPacked(const ShadowMapTexture& map, int texels, glm::ivec2 blockOffset);

// The 3x3 RGBA kernel (rows bottom-up as glConvolutionFilter2D reads them) for a block offset.
std::array<float, 36> packingKernel(glm::ivec2 blockOffset);

// Texgen + texture matrix of the camera passes (identity EYE_LINEAR planes, so the texture
// matrix receives camera eye coordinates): camera eye -> light eye -> ramp (minus bias), and
// camera eye -> shadow-map coordinates (+ offset). The texgen is on texture unit 0 in
// `texgen`'s scope. Exposed for the texgen-matrix test.
void loadCameraToRampTexgen(const Scene& scene, const DepthEncoding& enc, double bias,
                            ScopedTexgen& texgen);
void loadProjectiveTexgen(const Scene& scene, const RenderParams& params, glm::vec2 offsetTexels,
                          ScopedTexgen& texgen);

// §2 second pass / §3 "z replicated over all four channels": the scene from the camera with
// the ramp on the light depth of every point (texture matrix camera eye -> light -> ramp),
// biased; non-receivers write 0 (nothing can be in front of them: lit).
void renderCameraDepth(const Scene& scene, const RenderParams& params, const DepthEncoding& enc,
                       const RampTexture& ramp, double bias, ChannelMask channels);

// The camera pass kept for the groups of PCF 3x3/4x4 (§3) and the phases of fast PCF 4x4 (§4):
// a window-sized texture of the encoding's map format (the window's values, exactly, at every
// precision).
// DEVIATION (Brabec–Seidel §3, §4): the paper draws the camera pass again before each
// subtraction of a footprint larger than 2x2 (each group of four samples, each 4x4 phase); we
// copy it to a texture once and restore it with one textured full-window quad (measured faster,
// docs/legacy.md).
// §3 counts "another eight passes ... to perform the subtraction" for 4x4 (the camera pass
// before each of the four subtractions, which overwrite it in place), and §4's "four shadow
// mapping phases" read alike; neither text requires the redraw.
inline const std::string kCameraPassCopyDeviation =
    "DEVIATION (Brabec–Seidel §3, §4): the paper draws the camera pass again before each "
    "subtraction of a footprint larger than 2x2 (each group of four samples, each 4x4 phase); we "
    "copy it to a texture once and restore it with one textured full-window quad (measured "
    "faster, docs/legacy.md).";
struct SavedCameraPass {
  Texture name = makeTexture();
};
void allocateSavedCameraPass(SavedCameraPass& saved, const RenderParams& params,
                             const DepthEncoding& enc);
// glCopyTexSubImage2D of the window into the saved texture.
void saveCameraPass(const SavedCameraPass& saved, const RenderParams& params);
// The saved texture drawn over the window (GL_REPLACE, NEAREST, texel centres on pixel centres;
// no depth test, the depth buffer is the camera pass's own and stays).
void restoreCameraPass(const SavedCameraPass& saved, const RenderParams& params);

// §2 third pass: the shadow map as a projective texture (texture matrix from camera eye to
// shadow-map coordinates) subtracted from the camera pass by the blending unit
// (GL_FUNC_REVERSE_SUBTRACT: framebuffer - fragment, clamped at 0). > 0 = shadowed sample.
// Points behind the light (q < 0) get a mirrored lookup, as in the paper, which does not treat
// them (Everitt's negative-projection fix is in legacy.hw); the built-in scenes have none.
void subtractProjectedMap(const Scene& scene, const RenderParams& params,
                          const ShadowMapTexture& map, glm::vec2 offsetTexels,
                          ChannelMask channels);

// For --dump-passes only: the projected map alone (no blending) into the framebuffer.
void renderProjectedMapOnly(const Scene& scene, const RenderParams& params,
                            const ShadowMapTexture& map, glm::vec2 offsetTexels);

// §2 footnote 1: the extra framebuffer copy that brings every value > 0 to 1 (alpha scale).
void saturateAlphaByCopy(const RenderParams& params, const DepthEncoding& enc);

// §3 Fig. 4: colour-table shares per channel for a group of `samples` (1..4) samples:
// channels 0..samples-1 get ceil(M / samples) except the last, which makes the sum M.
std::array<double, 4> shadowShares(const DepthEncoding& enc, int samples);
// Loads the colour table (index 0 -> 0, every other index -> the channel's share) and the
// pixel-transfer scale that maps one depth step onto index 1.
void loadShadowCountTable(const DepthEncoding& enc, int samples);
// Loads the colour matrix whose alpha row sums R + G + B + A (other rows zero).
void loadSumIntoAlphaMatrix();
// §3 Fig. 4: glCopyPixels of the window onto itself through the table and the matrix: alpha =
// the share of shadowed samples (0 .. M). Leaves the imaging state disabled.
void countShadowSamplesByCopy(const RenderParams& params, const DepthEncoding& enc, int samples);
// The window read back through the colour table only (--dump-passes "after colour table").
Image readThroughColorTable(const RenderParams& params, const DepthEncoding& enc, int samples);

// §3 "summed up using the accumulation buffer": first group GL_LOAD, the others GL_ACCUM.
void accumulateGroup(double weight, bool first);
void returnAccumulation();

// §5 "normal OpenGL lighting": direct light (diffuse + specular) scaled by 1 - alpha through
// GL_ONE_MINUS_DST_ALPHA blending, then the ambient added (Kilgard's note in Everitt), the
// spotlight's cone from `cone` (made by the caller before the timed pass: it depends on
// neither the light nor the scene).
void shadeWithShadowTerm(const Scene& scene, const RenderParams& params,
                         const SpotlightConeTexture& cone);

// Reads the window: visibility = 1 - alpha (see brabec_seidel.h).
Image readVisibilityFromAlpha(const RenderParams& params);

// --dump-passes helpers.
Image readWindowRgba(const RenderParams& params);
Image readShadowMap(const ShadowMapTexture& map, int texels);
Image channelPanels(const Image& rgba);           // R | G | B | A as grey panels side by side
Image amplified(const Image& image, float gain);  // small differences made visible
// The channels of a packed map minus a centre, as grey panels side by side: 0.5 + gain (c -
// centre), clamped; 0.5 = equal. centre: a channel index (that channel is left out), or -1 for the
// mean of the channels. Where the samples of one texel differ (the jitter of Fig. 3, the one-texel
// shift of Fig. 5), the panel is not grey.
Image channelsMinusCentre(const Image& rgba, int centre, float gain);
Image alphaOf(const Image& rgba);

// The footprint side of a technique from RenderParams::filter; throws InputError otherwise.
int footprintSide(const RenderParams& params, const std::string& technique);

}  // namespace sl::legacy::bs
