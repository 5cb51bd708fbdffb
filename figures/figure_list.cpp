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

#include "figures/figure_composite.h"
#include "figures/figure_list_parts.h"
#include "figures/figure_spec.h"
#include "measure/bench.h"
#include "registry/registry.h"
#include "registry/shadow_error.h"

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

// The filtered shadow maps of 2001-2004 beside later ones, on three scenes, each panel's error by
// both metrics of docs/error.md (FigureSpec::bothMetrics). Columns by year, rows by scene.
FigureSpec earlyAgainstLate() {
  struct Column {
    const char* technique;
    int year;  // of the paper it follows (the registry's citation)
  };
  static constexpr Column kColumns[] = {
      {"legacy.pcf", 2001},  {"legacy.fast-pcf", 2001}, {"modern.gems16", 2004},
      {"modern.pcss", 2005}, {"modern.vsm", 2006},      {"modern.evsm4", 2008},
      {"modern.msm", 2015},
  };
  static constexpr const char* kScenes[] = {"brabec", "fence", "bleeding"};
  FigureSpec f;
  f.id = "2001-vs-2015";
  f.paper = "All papers";
  f.paperFigure = "(ours)";
  f.title = "Filtered shadow maps of 2001-2004 beside those of 2005-2015, by both error metrics";
  f.columns = int(std::size(kColumns));
  // As wide as figure.png holds its columns without shrinking them (figure_composite.h), in
  // steps of 8 pixels, at the 4:3 of the other figures; the default 512² map.
  constexpr int kStep = 8;
  constexpr int kAspectWidth = 4, kAspectHeight = 3;
  f.width = (kCompositeMaxWidth - (f.columns - 1) * kCompositeGap) / f.columns / kStep * kStep;
  f.height = f.width * kAspectHeight / kAspectWidth;
  f.twins = false;
  f.bothMetrics = true;
  std::string scenes;
  for (const char* scene : kScenes) {
    scenes += (scenes.empty() ? "" : ", ") + std::string(scene);
    for (const Column& c : kColumns) {
      PanelSpec p =
          render(std::string(c.technique) + " (" + std::to_string(c.year) + ")", c.technique);
      p.scene = scene;
      for (const Technique& t : allTechniques())
        if (t.name == c.technique && t.light == Technique::Light::kArea)
          p.reference = "reference.soft";
      f.panels.push_back(p);
    }
  }
  const std::string side = std::to_string(kFigureReferencePixelSamplesPerSide);
  f.caption =
      "Columns by the year of the paper each technique follows: Brabec & Seidel 2001's PCF (§3) "
      "and fast PCF (§4) and GPU Gems 2004's sixteen-lookup PCF (§11.3), then PCSS (ours, after "
      "Fernando 2005), variance shadow maps (Donnelly & Lauritzen 2006), EVSM with four moments "
      "(ours, after Lauritzen & McCool 2008) and moment shadow maps (ours, after Peters & Klein "
      "2015), each with its default parameters; rows: the scenes " +
      scenes + ", each rendered at " + std::to_string(f.width) + "x" + std::to_string(f.height) +
      " with a " + std::to_string(f.shadowMapTexels) +
      "² map. Every panel's visibility mask is scored against the ray-traced reference, "
      "reference.hard for the point-light techniques and reference.soft (the scene's spherical "
      "light) for PCSS, by both metrics of docs/error.md, over the scored pixels only (a "
      "receiver inside the light's frustum facing it): the area metric, whose truth is the "
      "reference's pixel=area form (visibility averaged over " +
      side + "x" + side +
      " sub-pixel samples on the surface the pixel centre sees), and the point metric, whose "
      "truth is its pixel=centre form (that surface point alone). The table gives each "
      "metric's RMSE and its share of pixels off by more than 0.5. Below the caption, computed "
      "from this run: per scene and reference, the technique with the smallest RMSE by each "
      "metric, and each panel's share of its area-metric squared error within " +
      std::to_string(kBandRadiusPixels) + " px of the reference's shadow edges (the edge band).";
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
    v.push_back(earlyAgainstLate());
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
