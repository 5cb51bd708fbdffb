// core/gl/context.h — a GL context that shadowlab renders into, on one of three back ends.
//
//   osmesa     Debian's Mesa OSMesa (llvmpipe): compatibility or core profile, colour buffers
//              of 8-bit, 16-bit or float channels, depth 24, stencil 8, accumulation 16.
//              No ARB_imaging: imaging/ emulates it.
//   reference  Mesa 7.8.2 OSMesa (../shared/reference-gl), loaded privately by path: GL 2.1,
//              native ARB_imaging and accumulation buffer, 8-bit colour only.
//   egl        EGL (NVIDIA's driver on the GPU machine, Mesa's llvmpipe here), pbuffer surface.
//
// No GL library is linked at build time: each back end is dlopen()ed and resolves its own
// entry points into a GlDispatch (see core/gl/gl.h).
#pragma once

#include <memory>
#include <set>
#include <string>

#include "core/gl/gl.h"

namespace sl {

enum class Backend { kOsmesa, kReference, kEgl };
enum class Profile { kCompatibility, kCore };
enum class ColorFormat { kRgba8, kRgba16, kRgba32f };

const char* backendName(Backend b);
Backend parseBackend(const std::string& name);  // throws InputError
const char* colorFormatName(ColorFormat f);

struct ContextSpec {
  Backend backend = Backend::kOsmesa;
  Profile profile = Profile::kCompatibility;
  int width = 800;
  int height = 600;
  ColorFormat color = ColorFormat::kRgba8;
  bool accumulation = true;  // ask for a 16-bit-per-channel accumulation buffer
};

struct Capabilities {
  std::string version;
  std::string renderer;
  std::set<std::string> extensions;
  int redBits = 0;
  int alphaBits = 0;
  int accumRedBits = 0;
  int depthBits = 0;
  int stencilBits = 0;
  int maxTextureSize = 0;
  int maxViewportWidth = 0;
  bool hasExtension(const std::string& name) const { return extensions.count(name) != 0; }
  bool nativeImaging() const { return hasExtension("GL_ARB_imaging"); }
  bool depthBoundsTest() const { return hasExtension("GL_EXT_depth_bounds_test"); }
};

class GlContext {
 public:
  // Creates and makes current a context; throws GlError when the back end cannot make one
  // (library missing, profile unsupported) and InputError for an impossible size.
  static std::unique_ptr<GlContext> create(const ContextSpec& spec);
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  void makeCurrent();
  static GlContext* current();  // the context current on this thread, or nullptr

  // Wraps a context that the program made and made current on this thread itself (the drop-in
  // imaging library sees it through glXMakeCurrent, eglMakeCurrent or OSMesaMakeCurrent):
  // entry points from `resolve`, capabilities and profile queried now. The wrapper never binds
  // or destroys the program's context: makeCurrent() only marks it current for the dispatch.
  // `api` names the window system that made it ("glx", "egl", "osmesa"); `backend` is the
  // nearest of ours (messages only). Throws GlError when the context answers no GL_VERSION.
  static std::unique_ptr<GlContext> adopt(const std::string& api, Backend backend, int width,
                                          int height, GlResolver resolve, void* user);
  // The size of an adopted context's drawable (a window resized, another surface bound).
  void setDrawableSize(int width, int height);
  // No context of ours is current on this thread (the program released or switched to one
  // that is not adopted).
  static void clearCurrent();
  bool adopted() const;

  const ContextSpec& spec() const { return spec_; }
  const Capabilities& caps() const { return caps_; }

  // The entry-point table. imaging/ replaces the imaging entries when the context has no
  // native ARB_imaging; call makeCurrent() afterwards is not needed (the table is shared).
  GlDispatch& dispatch() { return dispatch_; }

  // Per-context state of layers above core (the imaging emulation keeps its state tables here,
  // as a driver keeps them in its context). Keyed by a name; owned by the context.
  void setLayerState(const std::string& key, std::shared_ptr<void> state);
  void* layerState(const std::string& key) const;

  struct Impl;

 private:
  GlContext() = default;
  void queryCapabilities();

  ContextSpec spec_;
  Capabilities caps_;
  GlDispatch dispatch_;
  std::unique_ptr<Impl> impl_;
};

// Path of the reference Mesa 7.8.2 library: $SHADOWLAB_REFERENCE_GL if set, else the path
// configured at build time (../shared/reference-gl/libOSMesa.so.7.8.2 when it exists).
// Empty when neither exists.
std::string referenceGlPath();

}  // namespace sl
