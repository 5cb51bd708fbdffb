// core/gl/gl_objects.cpp — see gl_objects.h.
#include "core/gl/gl_objects.h"

#include <stdexcept>

#include "core/base/errors.h"
#include "core/gl/context.h"

namespace sl {
using namespace sl::gl;

void deleteTexture(GLuint id) { glDeleteTextures(1, &id); }
void deleteFramebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
void deleteRenderbuffer(GLuint id) { glDeleteRenderbuffers(1, &id); }
void deleteBuffer(GLuint id) { glDeleteBuffers(1, &id); }
void deleteVertexArray(GLuint id) { glDeleteVertexArrays(1, &id); }
void deleteShader(GLuint id) { glDeleteShader(id); }
void deleteProgram(GLuint id) { glDeleteProgram(id); }
void deleteQuery(GLuint id) { glDeleteQueries(1, &id); }

Texture makeTexture() {
  GLuint id = 0;
  glGenTextures(1, &id);
  return Texture(id);
}

Framebuffer makeFramebuffer() {
  GLuint id = 0;
  glGenFramebuffers(1, &id);
  return Framebuffer(id);
}

Renderbuffer makeRenderbuffer() {
  GLuint id = 0;
  glGenRenderbuffers(1, &id);
  return Renderbuffer(id);
}

Buffer makeBuffer() {
  GLuint id = 0;
  glGenBuffers(1, &id);
  return Buffer(id);
}

VertexArray makeVertexArray() {
  GLuint id = 0;
  glGenVertexArrays(1, &id);
  return VertexArray(id);
}

double countFragmentInvocations(const std::function<void()>& draws) {
  const GlContext* ctx = GlContext::current();
  if (ctx == nullptr || !ctx->caps().hasExtension("GL_ARB_pipeline_statistics_query")) {
    draws();
    return -1;
  }
  const Query query = makeQuery();
  glBeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, query.id());
  draws();
  glEndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
  GLuint invocations = 0;
  glGetQueryObjectuiv(query.id(), GL_QUERY_RESULT, &invocations);
  checkGl("fragment-shader invocation query");
  return double(invocations);
}

Query makeQuery() {
  GLuint id = 0;
  glGenQueries(1, &id);
  return Query(id);
}

ScopedEnable::ScopedEnable(GLenum cap) : cap_(cap) { glEnable(cap_); }

ScopedEnable::~ScopedEnable() {
  try {
    glDisable(cap_);
  } catch (...) {  // the context is beyond repair (core/gl/gl_objects.h)
  }
}

ScopedAttrib::ScopedAttrib(GLbitfield mask) { glPushAttrib(mask); }

ScopedAttrib::~ScopedAttrib() {
  try {
    glPopAttrib();
  } catch (...) {  // the context is beyond repair (core/gl/gl_objects.h)
  }
}

ScopedClientAttrib::ScopedClientAttrib(GLbitfield mask) { glPushClientAttrib(mask); }

ScopedClientAttrib::~ScopedClientAttrib() {
  try {
    glPopClientAttrib();
  } catch (...) {  // the context is beyond repair (core/gl/gl_objects.h)
  }
}

ScopedPushMatrix::ScopedPushMatrix() { glPushMatrix(); }

ScopedPushMatrix::~ScopedPushMatrix() {
  try {
    glPopMatrix();
  } catch (...) {  // the context is beyond repair (core/gl/gl_objects.h)
  }
}

ScopedClientState::ScopedClientState(GLenum array) : array_(array) { glEnableClientState(array_); }

ScopedClientState::~ScopedClientState() {
  try {
    glDisableClientState(array_);
  } catch (...) {  // the context is beyond repair (core/gl/gl_objects.h)
  }
}

ScopedMatrices::ScopedMatrices() {
  for (const GLenum mode : {GLenum(GL_PROJECTION), GLenum(GL_MODELVIEW), GLenum(GL_TEXTURE)}) {
    glMatrixMode(mode);
    glPushMatrix();
  }
}

ScopedMatrices::~ScopedMatrices() {
  try {
    for (const GLenum mode : {GLenum(GL_TEXTURE), GLenum(GL_MODELVIEW), GLenum(GL_PROJECTION)}) {
      glMatrixMode(mode);
      glPopMatrix();
    }
  } catch (...) {  // the context is beyond repair (core/gl/gl_objects.h)
  }
}

void ScopedTexgen::enable(GLenum gen) {
  for (int i = 0; i < count_; ++i)
    if (enabled_[i] == gen) return;
  if (count_ == kCoordinates)
    throw std::logic_error("ScopedTexgen: more than four texture-coordinate generations");
  GLint active = GL_TEXTURE0;
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
  if (GLenum(active) != unit_)
    throw std::logic_error("ScopedTexgen: enable() while another texture unit is active");
  glEnable(gen);
  enabled_[count_++] = gen;
}

ScopedTexgen::~ScopedTexgen() {
  if (count_ == 0) return;
  try {
    GLint active = GL_TEXTURE0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    const bool switchUnit = GLenum(active) != unit_;
    if (switchUnit) glActiveTexture(unit_);
    for (int i = 0; i < count_; ++i) glDisable(enabled_[i]);
    if (switchUnit) glActiveTexture(GLenum(active));
  } catch (...) {  // the context is beyond repair (core/gl/gl_objects.h)
  }
}

}  // namespace sl
