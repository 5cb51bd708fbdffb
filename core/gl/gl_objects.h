// core/gl/gl_objects.h — one discipline for GL resources and GL state, for every module:
//
//   GlName<Deleter> — the owner of one GL object name (a texture, a framebuffer, ...): made by
//                     makeTexture() and the like, deleted when the owner goes, movable, never
//                     copied. legacy_gl/ and modern/ hold every object they make in one.
//   ScopedEnable    — a capability (glEnable) on for a scope, off again after it.
//   ScopedAttrib    — glPushAttrib / glPopAttrib (and the client-side pair) as a scope.
//   ScopedMatrices  — the projection, modelview and texture matrices pushed for a scope;
//                     ScopedPushMatrix the current matrix alone.
//   ScopedClientState — a client-side array (glEnableClientState) on for a scope.
//   ScopedTexgen    — texture-coordinate generation (GL_TEXTURE_GEN_S..Q) of one texture unit
//                     on for a scope, coordinate by coordinate, off again after it.
//
// The restoring destructors run also when a pass throws (a GL error, bad input), so a context
// the lab or the benchmark reuses is left as the code found it. They never throw: when the GL
// call itself fails (no current context, a missing entry point) the context is beyond repair
// and the error that is already on its way says why.
#pragma once

#include <functional>
#include <utility>

#include "core/gl/gl.h"

namespace sl {

// A move-only owner of one GL name; `Deleter` releases it. Name 0 is "none".
template <void (*Deleter)(GLuint)>
class GlName {
 public:
  GlName() = default;
  explicit GlName(GLuint id) : id_(id) {}
  ~GlName() {
    try {
      reset();
    } catch (...) {  // the context is gone (see above); it took the name with it
    }
  }
  GlName(GlName&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  GlName& operator=(GlName&& o) noexcept {
    if (this != &o) {
      GlName old(std::exchange(id_, std::exchange(o.id_, 0)));  // deleted as `old` goes
    }
    return *this;
  }
  GlName(const GlName&) = delete;
  GlName& operator=(const GlName&) = delete;
  GLuint id() const { return id_; }
  // Gives the name up without deleting it (its context is about to delete it).
  GLuint release() { return std::exchange(id_, 0); }
  void reset() {
    if (id_ != 0) Deleter(std::exchange(id_, 0));
  }

 private:
  GLuint id_ = 0;
};

void deleteTexture(GLuint id);
void deleteFramebuffer(GLuint id);
void deleteRenderbuffer(GLuint id);
void deleteBuffer(GLuint id);
void deleteVertexArray(GLuint id);
void deleteShader(GLuint id);
void deleteProgram(GLuint id);
void deleteQuery(GLuint id);

using Texture = GlName<deleteTexture>;
using Framebuffer = GlName<deleteFramebuffer>;
using Renderbuffer = GlName<deleteRenderbuffer>;
using Buffer = GlName<deleteBuffer>;
using VertexArray = GlName<deleteVertexArray>;
using ShaderName = GlName<deleteShader>;
using ProgramName = GlName<deleteProgram>;
using Query = GlName<deleteQuery>;

// A new name of each kind (glGen*), owned.
Texture makeTexture();
Framebuffer makeFramebuffer();
Renderbuffer makeRenderbuffer();
Buffer makeBuffer();
VertexArray makeVertexArray();
Query makeQuery();

// GL_ARB_pipeline_statistics_query (core in GL 4.6): how many fragment-shader invocations the
// draws issued by `draws` cost — the fragments the rasteriser hands to the fragment stage,
// whether or not a later test then lets them update (llvmpipe counts whole 4x4 blocks). -1
// where the driver has no such query (`draws` still runs).
double countFragmentInvocations(const std::function<void()>& draws);

// glEnable(cap) now, glDisable(cap) at the end of the scope: the hand-written pair, also when
// the scope is left by an exception. For capabilities a pass switches on for some of its draws
// (the state between passes has them off).
class ScopedEnable {
 public:
  explicit ScopedEnable(GLenum cap);
  ~ScopedEnable();
  ScopedEnable(const ScopedEnable&) = delete;
  ScopedEnable& operator=(const ScopedEnable&) = delete;

 private:
  GLenum cap_;
};

// glPushAttrib(mask) now, glPopAttrib() at the end of the scope.
class ScopedAttrib {
 public:
  explicit ScopedAttrib(GLbitfield mask);
  ~ScopedAttrib();
  ScopedAttrib(const ScopedAttrib&) = delete;
  ScopedAttrib& operator=(const ScopedAttrib&) = delete;
};

// glPushClientAttrib(mask) now, glPopClientAttrib() at the end of the scope.
class ScopedClientAttrib {
 public:
  explicit ScopedClientAttrib(GLbitfield mask);
  ~ScopedClientAttrib();
  ScopedClientAttrib(const ScopedClientAttrib&) = delete;
  ScopedClientAttrib& operator=(const ScopedClientAttrib&) = delete;
};

// glPushMatrix() now, glPopMatrix() at the end of the scope, on the stack of the matrix mode
// current at both ends (the scope must leave that mode as it found it).
class ScopedPushMatrix {
 public:
  ScopedPushMatrix();
  ~ScopedPushMatrix();
  ScopedPushMatrix(const ScopedPushMatrix&) = delete;
  ScopedPushMatrix& operator=(const ScopedPushMatrix&) = delete;
};

// glEnableClientState(array) now, glDisableClientState(array) at the end of the scope.
class ScopedClientState {
 public:
  explicit ScopedClientState(GLenum array);
  ~ScopedClientState();
  ScopedClientState(const ScopedClientState&) = delete;
  ScopedClientState& operator=(const ScopedClientState&) = delete;

 private:
  GLenum array_;
};

// glPushMatrix on the projection, modelview and texture stacks now (in that order), glPopMatrix
// on each in reverse order at the end of the scope. The matrix mode is GL_TEXTURE after the
// constructor and GL_PROJECTION after the destructor: a ScopedAttrib around it (GL_TRANSFORM_BIT)
// gives the caller's mode back.
class ScopedMatrices {
 public:
  ScopedMatrices();
  ~ScopedMatrices();
  ScopedMatrices(const ScopedMatrices&) = delete;
  ScopedMatrices& operator=(const ScopedMatrices&) = delete;
};

// Texture-coordinate generation on texture unit `unit` (GL_TEXTURE0 + i) for a scope: enable()
// switches one coordinate on (glEnable(GL_TEXTURE_GEN_S..Q)) where the caller sets its plane;
// the destructor switches each off again, in the order they were switched on, on that unit,
// and leaves the active texture unit as it found it. The constructor makes no GL call.
class ScopedTexgen {
 public:
  explicit ScopedTexgen(GLenum unit) : unit_(unit) {}
  ~ScopedTexgen();
  ScopedTexgen(const ScopedTexgen&) = delete;
  ScopedTexgen& operator=(const ScopedTexgen&) = delete;

  // glEnable(gen) on the scope's unit, which must be the active one (the caller sets the
  // coordinate's mode and plane there); a coordinate already on is not switched on twice.
  void enable(GLenum gen);

 private:
  static constexpr int kCoordinates = 4;  // s, t, r, q
  GLenum unit_;
  GLenum enabled_[kCoordinates] = {0, 0, 0, 0};
  int count_ = 0;
};

}  // namespace sl
