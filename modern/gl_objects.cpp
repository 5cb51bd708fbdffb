#include "modern/gl_objects.h"

#include <glm/gtc/type_ptr.hpp>

#include "core/base/errors.h"
#include "core/gl/context.h"
#include "core/gl/shaders.h"

namespace sl::modern {
using namespace sl::gl;

Program::Program(const std::string& vertexFile, const std::string& fragmentFile,
                 const std::vector<std::pair<std::string, std::string>>& defines,
                 const std::string& geometryFile)
    : program_(compileShaderProgram(vertexFile, fragmentFile, defines, geometryFile)) {}

namespace {
struct ProgramCache {
  std::map<std::string, std::unique_ptr<Program>> programs;
  ProgramCache() = default;
  ProgramCache(const ProgramCache&) = delete;
  ProgramCache& operator=(const ProgramCache&) = delete;
  // Runs after the GL context is gone (GlContext::Impl destroys it first): nothing to delete.
  ~ProgramCache() {
    for (auto& entry : programs) entry.second->abandon();
  }
};
constexpr const char* kProgramCacheKey = "modern.programs";
}  // namespace

const Program& cachedProgram(const std::string& vertexFile, const std::string& fragmentFile,
                             const std::vector<std::pair<std::string, std::string>>& defines) {
  GlContext* context = GlContext::current();
  if (context == nullptr) throw GlError("no current GL context for " + fragmentFile);
  auto* cache = static_cast<ProgramCache*>(context->layerState(kProgramCacheKey));
  if (cache == nullptr) {
    auto fresh = std::make_shared<ProgramCache>();
    cache = fresh.get();
    context->setLayerState(kProgramCacheKey, fresh);
  }
  std::string key = vertexFile + "|" + fragmentFile;
  for (const auto& [k, v] : defines) key += "|" + k + "=" + v;
  auto it = cache->programs.find(key);
  if (it == cache->programs.end())
    it = cache->programs.emplace(key, std::make_unique<Program>(vertexFile, fragmentFile, defines))
             .first;
  return *it->second;
}

void Program::use() const { glUseProgram(program_.id()); }
GLint Program::uniform(const char* name) const { return glGetUniformLocation(program_.id(), name); }
void Program::set(const char* name, int v) const { glUniform1i(uniform(name), v); }
void Program::set(const char* name, float v) const { glUniform1f(uniform(name), v); }
void Program::set(const char* name, const glm::vec2& v) const {
  glUniform2fv(uniform(name), 1, glm::value_ptr(v));
}
void Program::set(const char* name, const glm::vec3& v) const {
  glUniform3fv(uniform(name), 1, glm::value_ptr(v));
}
void Program::set(const char* name, const glm::vec4& v) const {
  glUniform4fv(uniform(name), 1, glm::value_ptr(v));
}
void Program::set(const char* name, const glm::mat4& m) const {
  glUniformMatrix4fv(uniform(name), 1, GL_FALSE, glm::value_ptr(m));
}

GpuScene::GpuScene(const Scene& scene) : scene_(scene) {
  for (const Object& o : scene.objects) {
    GpuObject g;
    g.object = &o;
    g.vao = makeVertexArray();
    g.positions = makeBuffer();
    g.normals = makeBuffer();
    g.indices = makeBuffer();
    glBindVertexArray(g.vao.id());
    glBindBuffer(GL_ARRAY_BUFFER, g.positions.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(o.mesh->positions.size() * sizeof(glm::vec3)),
                 o.mesh->positions.data(), GL_STATIC_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    glEnableVertexAttribArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, g.normals.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(o.mesh->normals.size() * sizeof(glm::vec3)),
                 o.mesh->normals.data(), GL_STATIC_DRAW);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    glEnableVertexAttribArray(1);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.indices.id());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(o.mesh->indices.size() * sizeof(unsigned)),
                 o.mesh->indices.data(), GL_STATIC_DRAW);
    g.indexCount = GLsizei(o.mesh->indices.size());
    glBindVertexArray(0);
    objects_.push_back(std::move(g));
  }
  checkGl("upload scene");
}

void RenderTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
  glViewport(0, 0, width, height);
}

RenderTarget makeRenderTarget(int width, int height, const std::vector<GLenum>& colorFormats,
                              bool withDepth, GLenum depthFormat) {
  RenderTarget t;
  t.width = width;
  t.height = height;
  t.fbo = makeFramebuffer();
  glBindFramebuffer(GL_FRAMEBUFFER, t.fbo.id());
  std::vector<GLenum> drawBuffers;
  for (size_t i = 0; i < colorFormats.size(); ++i) {
    Texture tex = makeTexture();
    glBindTexture(GL_TEXTURE_2D, tex.id());
    glTexImage2D(GL_TEXTURE_2D, 0, GLint(colorFormats[i]), width, height, 0, GL_RGBA, GL_FLOAT,
                 nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    const GLenum attachment = GLenum(GL_COLOR_ATTACHMENT0 + i);
    glFramebufferTexture2D(GL_FRAMEBUFFER, attachment, GL_TEXTURE_2D, tex.id(), 0);
    drawBuffers.push_back(attachment);
    t.color.push_back(std::move(tex));
  }
  if (withDepth) {
    t.depth = makeTexture();
    glBindTexture(GL_TEXTURE_2D, t.depth.id());
    glTexImage2D(GL_TEXTURE_2D, 0, GLint(depthFormat), width, height, 0, GL_DEPTH_COMPONENT,
                 GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, t.depth.id(), 0);
  }
  if (drawBuffers.empty()) {
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
  } else {
    glDrawBuffers(GLsizei(drawBuffers.size()), drawBuffers.data());
  }
  glBindTexture(GL_TEXTURE_2D, 0);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw GlError("render target " + std::to_string(width) + "x" + std::to_string(height) +
                  " is incomplete");
  return t;
}

FullScreenTriangle::FullScreenTriangle() : vao_(makeVertexArray()) {}

void FullScreenTriangle::draw() const {
  glBindVertexArray(vao_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
}

}  // namespace sl::modern
