// core/gl/shaders.h — the GLSL of every module and one way to compile it.
//
// Shaders live beside the C++ that drives them: modern/shaders/, reference/shaders/,
// figures/shaders/ (*.glsl, one name space: file names are unique across the folders). The
// build embeds them (core/embed_shaders.cmake), so the program runs from any directory.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/gl/gl.h"

namespace sl {

using ShaderDefines = std::vector<std::pair<std::string, std::string>>;

// Every embedded shader, by file name ("scene.vert.glsl").
const std::map<std::string, std::string>& embeddedShaders();
// One shader's text; throws GlError naming the file when this build has no such shader.
const std::string& shaderSource(const std::string& file);
// The text GL receives: each line `#include "x.glsl"` replaced by that file (one level deep:
// included files hold shared functions such as the fixed-function lighting model), and
// `defines` inserted right after the #version line as "#define NAME VALUE".
std::string preprocessShader(const std::string& file, const ShaderDefines& defines = {});
// Compiles and links a program from embedded files (attribute 0 = aPosition, 1 = aNormal).
// Returns the program name (the caller owns it); throws GlError with the compiler's log.
GLuint compileShaderProgram(const std::string& vertexFile, const std::string& fragmentFile,
                            const ShaderDefines& defines = {},
                            const std::string& geometryFile = "");

// A pass of a modern technique marked in the shader source that does it:
//   // @pass ID: what the lines do (paper section)
//   // @replaces legacy.fast-pcf 2
//   // @replaces legacy.pcf 5a 5b
//   ... the GLSL of the pass ...
//   // @end ID
// One ID may be marked in several files (a vertex and a fragment stage) and several times in a
// file; @replaces lines (any number, right after @pass) name the legacy passes the lines replace:
// a legacy technique and one or more ids of its pass table (core/technique/pass_table.h), nothing
// else.
struct ShaderReplaces {
  std::string technique;  // "legacy.fast-pcf"
  std::string passId;     // "6a"
  bool operator==(const ShaderReplaces& o) const {
    return technique == o.technique && passId == o.passId;
  }
};
struct ShaderPassMarker {
  std::string id;
  std::string file;   // "fast_pcf_pack.frag.glsl"
  int firstLine = 0;  // the marked code, 1-based, without the marker lines
  int lastLine = 0;
  std::string title;                     // the text after "@pass ID:"
  std::vector<ShaderReplaces> replaces;  // in the order of the @replaces lines
};
// Every marker of every embedded shader, by file then line. Throws GlError naming the file and
// line of a marker without its @end, an @end without its @pass, an empty block, or an @replaces
// line that is not "TECHNIQUE ID [ID ...]" (the technique a legacy one: the registry checks it).
std::vector<ShaderPassMarker> shaderPassMarkers();

}  // namespace sl
