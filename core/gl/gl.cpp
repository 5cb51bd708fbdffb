#include "core/gl/gl.h"

#include "core/base/errors.h"
#include "core/gl/gl_fault.h"

namespace sl {
namespace {
// The current context's table on this thread: GL's own model of "the current context".
thread_local const GlDispatch* tCurrent = nullptr;
}  // namespace

void resolveGlDispatch(GlDispatch& table, GlResolver resolve, void* user) {
#define SL_GL(name) table.name = reinterpret_cast<decltype(table.name)>(resolve("gl" #name, user));
#include "core/gl/gl_functions.inc"
#undef SL_GL
}

const GlDispatch& currentGl() {
  if (tCurrent == nullptr) throw GlError("no GL context is current on this thread");
  return *tCurrent;
}

void setCurrentGl(const GlDispatch* table) { tCurrent = table; }

namespace gl {
void throwMissingEntryPoint(const char* name) {
  // An injected fault (core/gl/gl_fault.h) that made the entry point absent says so.
  throw GlError(std::string("the current GL implementation has no entry point ") + name +
                takeGlFaultNote());
}
}  // namespace gl
}  // namespace sl
