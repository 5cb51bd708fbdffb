// core/gl/gl_trace.cpp — see gl_trace.h: the tracing dispatch table, one record() per decoded entry
// point, and the pass boundaries. Text of arguments: gl_trace_text.cpp; folding of a pass's
// lines: gl_trace_lines.cpp.
#include "core/gl/gl_trace.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <string_view>
#include <type_traits>
#include <unordered_map>
#include <utility>

#include "core/base/errors.h"
#include "core/gl/gl_trace_internal.h"

// GCC 12 warns about string concatenations of the form `"text" + std::string(...)` at -O2
// (a false positive: GCC bug 105329); this file builds its lines that way.
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ == 12
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

namespace sl {

using namespace gl_trace_detail;  // NOLINT: the trace's own helpers (gl_trace_internal.h)

struct GlTrace::Impl {
  const GlDispatch* previous = nullptr;
  GlDispatch inner;                         // the table the calls go to
  GlDispatch traced;                        // the table current while tracing
  std::vector<std::vector<Line>> stack{1};  // [0]: outside passes; one more per open pass
  std::vector<std::vector<Line>> setups;    // setup lines of each open pass
  int paused = 0;

  // State followed to make lines readable.
  GLenum matrixMode = GL_MODELVIEW;
  bool inBegin = false;
  GLenum beginMode = 0;
  long long beginVertices = 0;
  GLenum activeUnit = GL_TEXTURE0;
  std::map<std::pair<GLenum, GLenum>, GLuint> bound;  // (unit, target) -> texture
  std::map<GLuint, std::string> textureShape;         // texture -> "512x512 GL_RGBA8"
  std::map<GLuint, std::string> programFiles;         // program -> "a.vert.glsl + b.frag.glsl"
  std::map<std::pair<GLuint, GLint>, std::string> uniformNames;
  GLuint program = 0;
  std::map<GLuint, std::map<GLenum, std::string>> attachments;  // framebuffer -> attachments
  GLuint drawFramebuffer = 0;

  void add(const char* group, std::string text) {
    if (paused > 0 || group == nullptr) return;
    std::vector<Line>& lines = stack.back();
    if (!lines.empty() && lines.back().drawKey.empty() && lines.back().group == group &&
        lines.back().text == text) {
      ++lines.back().repeat;
      return;
    }
    Line l;
    l.group = group;
    l.text = std::move(text);
    lines.push_back(std::move(l));
  }
  void addDraw(std::string key, long long count, const char* unit) {
    if (paused > 0) return;
    std::vector<Line>& lines = stack.back();
    if (!lines.empty() && lines.back().drawKey == key) {
      ++lines.back().calls;
      lines.back().count += count;
      return;
    }
    Line l;
    l.group = "draw";
    l.drawKey = std::move(key);
    l.unit = unit;
    l.calls = 1;
    l.count = count;
    lines.push_back(std::move(l));
  }

  GLuint boundTexture(GLenum target) const {
    auto it = bound.find({activeUnit, target});
    return it == bound.end() ? 0 : it->second;
  }
  std::string texture(GLuint id) const {
    auto it = textureShape.find(id);
    return "texture " + std::to_string(id) +
           (it == textureShape.end() ? "" : " (" + it->second + ")");
  }
  std::string boundName(GLenum target) const {
    return texture(boundTexture(target)) + " [" + glEnumName(target) + "]";
  }
  const char* matrixGroup() const { return matrixMode == GL_COLOR ? "colour matrix" : "matrix"; }
  std::string modeWord() const {
    switch (matrixMode) {
      case GL_MODELVIEW: return "modelview";
      case GL_PROJECTION: return "projection";
      case GL_TEXTURE:
        return "texture matrix (unit " + std::to_string(activeUnit - GL_TEXTURE0) + ")";
      case GL_COLOR: return "colour matrix";
      default: return glEnumName(matrixMode);
    }
  }
  void matrix(const std::string& what) { add(matrixGroup(), modeWord() + ": " + what); }
  void setShape(GLenum target, std::string shape) {
    if (GLuint id = boundTexture(target)) textureShape[id] = std::move(shape);
  }
};

namespace {
thread_local GlTrace::Impl* tTracer = nullptr;

using T = GlTrace::Impl;
namespace e = gl::entry;

// ---- arguments of calls decoded generically ----
template <class A>
std::string argText(A a) {
  if constexpr (std::is_pointer_v<A>) {
    return a == nullptr ? "null" : "*";
  } else if constexpr (std::is_floating_point_v<A>) {
    return num(double(a));
  } else if constexpr (std::is_same_v<A, GLboolean>) {
    return a ? "GL_TRUE" : "GL_FALSE";
  } else if constexpr (std::is_same_v<A, GLenum>) {
    // GLenum and GLuint are one type: small values (object names) stay numbers.
    return a < kFirstUnambiguousEnum ? std::to_string(a) : glEnumName(a);
  } else {
    return std::to_string(a);
  }
}

template <class E, class... A>
void record(T& t, E, A... a) {
  const std::string_view name = std::string_view(E::kName).substr(2);
  const char* group = groupOf(name);
  if (group == nullptr) return;
  // Current attributes inside glBegin/glEnd are part of the draw.
  if (t.inBegin && (std::string_view(group) == "vertex")) return;
  std::string text = std::string(E::kName) + "(";
  bool first = true;
  ((text += (first ? "" : ", ") + argText(a), first = false), ...);
  t.add(group, text + ")");
}

template <class E, class R, class... A>
void after(T&, E, R, A...) {}

// ---- current attributes and lighting ----
void record(T& t, e::Color4fv, const GLfloat* v) {
  if (!t.inBegin) t.add("vertex", "current colour " + tuple(v, 4));
}
int lightValues(GLenum pname) {
  switch (pname) {
    case GL_SPOT_DIRECTION: return 3;
    case GL_SHININESS:
    case GL_SPOT_EXPONENT:
    case GL_SPOT_CUTOFF:
    case GL_CONSTANT_ATTENUATION:
    case GL_LINEAR_ATTENUATION:
    case GL_QUADRATIC_ATTENUATION: return 1;
    default: return 4;
  }
}
void record(T& t, e::Materialfv, GLenum face, GLenum pname, const GLfloat* v) {
  t.add("lighting", "material " + glEnumName(face) + " " + glEnumName(pname) + " = " +
                        tuple(v, lightValues(pname)));
}
void record(T& t, e::Materialf, GLenum face, GLenum pname, GLfloat v) {
  t.add("lighting", "material " + glEnumName(face) + " " + glEnumName(pname) + " = " + num(v));
}
void record(T& t, e::Lightfv, GLenum light, GLenum pname, const GLfloat* v) {
  t.add("lighting", glEnumName(light) + " " + glEnumName(pname) + " = " +
                        tuple(v, lightValues(pname)) +
                        (pname == GL_POSITION || pname == GL_SPOT_DIRECTION
                             ? " (object space, times the modelview of this moment)"
                             : ""));
}
void record(T& t, e::LightModelfv, GLenum pname, const GLfloat* v) {
  t.add("lighting", glEnumName(pname) + " = " + tuple(v, pname == GL_LIGHT_MODEL_AMBIENT ? 4 : 1));
}
void record(T& t, e::LightModeli, GLenum pname, GLint v) {
  t.add("lighting", glEnumName(pname) + " = " + enumOrNumber(v));
}

// ---- texgen ----
// Texgen state and the texture enables belong to the active texture unit: the lines say which.
std::string unitTag(const T& t) { return "unit " + std::to_string(t.activeUnit - GL_TEXTURE0); }
void record(T& t, e::TexGeni, GLenum coord, GLenum pname, GLint param) {
  t.add("texgen", glEnumName(coord) + ": " + glEnumName(pname) + " = " + enumOrNumber(param) +
                      " (" + unitTag(t) + ")");
}
void record(T& t, e::TexGenfv, GLenum coord, GLenum pname, const GLfloat* p) {
  const bool plane = pname == GL_EYE_PLANE || pname == GL_OBJECT_PLANE;
  t.add("texgen", glEnumName(coord) + ": " + glEnumName(pname) + " = " +
                      (plane ? planeTuple(p) : tuple(p, 1)) + " (" + unitTag(t) +
                      (pname == GL_EYE_PLANE ? "; given in object space, GL stores it times "
                                               "the inverse modelview of this moment)"
                                             : ")"));
}

// ---- matrices ----
void record(T& t, e::MatrixMode, GLenum mode) { t.matrixMode = mode; }
void record(T& t, e::LoadIdentity) { t.matrix("identity"); }
void record(T& t, e::LoadMatrixf, const GLfloat* m) { t.matrix("load " + matrixRows(m)); }
void record(T& t, e::LoadMatrixd, const GLdouble* m) { t.matrix("load " + matrixRows(m)); }
void record(T& t, e::MultMatrixf, const GLfloat* m) { t.matrix("multiply by " + matrixRows(m)); }
void record(T& t, e::MultMatrixd, const GLdouble* m) { t.matrix("multiply by " + matrixRows(m)); }
void record(T& t, e::LoadTransposeMatrixf, const GLfloat* m) {
  t.matrix("load " + transposedRows(m));
}
void record(T& t, e::MultTransposeMatrixf, const GLfloat* m) {
  t.matrix("multiply by " + transposedRows(m));
}
void record(T& t, e::PushMatrix) { t.matrix("push"); }
void record(T& t, e::PopMatrix) { t.matrix("pop"); }
void record(T& t, e::Translatef, GLfloat x, GLfloat y, GLfloat z) {
  t.matrix("translate " + tuple(std::vector<float>{x, y, z}.data(), 3));
}
void record(T& t, e::Translated, GLdouble x, GLdouble y, GLdouble z) {
  t.matrix("translate " + tuple(std::vector<double>{x, y, z}.data(), 3));
}
void record(T& t, e::Scalef, GLfloat x, GLfloat y, GLfloat z) {
  t.matrix("scale " + tuple(std::vector<float>{x, y, z}.data(), 3));
}
void record(T& t, e::Scaled, GLdouble x, GLdouble y, GLdouble z) {
  t.matrix("scale " + tuple(std::vector<double>{x, y, z}.data(), 3));
}
void record(T& t, e::Rotatef, GLfloat a, GLfloat x, GLfloat y, GLfloat z) {
  t.matrix("rotate " + num(a) + " deg about " + tuple(std::vector<float>{x, y, z}.data(), 3));
}
void record(T& t, e::Rotated, GLdouble a, GLdouble x, GLdouble y, GLdouble z) {
  t.matrix("rotate " + num(a) + " deg about " + tuple(std::vector<double>{x, y, z}.data(), 3));
}
void record(T& t, e::Ortho, GLdouble l, GLdouble r, GLdouble b, GLdouble tp, GLdouble n,
            GLdouble f) {
  t.matrix("ortho " + tuple(std::vector<double>{l, r, b, tp, n, f}.data(), 6));
}
void record(T& t, e::Frustum, GLdouble l, GLdouble r, GLdouble b, GLdouble tp, GLdouble n,
            GLdouble f) {
  t.matrix("frustum " + tuple(std::vector<double>{l, r, b, tp, n, f}.data(), 6));
}

// ---- enables ----
// The caps of a texture unit (texgen, texture targets) name the unit.
bool perUnitCap(GLenum cap) {
  switch (cap) {
    case GL_TEXTURE_GEN_S:
    case GL_TEXTURE_GEN_T:
    case GL_TEXTURE_GEN_R:
    case GL_TEXTURE_GEN_Q:
    case GL_TEXTURE_1D:
    case GL_TEXTURE_2D:
    case GL_TEXTURE_3D: return true;
    default: return false;
  }
}
void enableLine(T& t, const char* verb, GLenum cap) {
  t.add(capGroup(cap), verb + glEnumName(cap) + (perUnitCap(cap) ? " (" + unitTag(t) + ")" : ""));
}
void record(T& t, e::Enable, GLenum cap) { enableLine(t, "enable ", cap); }
void record(T& t, e::Disable, GLenum cap) { enableLine(t, "disable ", cap); }

// ---- imaging subset ----
void colorTable(T& t, const char* call, GLenum target, GLsizei first, GLsizei count, GLenum format,
                GLenum type, const void* data, const std::string& internal) {
  std::string text = glEnumName(target) + internal + ": " + call + " " + std::to_string(count) +
                     " entries" + (first ? " from " + std::to_string(first) : "") + " (" +
                     glEnumName(format) + ", " + glEnumName(type) + ")";
  const auto values = components(data, count, format, type);
  if (!values.empty()) text += ", " + perComponent(values, format, runs);
  t.add("colour table", text);
}
void record(T& t, e::ColorTable, GLenum target, GLenum internal, GLsizei width, GLenum format,
            GLenum type, const void* data) {
  colorTable(t, "glColorTable", target, 0, width, format, type, data,
             " [" + glEnumName(internal) + "]");
}
void record(T& t, e::ColorSubTable, GLenum target, GLsizei start, GLsizei count, GLenum format,
            GLenum type, const void* data) {
  colorTable(t, "glColorSubTable", target, start, count, format, type, data, "");
}
void record(T& t, e::ColorTableParameterfv, GLenum target, GLenum pname, const GLfloat* p) {
  t.add("colour table", glEnumName(target) + ": " + glEnumName(pname) + " = " + tuple(p, 4));
}
void record(T& t, e::ConvolutionFilter2D, GLenum target, GLenum internal, GLsizei w, GLsizei h,
            GLenum format, GLenum type, const void* data) {
  std::string text = glEnumName(target) + " [" + glEnumName(internal) + "]: " + std::to_string(w) +
                     "x" + std::to_string(h) + " kernel (" + glEnumName(format) + ", " +
                     glEnumName(type) + ")";
  const auto values = components(data, w * h, format, type);
  if (!values.empty())
    text +=
        ", rows top to bottom: " +
        perComponent(values, format, [&](const std::vector<double>& v) { return grid(v, w, h); });
  t.add("convolution", text);
}
void record(T& t, e::ConvolutionFilter1D, GLenum target, GLenum internal, GLsizei w, GLenum format,
            GLenum type, const void* data) {
  std::string text =
      glEnumName(target) + " [" + glEnumName(internal) + "]: " + std::to_string(w) + " taps";
  const auto values = components(data, w, format, type);
  if (!values.empty())
    text += ", " + perComponent(values, format,
                                [&](const std::vector<double>& v) { return grid(v, w, 1); });
  t.add("convolution", text);
}
void record(T& t, e::SeparableFilter2D, GLenum target, GLenum internal, GLsizei w, GLsizei h,
            GLenum format, GLenum type, const void* row, const void* column) {
  std::string text = glEnumName(target) + " [" + glEnumName(internal) + "]: separable " +
                     std::to_string(w) + "x" + std::to_string(h);
  const auto r = components(row, w, format, type), c = components(column, h, format, type);
  auto line = [&](const std::vector<double>& v) { return grid(v, int(v.size()), 1); };
  if (!r.empty()) text += ", row " + perComponent(r, format, line);
  if (!c.empty()) text += ", column " + perComponent(c, format, line);
  t.add("convolution", text);
}
void record(T& t, e::ConvolutionParameteri, GLenum target, GLenum pname, GLint v) {
  t.add("convolution", glEnumName(target) + ": " + glEnumName(pname) + " = " + enumOrNumber(v));
}
void record(T& t, e::ConvolutionParameteriv, GLenum target, GLenum pname, const GLint* v) {
  t.add("convolution",
        glEnumName(target) + ": " + glEnumName(pname) + " = " + (v ? enumOrNumber(v[0]) : "null"));
}
void record(T& t, e::ConvolutionParameterfv, GLenum target, GLenum pname, const GLfloat* v) {
  const bool one = pname == GL_CONVOLUTION_BORDER_MODE;
  t.add("convolution",
        glEnumName(target) + ": " + glEnumName(pname) + " = " + tuple(v, one ? 1 : 4));
}

// ---- blend, stencil ----
void record(T& t, e::BlendFunc, GLenum s, GLenum d) {
  t.add("blend", "glBlendFunc(" + factorName(s) + ", " + factorName(d) + ")");
}
void record(T& t, e::BlendFuncSeparate, GLenum s, GLenum d, GLenum sa, GLenum da) {
  t.add("blend", "glBlendFuncSeparate(" + factorName(s) + ", " + factorName(d) + ", " +
                     factorName(sa) + ", " + factorName(da) + ")");
}
void record(T& t, e::StencilOp, GLenum f, GLenum zf, GLenum zp) {
  t.add("stencil",
        "glStencilOp(" + factorName(f) + ", " + factorName(zf) + ", " + factorName(zp) + ")");
}
void record(T& t, e::StencilOpSeparate, GLenum face, GLenum f, GLenum zf, GLenum zp) {
  t.add("stencil", "glStencilOpSeparate(" + glEnumName(face) + ", " + factorName(f) + ", " +
                       factorName(zf) + ", " + factorName(zp) + ")");
}

// ---- pixels ----
std::string size(GLsizei w, GLsizei h) { return std::to_string(w) + "x" + std::to_string(h); }
std::string at(GLint x, GLint y) {
  return "(" + std::to_string(x) + ", " + std::to_string(y) + ")";
}
void record(T& t, e::CopyPixels, GLint x, GLint y, GLsizei w, GLsizei h, GLenum type) {
  t.add("pixels", "glCopyPixels " + size(w, h) + " " + glEnumName(type) + " from " + at(x, y) +
                      " to the raster position (through the pixel transfer path)");
}
void record(T& t, e::DrawPixels, GLsizei w, GLsizei h, GLenum format, GLenum type, const void*) {
  t.add("pixels", "glDrawPixels " + size(w, h) + " " + glEnumName(format) + " " + glEnumName(type));
}
void record(T& t, e::ReadPixels, GLint x, GLint y, GLsizei w, GLsizei h, GLenum format, GLenum type,
            void*) {
  t.add("pixels", "glReadPixels " + size(w, h) + " at " + at(x, y) + " " + glEnumName(format) +
                      " " + glEnumName(type));
}
void record(T& t, e::CopyTexSubImage2D, GLenum target, GLint level, GLint xo, GLint yo, GLint x,
            GLint y, GLsizei w, GLsizei h) {
  t.add("pixels", "glCopyTexSubImage2D " + size(w, h) + " from the framebuffer at " + at(x, y) +
                      " into " + t.boundName(target) + " level " + std::to_string(level) + " at " +
                      at(xo, yo));
}
void record(T& t, e::CopyTexImage2D, GLenum target, GLint level, GLenum internal, GLint x, GLint y,
            GLsizei w, GLsizei h, GLint) {
  t.setShape(target, size(w, h) + " " + glEnumName(internal));
  t.add("pixels", "glCopyTexImage2D " + size(w, h) + " from the framebuffer at " + at(x, y) +
                      " into " + t.boundName(target) + " level " + std::to_string(level));
}
void record(T& t, e::CopyTexSubImage1D, GLenum target, GLint level, GLint xo, GLint x, GLint y,
            GLsizei w) {
  t.add("pixels", "glCopyTexSubImage1D " + std::to_string(w) + " texels from " + at(x, y) +
                      " into " + t.boundName(target) + " level " + std::to_string(level) + " at " +
                      std::to_string(xo));
}

// ---- textures ----
void record(T& t, e::ActiveTexture, GLenum unit) { t.activeUnit = unit; }
void record(T& t, e::BindTexture, GLenum target, GLuint id) {
  t.bound[{t.activeUnit, target}] = id;
  t.add("texture", "unit " + std::to_string(t.activeUnit - GL_TEXTURE0) + " " + glEnumName(target) +
                       " = " + t.texture(id));
}
void record(T& t, e::TexParameteri, GLenum target, GLenum pname, GLint v) {
  t.add("texture", t.boundName(target) + ": " + glEnumName(pname) + " = " + enumOrNumber(v));
}
void record(T& t, e::TexParameterf, GLenum target, GLenum pname, GLfloat v) {
  const bool whole = v == std::floor(v) && v >= float(kFirstUnambiguousEnum);
  t.add("texture", t.boundName(target) + ": " + glEnumName(pname) + " = " +
                       (whole ? enumOrNumber((long long)v) : num(v)));
}
void record(T& t, e::TexParameterfv, GLenum target, GLenum pname, const GLfloat* v) {
  t.add("texture", t.boundName(target) + ": " + glEnumName(pname) + " = " +
                       tuple(v, pname == GL_TEXTURE_BORDER_COLOR ? 4 : 1));
}
void record(T& t, e::TexEnvi, GLenum target, GLenum pname, GLint v) {
  t.add("texture", glEnumName(target) + ": " + glEnumName(pname) + " = " + enumOrNumber(v));
}
void record(T& t, e::TexImage2D, GLenum target, GLint level, GLint internal, GLsizei w, GLsizei h,
            GLint, GLenum format, GLenum type, const void* data) {
  if (level == 0) t.setShape(target, size(w, h) + " " + enumOrNumber(internal));
  t.add("texture", t.boundName(target) + ": level " + std::to_string(level) + " " + size(w, h) +
                       " " + enumOrNumber(internal) +
                       (data ? " from " + glEnumName(format) + " " + glEnumName(type) : ", empty"));
}
void record(T& t, e::TexImage1D, GLenum target, GLint level, GLint internal, GLsizei w, GLint,
            GLenum format, GLenum type, const void* data) {
  std::string text = t.boundName(target) + ": level " + std::to_string(level) + ", " +
                     std::to_string(w) + " texels " + enumOrNumber(internal);
  const auto values = components(data, w, format, type);
  if (!values.empty()) text += ", " + perComponent(values, format, runs);
  if (level == 0) t.setShape(target, std::to_string(w) + " " + enumOrNumber(internal));
  t.add("texture", text);
}
void record(T& t, e::TexStorage2D, GLenum target, GLsizei levels, GLenum internal, GLsizei w,
            GLsizei h) {
  t.setShape(target, size(w, h) + " " + glEnumName(internal));
  t.add("texture", t.boundName(target) + ": storage " + std::to_string(levels) + " level(s)");
}
void record(T& t, e::TexStorage3D, GLenum target, GLsizei levels, GLenum internal, GLsizei w,
            GLsizei h, GLsizei d) {
  t.setShape(target, size(w, h) + "x" + std::to_string(d) + " " + glEnumName(internal));
  t.add("texture", t.boundName(target) + ": storage " + std::to_string(levels) + " level(s)");
}

// ---- programs and uniforms ----
void record(T& t, e::UseProgram, GLuint p) {
  t.program = p;
  auto it = t.programFiles.find(p);
  t.add("program", p == 0 ? "program 0 (fixed function)"
                          : "program " + std::to_string(p) +
                                (it == t.programFiles.end() ? "" : ": " + it->second));
}
void after(T& t, e::GetUniformLocation, GLint location, GLuint program, const GLchar* name) {
  if (location >= 0 && name != nullptr) t.uniformNames[{program, location}] = name;
}
std::string uniformName(const T& t, GLint location) {
  auto it = t.uniformNames.find({t.program, location});
  return it == t.uniformNames.end() ? "location " + std::to_string(location) : it->second;
}
void uniform(T& t, GLint location, const std::string& value) {
  if (location < 0) return;  // a uniform the compiler removed: no state changes
  t.add("uniforms", uniformName(t, location) + " = " + value);
}
void record(T& t, e::Uniform1i, GLint l, GLint v) { uniform(t, l, std::to_string(v)); }
void record(T& t, e::Uniform1f, GLint l, GLfloat v) { uniform(t, l, num(v)); }
void record(T& t, e::Uniform2f, GLint l, GLfloat x, GLfloat y) {
  uniform(t, l, tuple(std::vector<float>{x, y}.data(), 2));
}
void record(T& t, e::Uniform2i, GLint l, GLint x, GLint y) {
  uniform(t, l, "(" + std::to_string(x) + ", " + std::to_string(y) + ")");
}
void record(T& t, e::Uniform3f, GLint l, GLfloat x, GLfloat y, GLfloat z) {
  uniform(t, l, tuple(std::vector<float>{x, y, z}.data(), 3));
}
void record(T& t, e::Uniform4f, GLint l, GLfloat x, GLfloat y, GLfloat z, GLfloat w) {
  uniform(t, l, tuple(std::vector<float>{x, y, z, w}.data(), 4));
}
void uniformArray(T& t, GLint l, GLsizei count, int n, const GLfloat* v) {
  std::string text;
  for (GLsizei i = 0; i < count; ++i) text += (i ? " " : "") + tuple(v + i * n, n);
  uniform(t, l, count > 1 ? "[" + text + "]" : text);
}
void record(T& t, e::Uniform1fv, GLint l, GLsizei c, const GLfloat* v) {
  uniformArray(t, l, c, 1, v);
}
void record(T& t, e::Uniform2fv, GLint l, GLsizei c, const GLfloat* v) {
  uniformArray(t, l, c, 2, v);
}
void record(T& t, e::Uniform3fv, GLint l, GLsizei c, const GLfloat* v) {
  uniformArray(t, l, c, 3, v);
}
void record(T& t, e::Uniform4fv, GLint l, GLsizei c, const GLfloat* v) {
  uniformArray(t, l, c, 4, v);
}
void record(T& t, e::UniformMatrix4fv, GLint l, GLsizei c, GLboolean transpose, const GLfloat* v) {
  if (c == 1 && v != nullptr)
    uniform(t, l, "mat4 " + (transpose ? transposedRows(v) : matrixRows(v)));
  else
    uniform(t, l, std::to_string(c) + " mat4");
}

// ---- render targets ----
void record(T& t, e::BindFramebuffer, GLenum target, GLuint fb) {
  if (target != GL_READ_FRAMEBUFFER) t.drawFramebuffer = fb;
  std::string text = glEnumName(target) + " = " +
                     (fb == 0 ? std::string("the window") : "framebuffer " + std::to_string(fb));
  auto it = t.attachments.find(fb);
  if (fb != 0 && it != t.attachments.end()) {
    std::string list;
    for (const auto& [point, what] : it->second)
      list += (list.empty() ? "" : ", ") + glEnumName(point) + " = " + what;
    text += " (" + list + ")";
  }
  t.add("target", text);
}
void record(T& t, e::FramebufferTexture2D, GLenum, GLenum point, GLenum, GLuint tex, GLint level) {
  const std::string what = t.texture(tex) + (level ? " level " + std::to_string(level) : "");
  t.attachments[t.drawFramebuffer][point] = what;
  t.add("target", "framebuffer " + std::to_string(t.drawFramebuffer) + ": " + glEnumName(point) +
                      " = " + what);
}
void record(T& t, e::FramebufferTextureLayer, GLenum, GLenum point, GLuint tex, GLint level,
            GLint layer) {
  t.add("target", "framebuffer " + std::to_string(t.drawFramebuffer) + ": " + glEnumName(point) +
                      " = " + t.texture(tex) + " layer " + std::to_string(layer) +
                      (level ? " level " + std::to_string(level) : ""));
}
void record(T& t, e::DrawBuffers, GLsizei n, const GLenum* bufs) {
  std::string list;
  for (GLsizei i = 0; i < n && bufs; ++i) list += (i ? ", " : "") + factorName(bufs[i]);
  t.add("target", "draw buffers " + list);
}

// ---- draws ----
void record(T& t, e::Begin, GLenum mode) {
  t.inBegin = true;
  t.beginMode = mode;
  t.beginVertices = 0;
}
void record(T& t, e::End) {
  t.inBegin = false;
  t.addDraw("glBegin(" + primitiveName(t.beginMode) + ")", t.beginVertices, "vertices");
}
void record(T& t, e::Vertex2f, GLfloat, GLfloat) { ++t.beginVertices; }
void record(T& t, e::Vertex3f, GLfloat, GLfloat, GLfloat) { ++t.beginVertices; }
void record(T& t, e::Vertex3fv, const GLfloat*) { ++t.beginVertices; }
void record(T& t, e::Vertex4f, GLfloat, GLfloat, GLfloat, GLfloat) { ++t.beginVertices; }
void record(T& t, e::DrawArrays, GLenum mode, GLint, GLsizei count) {
  t.addDraw("glDrawArrays(" + primitiveName(mode) + ")", count, "vertices");
}
void record(T& t, e::DrawElements, GLenum mode, GLsizei count, GLenum, const void*) {
  t.addDraw("glDrawElements(" + primitiveName(mode) + ")", count, "indices");
}
void record(T& t, e::DrawArraysInstanced, GLenum mode, GLint, GLsizei count, GLsizei n) {
  t.addDraw("glDrawArraysInstanced(" + primitiveName(mode) + ")", (long long)count * n, "vertices");
}
void record(T& t, e::DrawElementsInstanced, GLenum mode, GLsizei count, GLenum, const void*,
            GLsizei n) {
  t.addDraw("glDrawElementsInstanced(" + primitiveName(mode) + ")", (long long)count * n,
            "indices");
}
void record(T& t, e::CallList, GLuint list) {
  t.addDraw("glCallList(" + std::to_string(list) + ")", 0, "");
}
void record(T& t, e::Clear, GLbitfield mask) { t.add("clear", "clear " + clearMask(mask)); }

// Forwards one entry point: records it, then calls the table the trace wraps.
template <class Fn, class Entry>
struct Traced;
template <class R, class... Args, class Entry>
struct Traced<R (*)(Args...), Entry> {
  static R call(Args... args) {
    T* t = tTracer;
    if (t == nullptr)
      throw GlError("a traced GL entry point was called on a thread that is not tracing");
    auto fn = t->inner.*Entry::kMember;
    if (fn == nullptr) gl::throwMissingEntryPoint(Entry::kName);
    record(*t, Entry{}, args...);
    if constexpr (std::is_void_v<R>) {
      fn(args...);
    } else {
      R result = fn(args...);
      after(*t, Entry{}, result, args...);
      return result;
    }
  }
};

}  // namespace

GlTrace::GlTrace() : impl_(std::make_unique<Impl>()) {
  if (tTracer != nullptr) throw GlError("a GL trace is already running on this thread");
  Impl& t = *impl_;
  t.previous = &currentGl();
  t.inner = *t.previous;
#define SL_GL(name) \
  t.traced.name =   \
      t.inner.name == nullptr ? nullptr : &Traced<decltype(&::gl##name), gl::entry::name>::call;
#include "core/gl/gl_functions.inc"
#undef SL_GL
  tTracer = &t;
  setCurrentGl(&t.traced);
}

GlTrace::~GlTrace() {
  tTracer = nullptr;
  setCurrentGl(impl_->previous);
}

bool glTraceActive() { return tTracer != nullptr; }

void beginTracedPass() {
  if (tTracer == nullptr) return;
  T& t = *tTracer;
  // Lines recorded outside any pass are the setup of the next; a pass inside a pass has none.
  t.setups.emplace_back();
  if (t.stack.size() == 1) std::swap(t.setups.back(), t.stack.back());
  t.stack.emplace_back();
}

TracedPass endTracedPass() {
  if (tTracer == nullptr || tTracer->stack.size() < 2) return {};
  T& t = *tTracer;
  TracedPass out{finished(t.setups.back()), finished(t.stack.back())};
  t.setups.pop_back();
  t.stack.pop_back();
  return out;
}

void noteTracedProgram(GLuint program, const std::vector<std::string>& files) {
  if (tTracer == nullptr) return;
  std::string list;
  for (const std::string& f : files) list += (list.empty() ? "" : " + ") + f;
  tTracer->programFiles[program] = list;
}

GlTracePause::GlTracePause() {
  if (tTracer != nullptr) ++tTracer->paused;
}
GlTracePause::~GlTracePause() {
  if (tTracer != nullptr) --tTracer->paused;
}

}  // namespace sl
