// figures/diagnostics.cpp — small dedicated renders for Everitt Figs. 2, 4 and 6.
//
// Passes:
//   1. renderLightDepth   — the light's view into an R32F target holding linearised depth
//                           (the shadow map as Everitt Fig. 2 right shows it) and an RGBA8
//                           target with N.L shading (Fig. 2 centre)
//   2. renderEyeProbe     — the eye's view into an RGBA32F target: own light depth (Fig. 4
//                           centre), the map's value at the pixel's projection (Fig. 4 right)
//                           and shadow-map texels per pixel from dFdx/dFdy (Fig. 6 left)
//   3. colourCodeDensity  — log2 of eye pixels per texel as a colour ramp (CPU)
//   4. renderLightDensity — the light's view again, into two RGBA32F targets: where the eye
//                           sees each of its points and the eye's texels per pixel there
//                           (Fig. 6 right)
//   5. colourLightDensity — the light's view coloured as pass 3 where the eye sees the point,
//                           grey where it does not (CPU)
#include "figures/diagnostics.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>

#include "core/base/errors.h"
#include "core/gl/context.h"
#include "core/gl/shaders.h"
#include "core/technique/technique.h"
#include "modern/gl_objects.h"

namespace sl::figures {
using namespace sl::gl;
using modern::GlName;
using modern::GpuScene;
using modern::RenderTarget;

namespace {

constexpr float kDensityLog2Range = 2.0f;  // colour ramp spans 1/4 .. 4 eye pixels per texel
constexpr float kOutsideGrey = 0.35f;      // pixels outside the light frustum
constexpr float kAmbient = 0.15f;          // light-view shading floor
// Fig. 6 right: the light's view where the eye does not see the point, grey and dimmed so the
// coloured part stands out (a share of the N.L shading's luminance).
constexpr float kUnseenGrey = 0.45f;
// A light-view point counts as seen by the eye when the eye pixel it falls into sees a point at
// its light depth: within the depth change across this many eye pixels (the eye pixel's centre
// is up to half a pixel away along each axis; twice that for the derivatives' 2x2 quads)...
constexpr float kSeenDepthPixels = 1.0f;
// ... plus this much of the light's depth range (float rounding of the two renders' depths).
constexpr float kSeenDepthEpsilon = 1e-4f;

// Reads colour attachment `index` of a target as float RGBA.
Image readTarget(const RenderTarget& target, int index) {
  target.bind();
  glReadBuffer(GL_COLOR_ATTACHMENT0 + index);
  Image image = readColorBuffer(0, 0, target.width, target.height);
  checkGl("figures: read-back");
  return image;
}

void setMat(GLuint program, const char* name, const glm::mat4& m) {
  glUniformMatrix4fv(glGetUniformLocation(program, name), 1, GL_FALSE, glm::value_ptr(m));
}

struct LightMatrices {
  glm::mat4 view;
  glm::mat4 projection;
  glm::mat4 clip;  // texture-space bias * projection * view (Everitt Eq. 1)
  DepthRange range;
};

LightMatrices lightMatrices(const Scene& scene) {
  LightMatrices m;
  m.view = lightView(scene.light);
  m.projection = lightProjection(scene);
  const glm::mat4 bias(0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 0.5f, 0, 0.5f, 0.5f, 0.5f, 1);
  m.clip = bias * m.projection * m.view;
  m.range = lightDepthRange(scene);
  return m;
}

void setCommon(GLuint program, const LightMatrices& lm, const glm::mat4& viewProjection) {
  glUseProgram(program);
  setMat(program, "uViewProjection", viewProjection);
  setMat(program, "uLightView", lm.view);
  setMat(program, "uLightClip", lm.clip);
  glUniform2f(glGetUniformLocation(program, "uDepthRange"), lm.range.nearPlane, lm.range.farPlane);
}

// Pass 1 (Everitt Fig. 2): depth and shading from the light, at `side` x `side`.
RenderTarget renderLightDepth(const GpuScene& gpu, const LightMatrices& lm, int side) {
  RenderTarget target = modern::makeRenderTarget(side, side, {GL_R32F, GL_RGBA8}, true);
  target.bind();
  const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glDrawBuffers(2, both);
  const float farDepth[4] = {1, 1, 1, 1};
  const float black[4] = {0, 0, 0, 1};
  glClearBufferfv(GL_COLOR, 0, farDepth);
  glClearBufferfv(GL_COLOR, 1, black);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  GlName<modern::deleteProgram> program(
      compileShaderProgram("diagnostics.vert.glsl", "diagnostics_light.frag.glsl"));
  setCommon(program.id(), lm, lm.projection * lm.view);
  const Scene& scene = gpu.scene();
  glUniform3fv(glGetUniformLocation(program.id(), "uLightPosition"), 1,
               glm::value_ptr(scene.light.position));
  glUniform1f(glGetUniformLocation(program.id(), "uAmbient"), kAmbient);
  gpu.draw([](const Object&) { return true; },
           [&](const Object& o) {
             setMat(program.id(), "uModel", o.model);
             glUniform3fv(glGetUniformLocation(program.id(), "uDiffuse"), 1,
                          glm::value_ptr(o.diffuse));
           });
  checkGl("figures: light view");
  return target;
}

// Pass 2 (Everitt Figs. 4 and 6): what the eye's pixels see of the light's map.
Image renderEyeProbe(const GpuScene& gpu, const LightMatrices& lm, const RenderTarget& light,
                     int width, int height, int texels) {
  RenderTarget target = modern::makeRenderTarget(width, height, {GL_RGBA32F}, true);
  target.bind();
  const float clear[4] = {0, 0, 0, 0};
  glClearBufferfv(GL_COLOR, 0, clear);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  GlName<modern::deleteProgram> program(
      compileShaderProgram("diagnostics.vert.glsl", "diagnostics_eye.frag.glsl"));
  const Scene& scene = gpu.scene();
  const float aspect = float(width) / float(height);
  setCommon(program.id(), lm, cameraProjection(scene.camera, aspect) * cameraView(scene.camera));
  glUniform1f(glGetUniformLocation(program.id(), "uTexels"), float(texels));
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, light.color[0].id());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glUniform1i(glGetUniformLocation(program.id(), "uLinearDepth"), 0);
  gpu.draw([](const Object&) { return true; },
           [&](const Object& o) { setMat(program.id(), "uModel", o.model); });
  checkGl("figures: eye probe");
  return readTarget(target, 0);
}

// Pass 3 (Everitt Fig. 6): colour code of the density.
Image colourCodeDensity(const Image& probe) {
  Image rgb(probe.width, probe.height, 3);
  for (int y = 0; y < probe.height; ++y)
    for (int x = 0; x < probe.width; ++x) {
      float c[3] = {0, 0, 0};
      const float texelsPerPixel = probe.at(x, y, 2);
      if (probe.at(x, y, 3) > 0.5f) {
        if (texelsPerPixel > 0.0f)
          densityColor(1.0f / texelsPerPixel, c);
        else
          c[0] = c[1] = c[2] = kOutsideGrey;
      }
      for (int k = 0; k < 3; ++k) rgb.at(x, y, k) = c[k];
    }
  return rgb;
}

// Pass 4 (Everitt Fig. 6 right): for each pixel of the light's view, its eye pixel, depth and
// the eye's density there, and the depth change across one eye pixel.
RenderTarget renderLightDensity(const GpuScene& gpu, const LightMatrices& lm, int side,
                                const glm::mat4& eyeViewProjection, int width, int height,
                                int texels) {
  RenderTarget target = modern::makeRenderTarget(side, side, {GL_RGBA32F, GL_RGBA32F}, true);
  target.bind();
  const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glDrawBuffers(2, both);
  const float nothing[4] = {0, 0, 0, -2};  // A = -2: no geometry
  glClearBufferfv(GL_COLOR, 0, nothing);
  glClearBufferfv(GL_COLOR, 1, nothing);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  GlName<modern::deleteProgram> program(
      compileShaderProgram("diagnostics.vert.glsl", "diagnostics_light_density.frag.glsl"));
  setCommon(program.id(), lm, lm.projection * lm.view);
  setMat(program.id(), "uEyeViewProjection", eyeViewProjection);
  glUniform2f(glGetUniformLocation(program.id(), "uEyeSize"), float(width), float(height));
  glUniform1f(glGetUniformLocation(program.id(), "uTexels"), float(texels));
  gpu.draw([](const Object&) { return true; },
           [&](const Object& o) { setMat(program.id(), "uModel", o.model); });
  checkGl("figures: light density");
  return target;
}

// Pass 5 (Everitt Fig. 6 right): "the very small portion of the light's image plane [that]
// needs high frequency sampling": the light's view in pass 3's colours where the eye sees the
// point (the eye pixel it falls into shows a point at its light depth, eye probe R), the
// light's N.L shading in dim grey elsewhere.
Image colourLightDensity(const Image& lightEye, const Image& lightSlope, const Image& shading,
                         const Image& probe) {
  Image rgb(lightEye.width, lightEye.height, 3);
  for (int y = 0; y < lightEye.height; ++y)
    for (int x = 0; x < lightEye.width; ++x) {
      float c[3];
      const float grey =
          kUnseenGrey * (0.299f * shading.at(x, y, 0) + 0.587f * shading.at(x, y, 1) +
                         0.114f * shading.at(x, y, 2));
      c[0] = c[1] = c[2] = grey;
      const float texelsPerPixel = lightEye.at(x, y, 3);
      const int ex = int(std::floor(lightEye.at(x, y, 0)));
      const int ey = int(std::floor(lightEye.at(x, y, 1)));
      if (texelsPerPixel > 0.0f && ex >= 0 && ey >= 0 && ex < probe.width && ey < probe.height &&
          probe.at(ex, ey, 3) > 0.5f) {
        const float tolerance = kSeenDepthPixels * lightSlope.at(x, y, 0) + kSeenDepthEpsilon;
        if (std::fabs(probe.at(ex, ey, 0) - lightEye.at(x, y, 2)) <= tolerance)
          densityColor(1.0f / texelsPerPixel, c);
      }
      for (int k = 0; k < 3; ++k) rgb.at(x, y, k) = c[k];
    }
  return rgb;
}

Image probeChannel(const Image& probe, int c) {
  Image out(probe.width, probe.height, 1);
  for (int y = 0; y < probe.height; ++y)
    for (int x = 0; x < probe.width; ++x)
      out.at(x, y) = probe.at(x, y, 3) > 0.5f ? std::clamp(probe.at(x, y, c), 0.0f, 1.0f) : 0.0f;
  return out;
}

}  // namespace

void densityColor(float pixelsPerTexel, float rgb[3]) {
  if (!(pixelsPerTexel > 0.0f) || !std::isfinite(pixelsPerTexel)) pixelsPerTexel = 1e-6f;
  // t in [0, 1]: 0 = 1/8 pixel per texel (red), 0.5 = one to one (green), 1 = 8 pixels (blue).
  const float t = std::clamp(
      (std::log2(pixelsPerTexel) + kDensityLog2Range) / (2.0f * kDensityLog2Range), 0.0f, 1.0f);
  if (t < 0.5f) {
    const float u = t / 0.5f;
    rgb[0] = 1.0f - u;
    rgb[1] = u;
    rgb[2] = 0.0f;
  } else {
    const float u = (t - 0.5f) / 0.5f;
    rgb[0] = 0.0f;
    rgb[1] = 1.0f - u;
    rgb[2] = u;
  }
}

DiagnosticViews renderDiagnostics(const Scene& scene, int width, int height, int texels,
                                  int lightSide) {
  ContextSpec spec;
  spec.profile = Profile::kCore;
  spec.width = std::max(width, lightSide);
  spec.height = std::max(height, lightSide);
  spec.accumulation = false;
  auto context = GlContext::create(spec);
  DiagnosticViews out;
  {
    GpuScene gpu(scene);
    const LightMatrices lm = lightMatrices(scene);
    // The map the eye probe reads has the shadow map's resolution; the picture of the light's
    // view has the figure's resolution.
    RenderTarget map = renderLightDepth(gpu, lm, texels);
    out.shadowMap = channel(readTarget(map, 0), 0);
    RenderTarget picture = renderLightDepth(gpu, lm, lightSide);
    out.lightView = toRgb(readTarget(picture, 1));
    const float aspect = float(width) / float(height);
    const glm::mat4 eyeViewProjection =
        cameraProjection(scene.camera, aspect) * cameraView(scene.camera);
    const Image probe = renderEyeProbe(gpu, lm, map, width, height, texels);
    out.lightDistance = probeChannel(probe, 0);
    out.projectedMap = probeChannel(probe, 1);
    out.texelDensity = colourCodeDensity(probe);
    RenderTarget density =
        renderLightDensity(gpu, lm, lightSide, eyeViewProjection, width, height, texels);
    out.lightDensity = colourLightDensity(readTarget(density, 0), readTarget(density, 1),
                                          readTarget(picture, 1), probe);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
  return out;
}

}  // namespace sl::figures
