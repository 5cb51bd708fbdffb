// figures/figure_list.cpp — the reproduced figures and tables of the five papers, as data.
//
// Every figure of the papers is listed, whether or not its techniques exist yet: the
// report shows a panel whose technique (or parameter, or intermediate buffer) is missing in
// red with the reason, so nothing is skipped silently. Sizes are the paper's where the size is
// the point (Brabec–Seidel 800x600, Table 1 1024x768) and 512x384 elsewhere so that the whole
// set renders in minutes on two cores.
//
// This file puts the papers' entries together in the report's order (figure_list_PAPER.cpp,
// built with figure_list_parts.h) and adds the one entry across the papers.
#include <algorithm>

#include "figures/figure_list_parts.h"
#include "figures/figure_spec.h"
#include "registry/registry.h"

namespace sl::figures {
namespace {
using list::plot;
using list::render;

FigureSpec errorAgainstTime() {
  FigureSpec f;
  f.id = "error-vs-time";
  f.paper = "All papers";
  f.paperFigure = "(ours)";
  f.title = "Error against the ray-traced reference vs frame time";
  f.caption =
      "Every technique of the registry on the Brabec scene (512x384, 512² map), each with its "
      "default parameters: RMSE of the visibility mask against the ray-traced reference, "
      "plotted against the measured frame time. Grouped as the registry declares them "
      "(Technique::edge and light): hard (a binary depth or stencil test per pixel), filtered "
      "(PCF footprints, the driver's 2x2 compare, prefiltered maps) against reference.hard, and "
      "soft (a spherical light's penumbra) against reference.soft. Each label is placed where "
      "it overlaps no other label and no point. Below the caption: the largest RMSE of each "
      "group and where that technique's error lies, as this run measured it. Where that is "
      "modern.hybrid's in the hard group, its error beyond modern.volumes' lies next to the "
      "terminators of the curved blockers (the spheres, the torus): the hybrid draws the same "
      "volumes at its silhouette pixels, so every pixel it decides otherwise than "
      "modern.volumes is one its 2x2 classification left to the shadow map (all four "
      "comparisons agreeing), where the map's depth at grazing light decides otherwise than the "
      "volumes; the band share below is how much of its error lies within 2 px of the shadow "
      "edges, terminators included.";
  f.columns = 4;
  f.twins = false;
  f.table = true;
  // The registry's techniques in its order, hard first, then filtered, then soft; the
  // references (the truth the others are scored against) are not plotted.
  for (const char* group : {"hard", "filtered", "soft"})
    for (const Technique& t : allTechniques()) {
      if (t.plan.shadowWork == PlanTraits::ShadowWork::kRays ||
          shadowGroup(t) != std::string(group))
        continue;
      PanelSpec p = render(t.name, t.name);
      if (t.light == Technique::Light::kArea) p.reference = "reference.soft";
      f.panels.push_back(p);
    }
  f.panels.push_back(plot("error vs time", "error-vs-time"));
  return f;
}

}  // namespace

const std::vector<FigureSpec>& figureList() {
  static const std::vector<FigureSpec> entries = [] {
    std::vector<FigureSpec> v;
    for (FigureSpec& f : list::brabecSeidelFigures()) v.push_back(std::move(f));
    for (FigureSpec& f : list::everittFigures()) v.push_back(std::move(f));
    v.push_back(list::gemsFigures());
    for (FigureSpec& f : list::csmFigures()) v.push_back(std::move(f));
    for (FigureSpec& f : list::chanFigures()) v.push_back(std::move(f));
    v.push_back(errorAgainstTime());
    return v;
  }();
  return entries;
}

std::vector<std::string> figureTechniques(const FigureSpec& figure) {
  std::vector<std::string> out;
  auto add = [&](const std::string& t) {
    if (!t.empty() && std::find(out.begin(), out.end(), t) == out.end()) out.push_back(t);
  };
  for (const PanelSpec& p : figure.panels) {
    add(p.technique);
    for (const std::string& t : p.errorsOf) add(t);
  }
  for (const std::string& t : figure.lessons) add(t);
  return out;
}

}  // namespace sl::figures
