#include "modern/brabec_seidel.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "core/base/errors.h"
#include "modern/camera_pass.h"

namespace sl::modern::bs {
using namespace sl::gl;

Arithmetic arithmeticOf(const RenderParams& params) {
  return params.text(arithmeticParam()) == "float" ? Arithmetic::kFloat : Arithmetic::kFaithful;
}

int depthBits(const RenderParams& params) {
  if (arithmeticOf(params) == Arithmetic::kFloat || params.precision == Precision::kFloat) return 0;
  return params.precision == Precision::k12 ? 12 : 8;
}

bool legacyFloatBuffer(const RenderParams& params) {
  return arithmeticOf(params) == Arithmetic::kFaithful && params.precision == Precision::kFloat;
}

GLenum encodedDepthFormat(const RenderParams& params) {
  switch (depthBits(params)) {
    case 8: return GL_RGBA8;
    case 12: return GL_RGBA16;  // 12-bit values in a 16-bit buffer (Octane VPro, §6)
    default: return GL_RGBA32F;
  }
}

namespace {
// The legacy colour buffer and pipeline constants (legacy_gl/brabec_seidel_passes.cpp).
constexpr double kStep8 = 1.0 / 255.0;          // 8-bit depth step
constexpr double kStep12 = 1.0 / 4095.0;        // 12-bit depth step
constexpr double kStepFloat = 1.0 / 1048576.0;  // the float pipeline's nominal step
constexpr double kChannelMax8 = 255.0;
constexpr double kChannelMax12 = 4095.0;
constexpr double kChannelMaxFloat = 65535.0;    // shares of a 16-bit colour table
constexpr float kColorTableLastIndex = 255.0f;  // 256-entry colour table
constexpr float kAccumSteps = 32767.0f;         // 16-bit signed accumulation buffer
constexpr int kRampTexels8 = 256;
constexpr int kRampTexels12 = 4096;
constexpr int kRampTexelsFloat = 2;  // legacy's float ramp: texels 0 and 1, LINEAR: d itself

double depthStep(const RenderParams& p) {
  return p.precision == Precision::k8    ? kStep8
         : p.precision == Precision::k12 ? kStep12
                                         : kStepFloat;
}
double channelMax(const RenderParams& p) {
  return p.precision == Precision::k8    ? kChannelMax8
         : p.precision == Precision::k12 ? kChannelMax12
                                         : kChannelMaxFloat;
}
}  // namespace

int rampTexels(const RenderParams& params) {
  if (legacyFloatBuffer(params)) return kRampTexelsFloat;
  return depthBits(params) == 12 ? kRampTexels12 : kRampTexels8;
}

Texture makeRampTexture(const RenderParams& params) {
  const int texels = rampTexels(params);
  std::vector<float> ramp(texels);
  for (int k = 0; k < texels; ++k) ramp[k] = float(k) / float(texels - 1);
  const GLenum format = texels == kRampTexelsFloat ? GL_R32F
                        : texels == kRampTexels8   ? GL_R8
                                                   : GL_R16;
  // The float ramp interpolates (legacy's GL_INTENSITY32F ramp, LINEAR); the others are
  // looked up texel by texel (GL_NEAREST, §2).
  const GLint filter = texels == kRampTexelsFloat ? GL_LINEAR : GL_NEAREST;
  Texture t = makeTexture();
  glBindTexture(GL_TEXTURE_1D, t.id());
  glTexImage1D(GL_TEXTURE_1D, 0, format, texels, 0, GL_RED, GL_FLOAT, ramp.data());
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, filter);
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_1D, 0);
  return t;
}

glm::vec4 depthPlane(const Scene& scene) {
  const DepthRange r = lightDepthRange(scene);
  const glm::mat4 view = lightView(scene.light);
  // Eye-space depth -z_e = -(row 2 of the view matrix) · world.
  const glm::vec4 depthRow(-view[0][2], -view[1][2], -view[2][2], -view[3][2]);
  glm::vec4 plane = depthRow / (r.farPlane - r.nearPlane);
  plane.w -= r.nearPlane / (r.farPlane - r.nearPlane);
  return plane;
}

namespace {
// The bias in units of d, in double as legacy_gl computes it before building its matrix.
double depthBiasD(const RenderParams& params) { return params.number(depthBiasParam()) * kStep8; }
}  // namespace

float depthBias(const RenderParams& params) { return float(depthBiasD(params)); }

void setLegacyArithmeticUniforms(const Program& program, const RenderParams& params) {
  const bool twelve = depthBits(params) == 12;
  const bool floatBuffer = legacyFloatBuffer(params);
  // A float colour buffer stores values as they are: no code, read back unscaled.
  const float bufferMax = floatBuffer ? 1.0f : twelve ? 65535.0f : 255.0f;
  program.set("uFloatBuffer", floatBuffer ? 1 : 0);
  program.set("uBufferMax", bufferMax);
  program.set("uReadScale", 1.0f / bufferMax);
  program.set("uSaturateScale", float(1.0 / depthStep(params)));
  program.set("uTableScale", float(1.0 / (depthStep(params) * kColorTableLastIndex)));
  program.set("uTableLastIndex", kColorTableLastIndex);
  // Mesa's own 16-bit accumulation buffer on OSMesa; imaging/'s emulation where the visual
  // has none (EGL pbuffers).
  program.set("uAccumMode", params.backend == Backend::kOsmesa ? 1 : 2);
  program.set("uAccumReturnScale", 1.0f / kAccumSteps);
}

glm::vec4 shadowShares(const RenderParams& params, int samples) {
  const double m = channelMax(params);
  const double each = std::ceil(m / samples);
  glm::vec4 shares(0.0f);
  for (int c = 0; c < samples; ++c) shares[c] = float(each / m);
  shares[samples - 1] = float((m - each * (samples - 1)) / m);
  return shares;
}

glm::mat4 eyeToRamp(const Scene& scene, int rampTexels, double bias) {
  const DepthRange range = lightDepthRange(scene);
  const double n = range.nearPlane, f = range.farPlane;
  const double texels = rampTexels;
  glm::mat4 m(0.0f);  // row 0 only (glm is [column][row]); q = w
  m[2][0] = float(-(texels - 1.0) / ((f - n) * texels));
  m[3][0] = float((0.5 + (texels - 1.0) * (-n / (f - n) - bias)) / texels);
  m[3][3] = 1.0f;
  return m;
}

glm::mat4 cameraEyeToRamp(const Scene& scene, const RenderParams& params) {
  const glm::mat4 cameraToLight = lightView(scene.light) * glm::inverse(cameraView(scene.camera));
  return eyeToRamp(scene, rampTexels(params), depthBiasD(params)) * cameraToLight;
}

glm::mat4 cameraEyeToShadowMap(const Scene& scene, int texels, glm::vec2 offsetTexels) {
  const glm::mat4 offset =
      glm::translate(glm::mat4(1.0f), glm::vec3(offsetTexels / float(texels), 0.0f));
  const glm::mat4 S = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) *
                      glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
  return offset * S * lightProjection(scene) * lightView(scene.light) *
         glm::inverse(cameraView(scene.camera));
}

void setTexgenObjectUniforms(const Program& program, const Object& object, const glm::mat4& view,
                             const glm::mat4& projection) {
  const glm::mat4 modelView = view * object.model;
  program.set("uModel", object.model);
  program.set("uModelView", modelView);
  program.set("uModelViewProjection", projection * modelView);
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
  const float farPlane[4] = {1, 1, 1, 1};
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
  glTexParameterfv(GL_TEXTURE_2D, GL_TEXTURE_BORDER_COLOR, farPlane);
  glBindTexture(GL_TEXTURE_2D, 0);
}

void renderEncodedDepth(const GpuScene& gpu, const RenderParams& params, const Texture& ramp,
                        const RenderTarget& target, glm::bvec4 channels, glm::vec2 offsetTexels) {
  target.bind();
  glClear(GL_DEPTH_BUFFER_BIT);  // each jittered pass has its own depth test
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glColorMask(channels.r, channels.g, channels.b, channels.a);
  const Program& program = cachedProgram("texgen.vert.glsl", "bs_encode_depth.frag.glsl");
  program.use();
  const Scene& scene = gpu.scene();
  // Shifting normalised device x by 2 j / N moves the image by j texels (Figure 3 jitter).
  const glm::mat4 jitter = glm::translate(
      glm::mat4(1.0f), glm::vec3(2.0f * offsetTexels / float(params.shadowMapTexels), 0.0f));
  const glm::mat4 projection = jitter * lightProjection(scene);
  const glm::mat4 view = lightView(scene.light);
  program.set("uEyeToRamp", eyeToRamp(scene, rampTexels(params), 0.0));
  program.set("uDepthPlane", depthPlane(scene));
  program.set("uFaithful", arithmeticOf(params) == Arithmetic::kFaithful ? 1 : 0);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_1D, ramp.id());
  program.set("uRamp", 0);
  gpu.draw([](const Object& o) { return o.castsShadow; },
           [&](const Object& o) { setTexgenObjectUniforms(program, o, view, projection); });
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void shadowTestAndShade(const GpuScene& gpu, const RenderParams& params, const Texture& ramp,
                        const std::vector<SampleGroup>& groups, Frame& frame,
                        const pcf_bias::Settings& bias) {
  constexpr int kMaxGroups = 4;  // 4x4 = 16 samples = four RGBA maps
  if (groups.empty() || groups.size() > size_t(kMaxGroups))
    throw InputError("the shadow test takes 1 to 4 groups of samples");
  const Scene& scene = gpu.scene();
  const bool faithful = arithmeticOf(params) == Arithmetic::kFaithful;
  RenderTarget target = makeCameraTarget(params, true);  // visibility exactly as computed
  clearCameraTarget(target);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  const Program& program = cachedProgram("texgen.vert.glsl", "pcf_shadow.frag.glsl");
  program.use();
  const glm::mat4 view = cameraView(scene.camera);
  const glm::mat4 projection =
      cameraProjection(scene.camera, float(params.width) / float(params.height));
  program.set("uEyeToRamp", cameraEyeToRamp(scene, params));
  program.set("uDepthPlane", depthPlane(scene));
  program.set("uBias", depthBias(params));
  program.set("uFaithful", faithful ? 1 : 0);
  // texgen.vert's normal offset (0: none); set on every use, the program is cached.
  program.set(
      "uNormalOffsetPerDistance",
      bias.normalOffsetTexels * pcf_bias::footprintPerDistance(scene, params.shadowMapTexels));
  program.set("uNormalOffsetByAngle", bias.normalOffsetByAngle ? 1 : 0);
  setLegacyArithmeticUniforms(program, params);
  program.set("uGroupCount", int(groups.size()));
  setLightingUniforms(program, scene);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_1D, ramp.id());
  program.set("uRamp", 0);
  int footprint = 0;
  for (const SampleGroup& group : groups) footprint += group.samples;
  for (int g = 0; g < kMaxGroups; ++g) {
    const SampleGroup& group = groups[std::min<size_t>(g, groups.size() - 1)];
    // The legacy weight: float(samples / footprint), computed in double as glAccum's value.
    const float weight = float(double(group.samples) / double(footprint));
    glActiveTexture(GLenum(GL_TEXTURE1 + g));
    glBindTexture(GL_TEXTURE_2D, group.map);
    // "[g]", built in place: GCC 12's -Wrestrict misfires on "[" + std::to_string(g).
    std::string i = std::to_string(g);
    i = '[' + i + ']';
    program.set(("uMaps" + i).c_str(), 1 + g);
    program.set(("uGroupSamples" + i).c_str(), group.samples);
    program.set(("uEyeToShadowMap" + i).c_str(),
                cameraEyeToShadowMap(scene, params.shadowMapTexels, group.offsetTexels));
    program.set(("uGroupShares" + i).c_str(), shadowShares(params, group.samples));
    program.set(("uGroupWeight" + i).c_str(), weight);
    program.set(("uGroupAccumScale" + i).c_str(), weight * kAccumSteps);
  }
  glActiveTexture(GL_TEXTURE0);
  gpu.draw([](const Object&) { return true; },
           [&](const Object& o) {
             setObjectUniforms(program, o);
             setTexgenObjectUniforms(program, o, view, projection);
           });
  readCameraTarget(target, frame);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

ParamSpec arithmeticParam() {
  return choiceParam("arithmetic", "faithful", {"faithful", "float"},
                     "faithful = the legacy twin's quantised steps bit for bit; float = plain "
                     "float arithmetic");
}

ParamSpec depthBiasParam() {
  constexpr double kMaxBiasSteps = 255.0;  // the whole depth range
  return numberParam("depth-bias", kDefaultDepthBiasSteps, 0.0, kMaxBiasSteps,
                     "depth bias in 8-bit depth steps, added before the comparison (§2)");
}

std::vector<ParamSpec> params() { return {arithmeticParam(), depthBiasParam()}; }

}  // namespace sl::modern::bs
