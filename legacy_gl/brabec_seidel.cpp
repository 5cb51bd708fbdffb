// legacy_gl/brabec_seidel.cpp — the matrices Brabec & Seidel 2001 §2 loads into the texture
// matrix (shared by legacy.ramp, legacy.pcf and legacy.fast-pcf; tests check them with GLM).
#include "legacy_gl/brabec_seidel.h"

#include <glm/gtc/matrix_transform.hpp>

namespace sl::legacy {

glm::mat4 lightEyeToRamp(const Scene& scene, int rampTexels, double bias) {
  const DepthRange range = lightDepthRange(scene);
  const double n = range.nearPlane, f = range.farPlane;
  const double texels = rampTexels;
  // d = (-z - n) / (f - n) - bias;  s = (0.5 + (N - 1) d) / N   (row 0; glm is [column][row])
  glm::mat4 m(0.0f);
  m[2][0] = float(-(texels - 1.0) / ((f - n) * texels));
  m[3][0] = float((0.5 + (texels - 1.0) * (-n / (f - n) - bias)) / texels);
  m[3][3] = 1.0f;  // q = w = 1: no projective division for the ramp
  return m;
}

glm::mat4 cameraEyeToShadowMap(const Scene& scene, int shadowMapTexels, glm::vec2 offsetTexels) {
  // S: clip [-1, 1] -> texture [0, 1] (Everitt Eq. 2); the offset of Fig. 6 added after the
  // projective division (a translation by offset * q before it).
  const glm::mat4 offset =
      glm::translate(glm::mat4(1.0f), glm::vec3(offsetTexels / float(shadowMapTexels), 0.0f));
  const glm::mat4 S = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) *
                      glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
  return offset * S * lightProjection(scene) * lightView(scene.light) *
         glm::inverse(cameraView(scene.camera));
}

}  // namespace sl::legacy
