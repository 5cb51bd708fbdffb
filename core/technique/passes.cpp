// core/technique/passes.cpp — see passes.h.
#include "core/technique/passes.h"

#include <cctype>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "core/base/errors.h"
#include "core/gl/gl.h"
#include "core/gl/gl_fault.h"
#include "core/gl/gl_trace.h"

namespace sl {
using namespace sl::gl;

namespace {

// "1 light pass: ..." for numbered ids ("1", "5c"); a named id ("mesh") is not shown.
std::string displayName(const PassSpec& spec, const PassPart& part, const std::string& suffix) {
  const bool numbered = !spec.id.empty() && std::isdigit(static_cast<unsigned char>(spec.id[0]));
  std::string name = (numbered ? spec.id + " " : "") + spec.name + suffix;
  if (!part.label.empty()) name += " " + part.label;
  return name;
}

std::string replaced(std::string text, const std::string& key, const std::string& value) {
  const std::string mark = "{" + key + "}";
  for (size_t at = text.find(mark); at != std::string::npos;
       at = text.find(mark, at + value.size()))
    text.replace(at, mark.size(), value);
  return text;
}

// Ends the pass's GL trace however the body leaves (the body may throw).
// Also the pass boundary of fault injection (core/gl/gl_fault.h): a fault armed for the pass
// id `id` fires inside it (`name` goes into its note).
class TracedScope {
 public:
  TracedScope(const std::string& id, const std::string& name) {
    beginTracedPass();
    glFaultPassBegin(id, name);
  }
  ~TracedScope() {
    if (!ended_) endTracedPass();
    glFaultPassEnd();
  }
  TracedPass end() {
    ended_ = true;
    return endTracedPass();
  }
  TracedScope(const TracedScope&) = delete;
  TracedScope& operator=(const TracedScope&) = delete;

 private:
  bool ended_ = false;
};

}  // namespace

Passes::Passes(Frame& frame, const RenderParams& params, const PassTable& table)
    : frame_(frame), params_(params), table_(table) {}

void Passes::run(const std::string& id, const std::function<void()>& body, const PassPart& part,
                 const std::string& suffix, const char* file, const char* function) {
  const PassSpec& spec = findPassSpec(table_, id);
  PassTime pass;
  pass.name = displayName(spec, part, suffix);
  pass.id = spec.id;
  pass.floor = spec.floor;
  pass.role = spec.role;
  pass.part = part.index;
  pass.section = spec.reference;
  pass.glsl = spec.shaders;
  pass.keyState = spec.keyState;
  pass.sourceFile = sourceRelativePath(file);
  pass.sourceFunction = function;
  throwNotedGlError();  // a timed pass's failure (PassTimer) ends the render before this one
  glFinish();
  TracedScope trace(pass.id, pass.name);
  const double start = nowMilliseconds();
  body();
  glFinish();
  pass.milliseconds = nowMilliseconds() - start;
  pass.gl = trace.end();
  const std::string name = pass.name;
  frame_.passes.push_back(std::move(pass));
  checkGl(name.c_str());
}

void Passes::resume(const std::string& id, const std::function<void()>& body) {
  size_t at = frame_.passes.size();
  while (at > 0 && frame_.passes[at - 1].id != id) --at;
  if (at == 0) throw std::logic_error("pass \"" + id + "\" resumed before it ran");
  throwNotedGlError();
  glFinish();
  TracedScope trace(frame_.passes[at - 1].id, frame_.passes[at - 1].name);
  const double start = nowMilliseconds();
  body();
  glFinish();
  const double milliseconds = nowMilliseconds() - start;
  TracedPass gl = trace.end();
  PassTime& pass = frame_.passes[at - 1];
  pass.milliseconds += milliseconds;
  pass.gl.setup.insert(pass.gl.setup.end(), gl.setup.begin(), gl.setup.end());
  pass.gl.state.insert(pass.gl.state.end(), gl.state.begin(), gl.state.end());
  checkGl(pass.name.c_str());
}

void Passes::capture(const std::string& id, const std::string& buffer,
                     const std::function<Image()>& read, const PassPart& part,
                     const std::map<std::string, std::string>& words) {
  add(
      id, buffer, [&](const std::string& caption) { return std::pair(read(), caption); }, part,
      words);
}

void Passes::captureDepth(const std::string& id, const std::string& buffer,
                          const std::function<Image()>& readDepth, const PassPart& part,
                          const std::map<std::string, std::string>& words,
                          const std::function<WindowDepthSpan()>& span) {
  add(
      id, buffer,
      [&](const std::string& caption) {
        const Image depth = readDepth();
        PassImage grey =
            span ? greyDepth("", caption, depth, span()) : greyDepth("", caption, depth);
        return std::pair(std::move(grey.image), std::move(grey.caption));
      },
      part, words);
}

void Passes::add(const std::string& id, const std::string& buffer, const Reader& read,
                 const PassPart& part, const std::map<std::string, std::string>& words) {
  if (!params_.capturePasses) return;
  const PassSpec& spec = findPassSpec(table_, id);
  const PassBuffer* declared = nullptr;
  for (const PassBuffer& b : spec.writes)
    if (b.name == buffer) declared = &b;
  if (!declared)
    throw std::logic_error("pass \"" + id + "\" declares no buffer \"" + buffer + "\"");
  std::string caption = declared->caption;
  for (const auto& [key, value] : words) caption = replaced(caption, key, value);
  Image image;
  {
    const GlTracePause dumpOnly;  // a readback for the dump, not state of a pass
    std::tie(image, caption) = read(caption);
  }
  std::string name = replaced(declared->name, "part", part.fileTag);
  for (const auto& [key, value] : words) name = replaced(name, key, value);
  std::vector<std::string> meaning = declared->channelMeaning;
  for (std::string& m : meaning)
    for (const auto& [key, value] : words) m = replaced(m, key, value);
  PassImage out(id + "-" + name, caption, std::move(image));
  out.passId = id;
  out.centreChannel = declared->centreChannel;
  out.channelMeaning = std::move(meaning);
  frame_.intermediates.push_back(std::move(out));
}

}  // namespace sl
