// reference/surface_buffer.cpp — pass 1 of both references: world position, normals and
// object index per camera pixel, from a core-profile GL pass into float render targets.
//
// The vertex transform is the one of modern/shaders/scene.vert.glsl (uModel, then
// uViewProjection from the same glm matrices), so GL rasterises the same fragments here as in
// every technique's camera pass. The module keeps its own GL owners and its shaders in
// reference/shaders/: the reference does not depend on modern/ (DESIGN.md "Layout").
#include "reference/surface_buffer.h"

#include <glm/gtc/type_ptr.hpp>
#include <string>

#include "core/errors.h"
#include "core/shaders.h"

namespace sl::reference {
using namespace sl::gl;

namespace {

constexpr int kAttachments = 3;

// RAII owners of the few GL names this pass creates.
struct GlObjects {
  GLuint program = 0;
  GLuint framebuffer = 0;
  GLuint textures[kAttachments + 1] = {0, 0, 0, 0};  // + depth
  std::vector<GLuint> vertexArrays, buffers;
  GlObjects() = default;
  GlObjects(const GlObjects&) = delete;
  GlObjects& operator=(const GlObjects&) = delete;
  ~GlObjects() {
    if (program) glDeleteProgram(program);
    if (framebuffer) glDeleteFramebuffers(1, &framebuffer);
    glDeleteTextures(kAttachments + 1, textures);
    if (!vertexArrays.empty())
      glDeleteVertexArrays(GLsizei(vertexArrays.size()), vertexArrays.data());
    if (!buffers.empty()) glDeleteBuffers(GLsizei(buffers.size()), buffers.data());
  }
};

// reference/shaders/surface_points.{vert,frag}.glsl (embedded, core/shaders.h).
void buildProgram(GlObjects& gl) {
  gl.program = compileShaderProgram("surface_points.vert.glsl", "surface_points.frag.glsl");
}

void buildTarget(GlObjects& gl, int width, int height) {
  glGenFramebuffers(1, &gl.framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, gl.framebuffer);
  glGenTextures(kAttachments + 1, gl.textures);
  GLenum drawBuffers[kAttachments];
  for (int i = 0; i <= kAttachments; ++i) {
    const bool depth = i == kAttachments;
    glBindTexture(GL_TEXTURE_2D, gl.textures[i]);
    glTexImage2D(GL_TEXTURE_2D, 0, depth ? GL_DEPTH_COMPONENT24 : GL_RGBA32F, width, height, 0,
                 depth ? GL_DEPTH_COMPONENT : GL_RGBA, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glFramebufferTexture2D(GL_FRAMEBUFFER,
                           depth ? GL_DEPTH_ATTACHMENT : GLenum(GL_COLOR_ATTACHMENT0 + i),
                           GL_TEXTURE_2D, gl.textures[i], 0);
    if (!depth) drawBuffers[i] = GLenum(GL_COLOR_ATTACHMENT0 + i);
  }
  glDrawBuffers(kAttachments, drawBuffers);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw GlError("reference surface pass: float render target incomplete");
}

void uploadAndDraw(GlObjects& gl, const Scene& scene) {
  const GLint model = glGetUniformLocation(gl.program, "uModel");
  const GLint objectId = glGetUniformLocation(gl.program, "uObjectId");
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const Mesh& mesh = *scene.objects[i].mesh;
    GLuint vao = 0, vbo[3] = {0, 0, 0};
    glGenVertexArrays(1, &vao);
    gl.vertexArrays.push_back(vao);
    glGenBuffers(3, vbo);
    gl.buffers.insert(gl.buffers.end(), vbo, vbo + 3);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, vbo[0]);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(mesh.positions.size() * sizeof(glm::vec3)),
                 mesh.positions.data(), GL_STATIC_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    glEnableVertexAttribArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, vbo[1]);
    std::vector<glm::vec3> normals = mesh.normals;
    normals.resize(mesh.positions.size(), glm::vec3(0, 1, 0));  // a mesh without normals
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(normals.size() * sizeof(glm::vec3)), normals.data(),
                 GL_STATIC_DRAW);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    glEnableVertexAttribArray(1);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, vbo[2]);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(unsigned)),
                 mesh.indices.data(), GL_STATIC_DRAW);
    glUniformMatrix4fv(model, 1, GL_FALSE, glm::value_ptr(scene.objects[i].model));
    glUniform1f(objectId, float(i + 1));
    glDrawElements(GL_TRIANGLES, GLsizei(mesh.indices.size()), GL_UNSIGNED_INT, nullptr);
  }
  glBindVertexArray(0);
}

std::vector<float> readAttachment(int attachment, int width, int height) {
  std::vector<float> data(size_t(width) * height * 4);
  glReadBuffer(GLenum(GL_COLOR_ATTACHMENT0 + attachment));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, data.data());
  return data;
}

}  // namespace

std::vector<SurfacePoint> rasteriseSurfacePoints(const Scene& scene, const RenderParams& params) {
  const int w = params.width, h = params.height;
  GlObjects gl;
  buildProgram(gl);
  buildTarget(gl, w, h);
  glViewport(0, 0, w, h);
  const float none[4] = {0, 0, 0, 0};
  for (int i = 0; i < kAttachments; ++i) glClearBufferfv(GL_COLOR, i, none);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  glUseProgram(gl.program);
  // The same matrix as modern/camera_pass.cpp cameraViewProjection().
  const glm::mat4 viewProjection =
      cameraProjection(scene.camera, float(w) / float(h)) * cameraView(scene.camera);
  glUniformMatrix4fv(glGetUniformLocation(gl.program, "uViewProjection"), 1, GL_FALSE,
                     glm::value_ptr(viewProjection));
  uploadAndDraw(gl, scene);
  const std::vector<float> position = readAttachment(0, w, h);
  const std::vector<float> shading = readAttachment(1, w, h);
  const std::vector<float> geometric = readAttachment(2, w, h);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glUseProgram(0);
  checkGl("reference surface pass");

  std::vector<SurfacePoint> points(size_t(w) * h);
  for (size_t p = 0; p < points.size(); ++p) {
    const float* pos = &position[p * 4];
    const int id = int(pos[3] + 0.5f) - 1;
    if (id < 0 || id >= int(scene.objects.size())) continue;
    SurfacePoint& s = points[p];
    s.object = id;
    s.position = {pos[0], pos[1], pos[2]};
    s.shadingNormal = {shading[p * 4], shading[p * 4 + 1], shading[p * 4 + 2]};
    s.geometricNormal = {geometric[p * 4], geometric[p * 4 + 1], geometric[p * 4 + 2]};
  }
  return points;
}

}  // namespace sl::reference
