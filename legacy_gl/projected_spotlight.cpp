// legacy_gl/projected_spotlight.cpp — the spotlight cone projected from the light (Segal et al.
// 1992; Everitt 2001, "Projective Texture Mapping"); see projected_spotlight.h.
#include "legacy_gl/projected_spotlight.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <stdexcept>
#include <vector>

#include "core/base/errors.h"
#include "legacy_gl/fixed_function.h"

namespace sl::legacy {
using namespace sl::gl;

namespace {

// The width of one texel in light NDC.
double texelWidth() { return 2.0 * kConeTextureExtent / kConeTextureTexels; }

}  // namespace

float coneTextureAlpha(double x, double y) {
  const double halfWidth = kConeRampTexels * texelWidth();
  const double inside = 1.0 - std::hypot(x, y);  // > 0 inside the disc
  return float(std::clamp(double(kConeEdgeAlpha) + inside / (2.0 * halfWidth), 0.0, 1.0));
}

glm::mat4 worldToConeTexture(const Scene& scene) {
  // Everitt 2001 (projective texture mapping), Eq. 5 of Everitt et al. 2001: S · P · L, with S
  // mapping [-E, E] (E = kConeTextureExtent) instead of [-1, 1] onto [0, 1]. Rows 0, 1 and 3 of
  // P (the light's projection, lightProjection) do not depend on its near and far planes.
  const float scale = float(0.5 / kConeTextureExtent);
  const glm::mat4 S = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 0.5f, 0.0f)) *
                      glm::scale(glm::mat4(1.0f), glm::vec3(scale, scale, 1.0f));
  return S * lightProjection(scene) * lightView(scene.light);
}

void uploadConeTexture(GLuint texture, const std::vector<float>& alpha) {
  if (alpha.size() != size_t(kConeTextureTexels) * kConeTextureTexels)
    throw std::invalid_argument("uploadConeTexture: kConeTextureTexels^2 alphas expected");
  // The active unit's binding is the caller's (legacy.hw's shadow map on unit 0): kept.
  GLint bound = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
  glBindTexture(GL_TEXTURE_2D, texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  // ALPHA16: the edge (alpha 0.5) stays where the distance puts it; 8 bits would move it by up
  // to half a step, 1/255 of the ramp's width.
  glTexImage2D(GL_TEXTURE_2D, 0, GL_ALPHA16, kConeTextureTexels, kConeTextureTexels, 0, GL_ALPHA,
               GL_FLOAT, alpha.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, GLuint(bound));
}

SpotlightConeTexture::SpotlightConeTexture() : texture_(makeTexture()) {
  std::vector<float> alpha(size_t(kConeTextureTexels) * kConeTextureTexels);
  const double w = texelWidth();
  for (int j = 0; j < kConeTextureTexels; ++j)
    for (int i = 0; i < kConeTextureTexels; ++i)  // texel centres
      alpha[size_t(j * kConeTextureTexels + i)] = coneTextureAlpha(
          -kConeTextureExtent + (i + 0.5) * w, -kConeTextureExtent + (j + 0.5) * w);
  uploadConeTexture(texture_.id(), alpha);
  checkGl("spotlight cone texture");
}

ProjectedSpotlightCone::ProjectedSpotlightCone(const Scene& scene,
                                               const SpotlightConeTexture& texture, GLenum unit)
    : unit_(unit) {
  // Everitt 2001: the planes are given in world space while the modelview holds the camera's
  // view matrix; GL keeps them as plane x (view)^-1, so eye coordinates map back to world.
  const glm::mat4 planes = glm::transpose(worldToConeTexture(scene));  // rows as columns
  glActiveTexture(unit);
  const GLenum coords[3] = {GL_S, GL_T, GL_Q};
  const GLenum enables[3] = {GL_TEXTURE_GEN_S, GL_TEXTURE_GEN_T, GL_TEXTURE_GEN_Q};
  const int rows[3] = {0, 1, 3};
  for (int i = 0; i < 3; ++i) {
    glTexGeni(coords[i], GL_TEXTURE_GEN_MODE, GL_EYE_LINEAR);
    glTexGenfv(coords[i], GL_EYE_PLANE, glm::value_ptr(planes[rows[i]]));
    glEnable(enables[i]);
  }
  glMatrixMode(GL_TEXTURE);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  glBindTexture(GL_TEXTURE_2D, texture.id());
  glEnable(GL_TEXTURE_2D);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
  glActiveTexture(GL_TEXTURE0);
  glAlphaFunc(GL_GEQUAL, kConeEdgeAlpha);
  glEnable(GL_ALPHA_TEST);
  // Everitt 2001 ("reverse projection"): behind the light q < 0 and (s/q, t/q) shows the cone
  // mirrored; the clip plane q >= 0 (world space, under the view matrix like the texgen planes)
  // removes it. Only triangles that cross the light's plane are clipped, and what the clipping
  // changes lies at 90 degrees or more off the light's axis, outside every cone.
  const glm::vec4 q = planes[3];
  const double plane[4] = {q.x, q.y, q.z, q.w};
  glClipPlane(GL_CLIP_PLANE0, plane);
  glEnable(GL_CLIP_PLANE0);
}

ProjectedSpotlightCone::~ProjectedSpotlightCone() {
  try {
    glDisable(GL_CLIP_PLANE0);
    glDisable(GL_ALPHA_TEST);
    glActiveTexture(unit_);
    glDisable(GL_TEXTURE_2D);
    for (GLenum e : {GL_TEXTURE_GEN_S, GL_TEXTURE_GEN_T, GL_TEXTURE_GEN_Q}) glDisable(e);
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE0);
  } catch (...) {  // the context is beyond repair (core/gl/gl_objects.h)
  }
}

}  // namespace sl::legacy
