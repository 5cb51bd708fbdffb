#include "modern/camera_pass.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "core/base/errors.h"
#include "core/gl/gl_trace.h"

namespace sl::modern {
using namespace sl::gl;

RenderTarget makeCameraTarget(const RenderParams& params, bool floatVisibility) {
  return makeRenderTarget(params.width, params.height,
                          {GL_RGBA8, GLenum(floatVisibility ? GL_R32F : GL_RGBA8)}, true,
                          GL_DEPTH_COMPONENT24);
}

void clearCameraTarget(const RenderTarget& target) {
  target.bind();
  const float black[4] = {0, 0, 0, 1};
  const float lit[4] = {1, 1, 1, 1};
  glClearBufferfv(GL_COLOR, 0, black);
  glClearBufferfv(GL_COLOR, 1, lit);
  glClear(GL_DEPTH_BUFFER_BIT);
}

void setLightingUniforms(const Program& program, const Scene& scene) {
  const SpotLight& l = scene.light;
  program.set("uLightPosition", l.position);
  program.set("uLightDirection", glm::normalize(l.target - l.position));
  // Same cone as legacy_gl/fixed_function.cpp (GL_SPOT_CUTOFF = half the frustum angle).
  const float cutoff = 0.5f * l.coneDegrees;
  program.set("uSpotCosCutoff", std::cos(glm::radians(cutoff)));
  program.set("uLightColor", l.color);
  program.set("uAmbient", l.ambient);
  program.set("uEyePosition", scene.camera.position);
}

void setObjectUniforms(const Program& program, const Object& object) {
  program.set("uModel", object.model);
  program.set("uDiffuse", object.diffuse);
  program.set("uSpecular", object.specular);
  program.set("uReceivesShadow", object.receivesShadow ? 1 : 0);
}

Image readAttachment(const RenderTarget& target, int attachment) {
  const GlTracePause dumpOnly;  // readbacks are not state of a pass (core/gl/gl_trace.h)
  Image image(target.width, target.height, 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, target.fbo.id());
  glReadBuffer(GLenum(GL_COLOR_ATTACHMENT0 + attachment));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, target.width, target.height, GL_RGBA, GL_FLOAT, image.data.data());
  checkGl("read attachment");
  return image;
}

namespace {
// Reads `channels` (GL_RGB or GL_RED) of one colour attachment straight into an image, as the
// legacy techniques read their window (no RGBA copy to convert afterwards).
Image readChannels(const RenderTarget& target, int attachment, GLenum format, int channels) {
  Image image(target.width, target.height, channels);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, target.fbo.id());
  glReadBuffer(GLenum(GL_COLOR_ATTACHMENT0 + attachment));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, target.width, target.height, format, GL_FLOAT, image.data.data());
  checkGl("read camera target");
  return image;
}
}  // namespace

void readCameraTarget(const RenderTarget& target, Frame& frame) {
  frame.color = readChannels(target, 0, GL_RGB, 3);
  frame.visibility = readChannels(target, 1, GL_RED, 1);
}

glm::mat4 cameraViewProjection(const Scene& scene, const RenderParams& params) {
  return cameraProjection(scene.camera, float(params.width) / float(params.height)) *
         cameraView(scene.camera);
}

}  // namespace sl::modern
