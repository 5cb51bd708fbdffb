// figures/figure_list_gems.cpp — the figure list's entry of Bunnell & Pellacini, GPU
// Gems ch. 11 (figure_list_parts.h): Figures 11-6 to 11-9.
#include <map>
#include <string>
#include <vector>

#include "figures/figure_list_parts.h"

namespace sl::figures::list {

constexpr const char* kGems = "Bunnell & Pellacini, GPU Gems ch. 11 (2004)";

FigureSpec gemsFigures() {
  FigureSpec f;
  f.id = "gems-11-6to9";
  f.paper = kGems;
  f.paperFigure = "Figures 11-6, 11-7, 11-8, 11-9";
  f.title = "One, four dithered and sixteen samples per pixel, and magnified";
  f.caption =
      "The chapter's ninja is not available: we use the Stanford bunny. 11-6: one hardware "
      "2x2 compare per pixel (modern.hw compare=linear, the bilinear-weighted depth comparison "
      "the chapter's one-sample figure shows); 11-7: four samples in the dithered "
      "pattern of Fig. 11-4; 11-8: sixteen samples at offsets -1.5..1.5 texels. The bottom row "
      "(11-9) magnifies the shadow edge of each. A 256x256 map makes the differences visible.";
  f.scene = "bunny";
  f.shadowMapTexels = 256;
  f.columns = 3;
  f.panels = {render("11-6 one sample", "modern.hw", {{"compare", "linear"}}),
              render("11-7 four dithered samples", "modern.gems4"),
              render("11-8 sixteen samples", "modern.gems16")};
  f.closeups = {{0.74f, 0.12f, 0.2f, 0.2f, 4}};
  f.twins = false;
  return f;
}

}  // namespace sl::figures::list
