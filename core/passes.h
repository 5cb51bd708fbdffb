// core/passes.h — the framework a technique's render() runs its passes through, by the ids of
// its pass table (core/pass_table.h): timing, GL tracing, the GL error check and the capture of
// declared buffers for --dump-passes.
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

#include "core/pass_table.h"
#include "core/technique.h"

namespace sl {

// Words that replace "{key}" in a declared buffer's name, caption and channel meanings.
using PassWords = std::map<std::string, std::string>;

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

  // --dump-passes: adds buffer `buffer` of pass `id` (declared in its `writes`) to
  // Frame::intermediates with its declared caption, calling `read` only while dumping, outside
  // any pass's GL trace. `words` replace "{key}" in its name, caption and channel
  // meanings ("{part}" in the name is the part's file tag).
  void capture(const std::string& id, const std::string& buffer, const std::function<Image()>& read,
               const PassPart& part = {}, const PassWords& words = {});
  // The same for a buffer whose words depend on what is read (the depth range a grey depth map
  // spans): `read` returns the image and sets those words.
  void capture(const std::string& id, const std::string& buffer,
               const std::function<Image(PassWords& words)>& read, const PassPart& part = {});

  bool capturing() const { return params_.capturePasses; }
  Frame& frame() { return frame_; }
  const PassTable& table() const { return table_; }

 private:
  Frame& frame_;
  const RenderParams& params_;
  const PassTable& table_;
};

}  // namespace sl
