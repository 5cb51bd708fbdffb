#include "modern/filtered_map_passes.h"

#include "modern/camera_pass.h"

namespace sl::modern {
using namespace sl::gl;

LayeredMap renderWarpedDepthFromLight(const GpuScene& gpu, const RenderParams& params,
                                      GLenum format, bool mipmaps, const char* fragmentShader,
                                      const float clear[4],
                                      const std::function<void(const Program&)>& uniforms) {
  const int n = params.shadowMapTexels;
  LayeredMap map = makeLayeredMap(n, 1, format, mipmaps);
  const Framebuffer fbo = makeFramebuffer();
  attachLayers(fbo, map, 0, 1);
  const Renderbuffer depth = makeRenderbuffer();
  glBindRenderbuffer(GL_RENDERBUFFER, depth.id());
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, n, n);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth.id());
  glClearBufferfv(GL_COLOR, 0, clear);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  const Program& program = cachedProgram("scene.vert.glsl", fragmentShader);
  program.use();
  program.set("uViewProjection", lightProjection(gpu.scene()) * lightView(gpu.scene().light));
  setLinearDepthUniforms(program, gpu.scene());
  uniforms(program);
  gpu.draw([](const Object& o) { return o.castsShadow; },
           [&](const Object& o) { program.set("uModel", o.model); });
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return map;
}

void shadeWithFilteredMap(const GpuScene& gpu, const RenderParams& params, const LayeredMap& map,
                          const char* fragmentShader,
                          const std::function<void(const Program&)>& uniforms, Frame& frame) {
  const Scene& scene = gpu.scene();
  RenderTarget target = makeCameraTarget(params, true);
  clearCameraTarget(target);
  glEnable(GL_DEPTH_TEST);
  const Program& program = cachedProgram("scene.vert.glsl", fragmentShader);
  program.use();
  program.set("uViewProjection", cameraViewProjection(scene, params));
  program.set("uWorldToShadowMap", worldToShadowMap(scene));
  setLinearDepthUniforms(program, scene);
  setLightingUniforms(program, scene);
  uniforms(program);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D_ARRAY, map.texture.id());
  program.set("uMap", 0);
  gpu.draw([](const Object&) { return true; },
           [&](const Object& o) { setObjectUniforms(program, o); });
  readCameraTarget(target, frame);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
}

}  // namespace sl::modern
