// core/gl/gl.h — the GL entry points shadowlab calls, dispatched through the current context.
//
// Why a dispatch table: the same legacy code must run on Debian's OSMesa (imaging subset
// emulated by imaging/), on the reference Mesa 7.8.2 loaded privately with dlopen (imaging
// native), and on EGL (NVIDIA or Mesa). No GL library is linked; every context resolves its
// own entry points (OSMesaGetProcAddress, dlsym, eglGetProcAddress) into a GlDispatch, and
// making a context current makes its table current on this thread — the same model GL itself
// uses. Code reads exactly like the 2001 code it reproduces: `glColorTable(GL_COLOR_TABLE, ...)`
// resolves to sl::gl::glColorTable, which calls through the current table.
//
// Usage: inside namespace sl (or below), write `using namespace sl::gl;` and call glXxx.
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/gl.h>
#include <GL/glext.h>

namespace sl {

// One function pointer per entry point in gl_functions.inc, typed from the system prototype.
struct GlDispatch {
#define SL_GL(name) decltype(&::gl##name) name = nullptr;
#include "core/gl/gl_functions.inc"
#undef SL_GL
};

// Fills every entry with resolve("glName"); entries the implementation lacks stay null.
using GlResolver = void* (*)(const char* name, void* user);
void resolveGlDispatch(GlDispatch& table, GlResolver resolve, void* user);

// The table of the context current on this thread (set by GlContext::makeCurrent).
// Calling GL with no current context throws sl::GlError rather than crashing.
const GlDispatch& currentGl();
void setCurrentGl(const GlDispatch* table);

namespace gl {

[[noreturn]] void throwMissingEntryPoint(const char* name);

template <class Fn, class Entry>
struct Forward;
template <class R, class... Args, class Entry>
struct Forward<R (*)(Args...), Entry> {
  static R call(Args... args) {
    auto fn = currentGl().*Entry::kMember;
    if (fn == nullptr) throwMissingEntryPoint(Entry::kName);
    return fn(args...);
  }
};

namespace entry {
#define SL_GL(name)                                    \
  struct name {                                        \
    static constexpr auto kMember = &GlDispatch::name; \
    static constexpr const char* kName = "gl" #name;   \
  };
#include "core/gl/gl_functions.inc"
#undef SL_GL
}  // namespace entry

// glName(...): the system prototype's signature, forwarded through currentGl().
#define SL_GL(name) \
  inline constexpr auto gl##name = &Forward<decltype(&::gl##name), entry::name>::call;
#include "core/gl/gl_functions.inc"
#undef SL_GL

}  // namespace gl
}  // namespace sl
