// measure/roofline.h — the llvmpipe floor of each Brabec & Seidel pass and of Everitt et al.'s
// legacy.hw:
// the least GL work of the same kind that the pass cannot do without, measured in the same
// context as the frames (legacy_bench interleaves them, so load hits both alike). A pass's
// floor is a sum of terms, each one named piece of real GL work at the pass's size: a clear, a
// full-window quad with the pass's class of fragment work (ramp-textured and depth-tested,
// projectively textured and subtracted, lit and blended), a glCopyTexSubImage2D, a plain
// glCopyPixels (no imaging state: the driver's copy), a glDrawPixels, a glAccum(GL_ACCUM) (Mesa
// accumulates on the CPU for all its drivers, main/accum.c, and imaging/ where a visual has no
// accumulation buffer: the call is the least work there is). A pass draws the scene, at least
// one layer of the window; the floor counts exactly one.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/technique/technique.h"

namespace sl::legacy {

enum class FloorWork {
  kClear,                     // glClear(colour | depth)
  kRampTexturedFill,          // 1D ramp texture (GL_REPLACE), depth test LESS + write (§2)
  kProjectiveSubtractFill,    // projective 2D map, GL_FUNC_REVERSE_SUBTRACT blend (§2 pass 3)
  kLitBlendedFill,            // GL lighting, GL_ONE_MINUS_DST_ALPHA blend, depth LEQUAL (§5)
  kCopyTexture,               // glCopyTexSubImage2D, no convolution
  kCopyPixels,                // glCopyPixels(GL_COLOR), no colour table or matrix
  kAccumulate,                // glAccum(GL_ACCUM, 1/4) of the window (Mesa's main/accum.c)
  kDrawPixels,                // glDrawPixels RGBA8 (what GL_RETURN must write)
  kTexturedFill,              // 2D texture (GL_REPLACE, NEAREST), no depth test (a restored copy)
  kClearColourKeepAlpha,      // glClear(colour) under glColorMask(R, G, B, not A) (§5's pass)
  kLitBlendedConeFill,        // kLitBlendedFill + the cone texture (MODULATE) and the alpha test
  kClearDepth,                // glClear(depth) (Everitt's light pass)
  kDepthOnlyOffsetFill,       // no colour, polygon offset, depth test LESS + write (Everitt Fig. 2)
  kCopyDepthToTexture,        // glCopyTexSubImage2D of the depth buffer into a depth texture
  kLitDepthFill,              // GL lighting, depth test LESS + write, no blend (ambient pass)
  kShadowComparedLitAddFill,  // lit x depth comparison x behind-light step x cone, added
  kShadowComparedFill,        // unlit: depth comparison x behind-light step, depth LESS + write
  kReadRedChannel,            // glReadPixels(GL_RED, GL_FLOAT) of the window (the mask)
};

struct FloorTerm {
  FloorWork work = FloorWork::kClear;
  int width = 0;
  int height = 0;
  int count = 1;  // how many times the pass does it
};

// "floor: ramp-textured fill 800x600" — the name the floor frame gives the term's timing.
std::string floorName(const FloorTerm& term);

// The floor of one pass of legacy.ramp, legacy.pcf, legacy.fast-pcf or legacy.hw (and the
// camera passes legacy.woo and legacy.second-depth share with it), by the floor class its
// pass table declares (core/technique/pass_table.h) at params' window, map and footprint (`part`:
// which PCF group a kJitteredLightGroup run is, 0-based): its terms, an empty list for a pass
// without GL work (the mesh feeding, the texgen planes), nullopt for a pass without a floor
// (PassFloor::kNone).
std::optional<std::vector<FloorTerm>> passFloor(PassFloor floor, int part,
                                                const RenderParams& params);
// The same for a pass a frame ran (its PassTime carries the floor and the part).
std::optional<std::vector<FloorTerm>> passFloor(const PassTime& pass, const RenderParams& params);

// The GL objects the floors draw with (a ramp texture, a map-sized texture, a window-sized one,
// a depth texture with comparison, the behind-light step, a cone-sized alpha texture, pixel
// buffers), made once in the current context.
class FloorResources;
std::shared_ptr<FloorResources> makeFloorResources(int mapTexels, int width, int height);

// Runs each term once (count ignored), each timed as a pass named floorName(term) (glFinish on
// both sides, core/technique/technique.h PassTimer), and restores the GL state it changed.
Frame renderFloors(FloorResources& resources, const std::vector<FloorTerm>& terms);

}  // namespace sl::legacy
