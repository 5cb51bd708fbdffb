#include "core/gl/context.h"

#include <GL/osmesa.h>
#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>
#include <vector>
#ifdef SHADOWLAB_HAVE_EGL
#include <EGL/egl.h>
#include <EGL/eglext.h>
#endif

#include "core/base/errors.h"
#include "core/gl/gl_fault.h"

#ifndef SHADOWLAB_DEFAULT_REFERENCE_GL
#define SHADOWLAB_DEFAULT_REFERENCE_GL ""
#endif

namespace sl {
namespace {

constexpr const char* kDebianOsmesaLibrary = "libOSMesa.so.8";
constexpr const char* kEglLibrary = "libEGL.so.1";
constexpr int kDepthBits = 24;
constexpr int kStencilBits = 8;
constexpr int kAccumBits = 16;  // per channel; what Brabec–Seidel's accumulation passes need

thread_local GlContext* tCurrentContext = nullptr;

#if defined(__SANITIZE_ADDRESS__)
// AddressSanitizer refuses RTLD_DEEPBIND. The reference library was linked with -Bsymbolic
// (its README), so its own calls stay inside it without DEEPBIND too.
constexpr int kReferenceDlopenFlags = RTLD_NOW | RTLD_LOCAL;
#else
constexpr int kReferenceDlopenFlags = RTLD_NOW | RTLD_LOCAL | RTLD_DEEPBIND;
#endif

struct Library {
  void* handle = nullptr;
  Library() = default;
  Library(const Library&) = delete;
  Library& operator=(const Library&) = delete;
  ~Library() {
    if (handle != nullptr) dlclose(handle);
  }
  template <class T>
  T symbol(const char* name) const {
    return reinterpret_cast<T>(dlsym(handle, name));
  }
};

// OSMesa entry points, from whichever libOSMesa the context uses.
struct OsmesaApi {
  decltype(&::OSMesaCreateContextAttribs) createContextAttribs = nullptr;  // Mesa >= 11
  decltype(&::OSMesaCreateContextExt) createContextExt = nullptr;
  decltype(&::OSMesaMakeCurrent) makeCurrent = nullptr;
  decltype(&::OSMesaDestroyContext) destroyContext = nullptr;
  decltype(&::OSMesaGetProcAddress) getProcAddress = nullptr;
  decltype(&::OSMesaGetCurrentContext) getCurrentContext = nullptr;
};

}  // namespace

struct GlContext::Impl {
  Library library;
  OsmesaApi osmesa;
  OSMesaContext osmesaContext = nullptr;
  std::vector<unsigned char> colorBuffer;  // the OSMesa "window"
  GLenum colorType = GL_UNSIGNED_BYTE;
  bool bound = false;      // OSMesaMakeCurrent has been called once
  std::string adoptedApi;  // non-empty: the program's context, seen through GlContext::adopt
  std::map<std::string, std::shared_ptr<void>> layers;
#ifdef SHADOWLAB_HAVE_EGL
  EGLDisplay eglDisplay = EGL_NO_DISPLAY;
  EGLContext eglContext = EGL_NO_CONTEXT;
  EGLSurface eglSurface = EGL_NO_SURFACE;
  PFNEGLMAKECURRENTPROC eglMakeCurrent = nullptr;
  PFNEGLDESTROYCONTEXTPROC eglDestroyContext = nullptr;
  PFNEGLDESTROYSURFACEPROC eglDestroySurface = nullptr;
  PFNEGLTERMINATEPROC eglTerminate = nullptr;
  PFNEGLGETPROCADDRESSPROC eglGetProcAddress = nullptr;
#endif
  ~Impl() {
    if (osmesaContext != nullptr && osmesa.destroyContext != nullptr)
      osmesa.destroyContext(osmesaContext);
#ifdef SHADOWLAB_HAVE_EGL
    if (eglDisplay != EGL_NO_DISPLAY) {
      eglMakeCurrent(eglDisplay, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (eglSurface != EGL_NO_SURFACE) eglDestroySurface(eglDisplay, eglSurface);
      if (eglContext != EGL_NO_CONTEXT) eglDestroyContext(eglDisplay, eglContext);
    }
#endif
  }
};

const char* backendName(Backend b) {
  switch (b) {
    case Backend::kOsmesa: return "osmesa";
    case Backend::kReference: return "reference";
    case Backend::kEgl: return "egl";
  }
  return "?";
}

Backend parseBackend(const std::string& name) {
  if (name == "osmesa") return Backend::kOsmesa;
  if (name == "reference") return Backend::kReference;
  if (name == "egl") return Backend::kEgl;
  throw InputError("unknown GL back end '" + name + "' (expected osmesa, reference or egl)");
}

const char* colorFormatName(ColorFormat f) {
  switch (f) {
    case ColorFormat::kRgba8: return "rgba8";
    case ColorFormat::kRgba16: return "rgba16";
    case ColorFormat::kRgba32f: return "rgba32f";
  }
  return "?";
}

std::string referenceGlPath() {
  if (const char* env = std::getenv("SHADOWLAB_REFERENCE_GL"); env != nullptr && *env != 0)
    return env;
  return SHADOWLAB_DEFAULT_REFERENCE_GL;
}

namespace {

void* osmesaResolve(const char* name, void* user) {
  auto* impl = static_cast<GlContext::Impl*>(user);
  void* p = reinterpret_cast<void*>(impl->osmesa.getProcAddress(name));
  if (p == nullptr) p = dlsym(impl->library.handle, name);
  return p;
}

void openOsmesa(GlContext::Impl& impl, const char* path, int flags) {
  impl.library.handle = dlopen(path, flags);
  if (impl.library.handle == nullptr)
    throw GlError(std::string("cannot load OSMesa library ") + path + ": " + dlerror());
  auto& o = impl.osmesa;
  o.createContextAttribs =
      impl.library.symbol<decltype(o.createContextAttribs)>("OSMesaCreateContextAttribs");
  o.createContextExt = impl.library.symbol<decltype(o.createContextExt)>("OSMesaCreateContextExt");
  o.makeCurrent = impl.library.symbol<decltype(o.makeCurrent)>("OSMesaMakeCurrent");
  o.destroyContext = impl.library.symbol<decltype(o.destroyContext)>("OSMesaDestroyContext");
  o.getProcAddress = impl.library.symbol<decltype(o.getProcAddress)>("OSMesaGetProcAddress");
  o.getCurrentContext =
      impl.library.symbol<decltype(o.getCurrentContext)>("OSMesaGetCurrentContext");
  if (o.makeCurrent == nullptr || o.destroyContext == nullptr || o.getProcAddress == nullptr)
    throw GlError(std::string(path) + " is not an OSMesa library");
}

size_t bytesPerChannel(ColorFormat f) {
  switch (f) {
    case ColorFormat::kRgba8: return 1;
    case ColorFormat::kRgba16: return 2;
    case ColorFormat::kRgba32f: return 4;
  }
  return 1;
}

GLenum osmesaType(ColorFormat f) {
  switch (f) {
    case ColorFormat::kRgba8: return GL_UNSIGNED_BYTE;
    case ColorFormat::kRgba16: return GL_UNSIGNED_SHORT;
    case ColorFormat::kRgba32f: return GL_FLOAT;
  }
  return GL_UNSIGNED_BYTE;
}

void createDebianOsmesa(GlContext::Impl& impl, const ContextSpec& spec) {
  openOsmesa(impl, kDebianOsmesaLibrary, RTLD_NOW | RTLD_LOCAL);
  if (impl.osmesa.createContextAttribs == nullptr)
    throw GlError("OSMesa has no OSMesaCreateContextAttribs (Mesa 11 or later is needed)");
  const bool core = spec.profile == Profile::kCore;
  // Highest version first; Mesa 22 llvmpipe gives 4.5 in both profiles.
  const int versions[][2] = {{4, 5}, {3, 3}, {2, 1}};
  for (const auto& v : versions) {
    if (core && v[0] < 3) break;
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           kDepthBits,
                           OSMESA_STENCIL_BITS,
                           kStencilBits,
                           OSMESA_ACCUM_BITS,
                           spec.accumulation ? kAccumBits : 0,
                           OSMESA_PROFILE,
                           core ? OSMESA_CORE_PROFILE : OSMESA_COMPAT_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           v[0],
                           OSMESA_CONTEXT_MINOR_VERSION,
                           v[1],
                           0};
    impl.osmesaContext = impl.osmesa.createContextAttribs(attribs, nullptr);
    if (impl.osmesaContext != nullptr) return;
  }
  throw GlError(std::string("OSMesa could not create a ") + (core ? "core" : "compatibility") +
                " profile context");
}

void createReferenceOsmesa(GlContext::Impl& impl, const ContextSpec& spec) {
  const std::string path = referenceGlPath();
  if (path.empty())
    throw GlError("the reference GL (Mesa 7.8.2) is not configured: set SHADOWLAB_REFERENCE_GL");
  if (spec.profile == Profile::kCore)
    throw GlError("the reference GL (Mesa 7.8.2, GL 2.1) has no core profile");
  if (spec.color != ColorFormat::kRgba8)
    throw GlError("the reference GL renders 8-bit RGBA colour buffers only");
  // Private load (its README): both libraries export the same symbols.
  openOsmesa(impl, path.c_str(), kReferenceDlopenFlags);
  if (impl.osmesa.createContextExt == nullptr)
    throw GlError(path + " has no OSMesaCreateContextExt");
  impl.osmesaContext = impl.osmesa.createContextExt(OSMESA_RGBA, kDepthBits, kStencilBits,
                                                    spec.accumulation ? kAccumBits : 0, nullptr);
  if (impl.osmesaContext == nullptr) throw GlError("the reference GL could not create a context");
}

#ifdef SHADOWLAB_HAVE_EGL
void* eglResolve(const char* name, void* user) {
  auto* impl = static_cast<GlContext::Impl*>(user);
  void* p = reinterpret_cast<void*>(impl->eglGetProcAddress(name));
  return p;
}

void createEgl(GlContext::Impl& impl, const ContextSpec& spec) {
  impl.library.handle = dlopen(kEglLibrary, RTLD_NOW | RTLD_LOCAL);
  if (impl.library.handle == nullptr)
    throw GlError(std::string("cannot load ") + kEglLibrary + ": " + dlerror());
  auto getProc = impl.library.symbol<PFNEGLGETPROCADDRESSPROC>("eglGetProcAddress");
  if (getProc == nullptr) throw GlError("libEGL has no eglGetProcAddress");
  impl.eglGetProcAddress = getProc;
  auto load = [&](const char* n) { return reinterpret_cast<void*>(getProc(n)); };
  auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(load("eglQueryDevicesEXT"));
  auto getPlatformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(load("eglGetPlatformDisplayEXT"));
  auto initialize = reinterpret_cast<PFNEGLINITIALIZEPROC>(load("eglInitialize"));
  auto chooseConfig = reinterpret_cast<PFNEGLCHOOSECONFIGPROC>(load("eglChooseConfig"));
  auto bindApi = reinterpret_cast<PFNEGLBINDAPIPROC>(load("eglBindAPI"));
  auto createContext = reinterpret_cast<PFNEGLCREATECONTEXTPROC>(load("eglCreateContext"));
  auto createPbuffer =
      reinterpret_cast<PFNEGLCREATEPBUFFERSURFACEPROC>(load("eglCreatePbufferSurface"));
  impl.eglMakeCurrent = reinterpret_cast<PFNEGLMAKECURRENTPROC>(load("eglMakeCurrent"));
  impl.eglDestroyContext = reinterpret_cast<PFNEGLDESTROYCONTEXTPROC>(load("eglDestroyContext"));
  impl.eglDestroySurface = reinterpret_cast<PFNEGLDESTROYSURFACEPROC>(load("eglDestroySurface"));
  impl.eglTerminate = reinterpret_cast<PFNEGLTERMINATEPROC>(load("eglTerminate"));
  if (!queryDevices || !getPlatformDisplay || !initialize || !chooseConfig || !bindApi ||
      !createContext || !createPbuffer || !impl.eglMakeCurrent)
    throw GlError("EGL lacks the device platform (EGL_EXT_device_enumeration)");

  constexpr int kMaxDevices = 16;
  EGLDeviceEXT devices[kMaxDevices];
  EGLint count = 0;
  if (!queryDevices(kMaxDevices, devices, &count) || count == 0)
    throw GlError("EGL found no device");
  const int r =
      spec.color == ColorFormat::kRgba8 ? 8 : (spec.color == ColorFormat::kRgba16 ? 16 : 32);
  const EGLint configAttribs[] = {EGL_SURFACE_TYPE,
                                  EGL_PBUFFER_BIT,
                                  EGL_RED_SIZE,
                                  8,
                                  EGL_GREEN_SIZE,
                                  8,
                                  EGL_BLUE_SIZE,
                                  8,
                                  EGL_ALPHA_SIZE,
                                  8,
                                  EGL_DEPTH_SIZE,
                                  kDepthBits,
                                  EGL_STENCIL_SIZE,
                                  kStencilBits,
                                  EGL_RENDERABLE_TYPE,
                                  EGL_OPENGL_BIT,
                                  EGL_NONE};
  (void)r;  // DEVIATION (EGL): pbuffer configs are 8-bit; higher precision goes through FBOs.
  for (EGLint i = 0; i < count; ++i) {
    EGLDisplay display = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
    if (display == EGL_NO_DISPLAY) continue;
    EGLint major = 0, minor = 0;
    if (!initialize(display, &major, &minor)) continue;
    EGLConfig config;
    EGLint nConfigs = 0;
    if (!chooseConfig(display, configAttribs, &config, 1, &nConfigs) || nConfigs == 0) continue;
    bindApi(EGL_OPENGL_API);
    const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                     4,
                                     EGL_CONTEXT_MINOR_VERSION,
                                     5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     spec.profile == Profile::kCore
                                         ? EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT
                                         : EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT,
                                     EGL_NONE};
    EGLContext context = createContext(display, config, EGL_NO_CONTEXT, contextAttribs);
    if (context == EGL_NO_CONTEXT) continue;
    const EGLint pbufferAttribs[] = {EGL_WIDTH, spec.width, EGL_HEIGHT, spec.height, EGL_NONE};
    EGLSurface surface = createPbuffer(display, config, pbufferAttribs);
    if (surface == EGL_NO_SURFACE) {
      impl.eglDestroyContext(display, context);
      continue;
    }
    impl.eglDisplay = display;
    impl.eglContext = context;
    impl.eglSurface = surface;
    return;
  }
  throw GlError("EGL could not create a pbuffer context on any device");
}
#endif

}  // namespace

std::unique_ptr<GlContext> GlContext::create(const ContextSpec& spec) {
  constexpr int kMaxWindowSide = 16384;
  if (spec.width <= 0 || spec.height <= 0 || spec.width > kMaxWindowSide ||
      spec.height > kMaxWindowSide) {
    std::ostringstream s;
    s << "impossible window size " << spec.width << "x" << spec.height << " (1.." << kMaxWindowSide
      << " per side)";
    throw InputError(s.str());
  }
  std::unique_ptr<GlContext> ctx(new GlContext());
  ctx->spec_ = spec;
  ctx->impl_ = std::make_unique<Impl>();
  Impl& impl = *ctx->impl_;
  switch (spec.backend) {
    case Backend::kOsmesa:
      createDebianOsmesa(impl, spec);
      resolveGlDispatch(ctx->dispatch_, osmesaResolve, &impl);
      break;
    case Backend::kReference:
      createReferenceOsmesa(impl, spec);
      // Mesa 7.8's OSMesaGetProcAddress knows only extension entry points; core ones via dlsym.
      resolveGlDispatch(ctx->dispatch_, osmesaResolve, &impl);
      break;
    case Backend::kEgl:
#ifdef SHADOWLAB_HAVE_EGL
      createEgl(impl, spec);
      resolveGlDispatch(ctx->dispatch_, eglResolve, &impl);
      break;
#else
      throw GlError("this build has no EGL back end (EGL headers were not found)");
#endif
  }
  if (spec.backend != Backend::kEgl) {
    impl.colorType = osmesaType(spec.color);
    impl.colorBuffer.assign(size_t(spec.width) * spec.height * 4 * bytesPerChannel(spec.color), 0);
  }
  ctx->makeCurrent();
  ctx->queryCapabilities();
  return ctx;
}

GlContext::~GlContext() {
  if (tCurrentContext == this) {
    tCurrentContext = nullptr;
    setCurrentGl(nullptr);
  }
}

std::unique_ptr<GlContext> GlContext::adopt(const std::string& api, Backend backend, int width,
                                            int height, GlResolver resolve, void* user) {
  std::unique_ptr<GlContext> ctx(new GlContext());
  ctx->spec_.backend = backend;
  ctx->spec_.width = width;
  ctx->spec_.height = height;
  ctx->spec_.color = ColorFormat::kRgba8;  // window-system colour buffers of 8-bit channels
  ctx->impl_ = std::make_unique<Impl>();
  ctx->impl_->adoptedApi = api;
  resolveGlDispatch(ctx->dispatch_, resolve, user);
  const GlDispatch& gl = ctx->dispatch_;
  if (gl.GetString == nullptr || gl.GetIntegerv == nullptr || gl.GetError == nullptr ||
      gl.GetString(GL_VERSION) == nullptr)
    throw GlError("the " + api + " context answers no GL_VERSION");
  // OpenGL 3.2 (glspec32 6.1.5): GL_CONTEXT_PROFILE_MASK tells a core profile from a
  // compatibility one; earlier versions have only the compatibility behaviour.
  const std::string version = reinterpret_cast<const char*>(gl.GetString(GL_VERSION));
  constexpr int kProfileMaskSince = 32;  // OpenGL 3.2, as major * 10 + minor
  int major = 0, minor = 0;
  if (std::sscanf(version.c_str(), "%d.%d", &major, &minor) == 2 &&
      major * 10 + minor >= kProfileMaskSince) {
    GLint mask = 0;
    gl.GetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
    if ((mask & GL_CONTEXT_CORE_PROFILE_BIT) != 0) ctx->spec_.profile = Profile::kCore;
  }
  ctx->makeCurrent();
  ctx->queryCapabilities();
  return ctx;
}

void GlContext::setDrawableSize(int width, int height) {
  spec_.width = width;
  spec_.height = height;
}

void GlContext::clearCurrent() {
  tCurrentContext = nullptr;
  setCurrentGl(nullptr);
}

bool GlContext::adopted() const { return !impl_->adoptedApi.empty(); }

void GlContext::makeCurrent() {
  Impl& impl = *impl_;
  bool ok = false;
  if (!impl.adoptedApi.empty()) {
    ok = true;  // the program bound it; only the dispatch follows
  } else if (impl.osmesaContext != nullptr) {
    const bool alreadyCurrent = impl.osmesa.getCurrentContext != nullptr &&
                                impl.osmesa.getCurrentContext() == impl.osmesaContext;
    if (spec_.backend == Backend::kReference && impl.bound) {
      // Mesa 7.8.2's OSMesaMakeCurrent adds the colour renderbuffer again on every call and
      // aborts on its own assertion. The library keeps its own current context (it is loaded
      // privately), so a context that is still current there needs no call at all.
      if (!alreadyCurrent)
        throw GlError(
            "the reference GL (Mesa 7.8.2) cannot re-bind a context after another "
            "reference context was made current; use one reference context at a time");
      ok = true;
    } else {
      ok = impl.osmesa.makeCurrent(impl.osmesaContext, impl.colorBuffer.data(), impl.colorType,
                                   spec_.width, spec_.height);
      impl.bound = ok;
    }
  }
#ifdef SHADOWLAB_HAVE_EGL
  else if (impl.eglContext != EGL_NO_CONTEXT) {
    ok = impl.eglMakeCurrent(impl.eglDisplay, impl.eglSurface, impl.eglSurface, impl.eglContext);
  }
#endif
  if (!ok)
    throw GlError(std::string("cannot make the ") + backendName(spec_.backend) +
                  " context current");
  tCurrentContext = this;
  setCurrentGl(glFaultLayer(&dispatch_));  // the table itself, unless a fault is armed
}

GlContext* GlContext::current() { return tCurrentContext; }

void GlContext::setLayerState(const std::string& key, std::shared_ptr<void> state) {
  impl_->layers[key] = std::move(state);
}

void* GlContext::layerState(const std::string& key) const {
  auto it = impl_->layers.find(key);
  return it == impl_->layers.end() ? nullptr : it->second.get();
}

void GlContext::queryCapabilities() {
  const GlDispatch& gl = dispatch_;
  auto str = [&](GLenum e) {
    const GLubyte* s = gl.GetString(e);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string();
  };
  caps_.version = str(GL_VERSION);
  caps_.renderer = str(GL_RENDERER);
  if (spec_.profile == Profile::kCore && gl.GetStringi != nullptr) {
    GLint n = 0;
    gl.GetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; ++i)
      caps_.extensions.insert(reinterpret_cast<const char*>(gl.GetStringi(GL_EXTENSIONS, i)));
  } else {
    std::istringstream all(str(GL_EXTENSIONS));
    std::string e;
    while (all >> e) caps_.extensions.insert(e);
  }
  auto integer = [&](GLenum e) {
    GLint v = 0;
    gl.GetIntegerv(e, &v);
    return v;
  };
  caps_.maxTextureSize = integer(GL_MAX_TEXTURE_SIZE);
  GLint viewport[2] = {0, 0};
  gl.GetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  caps_.maxViewportWidth = viewport[0];
  if (spec_.profile == Profile::kCompatibility) {
    caps_.redBits = integer(GL_RED_BITS);
    caps_.alphaBits = integer(GL_ALPHA_BITS);
    caps_.accumRedBits = integer(GL_ACCUM_RED_BITS);
    caps_.depthBits = integer(GL_DEPTH_BITS);
    caps_.stencilBits = integer(GL_STENCIL_BITS);
  }
  while (gl.GetError() != GL_NO_ERROR) {}
}

}  // namespace sl
