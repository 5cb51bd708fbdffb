// core/technique/pass_capture.h — helpers the techniques use to fill Frame::intermediates when
// RenderParams::capturePasses is set (--dump-passes): buffers a student can read.
//
// A depth buffer holds values crowded near 1 (window z of a perspective light), so shown as it
// is it looks white. greyDepth() stretches the values that are not the clear value over black
// .. white and says the mapping in the caption; the clear value ("nothing drawn") is white.
//
// Names follow the pass that makes the buffer: "<pass number>-<what>" ("1-light-depth"); the
// dump (teach/pass_dump.h) zero-pads the number and letters several images of one pass.
// Nothing here runs unless the technique checked capturePasses first.
#pragma once

#include <string>
#include <vector>

#include "core/technique/pass_table.h"
#include "core/technique/technique.h"

namespace sl {

class Passes;  // core/technique/passes.h (which includes this header)

// The depth value a cleared depth buffer holds (glClearDepth's default): "nothing drawn".
constexpr float kClearDepth = 1.0f;

// The range of a depth map's values that are not `clear`: [lo, hi]. When every value is
// `clear`, lo = hi = clear.
struct WindowDepthSpan {
  float lo = kClearDepth;
  float hi = kClearDepth;
};
WindowDepthSpan drawnDepthRange(const std::vector<const Image*>& depths, float clear = kClearDepth);

// Channel 0 of `depth` as grey: lo -> black, hi -> white, `clear` -> white; the caption is
// "<what>; window z <lo> (black) .. <hi> (white); <clear> = nothing".
PassImage greyDepth(std::string name, const std::string& what, const Image& depth,
                    float clear = kClearDepth);
// The same with a given range (several maps shown on one scale, e.g. Woo's two layers and
// their midpoint, so that the midpoint's grey lies between the layers' greys).
PassImage greyDepth(std::string name, const std::string& what, const Image& depth,
                    WindowDepthSpan range, float clear = kClearDepth);

// Reads level 0 of a DEPTH_COMPONENT texture as float window z (rows bottom-up); the
// GL_TEXTURE_2D binding of the active unit is restored. Compare mode does not apply to reads.
Image readDepthTexture(unsigned texture, int width, int height);

// The camera pass' outcome, as every technique fills Frame::color and Frame::visibility: its
// buffers "shaded" and "visibility" for its pass table (PassSpec::writes), captioned "pass
// <pass>: ..." with `source` (the paper section), and their capture as pass `id` from
// Frame::color and Frame::visibility (core/technique/passes.h).
std::vector<PassBuffer> cameraPassBuffers(const std::string& pass, const std::string& source);
void captureCameraPass(Passes& passes, const std::string& id);

}  // namespace sl
