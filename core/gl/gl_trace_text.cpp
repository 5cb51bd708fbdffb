// core/gl/gl_trace_text.cpp — GL arguments as readable text for the trace (gl_trace_internal.h):
// enum names, numbers, tuples and matrices, colour-table runs, kernel grids, call groups.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string_view>
#include <unordered_map>
#include <utility>

#include "core/gl/gl_trace_internal.h"

// GCC 12 warns about string concatenations of the form `"text" + std::string(...)` at -O2
// (a false positive: GCC bug 105329); this file builds its lines that way.
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ == 12
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

namespace sl::gl_trace_detail {

// A colour table or kernel with more runs of equal values than this is summarised by its
// first and last values instead of listing every run (a ramp of 256 entries is 256 runs).
constexpr size_t kMaxListedRuns = 6;
constexpr int kMatrixSide = 4;
// Planes and matrices are printed with this many significant digits: enough to check a
// product of matrices on the card (Everitt's planes against bias x projection x view) to
// float precision, as a slide shows them.
constexpr int kPreciseDigits = 6;

// Enum names by value; two names of one value are both given ("GL_COMPARE_REF_TO_TEXTURE =
// GL_COMPARE_R_TO_TEXTURE": OpenGL 3.0 renamed ARB_shadow's).
const std::unordered_map<GLenum, std::string>& enumNames() {
  static const std::unordered_map<GLenum, std::string> names = [] {
    std::unordered_map<GLenum, std::string> m;
#define SL_GL_ENUM(name) \
  if (auto [it, added] = m.emplace(GLenum(name), #name); !added) it->second += " = " #name;
#include "core/gl/gl_enum_names.inc"
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

std::string preciseNum(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*g", kPreciseDigits, v);
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
  static const char* const kModes[] = {
      "GL_POINTS",         "GL_LINES",        "GL_LINE_LOOP", "GL_LINE_STRIP", "GL_TRIANGLES",
      "GL_TRIANGLE_STRIP", "GL_TRIANGLE_FAN", "GL_QUADS",     "GL_QUAD_STRIP", "GL_POLYGON"};
  return mode < std::size(kModes) ? kModes[mode] : glEnumName(mode);
}

// Blend factors and stencil operations: GL_ZERO and GL_ONE are 0 and 1.
std::string factorName(GLenum f) {
  if (f == GL_ZERO) return "GL_ZERO";
  if (f == GL_ONE) return "GL_ONE";
  return glEnumName(f);
}

std::string clearMask(GLbitfield mask) {
  static const std::pair<GLbitfield, const char*> kBits[] = {{GL_COLOR_BUFFER_BIT, "colour"},
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
std::string planeTuple(const float* v) {
  if (v == nullptr) return "(null)";
  std::string out = "(";
  for (int i = 0; i < kMatrixSide; ++i) out += (i ? ", " : "") + preciseNum(v[i]);
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
      out += (c ? " " : "") + preciseNum(m[c * kMatrixSide + r]);
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
    if (!r.empty() && v[i] == v[r.back().second])
      r.back().second = i;
    else
      r.push_back({i, i});
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

// A kernel's values as a grid, top row first ("[0 0 0 / 0 0 0 / 1 0 0]"); GL stores row 0
// at the bottom (glspec121 3.6.3).
std::string grid(const std::vector<double>& v, int width, int height) {
  std::string out = "[";
  for (int row = height - 1; row >= 0; --row) {
    for (int col = 0; col < width; ++col)
      out += (col ? " " : "") + num(v[size_t(row * width + col)]);
    out += row > 0 ? " / " : "]";
  }
  return out;
}

// Which group an enable/disable of `cap` belongs to.
const char* capGroup(GLenum cap) {
  switch (cap) {
    case GL_TEXTURE_GEN_S:
    case GL_TEXTURE_GEN_T:
    case GL_TEXTURE_GEN_R:
    case GL_TEXTURE_GEN_Q: return "texgen";
    case GL_COLOR_TABLE:
    case GL_POST_CONVOLUTION_COLOR_TABLE:
    case GL_POST_COLOR_MATRIX_COLOR_TABLE: return "colour table";
    case GL_CONVOLUTION_1D:
    case GL_CONVOLUTION_2D:
    case GL_SEPARABLE_2D: return "convolution";
    case GL_HISTOGRAM:
    case GL_MINMAX: return "histogram";
    case GL_BLEND: return "blend";
    case GL_DEPTH_TEST: return "depth";
    case GL_ALPHA_TEST: return "alpha";
    case GL_STENCIL_TEST: return "stencil";
    case GL_POLYGON_OFFSET_FILL:
    case GL_POLYGON_OFFSET_LINE:
    case GL_POLYGON_OFFSET_POINT: return "polygon offset";
    case GL_TEXTURE_1D:
    case GL_TEXTURE_2D:
    case GL_TEXTURE_3D: return "texture";
    case GL_LIGHTING:
    case GL_COLOR_MATERIAL:
    case GL_NORMALIZE: return "lighting";
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
      n == "CompileShader" || n == "ShaderSource" || n == "AttachShader" || n == "LinkProgram" ||
      n == "BindAttribLocation" || n == "BindFragDataLocation" || n == "CheckFramebufferStatus" ||
      n == "Finish" || n == "Flush" || n == "BeginQuery" || n == "EndQuery")
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
      starts("RenderbufferStorage") || n == "DrawBuffer" || n == "DrawBuffers" || n == "Viewport" ||
      n == "BlitFramebuffer")
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

}  // namespace sl::gl_trace_detail

namespace sl {

std::string glEnumName(GLenum value) {
  auto it = gl_trace_detail::enumNames().find(value);
  return it == gl_trace_detail::enumNames().end() || value < gl_trace_detail::kFirstUnambiguousEnum
             ? gl_trace_detail::hex(value)
             : it->second;
}

}  // namespace sl
