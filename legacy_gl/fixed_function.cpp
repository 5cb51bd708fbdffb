#include "legacy_gl/fixed_function.h"

#include <glm/gtc/type_ptr.hpp>

#include "core/base/errors.h"
#include "core/gl/context.h"
#include "core/gl/gl.h"
#include "core/gl/gl_trace.h"
#include "core/gl/winding.h"

namespace sl::legacy {
using namespace sl::gl;

void loadMatrix(unsigned mode, const glm::mat4& m) {
  glMatrixMode(mode);
  glLoadMatrixf(glm::value_ptr(m));
}

void drawScene(const Scene& scene, Draw which, Colors colors) {
  const ScopedClientState vertices(GL_VERTEX_ARRAY);
  const ScopedClientState normals(GL_NORMAL_ARRAY);
  glMatrixMode(GL_MODELVIEW);
  for (const Object& o : scene.objects) {
    if (which == Draw::kCasters && !o.castsShadow) continue;
    if (which == Draw::kReceivers && !o.receivesShadow) continue;
    if (which == Draw::kNonReceivers && o.receivesShadow) continue;
    glm::vec4 diffuse(colors == Colors::kWhite ? glm::vec3(1.0f) : o.diffuse, 1.0f);
    if (colors == Colors::kBlack) diffuse = glm::vec4(0.0f);
    const glm::vec4 specular(glm::vec3(o.specular), 1.0f);
    glColor4fv(glm::value_ptr(diffuse));
    glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE, glm::value_ptr(diffuse));
    glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, glm::value_ptr(specular));
    glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, 32.0f);
    const ScopedPushMatrix modelMatrix;
    glMultMatrixf(glm::value_ptr(o.model));
    glVertexPointer(3, GL_FLOAT, 0, o.mesh->positions.data());
    glNormalPointer(GL_FLOAT, 0, o.mesh->normals.data());
    const FrontFaceForModel frontFace(o.model);  // culling keeps seeing a mirrored outside as front
    // Hidden back faces (Object::backFacesHidden) are culled: fragments saved, no pixel changed.
    // A pass that culls by itself (second-depth) keeps its own setting.
    const bool cull = o.backFacesHidden && !glIsEnabled(GL_CULL_FACE);
    if (cull) {
      glCullFace(GL_BACK);
      glEnable(GL_CULL_FACE);
    }
    glDrawElements(GL_TRIANGLES, GLsizei(o.mesh->indices.size()), GL_UNSIGNED_INT,
                   o.mesh->indices.data());
    if (cull) glDisable(GL_CULL_FACE);
  }
}

namespace {
// GL_SPOT_CUTOFF's special value: no cone (glspec121 §2.13.1).
constexpr float kNoSpotCutoffDegrees = 180.0f;
}  // namespace

void enableSpotlight(const Scene& scene, LightTerms terms) {
  const SpotLight& l = scene.light;
  const glm::vec4 zero(0, 0, 0, 1);
  const glm::vec4 color(l.color, 1.0f);
  const glm::vec4 ambient(l.ambient * l.color, 1.0f);
  const bool direct = terms != LightTerms::kAmbientOnly;
  const bool amb = terms != LightTerms::kDiffuseSpecularOnly;
  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  glEnable(GL_NORMALIZE);
  // The ambient term goes through the global light-model ambient (glspec121 §2.13.1), not the
  // light's own ambient, which GL would multiply by the spotlight cone: shadowed and unlit
  // surfaces keep the same ambient everywhere, as in modern/camera_pass.cpp.
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, glm::value_ptr(amb ? ambient : zero));
  glLightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, GL_TRUE);
  glLightfv(GL_LIGHT0, GL_AMBIENT, glm::value_ptr(zero));
  glLightfv(GL_LIGHT0, GL_DIFFUSE, glm::value_ptr(direct ? color : zero));
  glLightfv(GL_LIGHT0, GL_SPECULAR, glm::value_ptr(direct ? color : zero));
  const glm::vec4 position(l.position, 1.0f);
  const glm::vec3 direction = glm::normalize(l.target - l.position);
  glLightfv(GL_LIGHT0, GL_POSITION, glm::value_ptr(position));
  glLightfv(GL_LIGHT0, GL_SPOT_DIRECTION, glm::value_ptr(direction));
  // The spotlight cone is the circle inscribed in the light frustum: outside it there is no
  // direct light, so the map's border never shows. GL_SPOT_CUTOFF would test it per vertex; the
  // passes that add direct light test it per pixel with the projected cone texture instead
  // (legacy_gl/projected_spotlight.h), and GL lights every vertex as a point light.
  glLightf(GL_LIGHT0, GL_SPOT_CUTOFF, kNoSpotCutoffDegrees);
  glLightf(GL_LIGHT0, GL_SPOT_EXPONENT, 0.0f);
}

void disableLighting() {
  glDisable(GL_LIGHTING);
  glDisable(GL_LIGHT0);
}

void setCameraMatrices(const Scene& scene, int width, int height) {
  glViewport(0, 0, width, height);
  loadMatrix(GL_PROJECTION, cameraProjection(scene.camera, float(width) / float(height)));
  loadMatrix(GL_MODELVIEW, cameraView(scene.camera));
}

LightTarget::LightTarget(int texels, bool windowFits, bool needColor, unsigned colorFormat)
    : texels_(texels) {
  if (windowFits) return;
  fbo_ = makeFramebuffer();
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
  depth_ = makeTexture();
  glBindTexture(GL_TEXTURE_2D, depth_.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, texels, texels, 0, GL_DEPTH_COMPONENT,
               GL_UNSIGNED_INT, nullptr);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth_.id(), 0);
  if (needColor) {
    color_ = makeTexture();
    glBindTexture(GL_TEXTURE_2D, color_.id());
    glTexImage2D(GL_TEXTURE_2D, 0, GLint(colorFormat), texels, texels, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 nullptr);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_.id(), 0);
  } else {
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
  }
  glBindTexture(GL_TEXTURE_2D, 0);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (status != GL_FRAMEBUFFER_COMPLETE) throw GlError("light-pass framebuffer is incomplete");
}

void LightTarget::bind() {
  if (fbo_.id() != 0) glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
  glViewport(0, 0, texels_, texels_);
}

void LightTarget::unbind() {
  if (fbo_.id() != 0) glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

namespace {
// The imaging subset's colour matrix exists: native ARB_imaging or imaging/'s emulation.
bool hasColorMatrix() {
  const GlContext* context = GlContext::current();
  return context != nullptr &&
         (context->caps().nativeImaging() || context->layerState("imaging") != nullptr);
}

glm::mat4 readMatrix(GLenum query) {
  glm::mat4 m(1.0f);
  glGetFloatv(query, glm::value_ptr(m));
  return m;
}
}  // namespace

ScopedLegacyState::ScopedLegacyState() {
  const GlTracePause notAPass;
  glPushAttrib(GL_ALL_ATTRIB_BITS);
  glPushClientAttrib(GL_CLIENT_ALL_ATTRIB_BITS);
  projection_ = readMatrix(GL_PROJECTION_MATRIX);
  modelview_ = readMatrix(GL_MODELVIEW_MATRIX);
  if (hasColorMatrix()) color_ = readMatrix(GL_COLOR_MATRIX);
  GLint units = 1, active = GL_TEXTURE0;
  glGetIntegerv(GL_MAX_TEXTURE_UNITS, &units);
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
  for (GLint i = 0; i < units; ++i) {
    glActiveTexture(GLenum(GL_TEXTURE0 + i));
    texture_.push_back(readMatrix(GL_TEXTURE_MATRIX));
  }
  glActiveTexture(GLenum(active));
  glGetIntegerv(GL_FRAMEBUFFER_BINDING, &framebuffer_);
}

ScopedLegacyState::~ScopedLegacyState() {
  try {
    const GlTracePause notAPass;
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(framebuffer_));
    for (size_t i = 0; i < texture_.size(); ++i) {
      glActiveTexture(GLenum(GL_TEXTURE0 + i));
      loadMatrix(GL_TEXTURE, texture_[i]);
    }
    if (hasColorMatrix()) loadMatrix(GL_COLOR, color_);
    loadMatrix(GL_PROJECTION, projection_);
    loadMatrix(GL_MODELVIEW, modelview_);
    glPopClientAttrib();
    glPopAttrib();  // the matrix mode and the active unit too (GL_TRANSFORM_BIT, GL_TEXTURE_BIT)
  } catch (...) {   // no current context or entry point: the error on its way says why
  }
}

RenderFunction withScopedLegacyState(RenderFunction render) {
  return [render = std::move(render)](GlContext& context, const Scene& scene,
                                      const RenderParams& params) {
    const ScopedLegacyState state;
    return render(context, scene, params);
  };
}

Image readRedChannel(int width, int height) {
  Image red(width, height, 1);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RED, GL_FLOAT, red.data.data());
  checkGl("read visibility");
  return red;
}

Image readRgb(int width, int height) {
  const GlTracePause readback;  // reading the result is not state of a pass (core/gl/gl_trace.h)
  Image rgb(width, height, 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGB, GL_FLOAT, rgb.data.data());
  checkGl("read colour");
  return rgb;
}

}  // namespace sl::legacy
