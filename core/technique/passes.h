// core/technique/passes.h — the framework a technique's render() runs its passes through, by the
// ids of its pass table (core/technique/pass_table.h): timing, GL tracing, the GL error check and
// the capture of declared buffers for --dump-passes.
//
// A pass function reads:
//   // Pass 1 (Brabec & Seidel §4): "we store the encoded depth values in all four channels".
//   void renderDepthIntoAllChannels(Passes& passes, ...) {
//     passes.run("1", [&] { bs::renderLightDepth(...); });
//   }
// and render() adds the buffers the dump shows:
//   passes.capture("1", "light-pass-depth-rgba", [&] { return readColorBuffer(...); });
#pragma once

#include <functional>
#include <map>
#include <string>

#include "core/technique/pass_capture.h"
#include "core/technique/pass_table.h"
#include "core/technique/technique.h"

namespace sl {

// The framework a render() runs its passes through (one per render).
class Passes {
 public:
  Passes(Frame& frame, const RenderParams& params, const PassTable& table);

  // Runs pass `id` (its body), timed and traced: glFinish, the body, glFinish; the time, the GL
  // state the body set (while a GlTrace runs) and the pass's declaration go into
  // Frame::passes. A GL error at the end throws GlError naming the pass. `suffix` is appended
  // to the declared name as it is ("jittered light passes" + " (4)"); the function that calls
  // run is recorded as the pass's source (the pass function).
  void run(const std::string& id, const std::function<void()>& body, const PassPart& part = {},
           const std::string& suffix = "", const char* file = __builtin_FILE(),
           const char* function = __builtin_FUNCTION());

  // Runs `body` as more of pass `id`, run before in this render: a pass whose work comes in
  // pieces interleaved with another pass's (reference pixel=area: per sub-pixel position its
  // surface points, pass 3a, then its rays, pass 3b). The time and GL state of the piece are
  // added to the pass's last entry in Frame::passes (one entry, however many pieces); throws
  // std::logic_error when the pass has not run.
  void resume(const std::string& id, const std::function<void()>& body);

  // --dump-passes: adds buffer `buffer` of pass `id` (declared in its `writes`) to
  // Frame::intermediates with its declared caption, calling `read` only while dumping, outside
  // any pass's GL trace. `words` replace "{key}" in its name, caption and channel
  // meanings ("{part}" in the name is the part's file tag).
  void capture(const std::string& id, const std::string& buffer, const std::function<Image()>& read,
               const PassPart& part = {}, const std::map<std::string, std::string>& words = {});

  // --dump-passes: a depth buffer of pass `id` shown as grey (core/technique/pass_capture.h
  // greyDepth): `readDepth` returns window z; the caption is the declared one followed by the
  // window-z range the greys span: `span()` (several maps on one scale) or, when empty, the drawn
  // range of this buffer. Both run only while dumping.
  void captureDepth(const std::string& id, const std::string& buffer,
                    const std::function<Image()>& readDepth, const PassPart& part = {},
                    const std::map<std::string, std::string>& words = {},
                    const std::function<WindowDepthSpan()>& span = {});

  bool capturing() const { return params_.capturePasses; }
  Frame& frame() { return frame_; }
  const PassTable& table() const { return table_; }

 private:
  // The image and its caption, given the declared caption with its words replaced.
  using Reader = std::function<std::pair<Image, std::string>(const std::string& caption)>;
  void add(const std::string& id, const std::string& buffer, const Reader& read,
           const PassPart& part, const std::map<std::string, std::string>& words);

  Frame& frame_;
  const RenderParams& params_;
  const PassTable& table_;
};

}  // namespace sl
