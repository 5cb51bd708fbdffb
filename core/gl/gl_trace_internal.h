// core/gl/gl_trace_internal.h — what the three files of the GL trace share (core/gl/gl_trace.h is
// the interface): gl_trace_text.cpp turns arguments into readable text, gl_trace_lines.cpp folds
// the recorded lines of a pass (scene loops, uploads) and gl_trace.cpp records the calls.
#pragma once

#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/gl/gl.h"
#include "core/gl/gl_trace.h"

namespace sl::gl_trace_detail {

// Values below this are small enums that collide (GL_ZERO = GL_POINTS = GL_FALSE = 0, GL_ONE
// = GL_LINES = 1 ...); arguments that take them are decoded by the call that knows which.
constexpr GLenum kFirstUnambiguousEnum = 0x0100;

// ---- text of arguments (gl_trace_text.cpp) ----
// Enum names by value; two names of one value are both given.
const std::unordered_map<GLenum, std::string>& enumNames();
std::string hex(unsigned v);
std::string num(double v);
// A plane's or a matrix element's value: 6 significant digits.
std::string preciseNum(double v);
// An int argument that holds an enum (glTexParameteri's param, glTexGeni's mode).
std::string enumOrNumber(long long v);
std::string primitiveName(GLenum mode);
std::string factorName(GLenum f);
std::string clearMask(GLbitfield mask);
std::string tuple(const float* v, int n);
// A plane (a, b, c, d) with 6 significant digits.
std::string planeTuple(const float* v);
std::string tuple(const double* v, int n);
std::string matrixRows(const float* m);
std::string matrixRows(const double* m);
std::string transposedRows(const float* m);
// "0..63 -> 0, 64..255 -> 1", or the ends of a longer sequence.
std::string runs(const std::vector<double>& v);
std::string grid(const std::vector<double>& v, int width, int height);
// Which group an enable/disable of `cap` belongs to.
const char* capGroup(GLenum cap);
// The group of a call not decoded one by one, from its name (without "gl"); nullptr: not
// state of a pass.
const char* groupOf(std::string_view n);

// The component letters of a pixel format ("RGBA", "L").
std::string formatLetters(GLenum format);
// The values of a pixel array of `count` elements of `format` (float or unsigned byte, the
// types the project passes); empty when the type is another one.
std::vector<std::vector<double>> components(const void* data, int count, GLenum format,
                                            GLenum type);
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

// ---- the lines of a pass (gl_trace_lines.cpp) ----
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

// A pass's recorded lines as it shows them: scene loops and per-mesh uploads folded, repeats
// and draw counts written out.
std::vector<GlStateLine> finished(const std::vector<Line>& lines);

}  // namespace sl::gl_trace_detail
