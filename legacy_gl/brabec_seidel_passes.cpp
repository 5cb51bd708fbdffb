// legacy_gl/brabec_seidel_passes.cpp — the steps Brabec & Seidel 2001 §2-§5 share, in the
// paper's order: depth as colour (§2, Fig. 1; the precisions of §6), the light pass (§2; Fig. 3's
// jitter; §4's packing convolution), the camera pass (§2, §3) and its saved copy, the
// projective subtraction (§2) and footnote 1's saturation, the count through the colour table
// and the colour matrix (§3, Fig. 4), the accumulation (§3, §4), the lighting (§5); then the
// --dump-passes read-backs. The technique files (ramp_shadow_map.cpp, pcf.cpp, fast_pcf.cpp)
// run them as their passes.
// Only OpenGL 1.x calls (+ EXT_blend_subtract / ARB_imaging), so the same code runs on the
// reference Mesa 7.8.2 (native imaging) and on Debian's OSMesa (imaging/ emulation).
#include "legacy_gl/brabec_seidel_passes.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/base/errors.h"
#include "core/gl/gl_objects.h"
#include "legacy_gl/brabec_seidel.h"
#include "legacy_gl/projected_spotlight.h"

namespace sl::legacy::bs {
using namespace sl::gl;

namespace {

constexpr int kRampTexels8 = 256;    // 2^8 ramp texels: depth quantised to 8 bits
constexpr int kRampTexels12 = 4096;  // 2^12: the Octane VPro's 12-bit channels (§6)
constexpr int kRampTexelsFloat = 2;  // two texels 0 and 1, LINEAR: d itself, in float
// At float precision no quantisation step exists; this is the step the colour-table threshold
// and the depth bias are expressed in (2^-20 of the light's depth range).
constexpr double kFloatDepthStep = 1.0 / 1048576.0;
// M at float precision: the colour table's shares are counted in 16-bit steps (its format).
constexpr double kChannelMax16 = 65535.0;
// The unit of `depth-bias` at every precision: one 8-bit step of the light's depth range, so
// that 8-bit, 12-bit and float frames with the same bias differ only by quantisation.
constexpr double kBiasStep = 1.0 / 255.0;  // fraction of the light's depth range
// The colour table of Fig. 4: 256 entries (GL_MAX_COLOR_TABLE_WIDTH of the reference is 256).
constexpr int kShadowTableWidth = 256;
constexpr int kShadowTableLastIndex = kShadowTableWidth - 1;
constexpr float kFarDepth[4] = {1.0f, 1.0f, 1.0f, 1.0f};  // map border and clear value: lit

void setChannelMask(ChannelMask c) { glColorMask(c[0], c[1], c[2], c[3]); }

// Texgen s, t, r, q = x, y, z, w of eye coordinates (§2: "use eye ... coordinates as texture
// coordinates"): identity EYE_LINEAR planes, given while the modelview is the identity.
// On texture unit 0, in `texgen`'s scope (off again when it ends).
void enableEyeCoordinateTexgen(ScopedTexgen& texgen) {
  glMatrixMode(GL_MODELVIEW);
  const ScopedPushMatrix eyeSpace;
  glLoadIdentity();
  const GLenum coords[4] = {GL_S, GL_T, GL_R, GL_Q};
  const GLenum enables[4] = {GL_TEXTURE_GEN_S, GL_TEXTURE_GEN_T, GL_TEXTURE_GEN_R,
                             GL_TEXTURE_GEN_Q};
  for (int i = 0; i < 4; ++i) {
    float plane[4] = {0, 0, 0, 0};
    plane[i] = 1.0f;
    glTexGeni(coords[i], GL_TEXTURE_GEN_MODE, GL_EYE_LINEAR);
    glTexGenfv(coords[i], GL_EYE_PLANE, plane);
    texgen.enable(enables[i]);
  }
}

// The texture matrix back to the identity once a texgen scope has ended.
void resetTextureMatrix() {
  loadMatrix(GL_TEXTURE, glm::mat4(1.0f));
  glMatrixMode(GL_MODELVIEW);
}

// Texgen off and the texture matrix reset, whatever the previous pass left (the state reset of
// a pixel-copy pass).
void disableTexgen() {
  glDisable(GL_TEXTURE_GEN_S);
  glDisable(GL_TEXTURE_GEN_T);
  glDisable(GL_TEXTURE_GEN_R);
  glDisable(GL_TEXTURE_GEN_Q);
  resetTextureMatrix();
}

// Pixel rectangles (glCopyPixels) in window coordinates: raster position (0, 0), and every
// fragment operation that would alter the copied values off.
void prepareWindowCopy(const RenderParams& params) {
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_TEXTURE_1D);
  glDisable(GL_TEXTURE_2D);
  glDisable(GL_BLEND);
  glDisable(GL_LIGHTING);
  disableTexgen();
  glViewport(0, 0, params.width, params.height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0, params.width, 0, params.height, -1, 1);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glRasterPos2i(0, 0);
  setChannelMask(kAllChannels);
}

void setPixelTransferScale(double scale) {
  glPixelTransferf(GL_RED_SCALE, float(scale));
  glPixelTransferf(GL_GREEN_SCALE, float(scale));
  glPixelTransferf(GL_BLUE_SCALE, float(scale));
  glPixelTransferf(GL_ALPHA_SCALE, float(scale));
}

// One depth step onto colour-table index 1: c * scale * (N - 1) = 1 for c = depthStep.
double shadowTableScale(const DepthEncoding& enc) {
  return 1.0 / (enc.depthStep * kShadowTableLastIndex);
}

}  // namespace

// ---- Depth as colour (§2, Fig. 1; the precisions of §6): encoding, bias, ramp, map

DepthEncoding depthEncoding(Precision precision) {
  DepthEncoding e;
  e.precision = precision;
  switch (precision) {
    case Precision::k8: break;  // the defaults are the paper's 8-bit channels
    case Precision::k12:
      e.rampTexels = kRampTexels12;
      e.channelMax = double(kRampTexels12 - 1);
      e.depthStep = 1.0 / e.channelMax;
      e.rampFormat = GL_INTENSITY16;
      e.mapFormat = GL_RGBA16;
      e.tableFormat = GL_RGBA16;
      break;
    case Precision::kFloat:
      // DEVIATION (Brabec–Seidel §6): float channels did not exist in 2001; the ramp and the
      // map use ARB_texture_float formats (osmesa only; the reference is 8-bit only).
      e.rampTexels = kRampTexelsFloat;
      e.rampNearest = false;
      e.channelMax = kChannelMax16;
      e.depthStep = kFloatDepthStep;
      e.rampFormat = GL_INTENSITY32F_ARB;
      e.mapFormat = GL_RGBA32F;
      e.tableFormat = GL_RGBA16;
      break;
  }
  return e;
}

ParamSpec depthBiasParam() {
  constexpr double kMaxBiasSteps = 255.0;  // the whole depth range
  return numberParam("depth-bias", kDefaultDepthBiasSteps, 0.0, kMaxBiasSteps,
                     "depth bias in 8-bit depth steps, added before the comparison (§2)");
}

double depthBias(const RenderParams& params, const DepthEncoding& enc) {
  (void)enc;
  const double steps = params.number(depthBiasParam());
  return steps * kBiasStep;
}

void createRampTexture(RampTexture& ramp, const DepthEncoding& enc) {
  std::vector<float> texels(size_t(enc.rampTexels));
  for (int i = 0; i < enc.rampTexels; ++i) texels[size_t(i)] = float(i) / float(enc.rampTexels - 1);
  glBindTexture(GL_TEXTURE_1D, ramp.name.id());
  glTexImage1D(GL_TEXTURE_1D, 0, GLint(enc.rampFormat), enc.rampTexels, 0, GL_LUMINANCE, GL_FLOAT,
               texels.data());
  const GLint filter = enc.rampNearest ? GL_NEAREST : GL_LINEAR;
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, filter);
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  checkGl("create 1D ramp texture");
}

void allocateShadowMap(ShadowMapTexture& map, const DepthEncoding& enc, int texels) {
  glBindTexture(GL_TEXTURE_2D, map.name.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GLint(enc.mapFormat), texels, texels, 0, GL_RGBA, GL_UNSIGNED_BYTE,
               nullptr);
  // NEAREST: one stored depth per lookup, the comparison happens after (Reeves' order, §3).
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  // Outside the map: the far plane, so nothing there is shadowed.
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
  glTexParameterfv(GL_TEXTURE_2D, GL_TEXTURE_BORDER_COLOR, kFarDepth);
  checkGl("allocate shadow map texture");
}

// ---- The light pass (§2; Fig. 3's jitter into one channel) and the copy into the map (§4
// Eq. (1): packed)

ChannelMask onlyChannel(int c) {
  ChannelMask m = {false, false, false, false};
  m[size_t(c)] = true;
  return m;
}

const char* channelName(int c) {
  static const char* const kNames[4] = {"red", "green", "blue", "alpha"};
  return kNames[c & 3];
}

void renderLightDepth(const Scene& scene, const DepthEncoding& enc, const RampTexture& ramp,
                      int texels, glm::vec2 jitterTexels, ChannelMask channels, bool clear) {
  // Shifting normalised device x by 2 j / N moves the image by j texels (Fig. 3 jitter).
  const glm::mat4 jitter =
      glm::translate(glm::mat4(1.0f), glm::vec3(2.0f * jitterTexels / float(texels), 0.0f));
  glViewport(0, 0, texels, texels);
  setChannelMask(kAllChannels);
  glClearColor(kFarDepth[0], kFarDepth[1], kFarDepth[2], kFarDepth[3]);
  glClear(clear ? GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT : GL_DEPTH_BUFFER_BIT);
  disableLighting();
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  loadMatrix(GL_PROJECTION, jitter * lightProjection(scene));
  {
    ScopedTexgen texgen(GL_TEXTURE0);
    enableEyeCoordinateTexgen(texgen);
    loadMatrix(GL_TEXTURE, lightEyeToRamp(scene, enc.rampTexels, 0.0));
    loadMatrix(GL_MODELVIEW, lightView(scene.light));
    const ScopedEnable rampTexture(GL_TEXTURE_1D);
    glBindTexture(GL_TEXTURE_1D, ramp.name.id());
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
    setChannelMask(channels);
    drawScene(scene, Draw::kCasters, Colors::kWhite);
    setChannelMask(kAllChannels);
  }
  resetTextureMatrix();
}

void copyLightPassToMap(const ShadowMapTexture& map, int texels) {
  glBindTexture(GL_TEXTURE_2D, map.name.id());
  glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, texels, texels);
}

std::array<float, 36> packingKernel(glm::ivec2 blockOffset) {
  // Filter element (m, n) (m along x, n along y, row n = 0 first, i.e. the bottom row) reads
  // the source pixel (x + m - 1, y + n - 1) (CONSTANT border: centred, glspec121 §3.6.3).
  std::array<float, 36> k{};
  auto set = [&](int m, int n, int channel) { k[size_t((n * 3 + m) * 4 + channel)] = 1.0f; };
  const int ox = blockOffset.x, oy = blockOffset.y;
  set(ox, oy, 0);          // red:   lower left of the 2x2 block
  set(ox + 1, oy, 1);      // green: lower right ("lower mid" in Eq. (1))
  set(ox, oy + 1, 2);      // blue:  upper left  ("mid left")
  set(ox + 1, oy + 1, 3);  // alpha: upper right (the centre in Eq. (1))
  return k;
}

void copyLightPassToMapPacked(const ShadowMapTexture& map, int texels, glm::ivec2 blockOffset) {
  const std::array<float, 36> kernel = packingKernel(blockOffset);
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, kernel.data());
  // Neighbours outside the light image are the far plane (lit), as the map's border.
  glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, GL_CONSTANT_BORDER);
  glConvolutionParameterfv(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_COLOR, kFarDepth);
  const ScopedEnable convolution(GL_CONVOLUTION_2D);
  copyLightPassToMap(map, texels);
}

// ---- The camera pass (§2; §3: replicated over the channels) and its saved copy (ours)

void loadCameraToRampTexgen(const Scene& scene, const DepthEncoding& enc, double bias,
                            ScopedTexgen& texgen) {
  enableEyeCoordinateTexgen(texgen);
  const glm::mat4 cameraToLight = lightView(scene.light) * glm::inverse(cameraView(scene.camera));
  loadMatrix(GL_TEXTURE, lightEyeToRamp(scene, enc.rampTexels, bias) * cameraToLight);
  glMatrixMode(GL_MODELVIEW);
}

void loadProjectiveTexgen(const Scene& scene, const RenderParams& params, glm::vec2 offsetTexels,
                          ScopedTexgen& texgen) {
  enableEyeCoordinateTexgen(texgen);
  loadMatrix(GL_TEXTURE, cameraEyeToShadowMap(scene, params.shadowMapTexels, offsetTexels));
  glMatrixMode(GL_MODELVIEW);
}

void renderCameraDepth(const Scene& scene, const RenderParams& params, const DepthEncoding& enc,
                       const RampTexture& ramp, double bias, ChannelMask channels) {
  setCameraMatrices(scene, params.width, params.height);
  setChannelMask(kAllChannels);
  glClearColor(0, 0, 0, 0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  disableLighting();
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  setChannelMask(channels);
  // Objects that receive no shadow encode depth 0: nothing in the map lies in front of them.
  drawScene(scene, Draw::kNonReceivers, Colors::kBlack);
  // §2: "an additional 4x4 texture matrix ... transforms points from camera to light source
  // space", then onto the ramp.
  {
    ScopedTexgen texgen(GL_TEXTURE0);
    loadCameraToRampTexgen(scene, enc, bias, texgen);
    const ScopedEnable rampTexture(GL_TEXTURE_1D);
    glBindTexture(GL_TEXTURE_1D, ramp.name.id());
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
    drawScene(scene, Draw::kReceivers, Colors::kWhite);
  }
  resetTextureMatrix();
  setChannelMask(kAllChannels);
}

void allocateSavedCameraPass(SavedCameraPass& saved, const RenderParams& params,
                             const DepthEncoding& enc) {
  glBindTexture(GL_TEXTURE_2D, saved.name.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GLint(enc.mapFormat), params.width, params.height, 0, GL_RGBA,
               GL_UNSIGNED_BYTE, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, 0);
  checkGl("allocate saved camera pass");
}

void saveCameraPass(const SavedCameraPass& saved, const RenderParams& params) {
  glBindTexture(GL_TEXTURE_2D, saved.name.id());
  glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, params.width, params.height);
  glBindTexture(GL_TEXTURE_2D, 0);
}

void restoreCameraPass(const SavedCameraPass& saved, const RenderParams& params) {
  prepareWindowCopy(params);
  const float w = float(params.width), h = float(params.height);
  {
    const ScopedEnable savedTexture(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, saved.name.id());
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
    glBegin(GL_QUADS);
    glTexCoord2f(0.0f, 0.0f);
    glVertex2f(0.0f, 0.0f);
    glTexCoord2f(1.0f, 0.0f);
    glVertex2f(w, 0.0f);
    glTexCoord2f(1.0f, 1.0f);
    glVertex2f(w, h);
    glTexCoord2f(0.0f, 1.0f);
    glVertex2f(0.0f, h);
    glEnd();
    glBindTexture(GL_TEXTURE_2D, 0);
  }
  glEnable(GL_DEPTH_TEST);
}

// ---- The projective subtraction (§2) and footnote 1's saturation

namespace {
void drawProjectedMap(const Scene& scene, const RenderParams& params, const ShadowMapTexture& map,
                      glm::vec2 offsetTexels) {
  {
    ScopedTexgen texgen(GL_TEXTURE0);
    loadProjectiveTexgen(scene, params, offsetTexels, texgen);
    const ScopedEnable mapTexture(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, map.name.id());
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
    drawScene(scene, Draw::kReceivers, Colors::kWhite);
  }
  resetTextureMatrix();
}
}  // namespace

void subtractProjectedMap(const Scene& scene, const RenderParams& params,
                          const ShadowMapTexture& map, glm::vec2 offsetTexels,
                          ChannelMask channels) {
  setCameraMatrices(scene, params.width, params.height);
  disableLighting();
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);  // the camera pass's own surfaces (same transforms: invariant)
  glDepthMask(GL_FALSE);
  {
    const ScopedEnable blend(GL_BLEND);
    glBlendEquation(GL_FUNC_REVERSE_SUBTRACT);  // framebuffer - fragment (EXT_blend_subtract)
    glBlendFunc(GL_ONE, GL_ONE);
    setChannelMask(channels);
    drawProjectedMap(scene, params, map, offsetTexels);
    setChannelMask(kAllChannels);
    glBlendEquation(GL_FUNC_ADD);
  }
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
}

void renderProjectedMapOnly(const Scene& scene, const RenderParams& params,
                            const ShadowMapTexture& map, glm::vec2 offsetTexels) {
  setCameraMatrices(scene, params.width, params.height);
  setChannelMask(kAllChannels);
  glClearColor(0, 0, 0, 0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  disableLighting();
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  drawScene(scene, Draw::kNonReceivers, Colors::kBlack);
  drawProjectedMap(scene, params, map, offsetTexels);
}

void saturateAlphaByCopy(const RenderParams& params, const DepthEncoding& enc) {
  prepareWindowCopy(params);
  // Any alpha of at least one depth step becomes >= 1, clamped to 1 (glspec121 §3.6.3).
  glPixelTransferf(GL_ALPHA_SCALE, float(1.0 / enc.depthStep));
  setChannelMask(kAlphaOnly);
  glCopyPixels(0, 0, params.width, params.height, GL_COLOR);
  glPixelTransferf(GL_ALPHA_SCALE, 1.0f);
  if (enc.precision == Precision::kFloat) {
    // DEVIATION (float precision only): a float buffer keeps negative differences (lit points
    // in front of the map) and scaled values above 1; two full-window quads blended with
    // EXT_blend_minmax clamp alpha to [0, 1] as the fixed-point buffers of 2001 did by
    // themselves.
    const float corners[4][2] = {{0, 0},
                                 {float(params.width), 0},
                                 {float(params.width), float(params.height)},
                                 {0, float(params.height)}};
    const ScopedEnable blend(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    for (const GLenum op : {GLenum(GL_MAX), GLenum(GL_MIN)}) {
      glBlendEquation(op);
      const float bound = op == GL_MAX ? 0.0f : 1.0f;
      glColor4f(bound, bound, bound, bound);
      glBegin(GL_QUADS);
      for (const auto& c : corners) glVertex2f(c[0], c[1]);
      glEnd();
    }
    glBlendEquation(GL_FUNC_ADD);
  }
  setChannelMask(kAllChannels);
  glEnable(GL_DEPTH_TEST);
}

// ---- The count (§3, Fig. 4): colour table 0 / share, colour matrix sums into alpha

std::array<double, 4> shadowShares(const DepthEncoding& enc, int samples) {
  std::array<double, 4> shares = {0, 0, 0, 0};
  const double m = enc.channelMax;
  const double each = std::ceil(m / samples);
  for (int c = 0; c < samples; ++c) shares[size_t(c)] = each;
  shares[size_t(samples - 1)] = m - each * (samples - 1);  // footnote 2: the sum is exactly M
  return shares;
}

void loadShadowCountTable(const DepthEncoding& enc, int samples) {
  const std::array<double, 4> shares = shadowShares(enc, samples);
  std::vector<float> table(size_t(kShadowTableWidth) * 4, 0.0f);
  for (int i = 1; i < kShadowTableWidth; ++i)
    for (int c = 0; c < 4; ++c)
      table[size_t(i * 4 + c)] = float(shares[size_t(c)] / enc.channelMax);
  glColorTable(GL_COLOR_TABLE, enc.tableFormat, kShadowTableWidth, GL_RGBA, GL_FLOAT, table.data());
  setPixelTransferScale(shadowTableScale(enc));
}

void loadSumIntoAlphaMatrix() {
  glm::mat4 sum(0.0f);  // glm: sum[column][row]
  for (int c = 0; c < 4; ++c) sum[c][3] = 1.0f;
  loadMatrix(GL_COLOR, sum);
  glMatrixMode(GL_MODELVIEW);
}

void countShadowSamplesByCopy(const RenderParams& params, const DepthEncoding& enc, int samples) {
  prepareWindowCopy(params);
  loadShadowCountTable(enc, samples);
  loadSumIntoAlphaMatrix();
  {
    const ScopedEnable colourTable(GL_COLOR_TABLE);
    glCopyPixels(0, 0, params.width, params.height, GL_COLOR);
  }
  loadMatrix(GL_COLOR, glm::mat4(1.0f));
  glMatrixMode(GL_MODELVIEW);
  setPixelTransferScale(1.0);
  glEnable(GL_DEPTH_TEST);
}

Image readThroughColorTable(const RenderParams& params, const DepthEncoding& enc, int samples) {
  const GlTracePause dumpOnly;  // a readback for --dump-passes, not state of a pass
  loadShadowCountTable(enc, samples);
  Image image;
  {
    const ScopedEnable colourTable(GL_COLOR_TABLE);
    image = readColorBuffer(0, 0, params.width, params.height);
  }
  setPixelTransferScale(1.0);
  return image;
}

// ---- The accumulation (§3: "summed up using the accumulation buffer"; §4: 4x4 phases)

void accumulateGroup(double weight, bool first) {
  setChannelMask(kAllChannels);
  glAccum(first ? GL_LOAD : GL_ACCUM, float(weight));
}

void returnAccumulation() {
  setChannelMask(kAllChannels);
  glAccum(GL_RETURN, 1.0f);
}

// ---- Lighting x shadow term (§5) and the visibility read back

void shadeWithShadowTerm(const Scene& scene, const RenderParams& params,
                         const SpotlightConeTexture& coneTexture) {
  setCameraMatrices(scene, params.width, params.height);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);  // the shadow term stays in alpha
  glClearColor(0, 0, 0, 0);
  glClear(GL_COLOR_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  {
    const ScopedEnable blend(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    enableSpotlight(scene, LightTerms::kDiffuseSpecularOnly);
    glBlendFunc(GL_ONE_MINUS_DST_ALPHA, GL_ZERO);  // direct light x (1 - shadow)
    {
      // The cone per pixel (Segal et al. 1992): outside it the fragment is discarded, black.
      const ProjectedSpotlightCone cone(scene, coneTexture, GL_TEXTURE0);
      drawScene(scene, Draw::kAll);
    }
    enableSpotlight(scene, LightTerms::kAmbientOnly);
    glBlendFunc(GL_ONE, GL_ONE);  // + ambient, unshadowed
    drawScene(scene, Draw::kAll);
    disableLighting();
  }
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  setChannelMask(kAllChannels);
}

Image readVisibilityFromAlpha(const RenderParams& params) {
  Image alpha(params.width, params.height, 1);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, params.width, params.height, GL_ALPHA, GL_FLOAT, alpha.data.data());
  checkGl("read shadow term (alpha)");
  for (float& a : alpha.data) a = 1.0f - std::clamp(a, 0.0f, 1.0f);
  return alpha;
}

// ---- --dump-passes read-backs and the footprint parameter

Image readWindowRgba(const RenderParams& params) {
  const GlTracePause dumpOnly;  // a readback for --dump-passes, not state of a pass
  return readColorBuffer(0, 0, params.width, params.height);
}

Image readShadowMap(const ShadowMapTexture& map, int texels) {
  const GlTracePause dumpOnly;  // a readback for --dump-passes, not state of a pass
  Image image(texels, texels, 4);
  glBindTexture(GL_TEXTURE_2D, map.name.id());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, image.data.data());
  checkGl("read shadow map texture");
  return image;
}

Image channelPanels(const Image& rgba) {
  std::vector<Image> panels;
  for (int c = 0; c < rgba.channels; ++c) panels.push_back(channel(rgba, c));
  return sideBySide(panels);
}

Image channelsMinusCentre(const Image& rgba, int centre, float gain) {
  constexpr float kZero = 0.5f;  // grey: the channel equals the centre
  std::vector<Image> panels;
  for (int c = 0; c < rgba.channels; ++c) {
    if (c == centre) continue;
    Image panel(rgba.width, rgba.height, 1);
    for (int y = 0; y < rgba.height; ++y)
      for (int x = 0; x < rgba.width; ++x) {
        float mid = 0.0f;
        if (centre >= 0) {
          mid = rgba.at(x, y, centre);
        } else {
          for (int k = 0; k < rgba.channels; ++k) mid += rgba.at(x, y, k);
          mid /= float(rgba.channels);
        }
        panel.at(x, y, 0) = std::clamp(kZero + gain * (rgba.at(x, y, c) - mid), 0.0f, 1.0f);
      }
    panels.push_back(std::move(panel));
  }
  return sideBySide(panels);
}

Image amplified(const Image& image, float gain) {
  Image out = image;
  for (float& v : out.data) v = std::clamp(v * gain, 0.0f, 1.0f);
  return out;
}

Image alphaOf(const Image& rgba) { return channel(rgba, 3); }

int footprintSide(const RenderParams& params, const std::string& technique) {
  constexpr int kLargestFootprint = 4;  // the paper's largest (§3, §4)
  if (params.filter < 1 || params.filter > kLargestFootprint)
    throw InputError(technique + ": --filter must be 1, 2, 3 or 4 (footprint side), got " +
                     std::to_string(params.filter));
  return params.filter;
}

}  // namespace sl::legacy::bs
