// figures/figure_list_chan.cpp — the figure list's entries of Chan 2004 (MIT thesis)
// (figure_list_parts.h): depth bias and aliasing, the hybrid of shadow maps and volumes,
// smoothies.
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "figures/figure_list_parts.h"

namespace sl::figures::list {
namespace {

constexpr const char* kChan = "Chan 2004 (MIT thesis)";
constexpr float kSmoothieWidthPerRadius = 0.5f;  // smoothie width (map side = 1) per unit radius
// The contact scene's box foot and its shadow (512x384): Figs. 2-4 and 4-4.
constexpr Closeup kBoxFootCloseup{0.22f, 0.22f, 0.36f, 0.3f, 3};

FigureSpec chanFigure(std::string id, std::string figure, std::string title, std::string caption,
                      std::string scene, int columns, std::vector<PanelSpec> panels) {
  return paperFigure(kChan, std::move(id), std::move(figure), std::move(title), std::move(caption),
                     std::move(scene), columns, std::move(panels));
}

// Chan Fig. 3-5 (b, c): the hybrid's classification buffer, with close-ups, captioned with
// the colours' meaning (the pass's own caption names panel (b) only).
PanelSpec classification35(std::string label) {
  PanelSpec p = withCloseups(buffers(std::move(label), "modern.hybrid", "classif"));
  p.bufferCaption = "red/blue: shadow map shadowed/lit; black/green: volumes shadowed/lit";
  return p;
}

// Chan Fig. 4-10 (left, middle): the smoothie buffer's alpha, labelled as the thesis labels
// the two images; its images captioned by what they show (the pass's own caption names Fig. 4-1).
PanelSpec smoothieBuffer410(std::string label, std::string caption, Params params) {
  PanelSpec p = buffers(std::move(label), "modern.smoothies", "alpha", std::move(params));
  p.bufferCaption = std::move(caption);
  return p;
}

}  // namespace

std::vector<FigureSpec> chanFigures() {
  std::vector<FigureSpec> out;
  out.push_back(chanFigure(
      "chan-2-4", "Figure 2-4 (a-c)", "Depth bias: too little, too much, tuned",
      "Polygon offset (glPolygonOffset factor, units) on a box standing on a floor, as in the "
      "thesis (our scene: Fig. 4-4's box-floor contact): too little bias shadows lit surfaces "
      "(acne), too much detaches the shadow from the box-floor contact, a tuned value does "
      "neither. Bottom: the box's foot and its shadow magnified 3x.",
      "contact", 3,
      {render("(a) too little: 0, 0", "legacy.hw", {{"offset-factor", "0"}, {"offset-units", "0"}}),
       render("(b) too much: 8, 1000000", "legacy.hw",
              {{"offset-factor", "8"}, {"offset-units", "1000000"}}),
       render("(c) tuned: 2, 4", "legacy.hw", {{"offset-factor", "2"}, {"offset-units", "4"}})}));
  out.back().closeups = {kBoxFootCloseup};

  std::vector<PanelSpec> aliasing;
  for (int texels : {256, 512, 1024})
    aliasing.push_back(withMap(render("(" + std::string(1, char('a' + aliasing.size())) + ") " +
                                          std::to_string(texels) + "x" + std::to_string(texels),
                                      "modern.hw", {{"compare", "nearest"}}),
                               texels));
  out.push_back(chanFigure("chan-2-5", "Figure 2-5 (a-c)", "Shadow-map aliasing at 256, 512, 1024",
                           "A cylinder's shadow with 256², 512² and 1024² maps and one "
                           "nearest comparison per pixel: the stair steps shrink but never "
                           "vanish.",
                           "cylinder", 3, aliasing));
  out.back().closeups = {{0.55f, 0.2f, 0.2f, 0.2f, 3}};

  out.push_back(chanFigure(
      "chan-3-1", "Figure 3-1 (a-d)", "Hybrid shadows: overview",
      "(a) the shadow map; (b) the silhouette pixels found by the 2x2 comparison that is "
      "strictly between 0 and 1 (white here); (c) shadow volumes drawn only there: the stencil "
      "buffer they leave, black where the count is non-zero (in shadow), so only the silhouette "
      "pixels in shadow are black; (d) the final image. Bottom row: the shadow's end magnified "
      "3x.",
      "cylinder", 4,
      {view("(a) shadow map", PanelKind::kShadowMap),
       withCloseups(buffers("(b) silhouette pixels", "modern.hybrid", "silhouette")),
       withCloseups(buffers("(c) shadow volumes at silhouette pixels: the stencil buffer",
                            "modern.hybrid", "stencil")),
       render("(d) hybrid result", "modern.hybrid")}));
  out.back().closeups = {{0.50f, 0.22f, 0.2f, 0.25f, 3}};  // the rounded end of the shadow

  FigureSpec f35 = chanFigure(
      "chan-3-5", "Figure 3-5 (a-d)", "Mixing shadow maps and shadow volumes",
      "A ball's shadow. (a) a 256² shadow map alone aliases; (b) the classification with the "
      "256² map and (c) with a 512² map: non-silhouette pixels red (shadow map says shadow) and "
      "blue (lit), silhouette pixels black and green (shadow volumes decide); the band of "
      "silhouette pixels narrows as the map grows; (d) the hybrid result (256² map). Bottom: "
      "the shadow's lower left edge magnified 3x in every panel (the thesis's figure is itself "
      "a close-up of the ball's shadow).",
      "ball", 4,
      {render("(a) shadow map 256²", "modern.hw", {{"compare", "nearest"}}),
       classification35("(b) classification, 256² map"),
       withMap(classification35("(c) classification, 512² map"), 512),
       render("(d) hybrid", "modern.hybrid")});
  f35.shadowMapTexels = 256;
  f35.closeups = {{0.36f, 0.30f, 0.2f, 0.2f, 3}};  // the shadow's lower left edge
  out.push_back(f35);

  // Two close-ups per scene, 160x120 pixels each, magnified 6x so that a single pixel is still
  // 2x2 after figure.png is shrunk by 3. The first: the window holding the most coloured pixels
  // of the overlay (scored pixels the shadow map or the hybrid decide otherwise than the
  // volumes; found at 1024x768 with a 1024² map in the overlay panels, windows on a 4-pixel
  // grid, with Chan's literal classifier, classify=chan), near the blockers' terminators. The
  // second: a long shadow edge on the ground, picked by eye in the overlay, where the map's stair
  // steps are the wrong pixels: a tree's branch shadows, a bar's shadow, the large sphere's shadow.
  struct Scene37 {
    const char* scene;
    Closeup mostWrong, groundEdge;
  };
  const Scene37 scenes37[] = {
      {"trees", {0.703f, 0.474f, 0.156f, 0.156f, 6}, {0.254f, 0.258f, 0.156f, 0.156f, 6}},
      {"dragon", {0.473f, 0.370f, 0.156f, 0.156f, 6}, {0.801f, 0.219f, 0.156f, 0.156f, 6}},
      {"brabec", {0.309f, 0.417f, 0.156f, 0.156f, 6}, {0.674f, 0.414f, 0.156f, 0.156f, 6}}};
  std::vector<PanelSpec> p37;
  for (const auto& [scene, mostWrong, groundEdge] : scenes37) {
    PanelSpec sm = render(std::string(scene) + ": shadow map", "modern.hw");
    PanelSpec hy = render(std::string(scene) + ": hybrid", "modern.hybrid");
    PanelSpec sv = render(std::string(scene) + ": shadow volumes", "modern.volumes");
    PanelSpec wrong = render(std::string(scene) +
                                 ": wrong vs volumes (magenta SM, yellow both, "
                                 "cyan H)",
                             "modern.volumes");
    wrong.errorsOf = {"modern.hw", "modern.hybrid"};
    sm.scene = hy.scene = sv.scene = wrong.scene = scene;
    sm.ownCloseups = hy.ownCloseups = sv.ownCloseups = wrong.ownCloseups = {mostWrong, groundEdge};
    p37.insert(p37.end(), {sm, hy, sv, wrong});
  }
  constexpr int kThesisWidth = 1024, kThesisHeight = 768;  // Chan §3.3.1's Figure 3-7
  constexpr int kThesisMapTexels = 1024;  // "A shadow-map resolution of 1024x 1024" (Fig. 3-7)
  FigureSpec f37 = chanFigure(
      "chan-3-7", "Figure 3-7", "Image quality: shadow map, hybrid, shadow volumes",
      "At the thesis's size, " + std::to_string(kThesisWidth) + "x" +
          std::to_string(kThesisHeight) + ", with its " + std::to_string(kThesisMapTexels) +
          "² map. Rows: three scenes of high shadow complexity (our stand-ins: procedural trees, "
          "the Stanford dragon in a cage of bars for the Dragon Cage, the Brabec scene); "
          "columns: the shadow map, the hybrid method with the same map (its default "
          "classifier, which also sends the pixels the map is unsure of to the volumes: "
          "docs/volumes.md), shadow volumes, and where the first two decide lit or shadow "
          "otherwise than the volumes on the scored pixels of docs/error.md (surfaces facing the "
          "light; the sides facing away, unlit whatever the test says, are not counted), over "
          "the volumes' image in grey: magenta where only the shadow map is wrong (the hybrid "
          "corrects it), yellow where both are, cyan where only the hybrid is. The decimated "
          "dragon has holes; the volume-based columns give it the volume of its two-sided "
          "surface (counted in open_casters_two_sided, docs/volumes.md). Below: per scene, two "
          "windows of each column magnified 6x: a window where the overlay is dense near the "
          "blockers' terminators, and a long shadow edge on the ground (the map's stair steps). "
          "Whether the hybrid's error is below the shadow map's and whether it is faster than "
          "the volumes are not stated here: the wrong-pixel counts, each column's error against "
          "the reference and where the hybrid's time goes, as this run measured them, are "
          "stated below the caption.",
      "trees", 4, p37);
  // The thesis's speed statement for its scenes, quoted: it makes the panels timed in
  // interleaved rounds (figures.cpp timedSteadily), so that the measured block's frame and pass
  // times are steady-state medians, not first frames.
  f37.paperNumbers =
      "§3.3.2, Fig. 3-11 (hybrid against shadow volumes on the thesis's scenes): \"we observed "
      "speedups of 30% to over 100%, measured in frames per second\"";
  f37.width = kThesisWidth;
  f37.height = kThesisHeight;
  f37.shadowMapTexels = kThesisMapTexels;
  out.push_back(f37);

  out.push_back(chanFigure(
      "chan-3-9", "Figure 3-9 (a-c)", "Fill rate: overdraw vs silhouette pixels",
      "The dragon in its cage: (a) shadow-volume overdraw, brighter = more layers, on a "
      "logarithmic grey scale (log2(1 + n) / log2(1 + peak)) so that the typical count is not "
      "black beside the peak; the legend below (a) has one box per power of two up to the peak, "
      "and the image's caption gives the mean and the peak of this run; (b) the hybrid method's "
      "silhouette pixels (white here), the only pixels where it draws shadow volumes; (c) the "
      "resulting stencil buffer, black where the count is non-zero (in shadow), as Chan shows "
      "it. Bottom row: the dragon magnified 3x. Below the caption: our overdraw factor and "
      "share of silhouette pixels beside the thesis's for its Dragon Cage (ours is a stand-in "
      "scene), as this run measured them.",
      "dragon", 3,
      {withPaper(
           withCloseups(buffers("(a) shadow-volume overdraw", "modern.volumes", "volume-overdraw")),
           "overdraw factor 79"),
       withPaper(withCloseups(buffers("(b) silhouette pixels", "modern.hybrid", "silhouette")),
                 "silhouette pixels 5% of the image"),
       withCloseups(buffers("(c) stencil", "modern.hybrid", "stencil")),
       buffers("legend of (a)", "modern.volumes", "overdraw-legend")}));
  out.back().closeups = {{0.469f, 0.313f, 0.156f, 0.208f, 3}};  // the dragon, as in Fig. 3-7

  std::vector<PanelSpec> p310;
  for (const char* scene : {"fill-bound", "trees", "dragon", "brabec"}) {
    PanelSpec sv = render(std::string(scene) + " SV", "modern.volumes");
    sv.scene = scene;
    sv.counter = "volume_coverage";
    p310.push_back(sv);
    for (int texels : {256, 512, 1024}) {
      PanelSpec h = withMap(
          render(std::string(scene) + " H " + std::to_string(texels), "modern.hybrid"), texels);
      h.scene = scene;
      h.counter = "silhouette_fraction";
      p310.push_back(h);
    }
  }
  p310.push_back(plot("pixels drawn", "chan-3-10"));
  FigureSpec f310 = chanFigure(
      "chan-3-10", "Figure 3-10", "Shadow-volume coverage and silhouette pixels",
      "Per scene: the share of the image covered by shadow volumes (SV; the overdraw factor, "
      "Chan's number beside each bar, is volume_overdraw in the table) and the share of "
      "silhouette pixels of the hybrid method (H) at 256², 512² and 1024² maps, from the "
      "techniques' counters. fill-bound (assets/scenes/fill-bound.json, stacked floors) is "
      "the paper's setting: many overlapping volumes over most of the image and few silhouette "
      "pixels (Chan's scenes: overdraw up to 79). The overdraw and silhouette shares this run "
      "measured are stated below the caption.",
      "trees", 4, p310);
  f310.table = true;
  out.push_back(f310);

  // Figure 3-11 on the fill-bound scene first (the paper's setting), with both computation
  // masks llvmpipe can run, then our other scenes with the default mask.
  std::vector<PanelSpec> p311;
  const auto fillBound = [](PanelSpec p) {
    p.scene = "fill-bound";
    return p;
  };
  p311.push_back(fillBound(render("fill-bound SM", "modern.hw")));
  p311.push_back(
      fillBound(render("fill-bound H, stencil-bit mask", "modern.hybrid", {{"mask", "stencil"}})));
  p311.push_back(fillBound(
      render("fill-bound H, stencil bit + tile boxes", "modern.hybrid", {{"mask", "tiles"}})));
  p311.push_back(fillBound(
      withMap(render("fill-bound H 256², tile boxes", "modern.hybrid", {{"mask", "tiles"}}), 256)));
  p311.push_back(fillBound(render("fill-bound SV", "modern.volumes")));
  for (const char* scene : {"trees", "dragon", "brabec"})
    for (const char* t : {"modern.hw", "modern.hybrid", "modern.volumes"}) {
      PanelSpec p = render(std::string(scene) + " " + t, t);
      p.scene = scene;
      p311.push_back(p);
    }
  p311.push_back(plot("time per pass", "chan-3-11"));
  FigureSpec f311 = chanFigure(
      "chan-3-11", "Figure 3-11", "Frame time per part: SM, hybrid, SV",
      "Times: llvmpipe cannot reproduce Chan's speed-up of the hybrid over shadow volumes "
      "through its per-pixel computation mask (Chan: 30% to over 100% faster, on a GeForce 6800 "
      "with a 2.6 GHz Pentium 4 at 1024x768), because that speed-up is fill saved by hardware "
      "culling and llvmpipe culls none of it: it has no depth-bounds test and no early or "
      "hierarchical stencil/depth rejection; "
      "its stencil test runs inside the fragment function, so with the per-pixel stencil mask "
      "the volume pass runs as many fragment shaders as plain volumes although few fragments "
      "update the stencil. It does skip work outside the scissor box: the tile boxes (64x64 "
      "tiles holding silhouette pixels) cut the fragment-shader runs of the volume pass. "
      "The chart: stacked per-pass times of the shadow map (SM), hybrid (H) and shadow volume "
      "(SV) algorithms, one colour per pass, 1024² maps at 800x600; the table gives each part "
      "and the counters (volume_overdraw: volume fragments per pixel; masked_overdraw: those the "
      "mask lets update the stencil; tile_overdraw: those inside the tile boxes; "
      "volume_pass_fs_invocations: fragment-shader runs of the volume pass per pixel). "
      "fill-bound is the paper's setting: many overlapping volumes over most of the image, one "
      "shadow outline. Below the caption: the H/SV ratio of every hybrid panel against the "
      "volumes of its scene, with the rounds, and the counters, as this run measured them. "
      "Every bar and ratio is the median of interleaved rounds (all panels rendered once per "
      "round): compare ratios within this figure, not times.",
      "trees", 3, p311);
  f311.width = 800;
  f311.height = 600;
  f311.shadowMapTexels = 1024;
  f311.table = true;
  out.push_back(f311);

  out.push_back(chanFigure(
      "chan-4-1", "Figure 4-1 (a-d)", "Smoothies: overview",
      "(a) the shadow map; (b) smoothie depths; (c) smoothie alpha; (d) the final image with "
      "soft shadow edges.",
      "cylinder", 4,
      {view("(a) shadow map", PanelKind::kShadowMap),
       buffers("(b) smoothie depth", "modern.smoothies", "smoothie-depth"),
       buffers("(c) smoothie alpha", "modern.smoothies", "alpha"),
       withPaper(render("(d) smoothies", "modern.smoothies"), "39 fps, 10,000 triangles")}));

  // Figs. 4-4 and 4-10 use wider smoothies than the technique's default (t = 0.03) so that the
  // difference between linear and remapped alpha spans enough pixels to be seen.
  constexpr const char* kContactWidth = "0.06";  // t, light screen space (map side = 1)
  constexpr const char* kBoxesWidth = "0.08";
  out.push_back(chanFigure(
      "chan-4-4", "Figure 4-4 (b, d)", "Original vs remapped smoothie alpha",
      "A box standing on a floor (the figure's own scene), smoothie width t = 0.06. (b) With "
      "linearly interpolated alpha (--param remap=off) the penumbra has the fixed width t and "
      "the smoothie darkens the lit floor in front of the box where box and floor meet, a "
      "shadow that does not come from the box (Chan's \"contact error\"); (d) remapping alpha by "
      "the distance ratio b/r (Eq. 4.1) makes the penumbra vanish at the contact and grow away "
      "from it. Bottom: the box-floor contact magnified 3x.",
      "contact", 2,
      {render("(b) original alpha (remap=off)", "modern.smoothies",
              {{"remap", "off"}, {"width", kContactWidth}}),
       render("(d) remapped alpha (Eq. 4.1, the default)", "modern.smoothies",
              {{"width", kContactWidth}})}));
  out.back().closeups = {kBoxFootCloseup};  // the box's front foot and its shadow

  std::vector<PanelSpec> p48;
  const char* paperMs[3][4] = {{"16 ms", "129 ms", "19 ms", "19 ms"},
                               {"16 ms", "132 ms", "19 ms", "20 ms"},
                               {"17 ms", "142 ms", "22 ms", "24 ms"}};
  int row = 0;
  for (int texels : {256, 512, 1024}) {
    const std::string n = std::to_string(texels) + "²";
    p48.push_back(
        withPaper(withMap(render(n + " shadow map", "modern.hw", {{"compare", "nearest"}}), texels),
                  paperMs[row][0]));
    p48.push_back(withPaper(
        withMap(render(n + " bicubic 16 samples", "modern.gems16", {{"kernel", "bicubic"}}),
                texels),
        paperMs[row][1]));
    p48.push_back(withPaper(
        withMap(render(n + " smoothie width 0.025", "modern.smoothies", {{"width", "0.025"}}),
                texels),
        paperMs[row][2]));
    p48.push_back(withPaper(
        withMap(render(n + " smoothie width 0.1", "modern.smoothies", {{"width", "0.1"}}), texels),
        paperMs[row][3]));
    ++row;
  }
  FigureSpec f48 = chanFigure(
      "chan-4-8", "Figure 4-8",
      "Shadow edges: shadow map, 16-sample bicubic PCF, smoothies, with times",
      "Times: llvmpipe reproduces neither the cost of the thesis's bicubic filter nor its "
      "smoothies being much faster than that filter. On Chan's GeForce FX 5800 Ultra with a "
      "2.6 GHz Pentium 4, at 1024x1024, the 16-sample bicubic frame took 129-142 ms against "
      "16-17 ms for one comparison per pixel and 19-24 ms for smoothies; on llvmpipe the camera "
      "pass's fixed work per pixel (rasterisation, interpolation, lighting) outweighs the "
      "shadow-map lookups, so the 16 comparisons add far less than the thesis's factor, and a "
      "smoothie frame's five passes (silhouettes on the CPU, the map, smoothie depth, smoothie "
      "alpha, the camera pass) cost more than the bicubic frame's two (the measured ratios, per "
      "map size and per pass, are below). "
      "Images: the cylinder's shadow with 256², 512² and 1024² maps (rows). Columns: one "
      "comparison per pixel; percentage-closer filtering with a bicubic filter, 16 samples "
      "(modern.gems16 --param kernel=bicubic: 16 single comparisons over the 4x4 texels around "
      "the lookup, weighted by a cubic B-spline; the thesis does not say which cubic, "
      "bicubic_pcf.frag.glsl); smoothies of size 0.2 and 0.8 in the thesis's units, here "
      "widths 0.025 and 0.1 of the light's image (the same 1:4 ratio). Each panel's time "
      "stands beside the thesis's.",
      "cylinder", 4, p48);
  f48.closeups = {{0.5f, 0.2f, 0.25f, 0.25f, 2}};
  out.push_back(f48);

  std::vector<PanelSpec> p49;
  for (float radius : {0.05f, 0.1f, 0.2f}) {
    // The smoothie width stands for the light's size: it grows with the radius.
    const std::string width = std::to_string(radius * kSmoothieWidthPerRadius).substr(0, 5);
    PanelSpec s = render("smoothies, light radius " + std::to_string(radius).substr(0, 4),
                         "modern.smoothies", {{"width", width}});
    PanelSpec r =
        render("ray traced, light radius " + std::to_string(radius).substr(0, 4), "reference.soft");
    s.lightRadius = r.lightRadius = radius;
    p49.insert(p49.end(), {s, r});
  }
  FigureSpec f49 = chanFigure(
      "chan-4-9", "Figure 4-9", "Smoothies vs ray-traced soft shadows for growing lights",
      "Left: smoothies (1024² buffer, width 0.5 x the light radius); right: Monte Carlo "
      "ray-traced visibility of a spherical light (reference.soft). Each row a larger light; the "
      "error column measures the "
      "smoothie against the ray tracer with the same light.",
      "cylinder", 2, p49);
  f49.shadowMapTexels = 1024;
  f49.reference = "reference.soft";
  out.push_back(f49);

  out.push_back(chanFigure(
      "chan-4-10", "Figure 4-10", "Multiple blockers and receivers",
      "Box 1 (orange, above) casts a shadow onto box 2 (blue) and the ground; smoothie width "
      "t = 0.08. The smoothie buffer's alpha without remapping (left: the same thickness on "
      "both receivers) and with it (middle: thinner where box 1's shadow falls on box 2's top, "
      "which is closer to it); right: the result, seen so that box 1's shadow shows on box 2's "
      "top (the dark corner) and on the ground in front of box 2. Bottom: box 1's shadow edge "
      "on box 2 (harder) and on the ground (softer), magnified 3x.",
      "boxes", 3,
      {smoothieBuffer410("smoothie buffer (alpha not remapped): identical thickness",
                         "alpha interpolated linearly across each smoothie (remap=off)",
                         {{"remap", "off"}, {"width", kBoxesWidth}}),
       smoothieBuffer410("smoothie buffer (remapped alpha, Eq. 4.1): different thickness",
                         "alpha remapped by b/r (Eq. 4.1)", {{"width", kBoxesWidth}}),
       render("result (remapped)", "modern.smoothies", {{"width", kBoxesWidth}})}));
  out.back().closeups = {{0.34f, 0.46f, 0.16f, 0.2f, 3},   // box 1's shadow edge on box 2
                         {0.52f, 0.22f, 0.16f, 0.2f, 3}};  // and on the ground
  return out;
}

}  // namespace sl::figures::list
