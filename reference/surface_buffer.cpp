// reference/surface_buffer.cpp — pass 1 of both references: world position, normals and
// object index per camera pixel, from a core-profile GL pass into float render targets.
//
// The vertex transform is the one of modern/shaders/scene.vert.glsl (uModel, then
// uViewProjection from the same glm matrices), so GL rasterises the same fragments here as in
// every technique's camera pass. Its GL names are held by core's owners (core/gl/gl_objects.h)
// and its shaders are its own, in reference/shaders/: the reference does not depend on modern/
// (docs/design.md, layering).
#include "reference/surface_buffer.h"

#include <glm/gtc/type_ptr.hpp>
#include <string>

#include "core/base/errors.h"
#include "core/gl/gl_objects.h"
#include "core/gl/shaders.h"
#include "core/gl/winding.h"

namespace sl::reference {
using namespace sl::gl;

constexpr int kSurfaceAttachments = 3;

// The GL names this pass creates, each in its owner (core/gl/gl_objects.h).
struct SurfaceGlObjects {
  ProgramName program;
  Framebuffer framebuffer;
  Texture textures[kSurfaceAttachments + 1];  // + depth
  std::vector<VertexArray> vertexArrays;
  std::vector<Buffer> buffers;  // three per object: positions, normals, indices
};

namespace {

constexpr int kAttachments = kSurfaceAttachments;

// reference/shaders/surface_points.{vert,frag}.glsl (embedded, core/gl/shaders.h).
void buildProgram(SurfaceGlObjects& gl) {
  gl.program =
      ProgramName(compileShaderProgram("surface_points.vert.glsl", "surface_points.frag.glsl"));
}

void buildTarget(SurfaceGlObjects& gl, int width, int height) {
  gl.framebuffer = makeFramebuffer();
  glBindFramebuffer(GL_FRAMEBUFFER, gl.framebuffer.id());
  for (Texture& texture : gl.textures) texture = makeTexture();
  GLenum drawBuffers[kAttachments];
  for (int i = 0; i <= kAttachments; ++i) {
    const bool depth = i == kAttachments;
    glBindTexture(GL_TEXTURE_2D, gl.textures[i].id());
    glTexImage2D(GL_TEXTURE_2D, 0, depth ? GL_DEPTH_COMPONENT24 : GL_RGBA32F, width, height, 0,
                 depth ? GL_DEPTH_COMPONENT : GL_RGBA, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glFramebufferTexture2D(GL_FRAMEBUFFER,
                           depth ? GL_DEPTH_ATTACHMENT : GLenum(GL_COLOR_ATTACHMENT0 + i),
                           GL_TEXTURE_2D, gl.textures[i].id(), 0);
    if (!depth) drawBuffers[i] = GLenum(GL_COLOR_ATTACHMENT0 + i);
  }
  glDrawBuffers(kAttachments, drawBuffers);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw GlError("reference surface pass: float render target incomplete");
}

// Uploads every object's positions, normals and indices once (one vertex array per object).
void upload(SurfaceGlObjects& gl, const Scene& scene) {
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const Mesh& mesh = *scene.objects[i].mesh;
    const GLuint vao = gl.vertexArrays.emplace_back(makeVertexArray()).id();
    GLuint vbo[3];
    for (GLuint& name : vbo) name = gl.buffers.emplace_back(makeBuffer()).id();
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
  }
  glBindVertexArray(0);
}

void draw(const SurfaceGlObjects& gl, const Scene& scene) {
  const GLint model = glGetUniformLocation(gl.program.id(), "uModel");
  const GLint objectId = glGetUniformLocation(gl.program.id(), "uObjectId");
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    glBindVertexArray(gl.vertexArrays[i].id());
    glUniformMatrix4fv(model, 1, GL_FALSE, glm::value_ptr(scene.objects[i].model));
    glUniform1f(objectId, float(i + 1));
    // The fragment shader turns the normals by gl_FrontFacing: a mirrored object's outside
    // must stay its front (core/gl/winding.h).
    const FrontFaceForModel frontFace(scene.objects[i].model);
    glDrawElements(GL_TRIANGLES, GLsizei(scene.objects[i].mesh->indices.size()), GL_UNSIGNED_INT,
                   nullptr);
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

struct SurfaceRasteriser::GlState {
  SurfaceGlObjects objects;
};

SurfaceRasteriser::SurfaceRasteriser(const Scene& scene, const RenderParams& params)
    : scene_(scene), width_(params.width), height_(params.height), gl_(new GlState) {
  buildProgram(gl_->objects);
  buildTarget(gl_->objects, width_, height_);
  upload(gl_->objects, scene_);
}

SurfaceRasteriser::~SurfaceRasteriser() = default;

std::vector<SurfacePoint> SurfaceRasteriser::rasterise(glm::vec2 offsetPixels) {
  const int w = width_, h = height_;
  const SurfaceGlObjects& gl = gl_->objects;
  glBindFramebuffer(GL_FRAMEBUFFER, gl.framebuffer.id());
  glViewport(0, 0, w, h);
  const float none[4] = {0, 0, 0, 0};
  for (int i = 0; i < kAttachments; ++i) glClearBufferfv(GL_COLOR, i, none);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  glUseProgram(gl.program.id());
  // The same matrix as modern/camera_pass.cpp cameraViewProjection().
  glm::mat4 viewProjection =
      cameraProjection(scene_.camera, float(w) / float(h)) * cameraView(scene_.camera);
  // A sub-pixel sample: shift the image by -offset pixels in window space (NDC spans 2 per
  // window side; a clip-space translation scaled by w), so that the pixel centre rasterises
  // what lies at (x + 0.5 + offset.x, y + 0.5 + offset.y). Offset 0 keeps the matrix as is.
  if (offsetPixels != glm::vec2(0.0f)) {
    glm::mat4 shift(1.0f);
    shift[3][0] = -2.0f * offsetPixels.x / float(w);
    shift[3][1] = -2.0f * offsetPixels.y / float(h);
    viewProjection = shift * viewProjection;
  }
  glUniformMatrix4fv(glGetUniformLocation(gl.program.id(), "uViewProjection"), 1, GL_FALSE,
                     glm::value_ptr(viewProjection));
  draw(gl, scene_);
  const std::vector<float> position = readAttachment(0, w, h);
  // Sub-pixel samples only cast shadow rays (the geometric normal offsets their origin); the
  // shading normal, read for the pixel centre's shading, is left unread there.
  const bool subpixel = offsetPixels != glm::vec2(0.0f);
  const std::vector<float> shading = subpixel ? std::vector<float>() : readAttachment(1, w, h);
  const std::vector<float> geometric = readAttachment(2, w, h);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glUseProgram(0);
  checkGl("reference surface pass");

  std::vector<SurfacePoint> points(size_t(w) * h);
  for (size_t p = 0; p < points.size(); ++p) {
    const float* pos = &position[p * 4];
    const int id = int(pos[3] + 0.5f) - 1;
    if (id < 0 || id >= int(scene_.objects.size())) continue;
    SurfacePoint& s = points[p];
    s.object = id;
    s.position = {pos[0], pos[1], pos[2]};
    s.shadingNormal = subpixel
                          ? glm::vec3(geometric[p * 4], geometric[p * 4 + 1], geometric[p * 4 + 2])
                          : glm::vec3(shading[p * 4], shading[p * 4 + 1], shading[p * 4 + 2]);
    s.geometricNormal = {geometric[p * 4], geometric[p * 4 + 1], geometric[p * 4 + 2]};
  }
  return points;
}

std::vector<SurfacePoint> rasteriseSurfacePoints(const Scene& scene, const RenderParams& params) {
  return SurfaceRasteriser(scene, params).rasterise({0.0f, 0.0f});
}

}  // namespace sl::reference
