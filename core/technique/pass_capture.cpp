// core/technique/pass_capture.cpp — see pass_capture.h.
#include "core/technique/pass_capture.h"

#include <algorithm>
#include <cstdio>

#include "core/base/errors.h"
#include "core/gl/gl.h"
#include "core/gl/gl_trace.h"
#include "core/technique/passes.h"

namespace sl {
namespace {

// Window z printed with three decimals (a 24-bit depth buffer resolves far finer, but three
// decimals tell a student where the scene lies in [0, 1]).
std::string depthText(float z) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", double(z));
  return text;
}

}  // namespace

WindowDepthSpan drawnDepthRange(const std::vector<const Image*>& depths, float clear) {
  WindowDepthSpan r{clear, clear};
  bool any = false;
  for (const Image* depth : depths)
    for (int y = 0; y < depth->height; ++y)
      for (int x = 0; x < depth->width; ++x) {
        const float z = depth->at(x, y, 0);
        if (z == clear) continue;
        r.lo = any ? std::min(r.lo, z) : z;
        r.hi = any ? std::max(r.hi, z) : z;
        any = true;
      }
  return r;
}

PassImage greyDepth(std::string name, const std::string& what, const Image& depth, float clear) {
  return greyDepth(std::move(name), what, depth, drawnDepthRange({&depth}, clear), clear);
}

PassImage greyDepth(std::string name, const std::string& what, const Image& depth,
                    WindowDepthSpan range, float clear) {
  Image grey(depth.width, depth.height, 1);
  const float span = range.hi - range.lo;
  for (int y = 0; y < depth.height; ++y)
    for (int x = 0; x < depth.width; ++x) {
      const float z = depth.at(x, y, 0);
      // One drawn value (span 0) is shown mid-grey, so that it still differs from nothing.
      const float v = z == clear ? 1.0f : span > 0.0f ? (z - range.lo) / span : 0.5f;
      grey.at(x, y) = std::clamp(v, 0.0f, 1.0f);
    }
  std::string caption = what + "; window z " + depthText(range.lo) + " (black) .. " +
                        depthText(range.hi) + " (white); " + depthText(clear) + " = nothing";
  if (range.lo == clear && range.hi == clear) caption = what + "; empty: nothing drawn (white)";
  return {std::move(name), std::move(caption), std::move(grey)};
}

Image readDepthTexture(unsigned texture, int width, int height) {
  using namespace gl;
  const GlTracePause dumpOnly;  // a readback for --dump-passes, not state of a pass
  GLint previous = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &previous);
  Image depth(width, height, 1);
  glBindTexture(GL_TEXTURE_2D, texture);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data.data());
  glBindTexture(GL_TEXTURE_2D, GLuint(previous));
  checkGl("read depth texture (--dump-passes)");
  return depth;
}

std::vector<PassBuffer> cameraPassBuffers(const std::string& pass, const std::string& source) {
  return {{.name = "shaded", .caption = "pass " + pass + ": the shaded image (" + source + ")"},
          {.name = "visibility",
           .caption = "pass " + pass +
                      ": the shadow test's result alone, white = lit, black = shadow (" + source +
                      "); what --mask writes"}};
}

void captureCameraPass(Passes& passes, const std::string& id) {
  passes.capture(id, "shaded", [&] { return passes.frame().color; });
  passes.capture(id, "visibility", [&] { return passes.frame().visibility; });
}

}  // namespace sl
