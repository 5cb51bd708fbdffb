// figures/figure_list_brabec_seidel.cpp — the figure list's entries of Brabec & Seidel 2001
// (figure_list_parts.h): Figs. 7 and 8, and the packing figures of Figs. 3 and 5.
#include <map>
#include <string>
#include <vector>

#include "figures/figure_list_parts.h"

namespace sl::figures::list {
namespace {

constexpr const char* kBrabec = "Brabec & Seidel 2001";

FigureSpec brabecFig7() {
  FigureSpec f;
  f.id = "brabec-fig7";
  f.paper = kBrabec;
  f.paperFigure = "Figure 7 (a-h)";
  f.title = "Shadow filtering compared: unfiltered, PCF 2x2, fast PCF 2x2, fast PCF 4x4";
  f.caption =
      "The paper's own comparison at its own size: 800x600 window, 512x512 shadow map, one "
      "light, a scene of about 7000 triangles (ours is procedural: their model is not "
      "published). Top row (a-d) the full frames, bottom row (e-h) the red rectangle "
      "magnified 8x with nearest-neighbour sampling, so that the shadow-map texels and the "
      "shadow levels of each filter can be counted."
      " Frame rates: the paper's unfiltered frame is faster than fast PCF 2x2; here the two "
      "often tie or swap. Per pass (the table below) both frames are the same five "
      "full-window passes at about the same cost, and the one pass fast PCF adds, the 3x3 "
      "packing convolution of the map during its copy, is a small fraction of the frame on "
      "llvmpipe; whatever made it cost the Octane about a third of its frame is not there, so "
      "their order follows the machine's load (interleaved medians: docs/figures.md).";
  f.scene = "brabec";
  f.width = 800;
  f.height = 600;
  f.shadowMapTexels = 512;
  f.columns = 4;
  f.panels = {
      withPaper(withFilter(render("(a,e) unfiltered (§2)", "legacy.ramp"), 1),
                "25-30 fps on an SGI Octane VPro/8"),
      withPaper(withFilter(render("(b,f) PCF 2x2 (§3)", "legacy.pcf"), 2), "about 10 fps"),
      withPaper(withFilter(render("(c,g) fast PCF 2x2 (§4)", "legacy.fast-pcf"), 2), "15-20 fps"),
      withPaper(withFilter(render("(d,h) fast PCF 4x4, multipass (§4)", "legacy.fast-pcf"), 4),
                "about 5 fps"),
  };
  f.closeups = {{0.70f, 0.47f, 0.12f, 0.12f, 8}};  // magnified to about the panel's size
  f.paperNumbers =
      "§5, SGI Octane VPro/8, 800x600, 512x512 map, times include the shadow map: "
      "unfiltered 25-30 fps, PCF 2x2 about 10 fps, fast PCF 2x2 15-20 fps, fast PCF 4x4 about 5 "
      "fps.";
  return f;
}

// Brabec Fig. 8 (c): the 12-bit frame with the bias in 12-bit steps, two of them as the 8-bit
// default's two 8-bit steps; depth-bias is counted in 8-bit steps (docs/legacy.md).
constexpr const char* kTwelveBitDepthBias = "0.125";

FigureSpec brabecFig8() {
  FigureSpec f;
  f.id = "brabec-fig8";
  f.paper = kBrabec;
  f.paperFigure = "Figure 8 (a, b)";
  f.title = "A 1024x1024 map unfiltered vs fast PCF 2x2";
  f.caption =
      "On a CPU rasteriser the paper's timing cannot be reproduced: the pass fast PCF adds, "
      "the packing convolution of the map during its copy, costs a small share of the frame on "
      "llvmpipe, far from the share the paper's ratio needs, so the order of the two frames "
      "follows the machine's load; the tables below say it cell by cell and pass by pass, as "
      "for Fig. 7. "
      "Even a 1024x1024 shadow map leaves blocky shadow boundaries without filtering (a); fast "
      "PCF with a 2x2 footprint smooths them (b). The paper's second test scene is not "
      "published: we use the Utah teapot on a plane. The thin light line under the teapot's "
      "base in (a) and (b) (second row of close-ups) is the 8-bit method's depth bias (two 8-bit "
      "steps of the light's depth range, needed against self-shadowing): next to the base the "
      "teapot's lowest body is closer to the ground than that, so the ground counts as lit. "
      "Panel (c), ours, is (a) with 12-bit depth and the bias in 12-bit steps: the leak under "
      "the base nearly vanishes, and acne spreads over lit surfaces instead (third row of "
      "close-ups, the teapot's lit body); the counts of both below are this run's (test "
      "TeapotContactLeakIsTheEightBitDepthBias, docs/figures.md). "
      "Brabec & Seidel §6 name the 8-bit depth resolution as the limit. "
      "The legacy/modern twins' masks agree, but their images differ on the teapot beyond the "
      "twins' image bound (the counts below are this run's): the legacy pipeline lights per "
      "vertex (Gouraud) over the teapot's triangles, its GLSL twin per pixel, and on the "
      "teapot's curved, coarsely tessellated body, lid and spout the diffuse and specular terms "
      "interpolated across a triangle differ from the per-pixel values by more than the few "
      "8-bit steps the bound allows (registry/twins.h); the image-difference pictures show "
      "those differences on the teapot, nearly all of the ground within the bound.";
  f.scene = "teapot";
  f.width = 800;
  f.height = 600;
  f.shadowMapTexels = 1024;
  f.columns = 3;
  PanelSpec unfiltered =
      withPaper(withFilter(render("(a) unfiltered", "legacy.ramp"), 1), "about 15 fps");
  unfiltered.countDepthErrors = true;
  PanelSpec twelve = withFilter(render("(c) unfiltered, 12-bit depth, bias in 12-bit steps",
                                       "legacy.ramp", {{"depth-bias", kTwelveBitDepthBias}}),
                                1);
  twelve.precision = Precision::k12;
  twelve.countDepthErrors = true;
  f.panels = {
      unfiltered,
      withPaper(withFilter(render("(b) fast PCF 2x2", "legacy.fast-pcf"), 2), "about 10 fps"),
      twelve,
  };
  f.closeups = {{0.60f, 0.20f, 0.18f, 0.14f, 4},
                {0.475f, 0.275f, 0.125f, 0.067f, 4},  // under the base: the depth bias's leak
                {0.425f, 0.425f, 0.10f, 0.10f, 4}};   // the lit body: (c)'s acne
  f.paperNumbers = "§5: \"about 15 versus 10 frames per second\" (unfiltered vs fast PCF 2x2).";
  return f;
}

FigureSpec brabecPacking(const char* id, const char* figure, const char* technique,
                         const char* title, const char* caption) {
  FigureSpec f;
  f.id = id;
  f.paper = kBrabec;
  f.paperFigure = figure;
  f.title = title;
  f.caption = caption;
  f.scene = "brabec";
  f.width = 320;
  f.height = 240;
  f.shadowMapTexels = 128;
  f.columns = 4;
  f.twins = false;
  PanelSpec all = buffers("intermediate buffers", technique, "");
  all.filter = 2;
  f.panels = {all};
  return f;
}

}  // namespace

std::vector<FigureSpec> brabecSeidelFigures() {
  std::vector<FigureSpec> v;
  v.push_back(brabecFig7());
  v.push_back(brabecFig8());
  v.push_back(brabecPacking(
      "brabec-fig3-packing", "Figure 3 (teaching figure)", "legacy.pcf",
      "PCF: four jittered light passes packed into the RGBA channels",
      "The real intermediate buffers of legacy.pcf (128² map, 320x240 window): each light "
      "pass writes ramp-encoded depth into one colour channel with a sub-texel jitter "
      "(stratified sampling, Fig. 3), then the comparison, the colour table and the colour "
      "matrix of Fig. 4 turn four comparisons into five shadow levels. The jitter is a "
      "fraction of a texel, invisible in the channels themselves: the strip after the packed "
      "map shows each channel minus the mean of the four, amplified 32x (grey = equal), "
      "non-grey where a sample's offset carries it across a depth edge or a depth step."));
  v.push_back(brabecPacking(
      "brabec-fig5-packing", "Figure 5 (teaching figure)", "legacy.fast-pcf",
      "Fast PCF: neighbour packing by convolution",
      "The real intermediate buffers of legacy.fast-pcf (128² map, 320x240 window): one "
      "light pass writes the depth into all four channels, and the 3x3 convolution of Eq. (1) "
      "keeps each texel's own depth in A and packs its lower-left, lower and left neighbours "
      "into R, G and B (Fig. 5). The one-texel shift shows in the strip after the packed map: "
      "lower right, upper left and upper right of the 2x2 block minus its lower left (G, B, A "
      "minus R), amplified 32x (grey = equal), non-grey along the depth edges that run across "
      "the direction from the lower-left texel to each other one."));
  return v;
}

}  // namespace sl::figures::list
