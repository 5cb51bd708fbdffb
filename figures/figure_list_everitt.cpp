// figures/figure_list_everitt.cpp — the figure list's entries of Everitt, Rege &
// Cebenoyan 2001 (figure_list_parts.h): Figs. 2, 4, 5 and 6.
#include <map>
#include <string>
#include <vector>

#include "figures/figure_list_parts.h"

namespace sl::figures::list {
namespace {

constexpr const char* kEveritt = "Everitt, Rege & Cebenoyan 2001";

FigureSpec everittFig2() {
  FigureSpec f;
  f.id = "everitt-fig2";
  f.paper = kEveritt;
  f.paperFigure = "Figure 2";
  f.title = "Eye view, light view and the depth map";
  f.caption =
      "The shadowed scene from the eye (left), the same scene from the light (centre) and the "
      "light's depth buffer, the shadow map, with near depths dark and far depths light "
      "(right; rendered by the figure module itself, depth linearised between the light's "
      "near and far planes so that the grey levels are readable).";
  f.columns = 3;
  f.panels = {render("eye view (legacy.hw)", "legacy.hw"),
              view("light's view", PanelKind::kLightView),
              view("shadow map (depth)", PanelKind::kShadowMap)};
  return f;
}

FigureSpec everittFig4() {
  FigureSpec f;
  f.id = "everitt-fig4";
  f.paper = kEveritt;
  f.paperFigure = "Figure 4";
  f.title = "The depth comparison made visible";
  f.caption =
      "Left: the shadowed scene. Centre: each eye pixel's depth in the light's frustum (the "
      "value r that the texture matrix produces). Right: the shadow map projected onto the "
      "scene (the value the comparison reads); where centre and right differ, the pixel is in "
      "shadow.";
  f.columns = 3;
  f.panels = {render("shadow-mapped scene", "legacy.hw"),
              view("distance from the light", PanelKind::kLightDistance),
              view("shadow map projected on the scene", PanelKind::kProjectedMap)};
  return f;
}

FigureSpec everittFig5() {
  FigureSpec f;
  f.id = "everitt-fig5";
  f.paper = kEveritt;
  f.paperFigure = "Figure 5";
  f.title = "Nearest vs linear depth comparison on a very low-resolution map";
  f.caption =
      "A 32x32 shadow map makes the difference between GL_NEAREST (one comparison per "
      "lookup: blocky) and GL_LINEAR (four comparisons blended bilinearly, the hardware's 2x2 "
      "percentage-closer filter) obvious. The paper shows Mark Kilgard's picture; this is our "
      "scene.";
  f.shadowMapTexels = 32;
  f.columns = 2;
  f.panels = {render("GL_NEAREST", "legacy.hw", {{"compare", "nearest"}}),
              render("GL_LINEAR", "legacy.hw", {{"compare", "linear"}})};
  f.closeups = {{0.58f, 0.40f, 0.2f, 0.2f, 3}};
  return f;
}

FigureSpec everittFig6() {
  FigureSpec f;
  f.id = "everitt-fig6";
  f.paper = kEveritt;
  f.paperFigure = "Figure 6";
  f.title = "Dueling frusta: shadow-map sampling density seen from the eye";
  f.caption =
      "The light faces the camera. Left: eye pixels per shadow-map texel (log scale, computed "
      "per pixel from the screen-space derivatives of the shadow-map coordinate): blue where "
      "one texel covers 4 or more pixels (the map is magnified and its texels show as blocks), "
      "green at one pixel per texel, red where 4 or more texels fall into one pixel; grey is "
      "outside the light's frustum. Centre: the shadowed eye view. Right: the light's view in "
      "the same colours where the eye sees the surface, dim grey where it does not, as "
      "Everitt's right panel shows \"the very small portion of the light's image plane\" that "
      "needs high-frequency sampling: the blue part, which the eye sees magnified, is a small "
      "patch of the light's image; the rest of what the eye sees is green to red there.";
  f.scene = "dueling";
  f.columns = 3;
  f.twins = false;
  f.panels = {
      view("eye pixels per texel", PanelKind::kTexelDensity),
      render("eye view (modern.hw)", "modern.hw"),
      view("light's view, eye pixels per texel where the eye sees it", PanelKind::kLightDensity)};
  return f;
}

}  // namespace

std::vector<FigureSpec> everittFigures() {
  return {everittFig2(), everittFig4(), everittFig5(), everittFig6()};
}

}  // namespace sl::figures::list
