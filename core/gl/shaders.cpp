#include "core/gl/shaders.h"

#include <sstream>

#include "core/base/errors.h"
#include "core/gl/gl_objects.h"
#include "core/gl/gl_trace.h"

namespace sl {
using namespace sl::gl;

const std::string& shaderSource(const std::string& file) {
  const auto& all = embeddedShaders();
  auto it = all.find(file);
  if (it == all.end()) throw GlError("no shader " + file + " in this build");
  return it->second;
}

std::string preprocessShader(const std::string& file, const ShaderDefines& defines) {
  const std::string& source = shaderSource(file);
  constexpr size_t kIncludeLength = sizeof("#include \"") - 1;
  std::string out;
  size_t pos = 0;
  while (pos < source.size()) {
    size_t eol = source.find('\n', pos);
    if (eol == std::string::npos) eol = source.size();
    const std::string line = source.substr(pos, eol - pos);
    if (line.rfind("#include \"", 0) == 0) {
      const size_t close = line.find('"', kIncludeLength);
      if (close == std::string::npos) throw GlError("bad #include in " + file);
      out += shaderSource(line.substr(kIncludeLength, close - kIncludeLength));
    } else {
      out += line;
    }
    out += '\n';
    pos = eol + 1;
  }
  if (!defines.empty()) {  // after the #version line, which must stay first
    const size_t eol = out.find('\n', out.find("#version"));
    std::string block;
    for (const auto& [name, value] : defines) block += "#define " + name + " " + value + "\n";
    out.insert(eol == std::string::npos ? out.size() : eol + 1, block);
  }
  return out;
}

namespace {
ShaderName compileStage(GLenum type, const std::string& file, const ShaderDefines& defines) {
  const std::string source = preprocessShader(file, defines);
  ShaderName shader(glCreateShader(type));
  const char* text = source.c_str();
  glShaderSource(shader.id(), 1, &text, nullptr);
  glCompileShader(shader.id());
  GLint ok = 0;
  glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
  if (!ok) {
    constexpr int kLogBytes = 4096;
    char log[kLogBytes] = {0};
    glGetShaderInfoLog(shader.id(), kLogBytes, nullptr, log);
    throw GlError("compiling " + file + ": " + log);
  }
  return shader;
}
}  // namespace

std::vector<ShaderPassMarker> shaderPassMarkers() {
  static const std::string kPass = "// @pass ", kReplaces = "// @replaces ", kEnd = "// @end ";
  auto trimmed = [](std::string line) {
    const size_t first = line.find_first_not_of(" \t");
    const size_t last = line.find_last_not_of(" \t\r");
    return first == std::string::npos ? std::string() : line.substr(first, last - first + 1);
  };
  std::vector<ShaderPassMarker> out;
  for (const auto& [file, source] : embeddedShaders()) {
    std::vector<ShaderPassMarker> open;  // innermost last
    std::istringstream lines(source);
    std::string raw;
    for (int number = 1; std::getline(lines, raw); ++number) {
      const std::string line = trimmed(raw);
      const std::string where = file + ":" + std::to_string(number);
      if (line.rfind(kPass, 0) == 0) {
        ShaderPassMarker m;
        const std::string rest = line.substr(kPass.size());
        const size_t colon = rest.find(':');
        m.id = trimmed(rest.substr(0, colon));
        m.title = colon == std::string::npos ? "" : trimmed(rest.substr(colon + 1));
        m.file = file;
        m.firstLine = number + 1;
        if (m.id.empty()) throw GlError(where + ": @pass without a name");
        open.push_back(m);
      } else if (line.rfind(kReplaces, 0) == 0) {
        if (open.empty() || open.back().firstLine != number)
          throw GlError(where + ": @replaces must follow its @pass line");
        std::istringstream words(line.substr(kReplaces.size()));
        std::string technique, id;
        words >> technique;
        size_t ids = 0;
        while (words >> id) {
          open.back().replaces.push_back({technique, id});
          ++ids;
        }
        // That `technique` is a legacy one is the registry's to say (tests/modern/
        // twin_pass_links_test.cpp); here only the line's form is checked.
        if (technique.empty() || ids == 0)
          throw GlError(where +
                        ": @replaces takes a legacy technique and its pass ids "
                        "(\"legacy.fast-pcf 6a 6b\"), got \"" +
                        line + "\"");
        open.back().firstLine = number + 1;
      } else if (line.rfind(kEnd, 0) == 0) {
        const std::string id = trimmed(line.substr(kEnd.size()));
        if (open.empty() || open.back().id != id)
          throw GlError(where + ": @end " + id + " without its @pass");
        ShaderPassMarker m = open.back();
        open.pop_back();
        m.lastLine = number - 1;
        if (m.lastLine < m.firstLine) throw GlError(where + ": @pass " + id + " marks no line");
        out.push_back(m);
      }
    }
    if (!open.empty())
      throw GlError(file + ":" + std::to_string(open.back().firstLine) + ": @pass " +
                    open.back().id + " has no @end");
  }
  return out;
}

GLuint compileShaderProgram(const std::string& vertexFile, const std::string& fragmentFile,
                            const ShaderDefines& defines, const std::string& geometryFile) {
  std::vector<ShaderName> stages;
  stages.push_back(compileStage(GL_VERTEX_SHADER, vertexFile, defines));
  stages.push_back(compileStage(GL_FRAGMENT_SHADER, fragmentFile, defines));
  if (!geometryFile.empty())
    stages.push_back(compileStage(GL_GEOMETRY_SHADER, geometryFile, defines));
  ProgramName program(glCreateProgram());
  for (const ShaderName& s : stages) glAttachShader(program.id(), s.id());
  glBindAttribLocation(program.id(), 0, "aPosition");
  glBindAttribLocation(program.id(), 1, "aNormal");
  glLinkProgram(program.id());
  stages.clear();  // the linked program keeps what it needs
  GLint ok = 0;
  glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  if (!ok) {
    constexpr int kLogBytes = 4096;
    char log[kLogBytes] = {0};
    glGetProgramInfoLog(program.id(), kLogBytes, nullptr, log);
    throw GlError("linking " + vertexFile + " + " + fragmentFile + ": " + log);
  }
  std::vector<std::string> files = {vertexFile, fragmentFile};
  if (!geometryFile.empty()) files.push_back(geometryFile);
  noteTracedProgram(program.id(), files);
  return program.release();  // the caller owns it (modern/gl_objects.h Program)
}

}  // namespace sl
