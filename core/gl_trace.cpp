// core/gl_trace.cpp — see gl_trace.h.
#include "core/gl_trace.h"

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

#include "core/errors.h"

// GCC 12 warns about string concatenations of the form `"text" + std::string(...)` at -O2
// (a false positive: GCC bug 105329); this file builds its lines that way.
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ == 12
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

namespace sl {
namespace {

// A colour table or kernel with more runs of equal values than this is summarised by its
// first and last values instead of listing every run (a ramp of 256 entries is 256 runs).
constexpr size_t kMaxListedRuns = 6;
// Values below this are small enums that collide (GL_ZERO = GL_POINTS = GL_FALSE = 0, GL_ONE
// = GL_LINES = 1 ...); arguments that take them are decoded by the call that knows which.
constexpr GLenum kFirstUnambiguousEnum = 0x0100;
constexpr int kMatrixSide = 4;

// Enum names by value; two names of one value are both given ("GL_COMPARE_REF_TO_TEXTURE =
// GL_COMPARE_R_TO_TEXTURE": OpenGL 3.0 renamed ARB_shadow's).
const std::unordered_map<GLenum, std::string>& enumNames() {
  static const std::unordered_map<GLenum, std::string> names = [] {
    std::unordered_map<GLenum, std::string> m;
#define SL_GL_ENUM(name)                                          \
  if (auto [it, added] = m.emplace(GLenum(name), #name); !added) \
    it->second += " = " #name;
#include "core/gl_enum_names.inc"
#undef SL_GL_ENUM
    return m;
  }();
  return names;
}

std::string hex(unsigned v) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%04X", v);
  return text;
}

std::string num(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

// An int argument that holds an enum (glTexParameteri's param, glTexGeni's mode).
std::string enumOrNumber(long long v) {
  if (v >= kFirstUnambiguousEnum) {
    auto it = enumNames().find(GLenum(v));
    if (it != enumNames().end()) return it->second;
  }
  return std::to_string(v);
}

std::string primitiveName(GLenum mode) {
  static const char* const kModes[] = {"GL_POINTS",     "GL_LINES",          "GL_LINE_LOOP",
                                       "GL_LINE_STRIP", "GL_TRIANGLES",      "GL_TRIANGLE_STRIP",
                                       "GL_TRIANGLE_FAN", "GL_QUADS",        "GL_QUAD_STRIP",
                                       "GL_POLYGON"};
  return mode < std::size(kModes) ? kModes[mode] : glEnumName(mode);
}

// Blend factors and stencil operations: GL_ZERO and GL_ONE are 0 and 1.
std::string factorName(GLenum f) {
  if (f == GL_ZERO) return "GL_ZERO";
  if (f == GL_ONE) return "GL_ONE";
  return glEnumName(f);
}

std::string clearMask(GLbitfield mask) {
  static const std::pair<GLbitfield, const char*> kBits[] = {
      {GL_COLOR_BUFFER_BIT, "colour"},
      {GL_DEPTH_BUFFER_BIT, "depth"},
      {GL_STENCIL_BUFFER_BIT, "stencil"},
      {GL_ACCUM_BUFFER_BIT, "accumulation"}};
  std::string out;
  for (const auto& [bit, word] : kBits)
    if (mask & bit) out += (out.empty() ? "" : " + ") + std::string(word);
  return out.empty() ? hex(mask) : out;
}

std::string tuple(const float* v, int n) {
  if (v == nullptr) return "(null)";
  std::string out = "(";
  for (int i = 0; i < n; ++i) out += (i ? ", " : "") + num(v[i]);
  return out + ")";
}
std::string tuple(const double* v, int n) {
  float f[16];
  for (int i = 0; i < n; ++i) f[i] = float(v[i]);
  return tuple(f, n);
}

// A column-major 4x4 matrix as rows: "[a b c d; e f g h; ...]".
std::string matrixRows(const float* m) {
  if (m == nullptr) return "(null)";
  std::string out = "[";
  for (int r = 0; r < kMatrixSide; ++r) {
    for (int c = 0; c < kMatrixSide; ++c)
      out += (c ? " " : "") + num(m[c * kMatrixSide + r]);
    out += r + 1 < kMatrixSide ? "; " : "]";
  }
  return out;
}
std::string matrixRows(const double* m) {
  float f[16];
  if (m == nullptr) return "(null)";
  for (int i = 0; i < 16; ++i) f[i] = float(m[i]);
  return matrixRows(f);
}
std::string transposedRows(const float* m) {
  if (m == nullptr) return "(null)";
  float t[16];
  for (int r = 0; r < kMatrixSide; ++r)
    for (int c = 0; c < kMatrixSide; ++c) t[c * kMatrixSide + r] = m[r * kMatrixSide + c];
  return matrixRows(t);
}

// Components of a pixel format, and their letters.
std::string formatLetters(GLenum format) {
  switch (format) {
    case GL_RGBA: return "RGBA";
    case GL_RGB: return "RGB";
    case GL_LUMINANCE: return "L";
    case GL_LUMINANCE_ALPHA: return "LA";
    case GL_ALPHA: return "A";
    case GL_RED: return "R";
    case GL_GREEN: return "G";
    case GL_BLUE: return "B";
    case GL_INTENSITY: return "I";
    default: return "";
  }
}

// The values of a pixel array of `count` elements of `format` (float or unsigned byte, the
// types the project passes); empty when the type is another one.
std::vector<std::vector<double>> components(const void* data, int count, GLenum format,
                                            GLenum type) {
  const size_t n = formatLetters(format).size();
  std::vector<std::vector<double>> out(n);
  if (data == nullptr || n == 0 || count <= 0) return {};
  for (int i = 0; i < count; ++i)
    for (size_t c = 0; c < n; ++c) {
      const size_t k = size_t(i) * n + c;
      if (type == GL_FLOAT)
        out[c].push_back(static_cast<const float*>(data)[k]);
      else if (type == GL_UNSIGNED_BYTE)
        out[c].push_back(static_cast<const unsigned char*>(data)[k] / 255.0);
      else
        return {};
    }
  return out;
}

// A value with its 8-bit code when it is one exactly ("0.251 (64/255)"): the colour table of
// Brabec & Seidel §3 Fig. 4 holds 0 or 64 in 8-bit terms, which a reader looks for.
constexpr double kEightBitMax = 255.0;
constexpr double kCodeTolerance = 1e-4;  // in codes: float rounding of k / 255, nothing else
std::string numWithCode(double v) {
  const double code = v * kEightBitMax;
  const double nearest = std::round(code);
  if (v <= 0.0 || v >= 1.0 || std::abs(code - nearest) > kCodeTolerance) return num(v);
  return num(v) + " (" + num(nearest) + "/255)";
}

// "0..63 -> 0, 64..255 -> 1", or the ends of a longer sequence.
std::string runs(const std::vector<double>& v) {
  std::vector<std::pair<size_t, size_t>> r;  // [first, last] of equal values
  for (size_t i = 0; i < v.size(); ++i) {
    if (!r.empty() && v[i] == v[r.back().second]) r.back().second = i;
    else r.push_back({i, i});
  }
  std::string out;
  if (r.size() > kMaxListedRuns) {
    const bool rising = std::is_sorted(v.begin(), v.end());
    return std::string(rising ? "rising" : "varying") + " in " + std::to_string(r.size()) +
           " steps, [0] = " + num(v.front()) + " .. [" + std::to_string(v.size() - 1) +
           "] = " + num(v.back());
  }
  for (const auto& [first, last] : r)
    out += (out.empty() ? "" : ", ") +
           (first == last ? std::to_string(first)
                          : std::to_string(first) + ".." + std::to_string(last)) +
           " -> " + numWithCode(v[first]);
  return out;
}

// Per component, equal components merged: "R=G=B: ...; A: ...".
template <class Describe>
std::string perComponent(const std::vector<std::vector<double>>& values, GLenum format,
                         Describe describe) {
  const std::string letters = formatLetters(format);
  std::vector<bool> done(values.size(), false);
  std::string out;
  for (size_t c = 0; c < values.size(); ++c) {
    if (done[c]) continue;
    std::string names(1, letters[c]);
    for (size_t d = c + 1; d < values.size(); ++d)
      if (!done[d] && values[d] == values[c]) {
        names += std::string("=") + letters[d];
        done[d] = true;
      }
    out += (out.empty() ? "" : "; ") + names + ": " + describe(values[c]);
  }
  return out;
}

// A kernel's values as a grid, top row first ("[0 0 0 / 0 0 0 / 1 0 0]"); GL stores row 0
// at the bottom (glspec121 3.6.3).
std::string grid(const std::vector<double>& v, int width, int height) {
  std::string out = "[";
  for (int row = height - 1; row >= 0; --row) {
    for (int col = 0; col < width; ++col) out += (col ? " " : "") + num(v[size_t(row * width + col)]);
    out += row > 0 ? " / " : "]";
  }
  return out;
}

// Which group an enable/disable of `cap` belongs to.
const char* capGroup(GLenum cap) {
  switch (cap) {
    case GL_TEXTURE_GEN_S: case GL_TEXTURE_GEN_T: case GL_TEXTURE_GEN_R: case GL_TEXTURE_GEN_Q:
      return "texgen";
    case GL_COLOR_TABLE: case GL_POST_CONVOLUTION_COLOR_TABLE:
    case GL_POST_COLOR_MATRIX_COLOR_TABLE:
      return "colour table";
    case GL_CONVOLUTION_1D: case GL_CONVOLUTION_2D: case GL_SEPARABLE_2D:
      return "convolution";
    case GL_HISTOGRAM: case GL_MINMAX: return "histogram";
    case GL_BLEND: return "blend";
    case GL_DEPTH_TEST: return "depth";
    case GL_ALPHA_TEST: return "alpha";
    case GL_STENCIL_TEST: return "stencil";
    case GL_POLYGON_OFFSET_FILL: case GL_POLYGON_OFFSET_LINE: case GL_POLYGON_OFFSET_POINT:
      return "polygon offset";
    case GL_TEXTURE_1D: case GL_TEXTURE_2D: case GL_TEXTURE_3D: return "texture";
    case GL_LIGHTING: case GL_COLOR_MATERIAL: case GL_NORMALIZE: return "lighting";
    default:
      if (cap >= GL_LIGHT0 && cap <= GL_LIGHT7) return "lighting";
      return "enable";
  }
}

// The group of a call not decoded one by one, from its name (without "gl"); nullptr: not
// state of a pass (queries, names, shader compilation, synchronisation).
const char* groupOf(std::string_view n) {
  auto starts = [&](std::string_view p) { return n.substr(0, p.size()) == p; };
  if (starts("Get") || starts("Is") || starts("Gen") || starts("Create") || starts("Delete") ||
      n == "CompileShader" || n == "ShaderSource" || n == "AttachShader" ||
      n == "LinkProgram" || n == "BindAttribLocation" || n == "BindFragDataLocation" ||
      n == "CheckFramebufferStatus" || n == "Finish" || n == "Flush" || n == "BeginQuery" ||
      n == "EndQuery")
    return nullptr;
  if (starts("TexGen")) return "texgen";
  if (starts("Blend")) return "blend";
  if (starts("Depth") || n == "ClearDepth") return "depth";
  if (n == "AlphaFunc") return "alpha";
  if (starts("Stencil") || n == "ClearStencil") return "stencil";
  if (starts("PolygonOffset")) return "polygon offset";
  if (starts("Accum") || n == "ClearAccum") return "accum";
  if (starts("ColorTable") || starts("ColorSubTable") || starts("CopyColor")) return "colour table";
  if (starts("Convolution") || starts("CopyConvolution") || n == "SeparableFilter2D")
    return "convolution";
  if (n == "Histogram" || n == "Minmax" || starts("Reset")) return "histogram";
  if (starts("Pixel") || starts("RasterPos") || starts("WindowPos") || n == "CopyPixels" ||
      n == "DrawPixels" || n == "ReadPixels" || n == "ReadnPixels" || starts("CopyTex") ||
      n == "ReadBuffer" || n == "ClampColor")
    return "pixels";
  if (starts("Tex") || starts("BindTexture") || n == "ActiveTexture" || n == "GenerateMipmap")
    return "texture";
  if (n == "UseProgram") return "program";
  if (starts("Uniform")) return "uniforms";
  if (starts("BindFramebuffer") || starts("Framebuffer") || starts("BindRenderbuffer") ||
      starts("RenderbufferStorage") || n == "DrawBuffer" || n == "DrawBuffers" ||
      n == "Viewport" || n == "BlitFramebuffer")
    return "target";
  if (starts("Clear")) return "clear";
  if (starts("Light") || starts("Material") || n == "ColorMaterial" || n == "ShadeModel")
    return "lighting";
  if (starts("PushAttrib") || starts("PopAttrib") || starts("PushClient") || starts("PopClient"))
    return "attrib stack";
  if (starts("Draw") || n == "CallList" || n == "Begin") return "draw";
  if (starts("Bind") || starts("Buffer") || starts("Vertex") || starts("EnableVertex") ||
      starts("DisableVertex") || starts("EnableClient") || starts("DisableClient") ||
      starts("ColorPointer") || starts("NormalPointer") || starts("TexCoordPointer") ||
      n == "ClientActiveTexture")
    return "vertex arrays";
  if (n == "ColorMask") return "raster";
  if (starts("Color") || starts("Normal") || starts("TexCoord") || starts("MultiTexCoord"))
    return "vertex";
  return "raster";
}

// One recorded line; draws are merged while they follow each other.
struct Line {
  std::string group;
  std::string text;
  std::string drawKey;  // non-empty for a draw: "glBegin(GL_TRIANGLES)"
  const char* unit = "";
  long long calls = 0;
  long long count = 0;
  int repeat = 1;
  bool objects = false;  // a scene loop folded into this draw (foldedObjects)
};

std::string finished(const Line& l) {
  if (l.drawKey.empty()) return l.repeat > 1 ? l.text + " (x" + std::to_string(l.repeat) + ")" : l.text;
  const bool begin = l.drawKey.rfind("glBegin", 0) == 0;
  std::string out = l.drawKey;
  if (l.calls > 1)
    out += " x " + std::to_string(l.calls) + (begin || l.objects ? " objects" : " calls");
  if (*l.unit) out += ", " + std::to_string(l.count) + " " + l.unit;
  if (l.objects) out += " (a scene loop: each object with its own material and model matrix)";
  return out;
}

// Lines that only prepare the next object of a scene loop: its colour, material, model matrix,
// vertex pointers and uniforms. Between two draws of one kind they are folded into the draw line.
bool perObject(const Line& l) {
  auto starts = [&](const char* p) { return l.text.rfind(p, 0) == 0; };
  return (l.group == "vertex" && starts("current colour")) ||
         (l.group == "lighting" && starts("material ")) || l.group == "uniforms" ||
         (l.group == "matrix" && (starts("modelview: push") || starts("modelview: pop") ||
                                  starts("modelview: multiply by"))) ||
         (l.group == "vertex arrays" &&
          (starts("glVertexPointer") || starts("glNormalPointer") ||
           starts("glTexCoordPointer") || starts("glBindVertexArray")));
}

// What a per-object line sets, without the value: "uModel", "modelview: multiply by".
std::string settingOf(const Line& l) {
  const size_t end = std::min({l.text.find(" = "), l.text.find('('), l.text.find(" [")});
  return l.text.substr(0, end);
}

// Folds a scene loop (per object: colour, material, model matrix, draw) into one draw line per
// kind: "glDrawElements(GL_TRIANGLES) x 6 objects, 23172 indices (each ...)". Before the first
// draw, only lines setting what the loop sets again between draws are folded.
std::vector<Line> foldedObjects(const std::vector<Line>& lines) {
  std::vector<Line> out;
  for (const Line& l : lines) {
    if (!l.drawKey.empty()) {
      size_t k = out.size();
      while (k > 0 && perObject(out[k - 1])) --k;
      if (k > 0 && out[k - 1].drawKey == l.drawKey && k < out.size()) {
        std::vector<std::string> settings;
        for (size_t i = k; i < out.size(); ++i) settings.push_back(settingOf(out[i]));
        Line folded = out[k - 1];
        folded.calls += l.calls;
        folded.count += l.count;
        folded.objects = true;
        out.resize(k - 1);
        size_t first = out.size();
        while (first > 0 && perObject(out[first - 1]) &&
               std::find(settings.begin(), settings.end(), settingOf(out[first - 1])) !=
                   settings.end())
          --first;
        out.resize(first);
        out.push_back(std::move(folded));
        continue;
      }
    } else if (!out.empty() && out.back().objects && perObject(l) &&
               (l.text.rfind("modelview: pop", 0) == 0 ||
                l.text.rfind("glBindVertexArray(0)", 0) == 0)) {
      continue;  // the loop's last matrix pop or vertex-array unbind
    }
    out.push_back(l);
  }
  return out;
}

// A line of a vertex-array setup: binding, filling and describing buffers for a later draw.
bool uploadLine(const Line& l) {
  auto starts = [&](const char* p) { return l.text.rfind(p, 0) == 0; };
  return l.group == "vertex arrays" && l.drawKey.empty() &&
         (starts("glBindVertexArray") || starts("glBindBuffer") || starts("glBufferData") ||
          starts("glBufferSubData") || starts("glVertexAttribPointer") ||
          starts("glVertexAttribIPointer") || starts("glEnableVertexAttribArray"));
}

// The byte count of a "glBufferData(target, bytes, ...)" line; 0 for any other line.
long long uploadedBytes(const Line& l) {
  if (l.text.rfind("glBufferData(", 0) != 0) return 0;
  const size_t comma = l.text.find(", ");
  return comma == std::string::npos ? 0 : std::atoll(l.text.c_str() + comma + 2);
}

// Folds the upload of a scene's meshes (every vertex array's buffers filled, attributes
// described: tens of lines a pass card would open with) into one line that says what it did:
// "mesh upload: 6 vertex arrays, 18 buffers, 1234 bytes". A single buffer stays as it is.
std::vector<Line> foldedUploads(const std::vector<Line>& lines) {
  constexpr int kMinBuffersToFold = 2;
  std::vector<Line> out;
  for (size_t i = 0; i < lines.size();) {
    size_t end = i;
    while (end < lines.size() && uploadLine(lines[end])) ++end;
    // The block ends at its last unbind (or last fill); a bind that follows is the next draw's.
    size_t last = i;
    int buffers = 0;
    long long bytes = 0;
    std::set<std::string> arrays;
    for (size_t k = i; k < end; ++k) {
      const std::string& t = lines[k].text;
      if (t.rfind("glBufferData(", 0) == 0) {
        buffers += lines[k].repeat;
        bytes += uploadedBytes(lines[k]) * lines[k].repeat;
        last = k;
      } else if (t.rfind("glBindVertexArray(0)", 0) == 0) {
        last = k;
      } else if (t.rfind("glBindVertexArray(", 0) == 0) {
        arrays.insert(t);
      } else if (t.rfind("glVertexAttrib", 0) == 0 || t.rfind("glEnableVertexAttrib", 0) == 0) {
        last = k;
      }
    }
    if (buffers < kMinBuffersToFold) {
      out.push_back(lines[i]);
      ++i;
      continue;
    }
    Line folded;
    folded.group = "vertex arrays";
    folded.text = "mesh upload: " + std::to_string(arrays.size()) + " vertex arrays, " +
                  std::to_string(buffers) + " buffers, " + std::to_string(bytes) +
                  " bytes (glBindVertexArray, glBufferData, glVertexAttribPointer per mesh)";
    out.push_back(std::move(folded));
    i = last + 1;
  }
  return out;
}

std::vector<GlStateLine> finished(const std::vector<Line>& lines) {
  std::vector<GlStateLine> out;
  for (const Line& l : foldedObjects(foldedUploads(lines))) out.push_back({l.group, finished(l)});
  return out;
}

}  // namespace

std::string glEnumName(GLenum value) {
  auto it = enumNames().find(value);
  return it == enumNames().end() || value < kFirstUnambiguousEnum ? hex(value) : it->second;
}

struct GlTrace::Impl {
  const GlDispatch* previous = nullptr;
  GlDispatch inner;   // the table the calls go to
  GlDispatch traced;  // the table current while tracing
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
    return "texture " + std::to_string(id) + (it == textureShape.end() ? "" : " (" + it->second + ")");
  }
  std::string boundName(GLenum target) const {
    return texture(boundTexture(target)) + " [" + glEnumName(target) + "]";
  }
  const char* matrixGroup() const { return matrixMode == GL_COLOR ? "colour matrix" : "matrix"; }
  std::string modeWord() const {
    switch (matrixMode) {
      case GL_MODELVIEW: return "modelview";
      case GL_PROJECTION: return "projection";
      case GL_TEXTURE: return "texture matrix (unit " + std::to_string(activeUnit - GL_TEXTURE0) + ")";
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
    case GL_SHININESS: case GL_SPOT_EXPONENT: case GL_SPOT_CUTOFF: case GL_CONSTANT_ATTENUATION:
    case GL_LINEAR_ATTENUATION: case GL_QUADRATIC_ATTENUATION:
      return 1;
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
  t.add("texgen", glEnumName(coord) + ": " + glEnumName(pname) + " = " + tuple(p, plane ? 4 : 1) +
                      " (" + unitTag(t) +
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
    case GL_TEXTURE_GEN_S: case GL_TEXTURE_GEN_T: case GL_TEXTURE_GEN_R: case GL_TEXTURE_GEN_Q:
    case GL_TEXTURE_1D: case GL_TEXTURE_2D: case GL_TEXTURE_3D:
      return true;
    default:
      return false;
  }
}
void enableLine(T& t, const char* verb, GLenum cap) {
  t.add(capGroup(cap), verb + glEnumName(cap) + (perUnitCap(cap) ? " (" + unitTag(t) + ")" : ""));
}
void record(T& t, e::Enable, GLenum cap) { enableLine(t, "enable ", cap); }
void record(T& t, e::Disable, GLenum cap) { enableLine(t, "disable ", cap); }

// ---- imaging subset ----
void colorTable(T& t, const char* call, GLenum target, GLsizei first, GLsizei count,
                GLenum format, GLenum type, const void* data, const std::string& internal) {
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
  std::string text = glEnumName(target) + " [" + glEnumName(internal) + "]: " +
                     std::to_string(w) + "x" + std::to_string(h) + " kernel (" +
                     glEnumName(format) + ", " + glEnumName(type) + ")";
  const auto values = components(data, w * h, format, type);
  if (!values.empty())
    text += ", rows top to bottom: " +
            perComponent(values, format, [&](const std::vector<double>& v) { return grid(v, w, h); });
  t.add("convolution", text);
}
void record(T& t, e::ConvolutionFilter1D, GLenum target, GLenum internal, GLsizei w,
            GLenum format, GLenum type, const void* data) {
  std::string text = glEnumName(target) + " [" + glEnumName(internal) + "]: " +
                     std::to_string(w) + " taps";
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
  t.add("convolution", glEnumName(target) + ": " + glEnumName(pname) + " = " +
                           (v ? enumOrNumber(v[0]) : "null"));
}
void record(T& t, e::ConvolutionParameterfv, GLenum target, GLenum pname, const GLfloat* v) {
  const bool one = pname == GL_CONVOLUTION_BORDER_MODE;
  t.add("convolution", glEnumName(target) + ": " + glEnumName(pname) + " = " + tuple(v, one ? 1 : 4));
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
  t.add("stencil", "glStencilOp(" + factorName(f) + ", " + factorName(zf) + ", " + factorName(zp) + ")");
}
void record(T& t, e::StencilOpSeparate, GLenum face, GLenum f, GLenum zf, GLenum zp) {
  t.add("stencil", "glStencilOpSeparate(" + glEnumName(face) + ", " + factorName(f) + ", " +
                       factorName(zf) + ", " + factorName(zp) + ")");
}

// ---- pixels ----
std::string size(GLsizei w, GLsizei h) { return std::to_string(w) + "x" + std::to_string(h); }
std::string at(GLint x, GLint y) { return "(" + std::to_string(x) + ", " + std::to_string(y) + ")"; }
void record(T& t, e::CopyPixels, GLint x, GLint y, GLsizei w, GLsizei h, GLenum type) {
  t.add("pixels", "glCopyPixels " + size(w, h) + " " + glEnumName(type) + " from " + at(x, y) +
                      " to the raster position (through the pixel transfer path)");
}
void record(T& t, e::DrawPixels, GLsizei w, GLsizei h, GLenum format, GLenum type, const void*) {
  t.add("pixels", "glDrawPixels " + size(w, h) + " " + glEnumName(format) + " " + glEnumName(type));
}
void record(T& t, e::ReadPixels, GLint x, GLint y, GLsizei w, GLsizei h, GLenum format,
            GLenum type, void*) {
  t.add("pixels", "glReadPixels " + size(w, h) + " at " + at(x, y) + " " + glEnumName(format) +
                      " " + glEnumName(type));
}
void record(T& t, e::CopyTexSubImage2D, GLenum target, GLint level, GLint xo, GLint yo, GLint x,
            GLint y, GLsizei w, GLsizei h) {
  t.add("pixels", "glCopyTexSubImage2D " + size(w, h) + " from the framebuffer at " + at(x, y) +
                      " into " + t.boundName(target) + " level " + std::to_string(level) +
                      " at " + at(xo, yo));
}
void record(T& t, e::CopyTexImage2D, GLenum target, GLint level, GLenum internal, GLint x,
            GLint y, GLsizei w, GLsizei h, GLint) {
  t.setShape(target, size(w, h) + " " + glEnumName(internal));
  t.add("pixels", "glCopyTexImage2D " + size(w, h) + " from the framebuffer at " + at(x, y) +
                      " into " + t.boundName(target) + " level " + std::to_string(level));
}
void record(T& t, e::CopyTexSubImage1D, GLenum target, GLint level, GLint xo, GLint x, GLint y,
            GLsizei w) {
  t.add("pixels", "glCopyTexSubImage1D " + std::to_string(w) + " texels from " + at(x, y) +
                      " into " + t.boundName(target) + " level " + std::to_string(level) +
                      " at " + std::to_string(xo));
}

// ---- textures ----
void record(T& t, e::ActiveTexture, GLenum unit) { t.activeUnit = unit; }
void record(T& t, e::BindTexture, GLenum target, GLuint id) {
  t.bound[{t.activeUnit, target}] = id;
  t.add("texture", "unit " + std::to_string(t.activeUnit - GL_TEXTURE0) + " " +
                       glEnumName(target) + " = " + t.texture(id));
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
void record(T& t, e::TexImage2D, GLenum target, GLint level, GLint internal, GLsizei w,
            GLsizei h, GLint, GLenum format, GLenum type, const void* data) {
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
void record(T& t, e::Uniform1fv, GLint l, GLsizei c, const GLfloat* v) { uniformArray(t, l, c, 1, v); }
void record(T& t, e::Uniform2fv, GLint l, GLsizei c, const GLfloat* v) { uniformArray(t, l, c, 2, v); }
void record(T& t, e::Uniform3fv, GLint l, GLsizei c, const GLfloat* v) { uniformArray(t, l, c, 3, v); }
void record(T& t, e::Uniform4fv, GLint l, GLsizei c, const GLfloat* v) { uniformArray(t, l, c, 4, v); }
void record(T& t, e::UniformMatrix4fv, GLint l, GLsizei c, GLboolean transpose, const GLfloat* v) {
  if (c == 1 && v != nullptr) uniform(t, l, "mat4 " + (transpose ? transposedRows(v) : matrixRows(v)));
  else uniform(t, l, std::to_string(c) + " mat4");
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
void record(T& t, e::FramebufferTexture2D, GLenum, GLenum point, GLenum, GLuint tex,
            GLint level) {
  const std::string what = t.texture(tex) + (level ? " level " + std::to_string(level) : "");
  t.attachments[t.drawFramebuffer][point] = what;
  t.add("target", "framebuffer " + std::to_string(t.drawFramebuffer) + ": " + glEnumName(point) +
                      " = " + what);
}
void record(T& t, e::FramebufferTextureLayer, GLenum, GLenum point, GLuint tex, GLint level,
            GLint layer) {
  t.add("target", "framebuffer " + std::to_string(t.drawFramebuffer) + ": " + glEnumName(point) + " = " + t.texture(tex) + " layer " + std::to_string(layer) +
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
  t.addDraw("glDrawArraysInstanced(" + primitiveName(mode) + ")", (long long)count * n,
            "vertices");
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
    if (t == nullptr) throw GlError("a traced GL entry point was called on a thread that is not tracing");
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
#define SL_GL(name)                                                                         \
  t.traced.name = t.inner.name == nullptr                                                   \
                      ? nullptr                                                             \
                      : &Traced<decltype(&::gl##name), gl::entry::name>::call;
#include "core/gl_functions.inc"
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
