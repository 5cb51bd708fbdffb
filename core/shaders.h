// core/shaders.h — the GLSL of every module and one way to compile it.
//
// Shaders live beside the C++ that drives them: modern/shaders/, reference/shaders/,
// figures/shaders/ (*.glsl, one name space: file names are unique across the folders). The
// build embeds them (core/embed_shaders.cmake), so the program runs from any directory.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/gl.h"

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

}  // namespace sl
