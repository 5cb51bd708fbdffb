// interpose/preloaded_context.h — a context made the way an unchanged program makes one, for
// measuring and testing libshadowlab-imaging.so from inside shadowlab's own test and bench
// processes: the OSMesa context is created and bound through the process's global symbols
// (so the preloaded library's OSMesaMakeCurrent adopts it and installs its emulation), and
// every entry point of the wrapper comes from the global lookup too (OSMesaGetProcAddress,
// then dlsym RTLD_DEFAULT), as a program linked to libOSMesa would call them: the imaging
// calls reach the library's exports, not this process's own imaging/.
// The process must be started with LD_PRELOAD="libshadowlab-imaging.so libOSMesa.so.8" (the
// library first, so its definitions win; Debian's OSMesa after it, so the library's
// forwarding finds it); preloadedImagingLibrary() says whether it was.
#pragma once

#include <dlfcn.h>

#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "core/base/errors.h"
#include "core/gl/context.h"

// After core/gl/gl.h (through context.h), which includes GL/gl.h.
#include <GL/osmesa.h>

namespace sl::interpose {

// The file that defines the process's global glColorTable when it is the drop-in library
// ("" otherwise): the imaging calls of a program reach it.
inline std::string preloadedImagingLibrary() {
  Dl_info info{};
  void* fn = dlsym(RTLD_DEFAULT, "glColorTable");
  if (fn == nullptr || dladdr(fn, &info) == 0 || info.dli_fname == nullptr) return "";
  return std::strstr(info.dli_fname, "libshadowlab-imaging") != nullptr ? info.dli_fname : "";
}

// An OSMesa context (RGBA8, depth 24, stencil 8, accumulation 16 bits or none) made and bound
// through the global symbols, and its shadowlab wrapper (GlContext::adopt) current on this
// thread. Throws GlError when the process was not started as the header comment says.
class PreloadedOsmesaContext {
 public:
  PreloadedOsmesaContext(int width, int height, bool accumulation)
      : buffer_(size_t(width) * size_t(height) * kBytesPerPixel) {
    if (preloadedImagingLibrary().empty())
      throw GlError("libshadowlab-imaging.so is not preloaded (glColorTable is not its)");
    const auto create =
        globalFn<decltype(&::OSMesaCreateContextAttribs)>("OSMesaCreateContextAttribs");
    makeCurrent_ = globalFn<decltype(&::OSMesaMakeCurrent)>("OSMesaMakeCurrent");
    destroy_ = globalFn<decltype(&::OSMesaDestroyContext)>("OSMesaDestroyContext");
    getProcAddress_ = globalFn<decltype(&::OSMesaGetProcAddress)>("OSMesaGetProcAddress");
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           kDepthBits,
                           OSMESA_STENCIL_BITS,
                           kStencilBits,
                           OSMESA_ACCUM_BITS,
                           accumulation ? kAccumBits : 0,
                           OSMESA_PROFILE,
                           OSMESA_COMPAT_PROFILE,
                           0};
    osmesa_ = create(attribs, nullptr);
    if (osmesa_ == nullptr) throw GlError("OSMesaCreateContextAttribs failed");
    if (!makeCurrent_(osmesa_, buffer_.data(), GL_UNSIGNED_BYTE, width, height)) {
      destroy_(osmesa_);
      throw GlError("OSMesaMakeCurrent failed");
    }
    context_ = GlContext::adopt("osmesa", Backend::kOsmesa, width, height, resolve, this);
    context_->makeCurrent();
    // The wrapper's imaging entry must be the library's export, or nothing here is measured.
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(context_->dispatch().ColorTable), &info) == 0 ||
        info.dli_fname == nullptr || std::strstr(info.dli_fname, "libshadowlab-imaging") == nullptr)
      throw GlError("the adopted context's glColorTable is not libshadowlab-imaging.so's");
  }
  ~PreloadedOsmesaContext() {
    context_.reset();
    GlContext::clearCurrent();
    makeCurrent_(nullptr, nullptr, 0, 0, 0);
    destroy_(osmesa_);
  }
  PreloadedOsmesaContext(const PreloadedOsmesaContext&) = delete;
  PreloadedOsmesaContext& operator=(const PreloadedOsmesaContext&) = delete;

  GlContext& context() { return *context_; }

 private:
  static constexpr int kBytesPerPixel = 4;  // OSMESA_RGBA, GL_UNSIGNED_BYTE
  static constexpr int kDepthBits = 24, kStencilBits = 8, kAccumBits = 16;

  template <class Fn>
  static Fn globalFn(const char* name) {
    auto fn = reinterpret_cast<Fn>(dlsym(RTLD_DEFAULT, name));
    if (fn == nullptr)
      throw GlError(std::string(name) +
                    " is not in the process: start it with LD_PRELOAD=\"libshadowlab-imaging.so "
                    "libOSMesa.so.8\"");
    return fn;
  }
  // What a program linked to libOSMesa would call for `name`.
  static void* resolve(const char* name, void* user) {
    auto* self = static_cast<PreloadedOsmesaContext*>(user);
    if (void* p = reinterpret_cast<void*>(self->getProcAddress_(name))) return p;
    return dlsym(RTLD_DEFAULT, name);
  }

  std::vector<unsigned char> buffer_;
  OSMesaContext osmesa_ = nullptr;
  decltype(&::OSMesaMakeCurrent) makeCurrent_ = nullptr;
  decltype(&::OSMesaDestroyContext) destroy_ = nullptr;
  decltype(&::OSMesaGetProcAddress) getProcAddress_ = nullptr;
  std::unique_ptr<GlContext> context_;
};

}  // namespace sl::interpose
