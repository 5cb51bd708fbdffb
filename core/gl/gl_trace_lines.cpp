// core/gl/gl_trace_lines.cpp — the recorded lines of a pass as the dump shows them
// (gl_trace_internal.h): repeats counted, scene loops and per-mesh uploads folded into one line.
#include <algorithm>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/gl/gl_trace_internal.h"

// GCC 12 warns about string concatenations of the form `"text" + std::string(...)` at -O2
// (a false positive: GCC bug 105329); this file builds its lines that way.
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ == 12
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

namespace sl::gl_trace_detail {
namespace {

std::string finished(const Line& l) {
  if (l.drawKey.empty())
    return l.repeat > 1 ? l.text + " (x" + std::to_string(l.repeat) + ")" : l.text;
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
          (starts("glVertexPointer") || starts("glNormalPointer") || starts("glTexCoordPointer") ||
           starts("glBindVertexArray")));
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

}  // namespace

std::vector<GlStateLine> finished(const std::vector<Line>& lines) {
  std::vector<GlStateLine> out;
  for (const Line& l : foldedObjects(foldedUploads(lines))) out.push_back({l.group, finished(l)});
  return out;
}

}  // namespace sl::gl_trace_detail
