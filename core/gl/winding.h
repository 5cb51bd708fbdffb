// core/gl/winding.h — front faces of mirrored objects.
//
// GL tells front from back faces by the winding of a triangle's corners in window space
// (glspec121 §2.13.1 for lighting, §3.5.1 for polygons). Every mesh here winds its outside
// counter-clockwise, and the view and projection matrices keep that orientation. A model
// matrix with a negative determinant (a scale by -1 along one axis, say) mirrors the mesh and
// so reverses every triangle's winding: the outside turns clockwise on screen, and
// gl_FrontFacing, face culling and two-sided stencil would take the outside for the back.
// FrontFaceForModel flips glFrontFace while such an object is drawn, so that "front" keeps
// meaning the mesh's outside, as for the same geometry with its vertices mirrored and its
// corner order reversed.
#pragma once

#include <glm/glm.hpp>

#include "core/gl/gl.h"

namespace sl {

// True when `model` mirrors space (reverses the orientation of every triangle).
inline bool mirrors(const glm::mat4& model) { return glm::determinant(glm::mat3(model)) < 0.0f; }

// While alive: the front face is the caller's, turned over when `model` mirrors. Objects that
// do not mirror issue no GL call (their traces and pass dumps are unchanged).
class FrontFaceForModel {
 public:
  explicit FrontFaceForModel(const glm::mat4& model) : flipped_(mirrors(model)) {
    if (!flipped_) return;
    gl::glGetIntegerv(GL_FRONT_FACE, &caller_);
    gl::glFrontFace(caller_ == GL_CW ? GL_CCW : GL_CW);
  }
  ~FrontFaceForModel() {
    if (flipped_) gl::glFrontFace(GLenum(caller_));
  }
  FrontFaceForModel(const FrontFaceForModel&) = delete;
  FrontFaceForModel& operator=(const FrontFaceForModel&) = delete;

 private:
  bool flipped_ = false;
  GLint caller_ = GL_CCW;
};

}  // namespace sl
