// measure/roofline.cpp — the llvmpipe floors of the Brabec & Seidel passes (see roofline.h).
#include "measure/roofline.h"

#include <algorithm>
#include <cstdint>

#include "core/base/errors.h"
#include "core/gl/gl.h"
#include "core/gl/gl_objects.h"
#include "legacy_gl/fixed_function.h"
#include "legacy_gl/projected_spotlight.h"

namespace sl::legacy {
using namespace sl::gl;

namespace {

constexpr int kRampTexels = 256;            // the 8-bit ramp of §2
constexpr int kRgbaBytes = 4;               // RGBA8 pixel rectangles
constexpr float kNearWindowZ = -1.0f;       // glOrtho(-1, 1) z: window depth 0, passes LESS/LEQUAL
constexpr int kSamplesPerGroup = 4;         // §3: four jittered samples per RGBA map
constexpr float kAccumulateWeight = 0.25f;  // §4 fast PCF 4x4: four phases of weight 1/4
// The cone texture's alpha in the floors: above kConeEdgeAlpha, so every fragment is looked up,
// tested and kept (which fragments the pass discards is the scene's; the floor keeps all).
constexpr float kConeFloorAlpha = 0.75f;
// Everitt Fig. 3's light pass: legacy.hw's default glPolygonOffset(factor, units).
constexpr float kOffsetFactor = 2.0f;
constexpr float kOffsetUnits = 4.0f;
constexpr int kStepTexels = 2;  // legacy.hw's behind-the-light step texture (0 behind, 1 front)

// Window coordinates in pixels, every matrix identity but the projection.
void loadPixelMatrices(int width, int height) {
  glViewport(0, 0, width, height);
  glMatrixMode(GL_TEXTURE);
  glLoadIdentity();
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0, width, 0, height, -1, 1);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
}

// One quad covering width x height pixels at window depth 0; texture coordinates span [0, 1]
// with q = 1 (projective lookups divide by it, as texgen's q does) on the first `units` texture
// units, so that each unit the pass samples interpolates its own coordinates.
void fullWindowQuad(int width, int height, int units = 1) {
  const float w = float(width), h = float(height);
  const float corners[4][2] = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
  glBegin(GL_QUADS);
  glNormal3f(0.0f, 0.0f, 1.0f);
  for (const auto& c : corners) {
    for (int u = 0; u < units; ++u)
      glMultiTexCoord2f(GLenum(GL_TEXTURE0 + u), c[0], c[1]);  // r = 0, q = 1
    glVertex3f(c[0] * w, c[1] * h, -kNearWindowZ);
  }
  glEnd();
}

}  // namespace

class FloorResources {
 public:
  FloorResources(int mapTexels, int width, int height)
      : mapTexels_(mapTexels),
        pixels_(size_t(std::max(mapTexels * mapTexels, width * height)) * kRgbaBytes, 0x80) {
    std::vector<float> ramp(kRampTexels);
    for (int i = 0; i < kRampTexels; ++i) ramp[size_t(i)] = float(i) / float(kRampTexels - 1);
    glBindTexture(GL_TEXTURE_1D, ramp_.id());
    glTexImage1D(GL_TEXTURE_1D, 0, GL_INTENSITY8, kRampTexels, 0, GL_LUMINANCE, GL_FLOAT,
                 ramp.data());
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, map_.id());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, mapTexels, mapTexels, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 pixels_.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, window_.id());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 pixels_.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    // legacy.hw's shadow map: DEPTH_COMPONENT24 with the comparison it samples with.
    glBindTexture(GL_TEXTURE_2D, depthMap_.id());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, mapTexels, mapTexels, 0,
                 GL_DEPTH_COMPONENT, GL_UNSIGNED_BYTE, pixels_.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_R_TO_TEXTURE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    glTexParameteri(GL_TEXTURE_2D, GL_DEPTH_TEXTURE_MODE, GL_LUMINANCE);
    // The spotlight cone's size, format and filter (legacy_gl/projected_spotlight.h), every
    // texel kConeFloorAlpha.
    const std::vector<float> cone(size_t(kConeTextureTexels) * kConeTextureTexels, kConeFloorAlpha);
    uploadConeTexture(cone_.id(), cone);
    const GLubyte step[kStepTexels] = {0, 255};
    glBindTexture(GL_TEXTURE_1D, step_.id());
    glTexImage1D(GL_TEXTURE_1D, 0, GL_LUMINANCE8, kStepTexels, 0, GL_LUMINANCE, GL_UNSIGNED_BYTE,
                 step);
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindTexture(GL_TEXTURE_1D, 0);
    checkGl("floor resources");
  }

  unsigned ramp() const { return ramp_.id(); }
  unsigned map() const { return map_.id(); }
  // A texture that holds width x height: the map where it is large enough, else the
  // window-sized one (fast PCF 4x4's copy of its camera pass).
  unsigned textureFor(int width, int height) const {
    return width <= mapTexels_ && height <= mapTexels_ ? map_.id() : window_.id();
  }
  unsigned window() const { return window_.id(); }
  unsigned depthMap() const { return depthMap_.id(); }
  unsigned cone() const { return cone_.id(); }
  unsigned step() const { return step_.id(); }
  std::uint8_t* pixels() { return pixels_.data(); }

 private:
  Texture ramp_ = makeTexture();
  Texture map_ = makeTexture();
  Texture window_ = makeTexture();
  Texture depthMap_ = makeTexture();
  Texture cone_ = makeTexture();
  Texture step_ = makeTexture();
  int mapTexels_;
  std::vector<std::uint8_t> pixels_;
};

std::shared_ptr<FloorResources> makeFloorResources(int mapTexels, int width, int height) {
  return std::make_shared<FloorResources>(mapTexels, width, height);
}

namespace {

// Each floor: the named GL work alone, on state set by loadPixelMatrices and nothing else.

// A pass's clear (§2 every pass that starts a buffer).
void clearColorAndDepth(int width, int height) {
  glViewport(0, 0, width, height);
  glClearColor(1.0f, 1.0f, 1.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

// The light and camera passes' fragment class (§2): 1D ramp lookup, depth test and write.
void fillWithRampTexture(FloorResources& r, int width, int height) {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glEnable(GL_TEXTURE_1D);
  glBindTexture(GL_TEXTURE_1D, r.ramp());
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  fullWindowQuad(width, height);
}

// The projective pass's fragment class (§2 pass 3): projective 2D lookup, subtractive blend,
// depth LEQUAL without write.
void fillSubtractingProjectiveMap(FloorResources& r, int width, int height) {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_REVERSE_SUBTRACT);
  glBlendFunc(GL_ONE, GL_ONE);
  glEnable(GL_TEXTURE_2D);
  glBindTexture(GL_TEXTURE_2D, r.map());
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  fullWindowQuad(width, height);
}

// The lighting pass's fragment class (§5): lit (Gouraud) colour, blended with the destination
// alpha, depth LEQUAL without write.
void fillLitAndBlended(int width, int height) {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE_MINUS_DST_ALPHA, GL_ZERO);
  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
  fullWindowQuad(width, height);
}

// §2: the framebuffer copy into the shadow map.
void copyWindowToTexture(FloorResources& r, int width, int height) {
  glBindTexture(GL_TEXTURE_2D, r.textureFor(width, height));
  glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, width, height);
}

// Fast PCF 4x4's restore of its camera pass: one window-sized texture drawn over the window.
void fillWithWindowTexture(FloorResources& r, int width, int height) {
  glEnable(GL_TEXTURE_2D);
  glBindTexture(GL_TEXTURE_2D, r.window());
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  fullWindowQuad(width, height);
}

// §5's lighting pass: the colour cleared, the shadow term kept in alpha.
void clearColourKeepingAlpha(int width, int height) {
  glViewport(0, 0, width, height);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClear(GL_COLOR_BUFFER_BIT);
}

// The cone per pixel (legacy_gl/projected_spotlight.h) on the active unit: its texture,
// GL_MODULATE, and the alpha test at the cone's edge.
void enableConeLookup(FloorResources& r) {
  glEnable(GL_TEXTURE_2D);
  glBindTexture(GL_TEXTURE_2D, r.cone());
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
  glAlphaFunc(GL_GEQUAL, kConeEdgeAlpha);
  glEnable(GL_ALPHA_TEST);
}

// §5's direct-light layer as it is drawn now: lit and blended with the destination alpha, the
// cone texture looked up and alpha-tested per fragment.
void fillLitBlendedThroughCone(FloorResources& r, int width, int height) {
  enableConeLookup(r);
  fillLitAndBlended(width, height);
}

// Everitt Fig. 2: the light pass's clear (depth only).
void clearDepth(int width, int height) {
  glViewport(0, 0, width, height);
  glClear(GL_DEPTH_BUFFER_BIT);
}

// Everitt Figs. 2-3: depth only, with polygon offset, depth test LESS and write.
void fillDepthOnlyWithOffset(int width, int height) {
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(kOffsetFactor, kOffsetUnits);
  fullWindowQuad(width, height);
}

// Everitt Fig. 2 (ARB_depth_texture): the depth buffer copied into the depth texture.
void copyDepthToTexture(FloorResources& r, int width, int height) {
  glBindTexture(GL_TEXTURE_2D, r.depthMap());
  glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, width, height);
}

// Everitt (Kilgard's note): the ambient camera pass, lit, depth test LESS and write.
void fillLitWritingDepth(int width, int height) {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  fullWindowQuad(width, height);
}

// Everitt Figs. 4-5: unit 0 the depth texture with ARB_shadow's comparison, unit 1 the
// behind-the-light step, both GL_MODULATE; unit 0 stays active.
void enableShadowComparison(FloorResources& r) {
  glActiveTexture(GL_TEXTURE1);
  glEnable(GL_TEXTURE_1D);
  glBindTexture(GL_TEXTURE_1D, r.step());
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
  glActiveTexture(GL_TEXTURE0);
  glEnable(GL_TEXTURE_2D);
  glBindTexture(GL_TEXTURE_2D, r.depthMap());
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
}

// Everitt's direct-light pass: lit, x the comparison (unit 0) x the behind-light step (unit 1)
// x the cone with its alpha test (unit 2), added (GL_ONE, GL_ONE). The pass tests depth EQUAL
// against its ambient pass; the floor tests LEQUAL against the cleared buffer, the same
// per-fragment test, passed by every fragment.
void fillLitShadowComparedAdded(FloorResources& r, int width, int height) {
  constexpr int kUnits = 3;  // shadow map, behind-light step, cone
  enableShadowComparison(r);
  glActiveTexture(GL_TEXTURE2);
  enableConeLookup(r);
  glActiveTexture(GL_TEXTURE0);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  fullWindowQuad(width, height, kUnits);
}

// The visibility mask's layer: white, unlit, x the comparison x the behind-light step, depth
// test LESS and write.
void fillShadowCompared(FloorResources& r, int width, int height) {
  constexpr int kUnits = 2;  // shadow map, behind-light step
  enableShadowComparison(r);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glColor4f(1.0f, 1.0f, 1.0f, 1.0f);
  fullWindowQuad(width, height, kUnits);
}

// The mask read back: the red channel as floats.
void readRedChannel(FloorResources& r, int width, int height) {
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RED, GL_FLOAT, r.pixels());
}

// §2 footnote 1, §3 Fig. 4: the window copied onto itself, no pixel transfer.
void copyWindowOntoItself(int width, int height) {
  glRasterPos2i(0, 0);
  glCopyPixels(0, 0, width, height, GL_COLOR);
}

// §3 accumulation: the window added into the accumulation buffer. Mesa has one GL_ACCUM for
// all its drivers, main/accum.c on the CPU: both buffers mapped, each colour row unpacked to float,
// scaled and added into the 16-bit signed accumulation buffer. No cheaper GL call does this
// work (a glReadPixels of the window reads it but adds nothing; docs/legacy.md compares the two).
// The accumulation buffer's contents are no state of a frame: each frame starts with GL_LOAD.
void accumulateWindow(int width, int height) {
  glViewport(0, 0, width, height);
  glAccum(GL_ACCUM, kAccumulateWeight);
}

// §3 accumulation: what GL_RETURN must write.
void drawIntoWindow(FloorResources& r, int width, int height) {
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glRasterPos2i(0, 0);
  glDrawPixels(width, height, GL_RGBA, GL_UNSIGNED_BYTE, r.pixels());
}

void runFloor(FloorResources& r, const FloorTerm& t) {
  switch (t.work) {
    case FloorWork::kClear: return clearColorAndDepth(t.width, t.height);
    case FloorWork::kRampTexturedFill: return fillWithRampTexture(r, t.width, t.height);
    case FloorWork::kProjectiveSubtractFill:
      return fillSubtractingProjectiveMap(r, t.width, t.height);
    case FloorWork::kLitBlendedFill: return fillLitAndBlended(t.width, t.height);
    case FloorWork::kCopyTexture: return copyWindowToTexture(r, t.width, t.height);
    case FloorWork::kCopyPixels: return copyWindowOntoItself(t.width, t.height);
    case FloorWork::kAccumulate: return accumulateWindow(t.width, t.height);
    case FloorWork::kDrawPixels: return drawIntoWindow(r, t.width, t.height);
    case FloorWork::kTexturedFill: return fillWithWindowTexture(r, t.width, t.height);
    case FloorWork::kClearColourKeepAlpha: return clearColourKeepingAlpha(t.width, t.height);
    case FloorWork::kLitBlendedConeFill: return fillLitBlendedThroughCone(r, t.width, t.height);
    case FloorWork::kClearDepth: return clearDepth(t.width, t.height);
    case FloorWork::kDepthOnlyOffsetFill: return fillDepthOnlyWithOffset(t.width, t.height);
    case FloorWork::kCopyDepthToTexture: return copyDepthToTexture(r, t.width, t.height);
    case FloorWork::kLitDepthFill: return fillLitWritingDepth(t.width, t.height);
    case FloorWork::kShadowComparedLitAddFill:
      return fillLitShadowComparedAdded(r, t.width, t.height);
    case FloorWork::kShadowComparedFill: return fillShadowCompared(r, t.width, t.height);
    case FloorWork::kReadRedChannel: return readRedChannel(r, t.width, t.height);
  }
}

const char* workName(FloorWork w) {
  switch (w) {
    case FloorWork::kClear: return "clear colour + depth";
    case FloorWork::kRampTexturedFill: return "ramp-textured depth-tested fill";
    case FloorWork::kProjectiveSubtractFill: return "projective-textured subtracting fill";
    case FloorWork::kLitBlendedFill: return "lit blended fill";
    case FloorWork::kCopyTexture: return "glCopyTexSubImage2D";
    case FloorWork::kCopyPixels: return "glCopyPixels";
    case FloorWork::kAccumulate: return "glAccum(GL_ACCUM)";
    case FloorWork::kDrawPixels: return "glDrawPixels";
    case FloorWork::kTexturedFill: return "textured fill";
    case FloorWork::kClearColourKeepAlpha: return "clear colour, alpha kept";
    case FloorWork::kLitBlendedConeFill: return "lit blended fill through the cone texture";
    case FloorWork::kClearDepth: return "clear depth";
    case FloorWork::kDepthOnlyOffsetFill: return "depth-only offset fill";
    case FloorWork::kCopyDepthToTexture: return "glCopyTexSubImage2D of depth";
    case FloorWork::kLitDepthFill: return "lit depth-writing fill";
    case FloorWork::kShadowComparedLitAddFill:
      return "lit added fill x shadow comparison x cone texture";
    case FloorWork::kShadowComparedFill: return "shadow-compared fill";
    case FloorWork::kReadRedChannel: return "glReadPixels(GL_RED)";
  }
  return "?";
}

// The sample count of PCF group g (1-based) of a side x side footprint (§3: four per map).
int pcfGroupSamples(int side, int group) {
  const int left = side * side - kSamplesPerGroup * (group - 1);
  return std::max(0, std::min(kSamplesPerGroup, left));
}

}  // namespace

std::string floorName(const FloorTerm& term) {
  return "floor: " + std::string(workName(term.work)) + " " + std::to_string(term.width) + "x" +
         std::to_string(term.height);
}

std::optional<std::vector<FloorTerm>> passFloor(PassFloor floor, int part,
                                                const RenderParams& params) {
  const int w = params.width, h = params.height, n = params.shadowMapTexels;
  using W = FloorWork;
  switch (floor) {
    case PassFloor::kNone: return std::nullopt;
    case PassFloor::kCpuOnly:  // the mesh feeding: no GL work
      return std::vector<FloorTerm>{};
    case PassFloor::kJitteredLightGroup: {  // §3 Fig. 3 (legacy.pcf): group part + 1
      const int samples = pcfGroupSamples(params.filter, part + 1);
      return std::vector<FloorTerm>{{W::kClear, n, n, samples},
                                    {W::kRampTexturedFill, n, n, samples},
                                    {W::kCopyTexture, n, n, 1}};
    }
    case PassFloor::kLightDepth:  // §4: one light pass
      return std::vector<FloorTerm>{{W::kClear, n, n, 1}, {W::kRampTexturedFill, n, n, 1}};
    case PassFloor::kLightDepthAndCopy:  // §2: the light pass and its copy
      return std::vector<FloorTerm>{
          {W::kClear, n, n, 1}, {W::kRampTexturedFill, n, n, 1}, {W::kCopyTexture, n, n, 1}};
    case PassFloor::kCopyToTexture: return std::vector<FloorTerm>{{W::kCopyTexture, n, n, 1}};
    case PassFloor::kCameraDepth:
      return std::vector<FloorTerm>{{W::kClear, w, h, 1}, {W::kRampTexturedFill, w, h, 1}};
    case PassFloor::kProjectiveSubtract:
      return std::vector<FloorTerm>{{W::kProjectiveSubtractFill, w, h, 1}};
    case PassFloor::kCopyPixels: return std::vector<FloorTerm>{{W::kCopyPixels, w, h, 1}};
    case PassFloor::kAccumulationReturn: return std::vector<FloorTerm>{{W::kDrawPixels, w, h, 1}};
    case PassFloor::kAccumulate: return std::vector<FloorTerm>{{W::kAccumulate, w, h, 1}};
    case PassFloor::kLighting:  // §5: colour cleared (alpha kept), direct light in the cone,
                                // ambient
      return std::vector<FloorTerm>{{W::kClearColourKeepAlpha, w, h, 1},
                                    {W::kLitBlendedConeFill, w, h, 1},
                                    {W::kLitBlendedFill, w, h, 1}};
    case PassFloor::kCopyWindowToTexture: return std::vector<FloorTerm>{{W::kCopyTexture, w, h, 1}};
    case PassFloor::kTexturedWindowQuad: return std::vector<FloorTerm>{{W::kTexturedFill, w, h, 1}};
    case PassFloor::kStateOnly:  // Everitt's texgen planes: nothing drawn or copied
      return std::vector<FloorTerm>{};
    case PassFloor::kDepthFromLight:  // Everitt Figs. 2-3: depth only, offset, copied
      return std::vector<FloorTerm>{{W::kClearDepth, n, n, 1},
                                    {W::kDepthOnlyOffsetFill, n, n, 1},
                                    {W::kCopyDepthToTexture, n, n, 1}};
    case PassFloor::kAmbientCamera:  // Everitt, Kilgard's note: the ambient term, depth written
      return std::vector<FloorTerm>{{W::kClear, w, h, 1}, {W::kLitDepthFill, w, h, 1}};
    case PassFloor::kShadowedDirectLight:  // Everitt Figs. 4-5, the cone per pixel
      return std::vector<FloorTerm>{{W::kShadowComparedLitAddFill, w, h, 1}};
    case PassFloor::kVisibilityMask:  // the comparison alone, read back as the mask
      return std::vector<FloorTerm>{
          {W::kClear, w, h, 1}, {W::kShadowComparedFill, w, h, 1}, {W::kReadRedChannel, w, h, 1}};
  }
  return std::nullopt;
}

std::optional<std::vector<FloorTerm>> passFloor(const PassTime& pass, const RenderParams& params) {
  return passFloor(pass.floor, pass.part, params);
}

Frame renderFloors(FloorResources& resources, const std::vector<FloorTerm>& terms) {
  Frame frame;
  {
    const ScopedAttrib state(GL_ALL_ATTRIB_BITS);
    const ScopedClientAttrib clientState(GL_CLIENT_ALL_ATTRIB_BITS);
    const ScopedMatrices matrices;
    for (const FloorTerm& t : terms) {
      const ScopedAttrib termState(GL_ALL_ATTRIB_BITS);
      loadPixelMatrices(t.width, t.height);
      glClear(GL_DEPTH_BUFFER_BIT);  // untimed: every floor fragment passes its depth test
      PassTimer timer(frame, floorName(t));
      runFloor(resources, t);
    }
  }
  checkGl("roofline floors");
  return frame;
}

}  // namespace sl::legacy
