#include "modern/brabec_seidel.h"

#include <glm/gtc/matrix_transform.hpp>

#include "core/errors.h"
#include "modern/camera_pass.h"

namespace sl::modern::bs {
using namespace sl::gl;

Arithmetic arithmeticOf(const RenderParams& params) {
  return params.text("arithmetic", "faithful", {"faithful", "float"}) == "float"
             ? Arithmetic::kFloat
             : Arithmetic::kFaithful;
}

int depthBits(const RenderParams& params) {
  if (arithmeticOf(params) == Arithmetic::kFloat) return 0;
  return params.precision == Precision::k12 ? 12 : 8;
}

GLenum encodedDepthFormat(const RenderParams& params) {
  switch (depthBits(params)) {
    case 8: return GL_RGBA8;
    case 12: return GL_RGBA16;  // 12-bit values in a 16-bit buffer (Octane VPro, §6)
    default: return GL_RGBA32F;
  }
}

Texture makeRampTexture(int bits) {
  if (bits == 0) bits = 8;
  const int texels = 1 << bits;
  std::vector<float> ramp(texels);
  for (int k = 0; k < texels; ++k) ramp[k] = float(k) / float(texels - 1);
  Texture t = makeTexture();
  glBindTexture(GL_TEXTURE_1D, t.id());
  glTexImage1D(GL_TEXTURE_1D, 0, bits == 8 ? GL_R8 : GL_R16, texels, 0, GL_RED, GL_FLOAT,
               ramp.data());
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_1D, 0);
  return t;
}

glm::vec4 rampPlane(const Scene& scene) {
  const DepthRange r = lightDepthRange(scene);
  const glm::mat4 view = lightView(scene.light);
  // Eye-space depth -z_e = -(row 2 of the view matrix) · world.
  const glm::vec4 depthRow(-view[0][2], -view[1][2], -view[2][2], -view[3][2]);
  glm::vec4 plane = depthRow / (r.farPlane - r.nearPlane);
  plane.w -= r.nearPlane / (r.farPlane - r.nearPlane);
  return plane;
}

float bias(const RenderParams& params) {
  return float(params.number("bias", kDefaultBiasSteps / 255.0, -1.0, 1.0));
}

glm::mat4 worldToShadowMap(const Scene& scene) {
  const glm::mat4 S = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) *
                      glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
  return S * lightProjection(scene) * lightView(scene.light);
}

glm::mat4 jitteredLightViewProjection(const Scene& scene, glm::vec2 offsetTexels, int texels) {
  // One texel is 2 / texels in normalised device coordinates.
  const glm::vec2 ndc = 2.0f * offsetTexels / float(texels);
  return glm::translate(glm::mat4(1.0f), glm::vec3(ndc, 0.0f)) * lightProjection(scene) *
         lightView(scene.light);
}

RenderTarget makeEncodedDepthTarget(const RenderParams& params) {
  const int n = params.shadowMapTexels;
  RenderTarget t = makeRenderTarget(n, n, {encodedDepthFormat(params)}, true);
  t.bind();
  const float farPlane[4] = {1, 1, 1, 1};
  glClearBufferfv(GL_COLOR, 0, farPlane);
  glClear(GL_DEPTH_BUFFER_BIT);
  setMapSampling(t.color[0].id());
  return t;
}

void setMapSampling(GLuint texture) {
  glBindTexture(GL_TEXTURE_2D, texture);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, 0);
}

void renderEncodedDepth(const GpuScene& gpu, const RenderParams& params, const Texture& ramp,
                        const RenderTarget& target, glm::bvec4 channels, glm::vec2 offsetTexels) {
  target.bind();
  glClear(GL_DEPTH_BUFFER_BIT);  // each jittered pass has its own depth test
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glColorMask(channels.r, channels.g, channels.b, channels.a);
  Program program("scene.vert.glsl", "bs_encode_depth.frag.glsl");
  program.use();
  program.set("uViewProjection",
              jitteredLightViewProjection(gpu.scene(), offsetTexels, params.shadowMapTexels));
  program.set("uRampPlane", rampPlane(gpu.scene()));
  program.set("uFaithful", arithmeticOf(params) == Arithmetic::kFaithful ? 1 : 0);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_1D, ramp.id());
  program.set("uRamp", 0);
  gpu.draw([](const Object& o) { return o.castsShadow; },
           [&](const Object& o) { program.set("uModel", o.model); });
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void shadowTestAndShade(const GpuScene& gpu, const RenderParams& params, const Texture& ramp,
                        const std::vector<SampleGroup>& groups, Frame& frame) {
  constexpr int kMaxGroups = 4;  // 4x4 = 16 samples = four RGBA maps
  if (groups.empty() || groups.size() > size_t(kMaxGroups))
    throw InputError("the shadow test takes 1 to 4 groups of samples");
  const Scene& scene = gpu.scene();
  const bool faithful = arithmeticOf(params) == Arithmetic::kFaithful;
  RenderTarget target = makeCameraTarget(params, !faithful);
  clearCameraTarget(target);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  Program program("scene.vert.glsl", "pcf_shadow.frag.glsl");
  program.use();
  program.set("uViewProjection", cameraViewProjection(scene, params));
  program.set("uWorldToShadowMap", worldToShadowMap(scene));
  program.set("uRampPlane", rampPlane(scene));
  program.set("uBias", bias(params));
  program.set("uFaithful", faithful ? 1 : 0);
  program.set("uMapTexels", float(params.shadowMapTexels));
  program.set("uGroupCount", int(groups.size()));
  setLightingUniforms(program, scene);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_1D, ramp.id());
  program.set("uRamp", 0);
  for (int g = 0; g < kMaxGroups; ++g) {
    const SampleGroup& group = groups[std::min<size_t>(g, groups.size() - 1)];
    glActiveTexture(GLenum(GL_TEXTURE1 + g));
    glBindTexture(GL_TEXTURE_2D, group.map);
    const std::string i = "[" + std::to_string(g) + "]";
    program.set(("uMaps" + i).c_str(), 1 + g);
    program.set(("uGroupSamples" + i).c_str(), group.samples);
    program.set(("uGroupOffset" + i).c_str(), group.offsetTexels);
  }
  glActiveTexture(GL_TEXTURE0);
  gpu.draw([](const Object&) { return true; },
           [&](const Object& o) { setObjectUniforms(program, o); });
  readCameraTarget(target, frame);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

std::vector<std::string> paramKeys() { return {"arithmetic", "bias"}; }

}  // namespace sl::modern::bs
