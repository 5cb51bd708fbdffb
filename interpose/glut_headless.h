// interpose/glut_headless.h — what the two halves of libshadowlab-glut.so share
// (glut_headless.cpp: the window, callbacks and main loop; glut_shapes.cpp: the shapes): the
// GL, resolved at run time from whatever GL is preloaded after the library, and the one way
// it stops.
#pragma once

#include <dlfcn.h>

#include <string>

namespace sl::interpose {

constexpr int kExitGlFailure = 3;

// One line on stderr ("libshadowlab-glut: ..."), exit status kExitGlFailure.
[[noreturn]] void fatal(const std::string& message);

// The GL function `name`, as the process finds it (dlsym RTLD_DEFAULT); fatal when absent.
template <class Fn>
Fn gl(const char* name) {
  void* p = dlsym(RTLD_DEFAULT, name);
  if (p == nullptr) fatal(std::string("the GL has no ") + name);
  return reinterpret_cast<Fn>(p);
}

}  // namespace sl::interpose

#define SL_GL(name) static const auto name = ::sl::interpose::gl<decltype(&::name)>(#name)
