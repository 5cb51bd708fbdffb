// figures/figure_list_csm.cpp — the figure list's entries of Annen et al. 2007
// (figure_list_parts.h): Convolution Shadow Maps' figures and Table 1.
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "figures/figure_list_parts.h"

namespace sl::figures::list {
namespace {

constexpr const char* kCsm = "Annen et al. 2007 (Convolution Shadow Maps)";

FigureSpec csmFigure(std::string id, std::string figure, std::string title, std::string caption,
                     std::string scene, int columns, std::vector<PanelSpec> panels) {
  return paperFigure(kCsm, std::move(id), std::move(figure), std::move(title), std::move(caption),
                     std::move(scene), columns, std::move(panels));
}

PanelSpec far(PanelSpec p, float distance) {
  p.cameraDistance = distance;
  return p;
}

// CSM Fig. 10: the camera's distances (times the scene's), and from which one on the panels get
// a close-up of the trees' shadows: the panel's centre, where the trees stand once the camera
// is that far, magnified to the panel's size.
constexpr int kFig10Distances[] = {1, 2, 3, 4};
constexpr int kFig10CloseupFromDistance = 3;
constexpr int kFig10CloseupMagnify = 4;
constexpr float kFig10CloseupSide = 1.0f / float(kFig10CloseupMagnify);  // of the panel
constexpr Closeup kFig10Closeup{0.5f - 0.5f * kFig10CloseupSide, 0.5f - 0.5f * kFig10CloseupSide,
                                kFig10CloseupSide, kFig10CloseupSide, kFig10CloseupMagnify};

// CSM Table 1's interleaved rounds (at least 7, so that a trend's verdict
// "every round" or "the rounds disagree" rests on more than three frames per cell).
constexpr int kTable1Rounds = 7;

}  // namespace

std::vector<FigureSpec> csmFigures() {
  std::vector<FigureSpec> out;
  out.push_back(csmFigure(
      "csm-fig1", "Figure 1", "PCF vs CSM under minification",
      "Trees seen from far away, so that many shadow-map texels fall into one pixel. PCF "
      "(hardware 2x2 compare) aliases; CSM filters the basis textures tri-linearly, and the "
      "paper's extra 7x7 blur (its panel: \"CSM with 7x7 blur and mip-mapping\") hides the "
      "map's discretisation. The middle panel, tri-linear without the blur, is ours, to "
      "separate the two. Our trees are procedural stand-ins with thin branches; "
      "M = 16 (the paper does not give M for this figure).",
      "trees", 3,
      {far(render("PCF", "modern.hw"), 2.5f),
       far(render("CSM trilinear", "modern.csm",
                  {{"order", "16"}, {"filtering", "trilinear"}, {"blur", "0"}}),
           2.5f),
       far(render("CSM trilinear + 7x7 blur", "modern.csm",
                  {{"order", "16"}, {"filtering", "trilinear"}, {"blur", "7"}}),
           2.5f)}));
  out.back().closeups = {{0.4f, 0.35f, 0.2f, 0.2f, 3}};

  out.push_back(csmFigure(
      "csm-fig3", "Figure 3 (a-d)", "Reconstructing the shadow test from its Fourier series",
      "Computed from Eq. 10-14 (not rendered): the shadow test f as a function of d - z. (a) "
      "truncation order M = 4, 8, 16: steeper but ringing; (b) attenuation exp(-alpha (k/M)^2) "
      "removes the ringing at the price of a softer step; (c) an offset on d makes lit "
      "surfaces (d - z = 0) fully lit; (d) scaling by 2 and clamping does too, with a steeper "
      "step.",
      "analytic", 1, {plot("reconstruction (a-d)", "csm-reconstruction")}));
  out.back().lessons = {"modern.csm"};  // a computed chart: no panel renders the technique

  out.push_back(csmFigure(
      "csm-fig4", "Figure 4 (a, b)", "Scaling f vs offsetting d",
      "Two squares and a slanted square touching the plane, M = 16, 5x5 Gaussian blur. (a) "
      "Scaling the reconstruction sharpens shadows; (b) an offset keeps the blur but may show "
      "limits at contact points.",
      "squares", 2,
      {render("(a) scaled by 2", "modern.csm",
              {{"order", "16"}, {"blur", "5"}, {"scale", "2"}, {"offset", "0"}}),
       render("(b) offset (the technique's default for M = 16)", "modern.csm",
              {{"order", "16"}, {"blur", "5"}})}));
  out.back().closeups = {{0.55f, 0.45f, 0.25f, 0.25f, 3}};

  FigureSpec fig5 = csmFigure(
      "csm-fig5", "Figure 5", "A shadow map and its basis textures",
      "The depth map and the first sine and cosine basis textures B_i(z(p)) for M = 16 (the "
      "layers modern.csm captures), each RGBA channel shown as its own image (the paper "
      "colours positive blue and negative red; ours show the stored 8-bit value as grey, "
      "0.5 = zero).",
      "brabec", 4,
      {view("shadow map", PanelKind::kShadowMap),
       buffers("basis textures", "modern.csm", "basis", {{"order", "16"}})});
  fig5.width = 256;
  fig5.height = 192;
  fig5.shadowMapTexels = 256;
  out.push_back(fig5);

  out.push_back(csmFigure(
      "csm-fig6", "Figure 6 (a-c)", "Reconstruction order M",
      "Small M brightens shadows where occluder and receiver are close (the low square, the "
      "slanted square's contact), because the reconstructed step is smooth. With the light "
      "straight above and the depth range fitted to the casters and receivers in the light "
      "frustum (the caption's 'tightly fitted light frustum') the low square is a third of "
      "that range above the plane. As the paper's caption says that ringing varies the "
      "lightness inside the shadows, the series is not attenuated here (alpha = 0), and d is "
      "offset so that the step goes through 1 at d = z (§3.2.2; offset-rule=through-1) instead of "
      "to the step's top (the technique's default): with M = 4 the slanted square's shadow is "
      "then dark from about a seventh of the range above the plane on (the default: a third), "
      "see docs/figures.md. Basis stored in 8 bits as in the paper.",
      "squares", 3,
      {render("(a) M = 1", "modern.csm",
              {{"order", "1"}, {"alpha", "0"}, {"offset-rule", "through-1"}}),
       render("(b) M = 2", "modern.csm",
              {{"order", "2"}, {"alpha", "0"}, {"offset-rule", "through-1"}}),
       render("(c) M = 4", "modern.csm",
              {{"order", "4"}, {"alpha", "0"}, {"offset-rule", "through-1"}})}));

  // Fig. 7 with the reconstruction of Fig. 6 (alpha = 0, d offset so that the step goes through
  // 1 at d = z): with the technique's defaults the trunks' shadows are light for the first
  // 0.063 of the light's depth range behind the root (Eq. 11, M = 16), here 0.034
  // (docs/figures.md, csm-fig7).
  const Params fig7Csm = {{"order", "16"}, {"alpha", "0"}, {"offset-rule", "through-1"}};
  const auto fig7Panel = [&](std::string label, Params extra) {
    Params p = fig7Csm;
    p.insert(extra.begin(), extra.end());
    return render(std::move(label), "modern.csm", p);
  };
  FigureSpec fig7 = csmFigure(
      "csm-fig7", "Figure 7 (a-f)", "Filter modes on a scene of high depth complexity",
      "PCF loses thin branches; CSM with bilinear filtering gives the same picture; tri-linear "
      "filtering (16x anisotropic) and then 3x3, 5x5, 7x7 blurs improve it step by step. "
      "2048x2048 map as in the paper; procedural trees with thin branches stand in for the "
      "paper's; M = 16. The reconstruction is Fig. 6's (no attenuation, alpha = 0, and d offset "
      "so that the step goes through 1 at d = z, offset-rule=through-1): with the technique's "
      "defaults (alpha = 1, offset at the step's top) the trunks' shadows fade towards their "
      "roots, where the trunk is close to the ground (see docs/figures.md).",
      "trees", 3,
      {render("(a) PCF", "modern.hw"),
       fig7Panel("(b) CSM bilinear", {{"filtering", "bilinear"}, {"blur", "0"}}),
       fig7Panel("(c) CSM trilinear, 16x aniso",
                 {{"filtering", "trilinear"}, {"anisotropy", "16"}, {"blur", "0"}}),
       fig7Panel("(d) + 3x3", {{"filtering", "trilinear"}, {"anisotropy", "16"}, {"blur", "3"}}),
       fig7Panel("(e) + 5x5", {{"filtering", "trilinear"}, {"anisotropy", "16"}, {"blur", "5"}}),
       fig7Panel("(f) + 7x7", {{"filtering", "trilinear"}, {"anisotropy", "16"}, {"blur", "7"}})});
  fig7.shadowMapTexels = 2048;
  fig7.closeups = {{0.45f, 0.3f, 0.18f, 0.18f, 3}};
  out.push_back(fig7);

  std::vector<PanelSpec> fig8;
  for (int texels : {256, 512, 1024})
    for (const char* blur : {"0", "3", "7"})
      fig8.push_back(withMap(render(std::to_string(texels) + "², " +
                                        (blur[0] == '0' ? std::string("no blur")
                                                        : std::string("blur ") + blur + "x" + blur),
                                    "modern.csm", {{"order", "16"}, {"blur", blur}}),
                             texels));
  out.push_back(csmFigure(
      "csm-fig8", "Figure 8", "Map resolution x blur size",
      "Rows: 256, 512 and 1024 texel maps; columns: no blur, 3x3 and 7x7 Gaussian. Blurring "
      "the basis textures hides the map's blocks and, large enough, imitates soft shadows. The "
      "paper's caption names neither its map sizes nor its kernels, and our text of the paper "
      "does not show its panels: the full 3x3 grid of map size against kernel (nine panels, so "
      "that each row and each column changes one thing) is our choice, not the paper's layout.",
      "brabec", 3, fig8));
  out.back().closeups = {{0.70f, 0.47f, 0.14f, 0.14f, 3}};

  out.push_back(csmFigure(
      "csm-fig9", "Figure 9 (a, b)", "VSM light leaking vs CSM on the fence",
      "The paper: objects behind the fence raise the variance inside the filter kernel and VSM "
      "leaks light into the shadows (a); CSM does not (b). Same 5x5 blur for both. Below: "
      "RMSE, the error near the shadow edges and the leak this run measured, and why RMSE and "
      "the leak may rank the two differently. The bench's bleeding scene (docs/bench.md) is "
      "built to make VSM leak and tests the claim.",
      "fence", 2,
      {render("(a) VSM", "modern.vsm", {{"blur", "5"}}),
       render("(b) CSM", "modern.csm", {{"order", "16"}, {"blur", "5"}})}));
  out.back().closeups = {{0.15f, 0.04f, 0.3f, 0.25f, 3}};

  // Fig. 10: the paper's rows, top PCF, bottom CSM (§5: "The top row in Figure 10 shows
  // aliasing ... in the PCF renderings. The bottom row shows the same scene rendered with
  // CSMs."), the camera moving away from left to right. The two farthest columns get a
  // close-up of the trees' shadows, where the map is most strongly minified.
  std::vector<PanelSpec> fig10;
  for (const char* technique : {"modern.hw", "modern.csm"})
    for (int d : kFig10Distances) {
      const bool csm = std::string(technique) == "modern.csm";
      PanelSpec p = far(csm ? render("CSM, distance x" + std::to_string(d), technique,
                                     {{"order", "16"}, {"filtering", "trilinear"}, {"blur", "5"}})
                            : render("PCF, distance x" + std::to_string(d), technique),
                        float(d));
      if (d >= kFig10CloseupFromDistance)
        p.ownCloseups = {kFig10Closeup};
      else
        p.closeups = false;
      fig10.push_back(p);
    }
  out.push_back(csmFigure(
      "csm-fig10", "Figure 10", "Minification sequence",
      "The camera moves away from the trees, left to right. Top row PCF (hardware 2x2 "
      "compare), as in the paper, aliases as the shadows shrink; bottom row CSM with tri-linear "
      "filtering and the paper's 5x5 kernel stays smooth. Below, the trees' shadows in the two "
      "farthest columns magnified with nearest-neighbour sampling, PCF above CSM: under strong "
      "minification PCF's pixels pick single texels of the thin branches' shadows, CSM's "
      "average them through the mip-map.",
      "trees", 4, fig10));

  // Table 1: frame rates for S x M x C at 1024x768.
  FigureSpec table = csmFigure(
      "csm-table1", "Table 1", "Frame rates: map size x order M x convolution",
      "On a CPU rasteriser (llvmpipe, the default back end) the paper's GeForce 8800 GTX frame "
      "rates cannot be reproduced, only their ratios compared, and some of those invert: the "
      "tables below say which and why. "
      "Frames per second at 1024x768 for shadow maps of 256² to 2048² and M = 4, 8, 16, "
      "without convolution and with 3x3 and 7x7 kernels, beside the paper's "
      "figures (their scene: 365k faces; ours: the procedural trees). Below: each cell "
      "against PCF at its map size, ours beside the paper's, with whether the paper's trend "
      "holds; then the paper's three trends, frame rate falling as the kernel grows (none, "
      "3x3, 7x7; per order and map size), as the map grows (256² to 2048²; per kernel and "
      "order) and as the order grows (M = 4 to 16; per kernel and map size), each with the "
      "interleaved rounds and the per-pass times that tell noise from cost structure. All "
      "cells are timed in one round-robin: every round renders each cell once, so any two "
      "cells (across map sizes too) ran under the same load round by round. Each cell gives "
      "the median frame rate and the interquartile range of its rounds, and whether its frame "
      "built the mip chain (the frame's mip-maps counter); the CSM cells build it at every map "
      "size (mipmaps=always: the paper's timings \"include ... mip-map generation for all basis "
      "textures\"), PCF samples its depth map without one. rounds.csv in the figure's folder "
      "holds every round of every cell.",
      "trees", 4, {});
  table.width = 1024;
  table.height = 768;
  table.table = true;
  table.reference = "";  // a timing table
  table.timingRounds = kTable1Rounds;
  table.interleaveAllTimed = true;  // the trends pair cells of different map sizes
  const char* sizes[] = {"256", "512", "1024", "2048"};
  const char* paper[3][4][4] = {// C = none: PCF, M=4, M=8, M=16 rows
                                {{"76", "74", "71", "69"},
                                 {"64", "62", "60", "50"},
                                 {"55", "53", "49", "38"},
                                 {"47", "45", "39", "26"}},
                                {{"", "", "", ""},
                                 {"63", "61", "57", "43"},
                                 {"53", "50", "44", "30"},
                                 {"42", "39", "32", "19"}},
                                {{"", "", "", ""},
                                 {"62", "60", "53", "36"},
                                 {"52", "49", "41", "24"},
                                 {"41", "38", "28", "14"}}};
  const char* blurs[] = {"0", "3", "7"};
  const char* blurNames[] = {"none", "3x3", "7x7"};
  const char* orders[] = {"PCF", "4", "8", "16"};
  for (int c = 0; c < 3; ++c)
    for (int m = 0; m < 4; ++m) {
      if (m == 0 && c > 0) continue;
      for (int s = 0; s < 4; ++s) {
        const std::string label = std::string("C=") + blurNames[c] + " " +
                                  (m == 0 ? "PCF" : std::string("M=") + orders[m]) +
                                  " S=" + sizes[s];
        PanelSpec p = m == 0 ? render(label, "modern.hw")
                             : render(label, "modern.csm",
                                      {{"order", orders[m]},
                                       {"blur", blurs[c]},
                                       {"filtering", "trilinear"},
                                       {"anisotropy", "16"},
                                       {"mipmaps", "always"}});
        p.shadowMapTexels = std::stoi(sizes[s]);
        p.paperNumbers = std::string(paper[c][m][s]) + " fps";
        table.panels.push_back(p);
      }
    }
  out.push_back(table);
  return out;
}

}  // namespace sl::figures::list
