#include "modern/prefiltered_maps.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <string>

#include "core/base/errors.h"

namespace sl::modern {
using namespace sl::gl;

namespace {
constexpr int kMaxOutputsPerPass = 8;     // separable_gaussian.frag declares 8 outputs
constexpr float kMaxAnisotropy = 16.0f;   // Annen Table 1: "16x anisotropic tri-linear"
constexpr int kMaxBlurTaps = 7;           // 7x7, the largest kernel of Annen Table 1
constexpr float kFarAway = 1e30f;         // larger than any light-view distance
constexpr float kDepthMargin = 0.02f;     // of the span, as lightDepthRange (core/scene/scene.cpp)
constexpr float kMinDepthSpan = 1e-6f;    // world units: a flat scene still gets a range
constexpr float kMinNearOverFar = 1e-4f;  // as lightDepthRange
const char* const kAnisotropicExtension = "GL_EXT_texture_filter_anisotropic";
}  // namespace

void setLinearDepthUniforms(const Program& program, const Scene& scene) {
  setLinearDepthUniforms(program, scene, lightDepthRange(scene));
}

void setLinearDepthUniforms(const Program& program, const Scene& scene, const DepthRange& range) {
  program.set("uLightView", lightView(scene.light));
  program.set("uLightNear", range.nearPlane);
  program.set("uLightFar", range.farPlane);
}

namespace {
// Light-view vertices of one triangle of `o` (x, y lateral, z = distance along the axis).
void lightViewTriangle(const glm::mat4& toView, const Mesh& m, size_t t, glm::vec3 v[3]) {
  for (int k = 0; k < 3; ++k) {
    const glm::vec3 p = glm::vec3(toView * glm::vec4(m.positions[m.indices[t + k]], 1.0f));
    v[k] = {p.x, p.y, -p.z};
  }
}

// Certainly outside the square cone |x|, |y| <= tangent * z (all three vertices beyond the
// same lateral plane, or all behind the light).
bool outsideCone(const glm::vec3 v[3], float tangent) {
  auto all = [&](auto test) { return test(v[0]) && test(v[1]) && test(v[2]); };
  return all([&](const glm::vec3& p) { return p.x > tangent * p.z; }) ||
         all([&](const glm::vec3& p) { return p.x < -tangent * p.z; }) ||
         all([&](const glm::vec3& p) { return p.y > tangent * p.z; }) ||
         all([&](const glm::vec3& p) { return p.y < -tangent * p.z; }) ||
         all([](const glm::vec3& p) { return p.z <= 0.0f; });
}
}  // namespace

DepthRange fitShadowingDepthRange(const Scene& scene, float* nearestCaster) {
  const glm::mat4 view = lightView(scene.light);
  const float coneTangent = std::tan(glm::radians(0.5f * scene.light.coneDegrees));
  float casterNear = kFarAway, casterTangent = 0.0f;
  for (const Object& o : scene.objects) {
    if (!o.castsShadow || !o.mesh) continue;
    const glm::mat4 toView = view * o.model;
    for (size_t t = 0; t + 2 < o.mesh->indices.size(); t += 3) {
      glm::vec3 v[3];
      lightViewTriangle(toView, *o.mesh, t, v);
      if (outsideCone(v, coneTangent)) continue;
      for (const glm::vec3& p : v) {
        casterNear = std::min(casterNear, std::max(p.z, 0.0f));
        casterTangent =
            std::max(casterTangent,
                     p.z > 0.0f ? std::max(std::fabs(p.x), std::fabs(p.y)) / p.z : coneTangent);
      }
    }
  }
  if (casterNear >= kFarAway) {
    const DepthRange whole = lightDepthRange(scene);
    if (nearestCaster) *nearestCaster = whole.nearPlane;
    return whole;
  }
  if (nearestCaster) *nearestCaster = casterNear;
  casterTangent = std::min(casterTangent, coneTangent);
  float farthest = casterNear;
  for (const Object& o : scene.objects) {
    if (!o.receivesShadow || !o.mesh) continue;
    const glm::mat4 toView = view * o.model;
    for (size_t t = 0; t + 2 < o.mesh->indices.size(); t += 3) {
      glm::vec3 v[3];
      lightViewTriangle(toView, *o.mesh, t, v);
      if (outsideCone(v, casterTangent)) continue;
      for (const glm::vec3& p : v) farthest = std::max(farthest, p.z);
    }
  }
  const float span = std::max(farthest - casterNear, kMinDepthSpan);
  DepthRange r;
  r.farPlane = farthest + kDepthMargin * span;
  r.nearPlane = std::max(casterNear - kDepthMargin * span, r.farPlane * kMinNearOverFar);
  return r;
}

ParamSpec blurParam(int defaultTaps) {
  return integerParam("blur", defaultTaps, 0, kMaxBlurTaps,
                      "separable binomial blur of the map, taps per axis: 0 or 1 (none), 3, 5, 7 "
                      "(Annen §4.1, Table 1)");
}

ParamSpec filteringParam() {
  return choiceParam("filtering", "trilinear", {"anisotropic", "trilinear", "bilinear", "nearest"},
                     "how the camera pass samples the map (Annen Table 1: 16x anisotropic "
                     "tri-linear; Figs. 1, 10: tri-linear)");
}

ParamSpec anisotropyParam() {
  return autoNumberParam("anisotropy", 1, kMaxAnisotropy,
                         "GL_TEXTURE_MAX_ANISOTROPY; auto = 16 with filtering=anisotropic, else 1");
}

int parseBlurTaps(const RenderParams& params, const ParamSpec& blur) {
  const int taps = params.integer(blur);
  if (taps != 0 && taps != 1 && taps != 3 && taps != 5 && taps != 7)
    throw InputError("--param blur=" + std::to_string(taps) +
                     ": the Gaussian kernel must be 0 or 1 (none), 3, 5 or 7 texels wide");
  return taps <= 1 ? 0 : taps;
}

std::vector<float> binomialWeights(int taps) {
  // Row taps-1 of Pascal's triangle over 2^(taps-1): the binomial approximation of a Gaussian.
  std::vector<float> w(size_t(taps), 1.0f);
  for (int i = 1; i < taps; ++i) w[size_t(i)] = w[size_t(i - 1)] * float(taps - i) / float(i);
  const float total = std::ldexp(1.0f, taps - 1);
  for (float& v : w) v /= total;
  return w;
}

MapFiltering parseFiltering(const GlContext& context, const RenderParams& params) {
  MapFiltering f;
  // Default tri-linear, the filtering of Annen Figs. 1 and 10 ("regular tri-linear
  // filtering"); Table 1 and Fig. 7 (c)-(f) add 16x anisotropy (filtering=anisotropic).
  // Not anisotropic by default: llvmpipe filters anisotropically in software, up to 16
  // tri-linear probes per lookup, and CSM makes M lookups per pixel: its camera pass cost
  // 240-830 ms against 40-110 ms tri-linear on the bench scenes (brabec and fence, 256x192
  // and 400x300, map 512, M = 16), where the paper's GPU pays 1.6-3x PCF for all of CSM.
  const std::string mode = params.text(filteringParam());
  f.mipmaps = mode == "anisotropic" || mode == "trilinear";
  f.linear = mode != "nearest";
  // "anisotropic" is Table 1's "16x anisotropic tri-linear"; an explicit --param anisotropy
  // applies to "trilinear" too.
  const float fallback = mode == "anisotropic" ? kMaxAnisotropy : 1.0f;
  const float asked = float(params.numberOrAuto(anisotropyParam()).value_or(fallback));
  if (!context.caps().hasExtension(kAnisotropicExtension)) {
    f.anisotropy = 1.0f;
  } else {
    float most = 1.0f;
    glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &most);
    f.anisotropy = std::clamp(asked, 1.0f, std::max(most, 1.0f));
  }
  if (!f.mipmaps) f.anisotropy = 1.0f;  // anisotropic filtering refines the mip footprint
  return f;
}

LayeredMap makeLayeredMap(int size, int layers, GLenum format, bool mipmapped) {
  LayeredMap m;
  m.texture = makeTexture();
  m.size = size;
  m.layers = layers;
  m.format = format;
  m.levels = 1;
  if (mipmapped)
    while ((size >> m.levels) > 0) ++m.levels;
  glBindTexture(GL_TEXTURE_2D_ARRAY, m.texture.id());
  // Immutable storage, every level at once. Allocated level by level with glTexImage3D, a 2x2
  // or 3x3 map with two or more layers (two mip levels) came back GL_FRAMEBUFFER_UNSUPPORTED
  // from Mesa 22 llvmpipe when its layers were attached (stability case map_2x2, modern.csm);
  // 1x1 and 4x4 and up were complete. With glTexStorage3D every size is.
  glTexStorage3D(GL_TEXTURE_2D_ARRAY, m.levels, format, size, size, layers);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_BASE_LEVEL, 0);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, m.levels - 1);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  checkGl("allocate layered shadow map");
  return m;
}

const LayeredMap& reuseLayeredMap(LayeredMap& slot, int size, int layers, GLenum format,
                                  bool mipmapped) {
  int levels = 1;
  if (mipmapped)
    while ((size >> levels) > 0) ++levels;
  if (slot.texture.id() == 0 || slot.size != size || slot.layers != layers ||
      slot.format != format || slot.levels != levels)
    slot = makeLayeredMap(size, layers, format, mipmapped);
  return slot;
}

PrefilterWorkspace::~PrefilterWorkspace() {
  depth.fbo.release();
  for (Texture& t : depth.color) t.release();
  depth.depth.release();
  map.texture.release();
  scratch.texture.release();
  fbo.release();
  depthBounds.release();
  depthBoundsDilated.release();
}

PrefilterWorkspace& prefilterWorkspace(GlContext& context, const std::string& key) {
  auto* workspace = static_cast<PrefilterWorkspace*>(context.layerState(key));
  if (workspace == nullptr) {
    auto fresh = std::make_shared<PrefilterWorkspace>();
    workspace = fresh.get();
    context.setLayerState(key, fresh);
  }
  return *workspace;
}

std::vector<double> sceneViewKey(const Scene& scene, const RenderParams& params) {
  std::vector<double> k;
  // push_back, not insert of an initializer list: GCC 12's -Wstringop-overflow misfires on it.
  auto add = [&](const glm::vec3& v) {
    k.push_back(v.x);
    k.push_back(v.y);
    k.push_back(v.z);
  };
  const Camera& c = scene.camera;
  add(c.position);
  add(c.target);
  add(c.up);
  k.insert(k.end(), {c.fovyDegrees, c.nearPlane, c.farPlane});
  const SpotLight& l = scene.light;
  add(l.position);
  add(l.target);
  add(l.up);
  k.insert(k.end(), {l.coneDegrees, l.nearPlane.value_or(-1.0f), l.farPlane.value_or(-1.0f)});
  k.insert(k.end(), {double(params.width), double(params.height), double(params.shadowMapTexels)});
  for (const Object& o : scene.objects) {
    k.push_back(double(reinterpret_cast<std::uintptr_t>(o.mesh.get())));
    k.push_back(o.mesh ? double(o.mesh->positions.size()) : 0.0);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) k.push_back(o.model[i][j]);
    k.push_back((o.castsShadow ? 1.0 : 0.0) + (o.receivesShadow ? 2.0 : 0.0));
  }
  return k;
}

int layersPerPass() {
  GLint most = 1;
  glGetIntegerv(GL_MAX_DRAW_BUFFERS, &most);
  return std::clamp(int(most), 1, kMaxOutputsPerPass);
}

void attachLayers(const Framebuffer& fbo, const LayeredMap& map, int first, int count, int level) {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
  std::vector<GLenum> buffers;
  for (int i = 0; i < kMaxOutputsPerPass; ++i) {
    const GLenum attachment = GLenum(GL_COLOR_ATTACHMENT0 + i);
    if (i < count) {
      glFramebufferTextureLayer(GL_FRAMEBUFFER, attachment, map.texture.id(), level, first + i);
      buffers.push_back(attachment);
    } else if (i < layersPerPass()) {
      glFramebufferTextureLayer(GL_FRAMEBUFFER, attachment, 0, 0, 0);
    }
  }
  glDrawBuffers(GLsizei(buffers.size()), buffers.data());
  if (const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
      status != GL_FRAMEBUFFER_COMPLETE) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04X", unsigned(status));
    throw GlError("layered shadow map framebuffer is incomplete (status " + std::string(code) +
                  ", layers " + std::to_string(first) + ".." + std::to_string(first + count - 1) +
                  " of " + std::to_string(map.layers) + ", " + std::to_string(map.size) + "^2)");
  }
  const int side = std::max(map.size >> level, 1);
  glViewport(0, 0, side, side);
}

void blurLayers(const LayeredMap& map, int taps) {
  LayeredMap scratch;
  blurLayers(map, scratch, taps);
}

void blurLayersOneDirection(const LayeredMap& source, const LayeredMap& target, int taps,
                            BlurDirection direction, const Framebuffer& fbo) {
  const std::vector<float> weights = binomialWeights(taps);
  const FullScreenTriangle triangle;
  const bool horizontal = direction == BlurDirection::kHorizontal;
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D_ARRAY, source.texture.id());
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  const int perPass = layersPerPass();
  for (int first = 0; first < source.layers; first += perPass) {
    const int count = std::min(perPass, source.layers - first);
    // One program per (taps, layers per pass): constant loop bounds (the shader's header).
    const Program& program =
        cachedProgram("fullscreen.vert.glsl", "separable_gaussian.frag.glsl",
                      {{"TAPS", std::to_string(taps)}, {"LAYERS", std::to_string(count)}});
    program.use();
    program.set("uSource", 0);
    glUniform1fv(program.uniform("uWeights"), GLsizei(weights.size()), weights.data());
    glUniform2i(program.uniform("uStep"), horizontal ? 1 : 0, horizontal ? 0 : 1);
    attachLayers(fbo, target, first, count);
    program.set("uFirstLayer", first);
    triangle.draw();
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
}

void blurLayers(const LayeredMap& map, LayeredMap& scratchSlot, int taps) {
  const LayeredMap& scratch = reuseLayeredMap(scratchSlot, map.size, map.layers, map.format, false);
  const Framebuffer fbo = makeFramebuffer();
  // Horizontal: map -> scratch; vertical: scratch -> map (the separable kernel, §4.1).
  blurLayersOneDirection(map, scratch, taps, BlurDirection::kHorizontal, fbo);
  blurLayersOneDirection(scratch, map, taps, BlurDirection::kVertical, fbo);
}

namespace {
// DEVIATION (Annen et al. 2007, §4.1: "using the auto-mip-map feature of modern GPUs"): the
// chain is drawn level by level with layered_downsample.frag, up to GL_MAX_DRAW_BUFFERS layers
// per draw, instead of glGenerateMipmap. The filter is the same 2x2 box for the power-of-two
// maps; on Mesa 22 llvmpipe glGenerateMipmap of CSM's 8 layers of 512^2 took 13-83 ms on the
// bench scenes, the drawn chain 5-13 ms.
void drawMipChain(const LayeredMap& map) {
  const Framebuffer fbo = makeFramebuffer();
  const FullScreenTriangle triangle;
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D_ARRAY, map.texture.id());
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  const int perPass = layersPerPass();
  for (int level = 1; level < map.levels; ++level) {
    // Read level - 1 only while level is drawn: no feedback loop (glspec §4.4.3).
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_BASE_LEVEL, level - 1);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, level - 1);
    for (int first = 0; first < map.layers; first += perPass) {
      const int count = std::min(perPass, map.layers - first);
      const Program& program = cachedProgram("fullscreen.vert.glsl", "layered_downsample.frag.glsl",
                                             {{"LAYERS", std::to_string(count)}});
      program.use();
      program.set("uSource", 0);
      program.set("uFirstLayer", first);
      attachLayers(fbo, map, first, count, level);
      triangle.draw();
    }
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glBindTexture(GL_TEXTURE_2D_ARRAY, map.texture.id());
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_BASE_LEVEL, 0);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, map.levels - 1);
}
}  // namespace

const char* const kDrawnMipChainDeviation =
    "DEVIATION (Annen et al. 2007, §4.1: \"using the auto-mip-map feature of modern GPUs\"): the "
    "chain is drawn level by level with layered_downsample.frag, up to GL_MAX_DRAW_BUFFERS layers "
    "per draw, instead of glGenerateMipmap. The filter is the same 2x2 box for the power-of-two "
    "maps; on Mesa 22 llvmpipe glGenerateMipmap of CSM's 8 layers of 512^2 took 13-83 ms on the "
    "bench scenes, the drawn chain 5-13 ms.";

void buildMipmapsAndSetFiltering(const LayeredMap& map, const MapFiltering& filtering) {
  if (filtering.mipmaps && map.levels > 1) drawMipChain(map);
  glBindTexture(GL_TEXTURE_2D_ARRAY, map.texture.id());
  const GLint magnify = filtering.linear ? GL_LINEAR : GL_NEAREST;
  const GLint minify = filtering.mipmaps && map.levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : magnify;
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, minify);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, magnify);
  if (filtering.anisotropy > 1.0f)
    glTexParameterf(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_ANISOTROPY, filtering.anisotropy);
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  checkGl("mip-maps and filtering of the shadow map");
}

Image readLayer(const LayeredMap& map, int layer, float scale, float bias, int level) {
  const Framebuffer fbo = makeFramebuffer();
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo.id());
  glFramebufferTextureLayer(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, map.texture.id(), level,
                            layer);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  const int size = std::max(map.size >> level, 1);
  Image rgba(size, size, 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, size, size, GL_RGBA, GL_FLOAT, rgba.data.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  checkGl("read shadow map layer");
  for (float& v : rgba.data) v = std::clamp(v * scale + bias, 0.0f, 1.0f);
  return rgba;
}

}  // namespace sl::modern
