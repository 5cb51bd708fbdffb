// modern/gl_objects.h — RAII owners for GL objects (core/gl/gl_objects.h), shader programs from
// modern/shaders/*.glsl, and the scene uploaded into vertex buffers (module-internal header).
#pragma once

#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/gl/gl.h"
#include "core/gl/gl_objects.h"
#include "core/gl/winding.h"
#include "core/scene/scene.h"

namespace sl::modern {

// Shader sources and their compiler: core/gl/shaders.h (modern/shaders/*.glsl, embedded).

// The owners of GL names are core's (core/gl/gl_objects.h), one discipline with legacy_gl/; modern
// code names them as before.
using sl::Buffer;
using sl::deleteBuffer;
using sl::deleteFramebuffer;
using sl::deleteProgram;
using sl::deleteRenderbuffer;
using sl::deleteTexture;
using sl::deleteVertexArray;
using sl::Framebuffer;
using sl::GlName;
using sl::makeFramebuffer;
using sl::makeTexture;
using sl::Renderbuffer;
using sl::Texture;
using sl::VertexArray;

// A linked program from a vertex and a fragment shader file (and an optional geometry
// shader). `defines` are inserted after the #version line as "#define NAME VALUE".
class Program {
 public:
  Program(const std::string& vertexFile, const std::string& fragmentFile,
          const std::vector<std::pair<std::string, std::string>>& defines = {},
          const std::string& geometryFile = "");
  void use() const;
  GLint uniform(const char* name) const;  // -1 when the compiler removed it
  void set(const char* name, int v) const;
  void set(const char* name, float v) const;
  void set(const char* name, const glm::vec2& v) const;
  void set(const char* name, const glm::vec3& v) const;
  void set(const char* name, const glm::vec4& v) const;
  void set(const char* name, const glm::mat4& m) const;
  GLuint id() const { return program_.id(); }
  // Leaves the GL program to its context (used when the context itself is being destroyed).
  void abandon() { program_.release(); }

 private:
  GlName<deleteProgram> program_;
};

// The program for these files and defines, compiled and linked once per context and kept in the
// context's layer state: a technique rendered many times in one context (benchmarks) compiles
// its shaders in the first frame only. The context deletes the programs with itself.
const Program& cachedProgram(const std::string& vertexFile, const std::string& fragmentFile,
                             const std::vector<std::pair<std::string, std::string>>& defines = {});

// The scene in GPU buffers: one VAO per object (attribute 0 = position, 1 = normal).
struct GpuObject {
  VertexArray vao;
  Buffer positions;
  Buffer normals;
  Buffer indices;
  GLsizei indexCount = 0;
  const Object* object = nullptr;
};

class GpuScene {
 public:
  explicit GpuScene(const Scene& scene);
  const Scene& scene() const { return scene_; }
  const std::vector<GpuObject>& objects() const { return objects_; }
  // Draws each object for which `select` is true; `perObject` sets uniforms (model matrix...).
  template <class Select, class PerObject>
  void draw(Select select, PerObject perObject) const {
    for (const GpuObject& o : objects_) {
      if (!select(*o.object)) continue;
      perObject(*o.object);
      // gl_FrontFacing and culling see a mirrored object's outside as its front
      // (core/gl/winding.h).
      const FrontFaceForModel frontFace(o.object->model);
      gl::glBindVertexArray(o.vao.id());
      gl::glDrawElements(GL_TRIANGLES, o.indexCount, GL_UNSIGNED_INT, nullptr);
    }
    gl::glBindVertexArray(0);
  }

 private:
  const Scene& scene_;
  std::vector<GpuObject> objects_;
};

// An off-screen render target: colour textures (any number, for MRT) + a depth texture.
struct RenderTarget {
  Framebuffer fbo;
  std::vector<Texture> color;
  Texture depth;
  int width = 0;
  int height = 0;
  void bind() const;
};
// colorFormats: internal formats such as GL_RGBA8, GL_RGBA32F; empty = depth only.
RenderTarget makeRenderTarget(int width, int height, const std::vector<GLenum>& colorFormats,
                              bool withDepth = true, GLenum depthFormat = GL_DEPTH_COMPONENT24);

// An empty VAO for full-screen triangles generated in the vertex shader (gl_VertexID).
class FullScreenTriangle {
 public:
  FullScreenTriangle();
  void draw() const;

 private:
  VertexArray vao_;
};

// Reads back channel `c` of colour attachment `attachment` of the bound read framebuffer.
}  // namespace sl::modern
