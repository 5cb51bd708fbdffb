// interpose/imaging_preload.cpp — libshadowlab-imaging.so: the imaging subset of imaging/ for
// programs that were built against a plain libGL, by LD_PRELOAD.
//
// How it hooks in (docs/legacy-programs.md):
//   * The program's context: glXMakeCurrent, glXMakeContextCurrent, eglMakeCurrent and
//     OSMesaMakeCurrent are wrapped. After the real call binds a context, that context is
//     adopted once (sl::GlContext::adopt: its entry points resolved through the window
//     system's own GetProcAddress), imaging::install() puts the emulation on its dispatch
//     table when it lacks GL_ARB_imaging, and the wrapper is made current for this thread.
//     Each context keeps its own emulation state, each thread its own current context.
//   * The GL entry points the emulation replaces (the list is imaging/imaging.cpp's install())
//     are exported here under their GL names, so they come before libGL's in symbol lookup;
//     each calls the current adopted context's table entry (the emulation's or the driver's)
//     and, with no adopted context current, the next library's symbol (dlsym RTLD_NEXT).
//     Every other GL call never enters this library.
//   * glGetString / glGetStringi / glGetIntegerv(GL_NUM_EXTENSIONS) add GL_ARB_imaging;
//     glXGetProcAddress(ARB), eglGetProcAddress and OSMesaGetProcAddress hand out these
//     functions for the names exported here.
// Environment: SHADOWLAB_IMAGING=auto (default: emulate where the GL lacks ARB_imaging),
// emulate (also where it has it), off (pass everything through);
// SHADOWLAB_IMAGING_TRACE=FILE appends every glGetHistogram / glGetMinmax result as a JSON line;
// SHADOWLAB_IMAGING_VERBOSE=1 says on stderr what was chosen for each context.
#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include "core/base/errors.h"
#include "core/gl/context.h"
#include "imaging/imaging.h"
#include "imaging/internal.h"

// Window-system headers last: Xlib defines macros (None, Bool, Status) the others must not see.
#include <EGL/egl.h>
#include <GL/glx.h>
#include <GL/osmesa.h>

#define SL_EXPORT extern "C" __attribute__((visibility("default")))

namespace sl::interpose {
namespace {

constexpr const char* kImagingExtension = "GL_ARB_imaging";
constexpr const char* kLayerExtensions = "interpose.extensions";

enum class Policy { kAuto, kEmulate, kOff };

Policy policy() {
  static const Policy p = [] {
    const char* v = std::getenv("SHADOWLAB_IMAGING");
    if (v == nullptr || *v == 0 || std::strcmp(v, "auto") == 0) return Policy::kAuto;
    if (std::strcmp(v, "emulate") == 0) return Policy::kEmulate;
    if (std::strcmp(v, "off") == 0) return Policy::kOff;
    std::fprintf(stderr,
                 "libshadowlab-imaging: SHADOWLAB_IMAGING='%s' is not auto, emulate or off; "
                 "using auto\n",
                 v);
    return Policy::kAuto;
  }();
  return p;
}

// The definition that follows this library in the program's lookup order.
void* nextSymbol(const char* name) { return dlsym(RTLD_NEXT, name); }

template <class Fn>
Fn nextFn(const char* name) {
  return reinterpret_cast<Fn>(nextSymbol(name));
}

// Our exports by name (filled by the registrations below, read by the GetProcAddress hooks
// and by the resolver, which must never hand the emulation one of its own entry points).
std::map<std::string, void*>& exports() {
  static std::map<std::string, void*> table;
  return table;
}
struct Registration {
  Registration(const char* name, void* fn) { exports()[name] = fn; }
};

void* ownExport(const char* name) {
  auto it = exports().find(name);
  return it == exports().end() ? nullptr : it->second;
}

// ---- adopted contexts -------------------------------------------------------------------
enum class Api { kGlx, kEgl, kOsmesa };

struct Adopted {
  std::unique_ptr<GlContext> context;
  bool emulated = false;
  // How to ask the drawable's size (refreshDrawableSize), captured at make-current.
  Api api = Api::kGlx;
  void* display = nullptr;
  unsigned long drawable = 0;  // GLXDrawable or EGLSurface (as an integer)
};

std::mutex& registryMutex() {
  static std::mutex m;
  return m;
}
std::map<std::pair<int, const void*>, std::unique_ptr<Adopted>>& registry() {
  static std::map<std::pair<int, const void*>, std::unique_ptr<Adopted>> r;
  return r;
}
// Read on every wrapped call. initial-exec: the library is loaded at start-up (LD_PRELOAD), so
// its thread-local block is static and read without a call to __tls_get_addr.
__attribute__((tls_model("initial-exec"))) thread_local Adopted* tCurrent = nullptr;

struct ResolverInput {
  Api api;
};

// The driver's entry point for `name`: the window system's GetProcAddress first (the real
// one, found past this library), then the next library's symbol; never one of ours.
void* resolveDriver(const char* name, void* user) {
  const Api api = static_cast<ResolverInput*>(user)->api;
  void* p = nullptr;
  switch (api) {
    case Api::kGlx: {
      static auto real = nextFn<void (*(*)(const GLubyte*))()>("glXGetProcAddressARB");
      if (real != nullptr)
        p = reinterpret_cast<void*>(real(reinterpret_cast<const GLubyte*>(name)));
      break;
    }
    case Api::kEgl: {
      static auto real = nextFn<void (*(*)(const char*))()>("eglGetProcAddress");
      if (real != nullptr) p = reinterpret_cast<void*>(real(name));
      break;
    }
    case Api::kOsmesa: {
      static auto real = nextFn<OSMESAproc (*)(const char*)>("OSMesaGetProcAddress");
      if (real != nullptr) p = reinterpret_cast<void*>(real(name));
      break;
    }
  }
  if (p == nullptr || p == ownExport(name)) p = nextSymbol(name);
  if (p == ownExport(name)) p = nullptr;
  return p;
}

void refreshDrawableSize(Adopted& a);

// Called after the program's make-current succeeded with `handle` (null: released).
void bindContext(Api api, const void* handle, void* display, unsigned long drawable, int width,
                 int height) {
  if (policy() == Policy::kOff) return;
  if (handle == nullptr) {
    tCurrent = nullptr;
    GlContext::clearCurrent();
    return;
  }
  Adopted* a = nullptr;
  {
    std::lock_guard<std::mutex> lock(registryMutex());
    auto& slot = registry()[{int(api), handle}];
    if (!slot) {
      auto fresh = std::make_unique<Adopted>();
      ResolverInput input{api};
      static const char* kApiNames[] = {"glx", "egl", "osmesa"};
      try {
        fresh->context = GlContext::adopt(kApiNames[int(api)],
                                          api == Api::kOsmesa ? Backend::kOsmesa : Backend::kEgl,
                                          width, height, resolveDriver, &input);
        if (fresh->context->spec().profile == Profile::kCompatibility) {
          const imaging::Mode mode =
              policy() == Policy::kEmulate
                  ? imaging::install(*fresh->context, imaging::Mode::kEmulated)
                  : imaging::install(*fresh->context);
          fresh->emulated = mode == imaging::Mode::kEmulated;
        }
      } catch (const std::exception& e) {
        std::fprintf(stderr, "libshadowlab-imaging: context left to the driver: %s\n", e.what());
        fresh->context.reset();
      }
      if (std::getenv("SHADOWLAB_IMAGING_VERBOSE") != nullptr)
        std::fprintf(stderr, "libshadowlab-imaging: %s context %p: %s (accumulation bits %d)\n",
                     kApiNames[int(api)], handle,
                     !fresh->context   ? "left to the driver"
                     : fresh->emulated ? "imaging emulated"
                                       : "imaging native or core profile, passed through",
                     fresh->context ? fresh->context->caps().accumRedBits : 0);
      slot = std::move(fresh);
    }
    a = slot.get();
  }
  if (!a->context) {
    tCurrent = nullptr;
    GlContext::clearCurrent();
    return;
  }
  a->api = api;
  a->display = display;
  a->drawable = drawable;
  a->context->setDrawableSize(width, height);
  a->context->makeCurrent();
  tCurrent = a;
  refreshDrawableSize(*a);
}

void forgetContext(Api api, const void* handle) {
  std::lock_guard<std::mutex> lock(registryMutex());
  auto it = registry().find({int(api), handle});
  if (it == registry().end()) return;
  if (tCurrent == it->second.get()) {
    tCurrent = nullptr;
    GlContext::clearCurrent();
  }
  registry().erase(it);
}

// The window's size now (a window may be resized without a new make-current); the
// emulation's write-back and accumulation buffer follow it.
void refreshDrawableSize(Adopted& a) {
  int w = 0, h = 0;
  switch (a.api) {
    case Api::kGlx: {
      static auto query = nextFn<decltype(&::glXQueryDrawable)>("glXQueryDrawable");
      if (query == nullptr || a.display == nullptr || a.drawable == 0) return;
      unsigned int uw = 0, uh = 0;
      query(static_cast<Display*>(a.display), a.drawable, GLX_WIDTH, &uw);
      query(static_cast<Display*>(a.display), a.drawable, GLX_HEIGHT, &uh);
      w = int(uw);
      h = int(uh);
      break;
    }
    case Api::kEgl: {
      static auto query = nextFn<decltype(&::eglQuerySurface)>("eglQuerySurface");
      if (query == nullptr || a.drawable == 0) return;
      EGLint ew = 0, eh = 0;
      auto surface = reinterpret_cast<EGLSurface>(a.drawable);
      query(static_cast<EGLDisplay>(a.display), surface, EGL_WIDTH, &ew);
      query(static_cast<EGLDisplay>(a.display), surface, EGL_HEIGHT, &eh);
      w = ew;
      h = eh;
      break;
    }
    case Api::kOsmesa: return;  // OSMesaMakeCurrent gave the buffer's size
  }
  if (w > 0 && h > 0) a.context->setDrawableSize(w, h);
}

// The current adopted context's table (emulation entries where installed), or null.
inline GlDispatch* currentTable() {
  Adopted* a = tCurrent;
  return a != nullptr ? &a->context->dispatch() : nullptr;
}
inline bool currentEmulated() { return tCurrent != nullptr && tCurrent->emulated; }

// Stands in for an entry point that neither the context nor the next library has (a GL
// without the imaging names, a call before any context): does nothing, returns zero, as GL
// does for calls without a current context.
template <class Fn>
struct Absent;
template <class R, class... Args>
struct Absent<R (*)(Args...)> {
  static R call(Args...) { return R(); }
};

// The function to call for entry `Member`: the adopted context's, else the next library's.
template <auto Member, class Fn>
Fn route(const char* name) {
  if (GlDispatch* d = currentTable())
    if (Fn fn = d->*Member) return fn;
  static const Fn next = [name] {
    const Fn fn = nextFn<Fn>(name);
    return fn != nullptr ? fn : &Absent<Fn>::call;
  }();
  return next;
}

// Pixel paths read and write the window: bring its size up to date first.
inline void beforePixels() {
  if (Adopted* a = tCurrent; a != nullptr && a->emulated) refreshDrawableSize(*a);
}

// ---- trace of the values the program reads back --------------------------------------
// Components per group: the emulation's formats (imaging/pixel_memory.cpp), and GL_ABGR_EXT,
// which a native ARB_imaging driver may also return (EXT_abgr); the emulation refuses it.
int componentsOf(GLenum format) {
  return format == GL_ABGR_EXT ? 4 : imaging::detail::componentCount(format);
}

void traceReadBack(const char* call, GLenum format, GLenum type, int groups, const void* data) {
  static const char* path = std::getenv("SHADOWLAB_IMAGING_TRACE");
  if (path == nullptr || *path == 0 || data == nullptr) return;
  const int n = componentsOf(format) * groups;
  std::string line = std::string("{\"call\":\"") + call +
                     "\",\"format\":" + std::to_string(format) +
                     ",\"type\":" + std::to_string(type) + ",\"groups\":" + std::to_string(groups) +
                     ",\"values\":[";
  for (int i = 0; i < n; ++i) {
    char number[32];
    switch (type) {
      case GL_UNSIGNED_BYTE:
        std::snprintf(number, sizeof number, "%u", unsigned(static_cast<const GLubyte*>(data)[i]));
        break;
      case GL_BYTE:
        std::snprintf(number, sizeof number, "%d", int(static_cast<const GLbyte*>(data)[i]));
        break;
      case GL_UNSIGNED_SHORT:
        std::snprintf(number, sizeof number, "%u", unsigned(static_cast<const GLushort*>(data)[i]));
        break;
      case GL_SHORT:
        std::snprintf(number, sizeof number, "%d", int(static_cast<const GLshort*>(data)[i]));
        break;
      case GL_UNSIGNED_INT:
        std::snprintf(number, sizeof number, "%u", static_cast<const GLuint*>(data)[i]);
        break;
      case GL_INT:
        std::snprintf(number, sizeof number, "%d", static_cast<const GLint*>(data)[i]);
        break;
      case GL_FLOAT:
        std::snprintf(number, sizeof number, "%.9g", double(static_cast<const GLfloat*>(data)[i]));
        break;
      default: std::snprintf(number, sizeof number, "null"); break;
    }
    if (i > 0) line += ",";
    line += number;
  }
  line += "]}\n";
  static std::mutex m;
  std::lock_guard<std::mutex> lock(m);
  if (FILE* f = std::fopen(path, "a")) {
    std::fputs(line.c_str(), f);
    std::fclose(f);
  }
}

}  // namespace
}  // namespace sl::interpose

using sl::GlDispatch;
using sl::interpose::route;

// ---- the GL entry points the emulation replaces ------------------------------------------
// SL_ROUTE(ret, Name, (params), (args)): glName forwards to the current context's entry.
#define SL_ROUTE(ret, Name, params, args)                                         \
  SL_EXPORT ret gl##Name params {                                                 \
    return route<&GlDispatch::Name, decltype(GlDispatch::Name)>("gl" #Name) args; \
  }                                                                               \
  static sl::interpose::Registration sRegister##Name("gl" #Name,                  \
                                                     reinterpret_cast<void*>(&gl##Name));
// The same, after bringing the window size up to date (pixel paths).
#define SL_ROUTE_PIXELS(ret, Name, params, args)                                  \
  SL_EXPORT ret gl##Name params {                                                 \
    sl::interpose::beforePixels();                                                \
    return route<&GlDispatch::Name, decltype(GlDispatch::Name)>("gl" #Name) args; \
  }                                                                               \
  static sl::interpose::Registration sRegister##Name("gl" #Name,                  \
                                                     reinterpret_cast<void*>(&gl##Name));

// The imaging subset's own entry points (glspec121 3.6.3, 6.1.7-6.1.10).
SL_ROUTE(void, ColorTable, (GLenum t, GLenum i, GLsizei w, GLenum f, GLenum ty, const void* d),
         (t, i, w, f, ty, d))
SL_ROUTE(void, ColorSubTable, (GLenum t, GLsizei s, GLsizei c, GLenum f, GLenum ty, const void* d),
         (t, s, c, f, ty, d))
SL_ROUTE_PIXELS(void, CopyColorTable, (GLenum t, GLenum i, GLint x, GLint y, GLsizei w),
                (t, i, x, y, w))
SL_ROUTE_PIXELS(void, CopyColorSubTable, (GLenum t, GLsizei s, GLint x, GLint y, GLsizei w),
                (t, s, x, y, w))
SL_ROUTE(void, ColorTableParameterfv, (GLenum t, GLenum p, const GLfloat* v), (t, p, v))
SL_ROUTE(void, ColorTableParameteriv, (GLenum t, GLenum p, const GLint* v), (t, p, v))
SL_ROUTE(void, GetColorTable, (GLenum t, GLenum f, GLenum ty, void* d), (t, f, ty, d))
SL_ROUTE(void, GetColorTableParameterfv, (GLenum t, GLenum p, GLfloat* v), (t, p, v))
SL_ROUTE(void, GetColorTableParameteriv, (GLenum t, GLenum p, GLint* v), (t, p, v))
SL_ROUTE(void, ConvolutionFilter1D,
         (GLenum t, GLenum i, GLsizei w, GLenum f, GLenum ty, const void* d), (t, i, w, f, ty, d))
SL_ROUTE(void, ConvolutionFilter2D,
         (GLenum t, GLenum i, GLsizei w, GLsizei h, GLenum f, GLenum ty, const void* d),
         (t, i, w, h, f, ty, d))
SL_ROUTE(void, SeparableFilter2D,
         (GLenum t, GLenum i, GLsizei w, GLsizei h, GLenum f, GLenum ty, const void* r,
          const void* c),
         (t, i, w, h, f, ty, r, c))
SL_ROUTE_PIXELS(void, CopyConvolutionFilter1D, (GLenum t, GLenum i, GLint x, GLint y, GLsizei w),
                (t, i, x, y, w))
SL_ROUTE_PIXELS(void, CopyConvolutionFilter2D,
                (GLenum t, GLenum i, GLint x, GLint y, GLsizei w, GLsizei h), (t, i, x, y, w, h))
SL_ROUTE(void, ConvolutionParameterf, (GLenum t, GLenum p, GLfloat v), (t, p, v))
SL_ROUTE(void, ConvolutionParameterfv, (GLenum t, GLenum p, const GLfloat* v), (t, p, v))
SL_ROUTE(void, ConvolutionParameteri, (GLenum t, GLenum p, GLint v), (t, p, v))
SL_ROUTE(void, ConvolutionParameteriv, (GLenum t, GLenum p, const GLint* v), (t, p, v))
SL_ROUTE(void, GetConvolutionFilter, (GLenum t, GLenum f, GLenum ty, void* d), (t, f, ty, d))
SL_ROUTE(void, GetSeparableFilter, (GLenum t, GLenum f, GLenum ty, void* r, void* c, void* s),
         (t, f, ty, r, c, s))
SL_ROUTE(void, GetConvolutionParameterfv, (GLenum t, GLenum p, GLfloat* v), (t, p, v))
SL_ROUTE(void, GetConvolutionParameteriv, (GLenum t, GLenum p, GLint* v), (t, p, v))
SL_ROUTE(void, Histogram, (GLenum t, GLsizei w, GLenum i, GLboolean s), (t, w, i, s))
SL_ROUTE(void, Minmax, (GLenum t, GLenum i, GLboolean s), (t, i, s))
SL_ROUTE(void, ResetHistogram, (GLenum t), (t))
SL_ROUTE(void, ResetMinmax, (GLenum t), (t))
SL_ROUTE(void, GetHistogramParameterfv, (GLenum t, GLenum p, GLfloat* v), (t, p, v))
SL_ROUTE(void, GetHistogramParameteriv, (GLenum t, GLenum p, GLint* v), (t, p, v))
SL_ROUTE(void, GetMinmaxParameterfv, (GLenum t, GLenum p, GLfloat* v), (t, p, v))
SL_ROUTE(void, GetMinmaxParameteriv, (GLenum t, GLenum p, GLint* v), (t, p, v))

// glGetHistogram / glGetMinmax: the results also go to the trace when one is asked for.
SL_EXPORT void glGetHistogram(GLenum target, GLboolean reset, GLenum format, GLenum type,
                              void* values) {
  GLint width = 0;
  // Only a call that can succeed is traced: the width query must raise no error of its own,
  // and a failed call leaves `values` unwritten.
  const bool tracing = std::getenv("SHADOWLAB_IMAGING_TRACE") != nullptr && target == GL_HISTOGRAM;
  if (tracing)  // before a reset: the width the returned table has
    route<&GlDispatch::GetHistogramParameteriv, decltype(GlDispatch::GetHistogramParameteriv)>(
        "glGetHistogramParameteriv")(target, GL_HISTOGRAM_WIDTH, &width);
  route<&GlDispatch::GetHistogram, decltype(GlDispatch::GetHistogram)>("glGetHistogram")(
      target, reset, format, type, values);
  if (tracing) sl::interpose::traceReadBack("glGetHistogram", format, type, width, values);
}
static sl::interpose::Registration sRegisterGetHistogram("glGetHistogram",
                                                         reinterpret_cast<void*>(&glGetHistogram));
SL_EXPORT void glGetMinmax(GLenum target, GLboolean reset, GLenum format, GLenum type,
                           void* values) {
  route<&GlDispatch::GetMinmax, decltype(GlDispatch::GetMinmax)>("glGetMinmax")(
      target, reset, format, type, values);
  constexpr int kMinmaxGroups = 2;  // minimum then maximum (glspec121 6.1.10)
  if (target == GL_MINMAX)
    sl::interpose::traceReadBack("glGetMinmax", format, type, kMinmaxGroups, values);
}
static sl::interpose::Registration sRegisterGetMinmax("glGetMinmax",
                                                      reinterpret_cast<void*>(&glGetMinmax));

// Enables and queries of the imaging state (glspec121 tables 6.14-6.16).
SL_ROUTE(void, Enable, (GLenum c), (c))
SL_ROUTE(void, Disable, (GLenum c), (c))
SL_ROUTE(GLboolean, IsEnabled, (GLenum c), (c))
SL_ROUTE(void, GetFloatv, (GLenum p, GLfloat* v), (p, v))
SL_ROUTE(void, GetDoublev, (GLenum p, GLdouble* v), (p, v))
SL_ROUTE(void, GetBooleanv, (GLenum p, GLboolean* v), (p, v))
SL_ROUTE(void, PixelTransferf, (GLenum p, GLfloat v), (p, v))
SL_ROUTE(void, PixelTransferi, (GLenum p, GLint v), (p, v))
SL_ROUTE(GLenum, GetError, (), ())
SL_ROUTE(void, PushAttrib, (GLbitfield m), (m))
SL_ROUTE(void, PopAttrib, (), ())

// The matrix entries act on the color matrix stack in glMatrixMode(GL_COLOR) (3.6.3).
SL_ROUTE(void, MatrixMode, (GLenum m), (m))
SL_ROUTE(void, LoadIdentity, (), ())
SL_ROUTE(void, LoadMatrixf, (const GLfloat* m), (m))
SL_ROUTE(void, LoadMatrixd, (const GLdouble* m), (m))
SL_ROUTE(void, MultMatrixf, (const GLfloat* m), (m))
SL_ROUTE(void, MultMatrixd, (const GLdouble* m), (m))
SL_ROUTE(void, PushMatrix, (), ())
SL_ROUTE(void, PopMatrix, (), ())
SL_ROUTE(void, Scalef, (GLfloat x, GLfloat y, GLfloat z), (x, y, z))
SL_ROUTE(void, Scaled, (GLdouble x, GLdouble y, GLdouble z), (x, y, z))
SL_ROUTE(void, Translatef, (GLfloat x, GLfloat y, GLfloat z), (x, y, z))
SL_ROUTE(void, Translated, (GLdouble x, GLdouble y, GLdouble z), (x, y, z))
SL_ROUTE(void, Rotatef, (GLfloat a, GLfloat x, GLfloat y, GLfloat z), (a, x, y, z))
SL_ROUTE(void, Rotated, (GLdouble a, GLdouble x, GLdouble y, GLdouble z), (a, x, y, z))
SL_ROUTE(void, Ortho, (GLdouble l, GLdouble r, GLdouble b, GLdouble t, GLdouble n, GLdouble f),
         (l, r, b, t, n, f))
SL_ROUTE(void, Frustum, (GLdouble l, GLdouble r, GLdouble b, GLdouble t, GLdouble n, GLdouble f),
         (l, r, b, t, n, f))
SL_ROUTE(void, LoadTransposeMatrixf, (const GLfloat* m), (m))
SL_ROUTE(void, LoadTransposeMatrixd, (const GLdouble* m), (m))
SL_ROUTE(void, MultTransposeMatrixf, (const GLfloat* m), (m))
SL_ROUTE(void, MultTransposeMatrixd, (const GLdouble* m), (m))

// The pixel paths the pipeline of 3.6.5 changes (3.6.4, 4.3.2, 4.3.3, 3.8.1-3.8.2), and the
// accumulation buffer where the window has none (4.2.4).
SL_ROUTE_PIXELS(void, DrawPixels, (GLsizei w, GLsizei h, GLenum f, GLenum t, const void* d),
                (w, h, f, t, d))
SL_ROUTE_PIXELS(void, ReadPixels,
                (GLint x, GLint y, GLsizei w, GLsizei h, GLenum f, GLenum t, void* d),
                (x, y, w, h, f, t, d))
SL_ROUTE_PIXELS(void, CopyPixels, (GLint x, GLint y, GLsizei w, GLsizei h, GLenum t),
                (x, y, w, h, t))
SL_ROUTE_PIXELS(void, CopyTexImage1D,
                (GLenum t, GLint l, GLenum i, GLint x, GLint y, GLsizei w, GLint b),
                (t, l, i, x, y, w, b))
SL_ROUTE_PIXELS(void, CopyTexImage2D,
                (GLenum t, GLint l, GLenum i, GLint x, GLint y, GLsizei w, GLsizei h, GLint b),
                (t, l, i, x, y, w, h, b))
SL_ROUTE_PIXELS(void, CopyTexSubImage1D, (GLenum t, GLint l, GLint o, GLint x, GLint y, GLsizei w),
                (t, l, o, x, y, w))
SL_ROUTE_PIXELS(void, CopyTexSubImage2D,
                (GLenum t, GLint l, GLint ox, GLint oy, GLint x, GLint y, GLsizei w, GLsizei h),
                (t, l, ox, oy, x, y, w, h))
SL_ROUTE(void, TexImage1D,
         (GLenum t, GLint l, GLint i, GLsizei w, GLint b, GLenum f, GLenum ty, const void* d),
         (t, l, i, w, b, f, ty, d))
SL_ROUTE(void, TexImage2D,
         (GLenum t, GLint l, GLint i, GLsizei w, GLsizei h, GLint b, GLenum f, GLenum ty,
          const void* d),
         (t, l, i, w, h, b, f, ty, d))
SL_ROUTE(void, TexSubImage1D,
         (GLenum t, GLint l, GLint o, GLsizei w, GLenum f, GLenum ty, const void* d),
         (t, l, o, w, f, ty, d))
SL_ROUTE(void, TexSubImage2D,
         (GLenum t, GLint l, GLint ox, GLint oy, GLsizei w, GLsizei h, GLenum f, GLenum ty,
          const void* d),
         (t, l, ox, oy, w, h, f, ty, d))
SL_ROUTE_PIXELS(void, Accum, (GLenum o, GLfloat v), (o, v))
SL_ROUTE(void, ClearAccum, (GLfloat r, GLfloat g, GLfloat b, GLfloat a), (r, g, b, a))

SL_EXPORT void glClear(GLbitfield mask) {
  if ((mask & GL_ACCUM_BUFFER_BIT) != 0) sl::interpose::beforePixels();
  route<&GlDispatch::Clear, decltype(GlDispatch::Clear)>("glClear")(mask);
}
static sl::interpose::Registration sRegisterClear("glClear", reinterpret_cast<void*>(&glClear));

// ---- the extension strings ---------------------------------------------------------------
// glGetString(GL_EXTENSIONS) names GL_ARB_imaging on an emulated context (kept per context:
// the pointer GL returns stays valid while the context lives).
SL_EXPORT const GLubyte* glGetString(GLenum name) {
  const GLubyte* s =
      route<&GlDispatch::GetString, decltype(GlDispatch::GetString)>("glGetString")(name);
  if (name != GL_EXTENSIONS || s == nullptr || !sl::interpose::currentEmulated()) return s;
  sl::GlContext& c = *sl::interpose::tCurrent->context;
  auto* text = static_cast<std::string*>(c.layerState(sl::interpose::kLayerExtensions));
  if (text == nullptr) {
    auto made = std::make_shared<std::string>(reinterpret_cast<const char*>(s));
    if (made->find(sl::interpose::kImagingExtension) == std::string::npos) {
      if (!made->empty() && made->back() != ' ') *made += ' ';
      *made += sl::interpose::kImagingExtension;
    }
    text = made.get();
    c.setLayerState(sl::interpose::kLayerExtensions, made);
  }
  return reinterpret_cast<const GLubyte*>(text->c_str());
}
static sl::interpose::Registration sRegisterGetString("glGetString",
                                                      reinterpret_cast<void*>(&glGetString));

namespace sl::interpose {
namespace {
GLint driverExtensionCount() {
  GLint n = 0;
  // The driver's own answer: the emulation passes GL_NUM_EXTENSIONS through untouched.
  if (GlDispatch* d = currentTable()) d->GetIntegerv(GL_NUM_EXTENSIONS, &n);
  return n;
}
}  // namespace
}  // namespace sl::interpose

// glGetStringi(GL_EXTENSIONS, i): the emulated context has one more, at the end.
SL_EXPORT const GLubyte* glGetStringi(GLenum name, GLuint index) {
  if (name == GL_EXTENSIONS && sl::interpose::currentEmulated() &&
      GLint(index) == sl::interpose::driverExtensionCount())
    return reinterpret_cast<const GLubyte*>(sl::interpose::kImagingExtension);
  return route<&GlDispatch::GetStringi, decltype(GlDispatch::GetStringi)>("glGetStringi")(name,
                                                                                          index);
}
static sl::interpose::Registration sRegisterGetStringi("glGetStringi",
                                                       reinterpret_cast<void*>(&glGetStringi));

SL_EXPORT void glGetIntegerv(GLenum pname, GLint* v) {
  route<&GlDispatch::GetIntegerv, decltype(GlDispatch::GetIntegerv)>("glGetIntegerv")(pname, v);
  if (pname == GL_NUM_EXTENSIONS && sl::interpose::currentEmulated() && v != nullptr) *v += 1;
}
static sl::interpose::Registration sRegisterGetIntegerv("glGetIntegerv",
                                                        reinterpret_cast<void*>(&glGetIntegerv));

// ---- contexts ----------------------------------------------------------------------------
using sl::interpose::Api;
using sl::interpose::bindContext;
using sl::interpose::forgetContext;
using sl::interpose::nextFn;

SL_EXPORT Bool glXMakeCurrent(Display* dpy, GLXDrawable drawable, GLXContext ctx) {
  static auto real = nextFn<decltype(&::glXMakeCurrent)>("glXMakeCurrent");
  const Bool ok = real(dpy, drawable, ctx);
  if (ok) bindContext(Api::kGlx, ctx, dpy, drawable, 0, 0);
  return ok;
}

SL_EXPORT Bool glXMakeContextCurrent(Display* dpy, GLXDrawable draw, GLXDrawable read,
                                     GLXContext ctx) {
  static auto real = nextFn<decltype(&::glXMakeContextCurrent)>("glXMakeContextCurrent");
  const Bool ok = real(dpy, draw, read, ctx);
  if (ok) bindContext(Api::kGlx, ctx, dpy, draw, 0, 0);
  return ok;
}

SL_EXPORT void glXDestroyContext(Display* dpy, GLXContext ctx) {
  static auto real = nextFn<decltype(&::glXDestroyContext)>("glXDestroyContext");
  real(dpy, ctx);
  forgetContext(Api::kGlx, ctx);
}

SL_EXPORT EGLBoolean eglMakeCurrent(EGLDisplay dpy, EGLSurface draw, EGLSurface read,
                                    EGLContext ctx) {
  static auto real = nextFn<decltype(&::eglMakeCurrent)>("eglMakeCurrent");
  const EGLBoolean ok = real(dpy, draw, read, ctx);
  if (ok)
    bindContext(Api::kEgl, ctx == EGL_NO_CONTEXT ? nullptr : ctx, dpy,
                reinterpret_cast<unsigned long>(draw), 0, 0);
  return ok;
}

SL_EXPORT EGLBoolean eglDestroyContext(EGLDisplay dpy, EGLContext ctx) {
  static auto real = nextFn<decltype(&::eglDestroyContext)>("eglDestroyContext");
  const EGLBoolean ok = real(dpy, ctx);
  if (ok) forgetContext(Api::kEgl, ctx);
  return ok;
}

SL_EXPORT GLboolean OSMesaMakeCurrent(OSMesaContext ctx, void* buffer, GLenum type, GLsizei width,
                                      GLsizei height) {
  static auto real = nextFn<decltype(&::OSMesaMakeCurrent)>("OSMesaMakeCurrent");
  const GLboolean ok = real(ctx, buffer, type, width, height);
  if (ok) bindContext(Api::kOsmesa, ctx, nullptr, 0, width, height);
  return ok;
}

SL_EXPORT void OSMesaDestroyContext(OSMesaContext ctx) {
  static auto real = nextFn<decltype(&::OSMesaDestroyContext)>("OSMesaDestroyContext");
  real(ctx);
  forgetContext(Api::kOsmesa, ctx);
}

// ---- GetProcAddress: our entry points for the names exported above -----------------------
SL_EXPORT __GLXextFuncPtr glXGetProcAddressARB(const GLubyte* name) {
  if (void* own = sl::interpose::ownExport(reinterpret_cast<const char*>(name)))
    return reinterpret_cast<__GLXextFuncPtr>(own);
  static auto real = nextFn<decltype(&::glXGetProcAddressARB)>("glXGetProcAddressARB");
  return real(name);
}

SL_EXPORT __GLXextFuncPtr glXGetProcAddress(const GLubyte* name) {
  if (void* own = sl::interpose::ownExport(reinterpret_cast<const char*>(name)))
    return reinterpret_cast<__GLXextFuncPtr>(own);
  static auto real = nextFn<decltype(&::glXGetProcAddressARB)>("glXGetProcAddress");
  return real(name);
}

SL_EXPORT __eglMustCastToProperFunctionPointerType eglGetProcAddress(const char* name) {
  if (void* own = sl::interpose::ownExport(name))
    return reinterpret_cast<__eglMustCastToProperFunctionPointerType>(own);
  static auto real = nextFn<decltype(&::eglGetProcAddress)>("eglGetProcAddress");
  return real(name);
}

SL_EXPORT OSMESAproc OSMesaGetProcAddress(const char* name) {
  if (void* own = sl::interpose::ownExport(name)) return reinterpret_cast<OSMESAproc>(own);
  static auto real = nextFn<decltype(&::OSMesaGetProcAddress)>("OSMesaGetProcAddress");
  return real(name);
}

static sl::interpose::Registration sRegisterHooks[] = {
    {"glXMakeCurrent", reinterpret_cast<void*>(&glXMakeCurrent)},
    {"glXMakeContextCurrent", reinterpret_cast<void*>(&glXMakeContextCurrent)},
    {"glXDestroyContext", reinterpret_cast<void*>(&glXDestroyContext)},
    {"glXGetProcAddressARB", reinterpret_cast<void*>(&glXGetProcAddressARB)},
    {"glXGetProcAddress", reinterpret_cast<void*>(&glXGetProcAddress)},
    {"eglMakeCurrent", reinterpret_cast<void*>(&eglMakeCurrent)},
    {"eglDestroyContext", reinterpret_cast<void*>(&eglDestroyContext)},
    {"eglGetProcAddress", reinterpret_cast<void*>(&eglGetProcAddress)},
    {"OSMesaMakeCurrent", reinterpret_cast<void*>(&OSMesaMakeCurrent)},
    {"OSMesaDestroyContext", reinterpret_cast<void*>(&OSMesaDestroyContext)},
    {"OSMesaGetProcAddress", reinterpret_cast<void*>(&OSMesaGetProcAddress)},
};

// ---- dlsym: programs that load GL themselves ----------------------------------------------
// Loaders (waffle under piglit, glad, SDL) dlopen libGL / libEGL and look entry points up by
// handle, which never sees a preloaded library. For the names wrapped here, a lookup by handle
// answers ours. Lookups from shadowlab's own libraries (they ask libGL for the driver's
// functions by handle) and RTLD_DEFAULT / RTLD_NEXT lookups go to glibc's dlsym untouched.
// DEVIATION (dlsym(3)): an RTLD_NEXT lookup from another library is answered as if this
// library had asked (glibc takes the caller from the return address, which is now ours).
namespace sl::interpose {
namespace {
using DlsymFn = void* (*)(void*, const char*);
// Runs before any constructor of this library when a sanitizer runtime preloaded ahead of it
// looks its interceptors up (dlsym(RTLD_NEXT, "mmap") during its own start-up): no C++ static
// guard and no instrumentation on this path. The pointer is written once with one value.
DlsymFn gRealDlsym = nullptr;
__attribute__((no_sanitize("address", "undefined"))) DlsymFn realDlsym() {
  if (gRealDlsym == nullptr) {
    // glibc 2.34 moved dlsym into libc with a new version; older ones have only 2.2.5.
    void* p = dlvsym(RTLD_NEXT, "dlsym", "GLIBC_2.34");
    if (p == nullptr) p = dlvsym(RTLD_NEXT, "dlsym", "GLIBC_2.2.5");
    gRealDlsym = reinterpret_cast<DlsymFn>(p);
  }
  return gRealDlsym;
}

bool callerIsOurs(const void* returnAddress) {
  Dl_info info{};
  if (dladdr(returnAddress, &info) == 0 || info.dli_fname == nullptr) return false;
  return std::strstr(info.dli_fname, "libshadowlab-") != nullptr;
}
}  // namespace
}  // namespace sl::interpose

// Ours is answered only where the handle's own definition is the one our wrapper forwards to
// (the library the program's GL calls reach): a second GL opened privately beside it (a
// program comparing two implementations, as shadowlab's parity tests load Mesa 7.8.2) keeps
// its own entry points, which our wrappers could not forward to.
SL_EXPORT __attribute__((no_sanitize("address", "undefined"))) void* dlsym(void* handle,
                                                                           const char* name) {
  const sl::interpose::DlsymFn real = sl::interpose::realDlsym();
  if (handle == RTLD_NEXT || handle == RTLD_DEFAULT) return real(handle, name);
  void* theirs = real(handle, name);
  if (theirs == nullptr || sl::interpose::policy() == sl::interpose::Policy::kOff ||
      sl::interpose::callerIsOurs(__builtin_return_address(0)))
    return theirs;
  void* own = sl::interpose::ownExport(name);
  return own != nullptr && theirs == real(RTLD_NEXT, name) ? own : theirs;
}
