// modern.volumes — Everitt & Kilgard 2002, "Practical and Robust Stenciled Shadow Volumes for
// Hardware-Accelerated Rendering": z-fail ("Carmack's reverse") stencil shadow volumes with caps
// and an infinite far plane, in a core-profile context. Chan 2004 §2.1.2 summarises the
// algorithm and uses it as the accurate half of the hybrid (modern.hybrid) and as the
// reference its Figures 3-7, 3-9 and 3-10 compare against.
//
// Everitt–Kilgard and Chan §3.1 assume closed 2-manifold blockers. Zero-area triangles are
// dropped before the adjacency is built (they block no ray) and closedness is judged from the
// remaining topology. Open casters (the brabec ground plane, a single quad, the decimated
// dragon) are not skipped: they get the volume of the two-sided, zero-thickness solid made of
// both faces of their triangles (DEVIATION in modern/silhouettes.h), which is exact for them
// too; they are counted in Frame::counters["open_casters_two_sided"].
//
// Passes:
//   1. findSilhouettesAndBuildVolumes — CPU: silhouette edges w.r.t. the light from edge
//      adjacency; front cap, back cap at infinity, side quads (Everitt–Kilgard §4-5)
//   2. fillDepthFromCamera            — the scene's depth (infinite far plane), stencil = 0
//   3. countVolumeCrossings           — z-fail: back faces ++, front faces -- on depth fail
//   4. shadeFromStencil               — lit where the count is 0, shadowed elsewhere
//   (then, untimed: measureVolumeFill, the overdraw counters of Chan Figure 3-10)
// The passes are declared once in volumesPasses().
#include "modern/shadow_volumes.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "core/base/errors.h"
#include "core/gl/winding.h"
#include "core/technique/passes.h"
#include "modern/camera_pass.h"

namespace sl::modern {
using namespace sl::gl;

namespace {
// Everitt–Kilgard's "tweaked" infinite projection keeps w = 0 vertices at depth just under 1 so
// that round-off cannot push them beyond the far clip plane (their §"Infinite far plane").
constexpr float kInfinityEpsilon = 2.4e-7f * 4.0f;  // a few 24-bit depth steps
// Chan Fig. 3-9a ("brighter = more layers") made readable: scaled linearly to its peak, a
// typical count is a few percent of the peak and reads as black (dragon: mean 23 over the
// covered pixels, peak 252). The grey level is log2(1 + n) / log2(1 + peak) instead, and a
// legend strip shows one box per power of two up to the peak, named in its caption.
struct OverdrawView {
  Image image, legend;
  std::string caption;
  std::string levelNames;  // the legend's boxes left to right: "0, 1, 2, 4, 8, 11"
};

OverdrawView overdrawView(const Image& counts) {
  constexpr int kLegendBox = 24;  // pixels per legend box (square)
  float peak = 1.0f;
  double sum = 0, covered = 0;
  for (float v : counts.data) {
    peak = std::max(peak, v);
    if (v > 0.5f) {
      sum += v;
      covered += 1;
    }
  }
  const float logPeak = std::log2(1.0f + peak);
  const auto grey = [&](float n) { return std::log2(1.0f + std::max(n, 0.0f)) / logPeak; };
  OverdrawView out;
  out.image = counts;
  for (float& v : out.image.data) v = grey(v);
  std::vector<int> levels = {0};
  for (int n = 1; n < int(peak); n *= 2) levels.push_back(n);
  levels.push_back(int(std::lround(peak)));
  out.legend = Image(kLegendBox * int(levels.size()), kLegendBox, 1);
  for (size_t i = 0; i < levels.size(); ++i) {
    for (int y = 0; y < kLegendBox; ++y)
      for (int x = 0; x < kLegendBox; ++x)
        out.legend.at(int(i) * kLegendBox + x, y, 0) = grey(float(levels[i]));
    out.levelNames += (i ? ", " : "") + std::to_string(levels[i]);
  }
  const int mean = covered > 0 ? int(std::lround(sum / covered)) : 0;
  out.caption = "shadow-volume overdraw per pixel, grey = log2(1 + n) / log2(1 + " +
                std::to_string(int(std::lround(peak))) + "): mean " + std::to_string(mean) +
                " over the covered pixels (grey " + std::to_string(grey(float(mean))).substr(0, 4) +
                "), peak " + std::to_string(int(std::lround(peak))) + " (white)";
  return out;
}
}  // namespace

SceneVolumes buildSceneVolumes(const SceneCasters& casters, const glm::vec3& lightWorld) {
  SceneVolumes out;
  for (const ShadowCaster& c : casters.casters) {
    const glm::vec3 light = glm::vec3(glm::inverse(c.object->model) * glm::vec4(lightWorld, 1));
    const Silhouette silhouette = findSilhouette(c.adjacency, light);
    const std::vector<glm::vec4> vertices = buildShadowVolume(c.adjacency, silhouette, light);
    GpuVolume g;
    g.vao = makeVertexArray();
    g.vertices = makeBuffer();
    glBindVertexArray(g.vao.id());
    glBindBuffer(GL_ARRAY_BUFFER, g.vertices.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(glm::vec4)), vertices.data(),
                 GL_STREAM_DRAW);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 0, nullptr);
    glEnableVertexAttribArray(0);
    glBindVertexArray(0);
    g.vertexCount = GLsizei(vertices.size());
    g.model = c.object->model;
    out.silhouetteEdges += (long long)silhouette.edges.size();
    out.triangles += (long long)vertices.size() / 3;
    out.volumes.push_back(std::move(g));
  }
  checkGl("upload shadow volumes");
  return out;
}

void drawVolumes(const SceneVolumes& volumes, const Program& program) {
  for (const GpuVolume& v : volumes.volumes) {
    program.set("uModel", v.model);
    // Two-sided stencil counts front faces down and back faces up: a mirrored caster's volume
    // must keep its outside as the front, or its count cancels another's (core/gl/winding.h).
    const FrontFaceForModel frontFace(v.model);
    glBindVertexArray(v.vao.id());
    glDrawArrays(GL_TRIANGLES, 0, v.vertexCount);
  }
  glBindVertexArray(0);
}

glm::mat4 infiniteCameraViewProjection(const Scene& scene, const RenderParams& params) {
  const Camera& c = scene.camera;
  const float aspect = float(params.width) / float(params.height);
  return glm::tweakedInfinitePerspective(glm::radians(c.fovyDegrees), aspect, c.nearPlane,
                                         kInfinityEpsilon) *
         cameraView(c);
}

RenderTarget makeStencilCameraTarget(const RenderParams& params,
                                     const std::vector<GLenum>& extraColor) {
  std::vector<GLenum> formats = {GL_RGBA8, GL_R32F};
  formats.insert(formats.end(), extraColor.begin(), extraColor.end());
  RenderTarget t = makeRenderTarget(params.width, params.height, formats, false);
  t.depth = makeTexture();
  glBindTexture(GL_TEXTURE_2D, t.depth.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH24_STENCIL8, t.width, t.height, 0, GL_DEPTH_STENCIL,
               GL_UNSIGNED_INT_24_8, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindTexture(GL_TEXTURE_2D, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, t.fbo.id());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, t.depth.id(),
                         0);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw GlError("camera target with depth-stencil is incomplete");
  const float black[4] = {0, 0, 0, 1};
  const float lit[4] = {1, 1, 1, 1};
  glViewport(0, 0, t.width, t.height);
  glClearBufferfv(GL_COLOR, 0, black);
  glClearBufferfv(GL_COLOR, 1, lit);
  for (size_t i = 2; i < formats.size(); ++i) glClearBufferfv(GL_COLOR, GLint(i), black);
  glDepthMask(GL_TRUE);
  glStencilMask(0xFF);
  glClearDepth(1.0);
  glClearStencil(0);
  glClear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  return t;
}

void countVolumesZFail(const SceneVolumes& volumes, const Program& volumeProgram, GLuint maskBit) {
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glDepthMask(GL_FALSE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);  // both faces in one pass (two-sided stencil, EXT_stencil_two_side)
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_EQUAL, GLint(maskBit), maskBit);  // maskBit 0: always passes
  glStencilMask(kStencilCountBits);
  glStencilOpSeparate(GL_BACK, GL_KEEP, GL_INCR_WRAP, GL_KEEP);
  glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_DECR_WRAP, GL_KEEP);
  volumeProgram.use();
  drawVolumes(volumes, volumeProgram);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  glStencilMask(0xFF);
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  glDisable(GL_STENCIL_TEST);
}

namespace {
// One shading draw of the whole scene where the stencil test (func, ref, mask) passes, with
// `visibility` as the shader's light term. Depth test LEQUAL against the camera pass's depth,
// no depth or stencil writes.
void drawWhereStencil(const GpuScene& gpu, const Program& shadeProgram, GLenum func, GLuint ref,
                      GLuint mask, float visibility) {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glEnable(GL_STENCIL_TEST);
  glStencilMask(0);
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  glStencilFunc(func, GLint(ref), mask);
  shadeProgram.use();
  shadeProgram.set("uVisibility", visibility);
  gpu.draw([](const Object&) { return true; },
           [&](const Object& o) { setObjectUniforms(shadeProgram, o); });
  glDisable(GL_STENCIL_TEST);
  glStencilMask(0xFF);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
}
}  // namespace

void shadeFromStencil(const GpuScene& gpu, const Program& shadeProgram, GLuint maskBit) {
  // Everitt–Kilgard: in shadow where the count is non-zero. With a computation mask, every
  // masked pixel is drawn as shadowed first and the lit ones overwrite it below.
  if (maskBit == 0)
    drawWhereStencil(gpu, shadeProgram, GL_NOTEQUAL, 0, kStencilCountBits, 0.0f);
  else
    drawWhereStencil(gpu, shadeProgram, GL_EQUAL, maskBit, maskBit, 0.0f);
  // ...and lit where it is zero.
  shadeLitFromStencil(gpu, shadeProgram, maskBit);
}

void shadeLitFromStencil(const GpuScene& gpu, const Program& shadeProgram, GLuint maskBit) {
  drawWhereStencil(gpu, shadeProgram, GL_EQUAL, maskBit, kStencilCountBits | maskBit, 1.0f);
}

VolumeFill measureVolumeFill(const RenderTarget& cameraTarget, const SceneVolumes& volumes,
                             const glm::mat4& viewProjection, GLuint maskBit,
                             bool depthBoundsMask) {
  // A float count buffer that shares the camera target's depth-stencil (for the mask).
  RenderTarget count = makeRenderTarget(cameraTarget.width, cameraTarget.height, {GL_R32F}, false);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D,
                         cameraTarget.depth.id(), 0);
  glViewport(0, 0, count.width, count.height);
  const float zero[4] = {0, 0, 0, 0};
  glClearBufferfv(GL_COLOR, 0, zero);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glDisable(GL_CULL_FACE);
  if (maskBit != 0) {
    glEnable(GL_STENCIL_TEST);
    glStencilMask(0);
    glStencilFunc(GL_EQUAL, GLint(maskBit), maskBit);
  }
  if (depthBoundsMask) glEnable(GL_DEPTH_BOUNDS_TEST_EXT);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  Program program("shadow_volume.vert.glsl", "volume_count.frag.glsl");
  program.use();
  program.set("uViewProjection", viewProjection);
  drawVolumes(volumes, program);
  glDisable(GL_BLEND);
  if (depthBoundsMask) glDisable(GL_DEPTH_BOUNDS_TEST_EXT);
  glDisable(GL_STENCIL_TEST);
  glStencilMask(0xFF);
  glDepthMask(GL_TRUE);
  VolumeFill fill;
  fill.overdraw = channel(readAttachment(count, 0), 0);
  for (float v : fill.overdraw.data) {
    fill.fragments += v;
    if (v > 0.5f) fill.coveredPixels += 1;
  }
  checkGl("measure shadow-volume fill");
  return fill;
}

Image stencilCountImage(const RenderTarget& cameraTarget) {
  std::vector<GLubyte> stencil(size_t(cameraTarget.width) * size_t(cameraTarget.height));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, cameraTarget.fbo.id());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, cameraTarget.width, cameraTarget.height, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE,
               stencil.data());
  checkGl("read stencil");
  Image image(cameraTarget.width, cameraTarget.height, 1);
  for (size_t i = 0; i < stencil.size(); ++i)
    image.data[i] = (stencil[i] & kStencilCountBits) != 0 ? 0.0f : 1.0f;
  return image;
}

void reportVolumeCounters(const SceneCasters& casters, const SceneVolumes& volumes,
                          const VolumeFill& fill, const RenderParams& params, Frame& frame) {
  const double pixels = double(params.width) * params.height;
  frame.counters["closed_casters"] = casters.closed;
  frame.counters["open_casters_two_sided"] = casters.open;
  frame.counters["silhouette_edges"] = double(volumes.silhouetteEdges);
  frame.counters["volume_triangles"] = double(volumes.triangles);
  // Chan Figure 3-10: black bars (share of the image covered by shadow volumes) and the number
  // beside them (overdraw = shadow-polygon pixels / image size).
  frame.counters["volume_coverage"] = fill.coveredPixels / pixels;
  frame.counters["volume_overdraw"] = fill.fragments / pixels;
}

void reportVolumePassInvocations(double invocations, const RenderParams& params, Frame& frame) {
  // Fragment-shader invocations of the stencil pass per image pixel: beside volume_overdraw
  // (every rasterised volume fragment) and masked_overdraw (those the mask lets through), what
  // the driver actually ran. Absent where the driver has no pipeline statistics query.
  if (invocations >= 0)
    frame.counters["volume_pass_fs_invocations"] =
        invocations / (double(params.width) * params.height);
}

namespace {

// The passes, declared once: names, the paper's text, the buffers a dump shows, shaders.
PassTable volumesPasses() {
  return {
      {.id = "1",
       .name = "silhouettes and volumes (CPU)",
       .reference = "Chan 2004 §2.1.2 (Fig. 2-6; Everitt & Kilgard [EK02]): silhouette edges "
                    "extruded from the light, capped, to an infinite far plane",
       .deviations = {kOpenMeshTwoSidedDeviation}},
      {.id = "2",
       .name = "depth from camera",
       .reference = "Chan 2004 §2.1.2: the scene's depth from the camera, which the volumes are "
                    "tested against",
       .shaders = {"volume-vertex", "depth-only"}},
      {.id = "3",
       .name = "stencil volumes (z-fail)",
       .reference = "Chan 2004 §2.1.2 (Fig. 2-7) and §3.1 step 3: the robust z-fail stencil count "
                    "[EK02], front faces down, back faces up where the depth test fails",
       // The overdraw is measured after the frame (measureVolumeFill), untimed.
       .writes = {{.name = "volume-overdraw", .caption = "{overdraw} (Chan Fig. 3-9a)"},
                  {.name = "overdraw-legend",
                   .caption = "legend of the overdraw image: boxes left to right: {levels} layers"},
                  {.name = "stencil-count",
                   .caption = "stencil buffer after z-fail counting: black = non-zero count (in "
                              "shadow)"}},
       .shaders = {"volume-vertex", "depth-only"}},
      {.id = "4",
       .name = "shade from stencil",
       .reference = "Chan 2004 §2.1.2: lit where the stencil count is zero, shadowed elsewhere",
       .shaders = {"volume-vertex", "stencil-shade"}},
  };
}

const PassTable& passTable() {
  static const PassTable table = volumesPasses();
  return table;
}

// Pass 1 (Everitt–Kilgard; Chan §4.2 step 2): silhouette edges from edge adjacency, volumes.
SceneVolumes findSilhouettesAndBuildVolumes(Passes& passes, const Scene& scene,
                                            const SceneCasters& casters) {
  SceneVolumes volumes;
  passes.run("1", [&] { volumes = buildSceneVolumes(casters, scene.light.position); });
  return volumes;
}

// Pass 2 (Everitt–Kilgard, step 1 of the z-fail algorithm): depth of the visible surfaces.
void fillDepthFromCamera(Passes& passes, const GpuScene& gpu, const Program& depthProgram) {
  passes.run("2", [&] {
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    depthProgram.use();
    gpu.draw([](const Object&) { return true; },
             [&](const Object& o) { depthProgram.set("uModel", o.model); });
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  });
}

// Pass 3 (Everitt–Kilgard, z-fail): count the volume faces behind each visible surface.
void countVolumeCrossings(Passes& passes, const SceneVolumes& volumes,
                          const Program& volumeProgram) {
  passes.run("3", [&] { countVolumesZFail(volumes, volumeProgram, 0); });
}

// Pass 4 (Everitt–Kilgard, final pass): shade, lit only where the stencil count is zero.
void shadeWithStencil(Passes& passes, const GpuScene& gpu, const Program& shadeProgram) {
  passes.run("4", [&] { shadeFromStencil(gpu, shadeProgram, 0); });
}

Frame render(GlContext&, const Scene& scene, const RenderParams& params) {
  Frame frame;
  const SceneCasters casters = collectCasters(scene);
  GpuScene gpu(scene);
  const glm::mat4 viewProjection = infiniteCameraViewProjection(scene, params);
  Program depthProgram("shadow_volume.vert.glsl", "depth_only.frag.glsl");
  depthProgram.use();
  depthProgram.set("uViewProjection", viewProjection);
  Program shadeProgram("shadow_volume.vert.glsl", "stencil_shade.frag.glsl");
  shadeProgram.use();
  shadeProgram.set("uViewProjection", viewProjection);
  setLightingUniforms(shadeProgram, scene);
  RenderTarget target = makeStencilCameraTarget(params);
  Passes passes(frame, params, passTable());

  const SceneVolumes volumes = findSilhouettesAndBuildVolumes(passes, scene, casters);
  target.bind();
  fillDepthFromCamera(passes, gpu, depthProgram);
  const double volumeInvocations =
      countFragmentInvocations([&] { countVolumeCrossings(passes, volumes, depthProgram); });
  shadeWithStencil(passes, gpu, shadeProgram);
  readCameraTarget(target, frame);

  const VolumeFill fill = measureVolumeFill(target, volumes, viewProjection, 0, false);
  reportVolumeCounters(casters, volumes, fill, params, frame);
  reportVolumePassInvocations(volumeInvocations, params, frame);
  // The overdraw view's captions say its peak and mean: made only while dumping.
  if (passes.capturing()) {
    const OverdrawView view = overdrawView(fill.overdraw);
    passes.capture("3", "volume-overdraw", [&] { return view.image; }, {},
                   {{"overdraw", view.caption}});
    passes.capture("3", "overdraw-legend", [&] { return view.legend; }, {},
                   {{"levels", view.levelNames}});
  }
  passes.capture("3", "stencil-count", [&] { return stencilCountImage(target); });
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return frame;
}
}  // namespace

Technique shadowVolumesTechnique() {
  Technique t;
  t.name = "modern.volumes";
  t.paper = "Everitt & Kilgard 2002 (z-fail stencil shadow volumes; Chan 2004 §2.1.2)";
  t.summary = "z-fail stencil shadow volumes, CPU silhouettes, caps, infinite far plane";
  t.status = "complete (open casters get two-sided volumes)";
  t.needs.profile = Profile::kCore;
  t.reads = {};  // no shadow map, no filter, no colour-encoded depth
  t.plan.shadowWork = PlanTraits::ShadowWork::kShadowVolumes;
  t.passes = passTable();
  t.render = render;
  return t;
}

}  // namespace sl::modern
