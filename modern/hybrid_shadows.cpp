// modern.hybrid — Eric Chan, "Hardware-Accelerated Rendering of Hard and Soft Shadows", MIT
// 2004, chapter 3: "Hybrid Shadow Rendering Using Computation Masks" (after Chan & Durand 2004).
// A shadow map finds the pixels near shadow silhouettes; z-fail shadow volumes (Everitt &
// Kilgard 2002, modern.volumes) are rasterised only there, through a computation mask; the
// shadow map decides every other pixel.
//
// Passes (§3.1 steps 1-4, §3.2):
//   1. renderShadowMap          — step 1: depth from the light, hardware 2x2 compare
//   2. findSilhouettesAndBuildVolumes — CPU silhouette edges and capped volumes (as modern.volumes)
//   3. classifySilhouettePixels — step 2, Figure 3-3: camera pass; 2x2 compare strictly between
//                                 0 and 1 on a light-facing surface = silhouette pixel; others
//                                 are shaded from the shadow map; fills the depth buffer (and,
//                                 with mask-pass=classify, the stencil mask bit)
//   4. buildComputationMask     — §3.2: EXT_depth_bounds_test where the driver has it (depth of
//                                 non-silhouette pixels := 0, bounds [eps, 1]); otherwise a
//                                 stencil bit (same effect: no stencil update off the mask),
//                                 and with mask=tiles also the screen tiles that hold silhouette
//                                 pixels (§3.4.2's conservative tile culling, as scissor boxes)
//   5. drawVolumesThroughMask   — step 3: z-fail stencil counting at silhouette pixels only
//   6. shadeLitSilhouettePixels — step 4: the scene drawn once where the count is zero (the
//                                 classification pass already shaded silhouette pixels as
//                                 shadowed)
//   (then, untimed: counters of Figures 3-9 and 3-10 — overdraw with and without the mask, the
//    share of silhouette pixels)
// The passes are declared once in hybridPasses().
#include "modern/hybrid_shadows.h"

#include <algorithm>
#include <vector>

#include "core/base/errors.h"
#include "core/technique/passes.h"
#include "modern/camera_pass.h"
#include "modern/hardware_shadow_map.h"
#include "modern/shadow_volumes.h"

namespace sl::modern {
using namespace sl::gl;

namespace {
constexpr float kDefaultOffsetFactor = 2.0f;  // as modern.hw (Everitt et al. Fig. 3)
constexpr float kDefaultOffsetUnits = 4.0f;
constexpr double kLargestOffsetUnits = 1e6;  // depth steps; far beyond any useful offset
// §3.2: "set the depth bounds to [eps, 1] for some small constant eps ~ 0.001".
constexpr double kDepthBoundsMin = 0.001;
constexpr double kDepthBoundsMax = 1.0;

// llvmpipe's rasteriser bins every triangle into 64x64-pixel tiles (TILE_SIZE, Mesa
// lp_limits.h) after clipping its bounds to the scissor box: the scissor is the only test it
// applies before rasterisation, so it is the granularity at which a mask can skip work there.
constexpr int kMaskTilePixels = 64;
// Each scissor box re-issues every volume's draw call (llvmpipe sets up every volume triangle
// again per box); when the boxes cover more than this share of the image they skip too few
// fragments to pay for that, and the volumes are drawn once, through the stencil bit only.
// Measured at 800x600 (docs/volumes.md): dragon, boxes over 49.5% of the image holding 87% of
// the volume fragments, made the volume pass 1.6x slower; trees (39%) made it slower too;
// brabec (30%) halved its fragment-shader invocations at about the same time; fill-bound (18%)
// made it 2.3x cheaper.
constexpr double kMaxScissoredImageShare = 1.0 / 3.0;

enum class MaskKind { kDepthBounds, kStencil, kStencilTiles };

// The DEVIATION comments of the passes below, for the pass table.
constexpr const char* kMaskInClassificationDeviation =
    "DEVIATION (Chan §3.2, \"we draw a screen-aligned quad\" to set up the mask): the stencil "
    "mask bit is written here, by the fragment that wins the depth test (its stencil reference "
    "is the bit at silhouette pixels, 0 elsewhere), saving the full-screen pass. Chan's "
    "depth-bounds mask cannot be folded in: it overwrites the depth this pass must keep.";
constexpr const char* kStencilMaskDeviation =
    "DEVIATION (Chan §3.2): without EXT_depth_bounds_test (llvmpipe) the mask is stencil bit 7, "
    "set at silhouette pixels; later passes test it. Setting depth to 0 instead would not do: "
    "z-fail counts exactly the fragments that fail the depth test.";
constexpr const char* kScissorTilesDeviation =
    "DEVIATION (Chan §3.2, §3.4.2): the tile level of the mask is read back to the CPU and "
    "becomes scissor boxes, because llvmpipe rejects work before rasterisation only by the "
    "scissor; its per-fragment stencil test runs inside the fragment function, after the "
    "rasteriser has already produced every fragment (measured in docs/volumes.md).";

// The DEVIATION comments of hybrid_classify.frag's conservative classifier, for the pass table.
constexpr const char* kPlaneBackFacingDeviation =
    "DEVIATION (Chan 2004 §3.1 step 2, \"pixels that are back-facing with respect to "
    "the light are always in shadow\"): back-facing is judged by the triangle's "
    "plane, as the volumes' light-facing caps judge it, not by the interpolated "
    "normal, and only on objects that have a volume (a receiver that casts nothing "
    "has none around its far side).";
constexpr const char* kUnsureNeighbourhoodDeviation =
    "DEVIATION (Chan 2004 §3.3.1: an affected pixel's depth \"usually lies between "
    "the depth values of two adjacent samples\"; \"usually\" is not always): the "
    "pixel is unsure, and goes to the volumes, when any of the 4x4 samples around it "
    "— the 2x2 compares one texel off diagonally, together covering the 16 nearest "
    "texels — disagrees with the centre's.";

// The passes of §3.1 steps 1-4 and §3.2, declared once: names, the thesis's text, the buffers a
// dump shows, shaders and deviations.
PassTable hybridPasses() {
  return {
      {.id = "1",
       .name = "shadow map",
       .reference = "Chan 2004 §3.1 step 1 (\"Create a shadow map\"), read with the hardware 2x2 "
                    "compare",
       .shaders = {"depth-only"}},
      {.id = "2",
       .name = "silhouettes and volumes (CPU)",
       .reference = "Chan 2004 §3.1 step 3 needs them: silhouette edges and z-fail volumes "
                    "(§2.1.2, [EK02]) on the CPU",
       .deviations = {kOpenMeshTwoSidedDeviation}},
      {.id = "3",
       .name = "classify silhouette pixels",
       .reference = "Chan 2004 §3.1 step 2 (\"Identify shadow silhouette pixels\"), Fig. 3-3; "
                    "the other pixels shaded from the shadow map",
       .writes = {{.name = "silhouette-pixels",
                   .caption = "silhouette pixels (Chan Fig. 3-1b, 3-9b)"},
                  {.name = "decision",
                   .caption = "what decided each pixel: red = silhouette pixel (the volumes), "
                              "green = shadowed as back-facing to the light, blue = the shadow "
                              "map's centre 2x2 compare"}},
       .shaders = {"volume-vertex", "classify"},
       .deviations = {kMaskInClassificationDeviation, kPlaneBackFacingDeviation,
                      kUnsureNeighbourhoodDeviation}},
      {.id = "4",
       .name = "computation mask",
       .reference = "Chan 2004 §3.4.2 (computation masks): later passes run only at silhouette "
                    "pixels; here as depth and scissor boxes (DEVIATION)",
       .shaders = {"computation-mask"},
       .deviations = {kStencilMaskDeviation, kScissorTilesDeviation}},
      {.id = "5",
       .name = "shadow volumes at silhouette pixels",
       .reference = "Chan 2004 §3.1 step 3 (\"Draw shadow volumes\"): z-fail stencil counts at "
                    "silhouette pixels only",
       .writes = {{.name = "stencil-count",
                   .caption = "stencil buffer: volumes counted at silhouette pixels only, black = "
                              "non-zero (Chan Fig. 3-1c, 3-9c)"}},
       .shaders = {"volume-vertex", "depth-only"}},
      {.id = "6",
       .name = "shade silhouette pixels",
       .reference = "Chan 2004 §3.1 step 4 (\"Compute shadows\"): shade the silhouette pixels "
                    "whose stencil count is zero",
       .writes = {{.name = "classification",
                   .caption = "red/blue: shadow map shadowed/lit; black/green: volumes "
                              "shadowed/lit (Chan Fig. 3-5b)"}},
       .shaders = {"volume-vertex", "stencil-shade"}},
  };
}

const PassTable& passTable() {
  static const PassTable table = hybridPasses();
  return table;
}

// A scissor box in window pixels.
struct TileRect {
  int x = 0, y = 0, width = 0, height = 0;
};

// §3.4.2 ("non-silhouette pixels tend to occupy large contiguous regions of screen space and
// can benefit from conservative tile-based culling"): the kMaskTilePixels tiles holding at
// least one silhouette pixel, merged into boxes — runs along each tile row, and runs of equal
// extent in consecutive rows joined. `tags` is one byte per pixel, rows bottom-up.
std::vector<TileRect> silhouetteTileRects(const std::vector<unsigned char>& tags, int width,
                                          int height) {
  const int tilesX = (width + kMaskTilePixels - 1) / kMaskTilePixels;
  const int tilesY = (height + kMaskTilePixels - 1) / kMaskTilePixels;
  std::vector<char> hit(size_t(tilesX) * size_t(tilesY), 0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (tags[size_t(y) * size_t(width) + size_t(x)] != 0)
        hit[size_t(y / kMaskTilePixels) * size_t(tilesX) + size_t(x / kMaskTilePixels)] = 1;
  std::vector<TileRect> rects;
  for (int j = 0; j < tilesY; ++j)
    for (int i = 0; i < tilesX;) {
      if (!hit[size_t(j) * size_t(tilesX) + size_t(i)]) {
        ++i;
        continue;
      }
      const int start = i;
      while (i < tilesX && hit[size_t(j) * size_t(tilesX) + size_t(i)]) ++i;
      const TileRect run{start * kMaskTilePixels, j * kMaskTilePixels,
                         std::min(i * kMaskTilePixels, width) - start * kMaskTilePixels,
                         std::min((j + 1) * kMaskTilePixels, height) - j * kMaskTilePixels};
      const auto above = std::find_if(rects.begin(), rects.end(), [&](const TileRect& r) {
        return r.x == run.x && r.width == run.width && r.y + r.height == run.y;
      });
      if (above != rects.end())
        above->height += run.height;
      else
        rects.push_back(run);
    }
  return rects;
}

// Runs `draws` once per box with the scissor test on (once, unscissored, when `rects` is null).
template <typename Draws>
void forEachScissorBox(const std::vector<TileRect>* rects, const Draws& draws) {
  if (rects == nullptr) {
    draws();
    return;
  }
  const ScopedEnable scissor(GL_SCISSOR_TEST);
  for (const TileRect& r : *rects) {
    glScissor(r.x, r.y, r.width, r.height);
    draws();
  }
}

// Pass 1 (§3.1 step 1): an ordinary shadow map, read with the hardware 2x2 compare.
RenderTarget renderShadowMap(Passes& passes, const GpuScene& gpu, const RenderParams& params,
                             const Program& program, float factor, float units) {
  RenderTarget map;
  passes.run("1", [&] {
    const int n = params.shadowMapTexels;
    map = makeRenderTarget(n, n, {}, true, GL_DEPTH_COMPONENT24);
    map.bind();
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    {
      const ScopedEnable polygonOffset(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(factor, units * lightDepthRoundoffScale(gpu.scene()));
      program.use();
      program.set("uViewProjection", lightProjection(gpu.scene()) * lightView(gpu.scene().light));
      // Every caster: each one has a shadow volume (open ones two-sided), so both halves of the
      // hybrid see the same blockers.
      gpu.draw([](const Object& o) { return o.castsShadow; },
               [&](const Object& o) { program.set("uModel", o.model); });
    }
    // GL_LINEAR with compare mode = the 2x2 percentage-closer filter of Figure 3-3.
    setDepthCompareParameters(map.depth.id(), /*linear=*/true);  // hardware 2x2 compare
    glBindTexture(GL_TEXTURE_2D, 0);
  });
  return map;
}

// Pass 2 (§3.1 step 3 needs them; Everitt–Kilgard): silhouette edges on the CPU, volumes.
SceneVolumes findSilhouettesAndBuildVolumes(Passes& passes, const Scene& scene,
                                            const SceneCasters& casters) {
  SceneVolumes volumes;
  passes.run("2", [&] { volumes = buildSceneVolumes(casters, scene.light.position); });
  return volumes;
}

// Pass 3 (§3.1 step 2, Figure 3-3): shade from the shadow map and tag silhouette pixels; the
// depth buffer keeps the nearest surfaces for the volumes (same vertex shader as the volumes).
void classifySilhouettePixels(Passes& passes, const GpuScene& gpu, const RenderTarget& target,
                              const RenderTarget& map, const Program& program,
                              const glm::mat4& viewProjection, bool writeMask) {
  passes.run("3", [&] {
    const Scene& scene = gpu.scene();
    target.bind();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    if (writeMask) {
      // DEVIATION (Chan §3.2, "we draw a screen-aligned quad" to set up the mask): the stencil
      // mask bit is written here, by the fragment that wins the depth test (its stencil reference
      // is the bit at silhouette pixels, 0 elsewhere), saving the full-screen pass. Chan's
      // depth-bounds mask cannot be folded in: it overwrites the depth this pass must keep.
      glEnable(GL_STENCIL_TEST);
      glStencilFunc(GL_ALWAYS, 0, 0xFF);
      glStencilMask(kStencilMaskBit);
      glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    }
    program.use();
    program.set("uViewProjection", viewProjection);
    const glm::mat4 S = glm::mat4(0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 0.5f, 0, 0.5f, 0.5f, 0.5f, 1);
    program.set("uWorldToShadowMap", S * lightProjection(scene) * lightView(scene.light));
    setLightingUniforms(program, scene);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, map.depth.id());
    program.set("uShadowMap", 0);
    gpu.draw([](const Object&) { return true; },
             [&](const Object& o) {
               setObjectUniforms(program, o);
               program.set("uCastsShadow", o.castsShadow ? 1 : 0);
             });
    if (writeMask) {
      glDisable(GL_STENCIL_TEST);
      glStencilMask(0xFF);
      glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    }
    glDepthFunc(GL_LESS);
  });
}

// The state drawMaskQuad changes, put back when it ends as the later passes expect it: colour
// and depth writes on, depth test GL_LESS, stencil test off, every stencil bit writable,
// stencil operations GL_KEEP.
class MaskQuadStateRestore {
 public:
  MaskQuadStateRestore() = default;
  ~MaskQuadStateRestore() {
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glDisable(GL_STENCIL_TEST);
    glStencilMask(0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  }
  MaskQuadStateRestore(const MaskQuadStateRestore&) = delete;
  MaskQuadStateRestore& operator=(const MaskQuadStateRestore&) = delete;
};

// §3.2's screen-aligned quad: the mask from the silhouette tags (depth := 0 off the
// silhouette for depth bounds, else the stencil bit on it).
void drawMaskQuad(const RenderTarget& target, const Program& program, MaskKind kind) {
  const MaskQuadStateRestore restore;
  program.use();
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, target.color[2].id());
  program.set("uSilhouette", 0);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  if (kind == MaskKind::kDepthBounds) {
    // Chan's set-up: non-silhouette depth := 0, then bounds [eps, 1] discard them early.
    program.set("uMode", 0);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
  } else {
    // DEVIATION (Chan §3.2): without EXT_depth_bounds_test (llvmpipe) the mask is stencil bit 7,
    // set at silhouette pixels; later passes test it. Setting depth to 0 instead would not do:
    // z-fail counts exactly the fragments that fail the depth test.
    program.set("uMode", 1);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, GLint(kStencilMaskBit), kStencilMaskBit);
    glStencilMask(kStencilMaskBit);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
  }
  const FullScreenTriangle triangle;
  triangle.draw();
  // The tags are an attachment of the bound framebuffer: leaving them bound to a texture unit
  // would make the driver synchronise every later draw (llvmpipe flushes per draw).
  glBindTexture(GL_TEXTURE_2D, 0);
}

// Pass 4 (§3.2): the computation mask from the silhouette tags (with mask=tiles, also the
// scissor boxes of the tiles that hold silhouette pixels, returned in `tiles`).
// Returns whether the later passes are to be scissored to `tiles` (mask=tiles, boxes covering at
// most kMaxScissoredImageShare of the image); the quad is then drawn inside the boxes only, since
// every silhouette pixel lies in one and nothing outside them is drawn again.
bool buildComputationMask(Passes& passes, const RenderTarget& target, const Program& program,
                          MaskKind kind, bool maskWritten, std::vector<TileRect>& tiles) {
  bool scissored = false;
  passes.run("4", [&] {
    target.bind();
    if (kind == MaskKind::kStencilTiles) {
      // DEVIATION (Chan §3.2, §3.4.2): the tile level of the mask is read back to the CPU and
      // becomes scissor boxes, because llvmpipe rejects work before rasterisation only by the
      // scissor; its per-fragment stencil test runs inside the fragment function, after the
      // rasteriser has already produced every fragment (measured in docs/volumes.md).
      std::vector<unsigned char> tags(size_t(target.width) * size_t(target.height));
      glReadBuffer(GL_COLOR_ATTACHMENT2);
      glPixelStorei(GL_PACK_ALIGNMENT, 1);
      glReadPixels(0, 0, target.width, target.height, GL_RED, GL_UNSIGNED_BYTE, tags.data());
      glReadBuffer(GL_COLOR_ATTACHMENT0);
      tiles = silhouetteTileRects(tags, target.width, target.height);
      double tilePixels = 0;
      for (const TileRect& r : tiles) tilePixels += double(r.width) * r.height;
      scissored =
          tilePixels <= kMaxScissoredImageShare * double(target.width) * double(target.height);
    }
    if (!maskWritten)
      forEachScissorBox(scissored ? &tiles : nullptr, [&] { drawMaskQuad(target, program, kind); });
  });
  return scissored;
}
GLuint maskBitFor(MaskKind kind) { return kind == MaskKind::kDepthBounds ? 0u : kStencilMaskBit; }

// Pass 5 (§3.1 step 3): z-fail stencil updates only at silhouette pixels.
void drawVolumesThroughMask(Passes& passes, const SceneVolumes& volumes,
                            const Program& volumeProgram, MaskKind kind,
                            const std::vector<TileRect>* tiles) {
  passes.run("5", [&] {
    if (kind == MaskKind::kDepthBounds) {
      glEnable(GL_DEPTH_BOUNDS_TEST_EXT);
      glDepthBoundsEXT(kDepthBoundsMin, kDepthBoundsMax);
    }
    forEachScissorBox(tiles, [&] { countVolumesZFail(volumes, volumeProgram, maskBitFor(kind)); });
    if (kind == MaskKind::kDepthBounds) glDisable(GL_DEPTH_BOUNDS_TEST_EXT);
  });
}

// Pass 6 (§3.1 step 4, "draw and shade the scene only at pixels with stencil values equal to
// zero"): the silhouette pixels were shaded as shadowed by pass 3; the lit ones (count zero)
// are drawn here, once.
void shadeLitSilhouettePixels(Passes& passes, const GpuScene& gpu, const Program& shadeProgram,
                              MaskKind kind, const std::vector<TileRect>* tiles) {
  passes.run("6", [&] {
    if (kind == MaskKind::kDepthBounds) glEnable(GL_DEPTH_BOUNDS_TEST_EXT);
    forEachScissorBox(tiles, [&] { shadeLitFromStencil(gpu, shadeProgram, maskBitFor(kind)); });
    if (kind == MaskKind::kDepthBounds) glDisable(GL_DEPTH_BOUNDS_TEST_EXT);
  });
}

// The classification pass's tags as an RGB image (hybrid_classify.frag.glsl, oSilhouette): red =
// silhouette pixel, green = shadowed as back-facing to the light, blue = the centre 2x2 compare.
Image decisionImage(const Image& tags) {
  Image out(tags.width, tags.height, 3);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int k = 0; k < 3; ++k) out.at(x, y, k) = tags.at(x, y, k);
  return out;
}

// Figure 3-5b: non-silhouette pixels red (shadow map: shadowed) / blue (lit); silhouette pixels
// black (volumes: shadowed) / green (lit).
Image classificationImage(const Image& silhouette, const Image& visibility) {
  Image out(silhouette.width, silhouette.height, 3);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const bool sil = silhouette.at(x, y) > 0.5f;
      const bool lit = visibility.at(x, y) > 0.5f;
      const glm::vec3 c = sil ? (lit ? glm::vec3(0, 1, 0) : glm::vec3(0))
                              : (lit ? glm::vec3(0.2f, 0.3f, 1) : glm::vec3(1, 0.1f, 0.1f));
      for (int k = 0; k < 3; ++k) out.at(x, y, k) = c[k];
    }
  return out;
}

// --param mask: how the volume pass is restricted to the silhouette pixels (Chan §3.3).
ParamSpec maskParam() {
  return choiceParam("mask", "auto", {"auto", "depth-bounds", "stencil", "tiles"},
                     "computation mask of the volume pass (Chan §3.3): auto = depth-bounds where "
                     "the driver has it, else stencil + scissor tiles");
}

// --param classify: Chan's Figure 3-3 classifier as the thesis gives it, or ours, which also sends
// the pixels the map is unsure of to the volumes (hybrid_classify.frag.glsl, docs/volumes.md).
ParamSpec classifyParam() {
  return choiceParam("classify", "conservative", {"chan", "conservative"},
                     "silhouette pixels (Chan §3.1 step 2): chan = the 2x2 compare strictly "
                     "between 0 and 1 on a surface whose normal faces the light (Fig. 3-3); "
                     "conservative = also where a 2x2 compare one texel off disagrees, with "
                     "back-facing judged by the triangle as the volumes judge it");
}

// --param mask-pass: which pass writes the mask's stencil bit.
ParamSpec maskPassParam() {
  return choiceParam("mask-pass", "quad", {"classify", "quad"},
                     "who sets the stencil mask: Chan's full-screen quad, or the classification "
                     "pass (GL_ARB_shader_stencil_export)");
}

Frame render(GlContext& ctx, const Scene& scene, const RenderParams& params) {
  const float factor = float(params.number(offsetFactorParam(kDefaultOffsetFactor)));
  const float units =
      float(params.number(offsetUnitsParam(kDefaultOffsetUnits, kLargestOffsetUnits)));
  const std::string maskName = params.text(maskParam());
  const bool haveBounds = ctx.caps().depthBoundsTest();
  if (maskName == "depth-bounds" && !haveBounds)
    throw InputError(
        "modern.hybrid: --param mask=depth-bounds needs GL_EXT_depth_bounds_test, "
        "which this driver (" +
        ctx.caps().renderer + ") lacks; use mask=tiles or mask=stencil");
  // auto: Chan's depth bounds where the driver has them, else the stencil bit plus tiles.
  const MaskKind kind = maskName == "stencil" ? MaskKind::kStencil
                        : maskName == "tiles" || (maskName == "auto" && !haveBounds)
                            ? MaskKind::kStencilTiles
                            : MaskKind::kDepthBounds;
  Frame frame;
  const SceneCasters casters = collectCasters(scene);
  GpuScene gpu(scene);
  const glm::mat4 viewProjection = infiniteCameraViewProjection(scene, params);
  Program volumeProgram("shadow_volume.vert.glsl", "depth_only.frag.glsl");
  volumeProgram.use();
  volumeProgram.set("uViewProjection", viewProjection);
  Program shadeProgram("shadow_volume.vert.glsl", "stencil_shade.frag.glsl");
  shadeProgram.use();
  shadeProgram.set("uViewProjection", viewProjection);
  setLightingUniforms(shadeProgram, scene);
  // Programs are compiled before the timed passes.
  Program mapProgram("scene.vert.glsl", "depth_only.frag.glsl");
  // mask-pass=quad (default): Chan's full-screen pass sets the stencil mask bit; classify: the
  // classification pass writes it (where GL_ARB_shader_stencil_export exists). Measured on
  // llvmpipe: no gain — the pass saved moves into the classification, whose depth test runs
  // after a shader that writes the stencil reference (docs/volumes.md).
  const std::string maskPass = params.text(maskPassParam());
  const bool maskInClassify = kind != MaskKind::kDepthBounds && maskPass == "classify" &&
                              ctx.caps().hasExtension("GL_ARB_shader_stencil_export");
  const bool conservative = params.text(classifyParam()) == "conservative";
  std::vector<std::pair<std::string, std::string>> classifyDefines;
  if (maskInClassify) classifyDefines.push_back({"MASK_BIT", std::to_string(kStencilMaskBit)});
  if (conservative) classifyDefines.push_back({"CONSERVATIVE", "1"});
  Program classifyProgram("shadow_volume.vert.glsl", "hybrid_classify.frag.glsl", classifyDefines);
  Program maskProgram("computation_mask.vert.glsl", "computation_mask.frag.glsl");
  // Colour attachment 2 = the silhouette tags (Figure 3-1b).
  RenderTarget target = makeStencilCameraTarget(params, {GL_RGBA8});
  Passes passes(frame, params, passTable());

  RenderTarget map = renderShadowMap(passes, gpu, params, mapProgram, factor, units);
  const SceneVolumes volumes = findSilhouettesAndBuildVolumes(passes, scene, casters);
  classifySilhouettePixels(passes, gpu, target, map, classifyProgram, viewProjection,
                           maskInClassify);
  std::vector<TileRect> tiles;
  const bool scissored =
      buildComputationMask(passes, target, maskProgram, kind, maskInClassify, tiles);
  const std::vector<TileRect>* scissorBoxes = scissored ? &tiles : nullptr;
  target.bind();
  const double volumeInvocations = countFragmentInvocations(
      [&] { drawVolumesThroughMask(passes, volumes, volumeProgram, kind, scissorBoxes); });
  // The colour target has three attachments; the shading pass writes the first two.
  const GLenum shadeBuffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_NONE};
  glDrawBuffers(3, shadeBuffers);
  if (kind == MaskKind::kDepthBounds) glDepthBoundsEXT(kDepthBoundsMin, kDepthBoundsMax);
  shadeLitSilhouettePixels(passes, gpu, shadeProgram, kind, scissorBoxes);
  readCameraTarget(target, frame);

  // Untimed counters (Chan §3.3.2, Figures 3-9 and 3-10).
  const Image tags = readAttachment(target, 2);
  const Image silhouette = channel(tags, 0);
  double silhouettePixels = 0;
  for (float v : silhouette.data) silhouettePixels += v > 0.5f ? 1 : 0;
  const VolumeFill all = measureVolumeFill(target, volumes, viewProjection, 0, false);
  const VolumeFill masked = measureVolumeFill(target, volumes, viewProjection, maskBitFor(kind),
                                              kind == MaskKind::kDepthBounds);
  reportVolumeCounters(casters, volumes, all, params, frame);
  reportVolumePassInvocations(volumeInvocations, params, frame);
  const double pixels = double(params.width) * params.height;
  frame.counters["silhouette_fraction"] = silhouettePixels / pixels;
  frame.counters["masked_overdraw"] = masked.fragments / pixels;
  frame.counters["mask_depth_bounds"] = kind == MaskKind::kDepthBounds ? 1 : 0;
  frame.counters["mask_in_classification"] = maskInClassify ? 1 : 0;
  if (kind == MaskKind::kStencilTiles) {
    // What the scissor boxes leave to rasterise: their share of the image and the volume
    // fragments inside them (per image pixel, beside volume_overdraw).
    double tilePixels = 0, tileFragments = 0;
    for (const TileRect& r : tiles) {
      tilePixels += double(r.width) * r.height;
      for (int y = r.y; y < r.y + r.height; ++y)
        for (int x = r.x; x < r.x + r.width; ++x) tileFragments += all.overdraw.at(x, y);
    }
    frame.counters["mask_tiles"] = double(tiles.size());
    frame.counters["mask_tile_fraction"] = tilePixels / pixels;
    frame.counters["tile_overdraw"] = tileFragments / pixels;
    frame.counters["mask_tiles_scissored"] = scissored ? 1 : 0;
  }
  passes.capture("3", "silhouette-pixels", [&] { return silhouette; });
  passes.capture("3", "decision", [&] { return decisionImage(tags); });
  passes.capture("6", "classification",
                 [&] { return classificationImage(silhouette, frame.visibility); });
  passes.capture("5", "stencil-count", [&] { return stencilCountImage(target); });
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return frame;
}
}  // namespace

Technique hybridShadowsTechnique() {
  Technique t;
  t.name = "modern.hybrid";
  t.paper = "Chan 2004 thesis ch. 3 (hybrid shadow maps + shadow volumes, computation masks)";
  t.summary = "shadow map finds silhouette pixels; z-fail volumes only there through a mask";
  t.status =
      "complete (depth-bounds mask where the driver has it, else stencil bit + scissor tiles)";
  t.needs.profile = Profile::kCore;
  t.params = {offsetFactorParam(kDefaultOffsetFactor),
              offsetUnitsParam(kDefaultOffsetUnits, kLargestOffsetUnits), classifyParam(),
              maskParam(), maskPassParam()};
  t.reads = {.shadowMap = true};
  t.passes = passTable();
  t.render = render;
  return t;
}

}  // namespace sl::modern
