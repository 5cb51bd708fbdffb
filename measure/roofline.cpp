// measure/roofline.cpp — the llvmpipe floors of the Brabec & Seidel passes (see roofline.h).
#include "measure/roofline.h"

#include <algorithm>
#include <cstdint>

#include "core/base/errors.h"
#include "core/gl/gl.h"
#include "core/gl/gl_objects.h"
#include "legacy_gl/fixed_function.h"

namespace sl::legacy {
using namespace sl::gl;

namespace {

constexpr int kRampTexels = 256;            // the 8-bit ramp of §2
constexpr int kRgbaBytes = 4;               // RGBA8 pixel rectangles
constexpr float kNearWindowZ = -1.0f;       // glOrtho(-1, 1) z: window depth 0, passes LESS/LEQUAL
constexpr int kSamplesPerGroup = 4;         // §3: four jittered samples per RGBA map
constexpr float kAccumulateWeight = 0.25f;  // §4 fast PCF 4x4: four phases of weight 1/4

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
// with q = 1 (projective lookups divide by it, as texgen's q does).
void fullWindowQuad(int width, int height) {
  const float w = float(width), h = float(height);
  glBegin(GL_QUADS);
  glNormal3f(0.0f, 0.0f, 1.0f);
  glTexCoord4f(0.0f, 0.0f, 0.0f, 1.0f);
  glVertex3f(0.0f, 0.0f, -kNearWindowZ);
  glTexCoord4f(1.0f, 0.0f, 0.0f, 1.0f);
  glVertex3f(w, 0.0f, -kNearWindowZ);
  glTexCoord4f(1.0f, 1.0f, 0.0f, 1.0f);
  glVertex3f(w, h, -kNearWindowZ);
  glTexCoord4f(0.0f, 1.0f, 0.0f, 1.0f);
  glVertex3f(0.0f, h, -kNearWindowZ);
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
  std::uint8_t* pixels() { return pixels_.data(); }

 private:
  Texture ramp_ = makeTexture();
  Texture map_ = makeTexture();
  Texture window_ = makeTexture();
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
    case PassFloor::kLighting:  // §5: direct light, then ambient: two layers
      return std::vector<FloorTerm>{{W::kClear, w, h, 1}, {W::kLitBlendedFill, w, h, 2}};
    case PassFloor::kCopyWindowToTexture: return std::vector<FloorTerm>{{W::kCopyTexture, w, h, 1}};
    case PassFloor::kTexturedWindowQuad: return std::vector<FloorTerm>{{W::kTexturedFill, w, h, 1}};
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
