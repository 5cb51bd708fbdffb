// figures/figure_list_parts.h — the parts of the figure list (figure_spec.h figureList): the
// small builders every paper's entries are written with, and one function per paper returning
// its entries in the report's order. figure_list.cpp puts them together.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "figures/figure_spec.h"

namespace sl::figures::list {

using Params = std::map<std::string, std::string>;

inline PanelSpec render(std::string label, std::string technique, Params params = {}) {
  PanelSpec p;
  p.label = std::move(label);
  p.technique = std::move(technique);
  p.params = std::move(params);
  return p;
}

inline PanelSpec withMap(PanelSpec p, int texels) {
  p.shadowMapTexels = texels;
  return p;
}

inline PanelSpec withFilter(PanelSpec p, int filter) {
  p.filter = filter;
  return p;
}

inline PanelSpec withPaper(PanelSpec p, std::string numbers) {
  p.paperNumbers = std::move(numbers);
  return p;
}

inline PanelSpec view(std::string label, PanelKind kind) {
  PanelSpec p;
  p.label = std::move(label);
  p.kind = kind;
  p.closeups = false;
  return p;
}

inline PanelSpec buffers(std::string label, std::string technique, std::string match,
                         Params params = {}) {
  PanelSpec p = render(std::move(label), std::move(technique), std::move(params));
  p.kind = PanelKind::kIntermediates;
  p.intermediate = std::move(match);
  p.closeups = false;
  return p;
}

inline PanelSpec withCloseups(PanelSpec p) {
  p.closeups = true;
  return p;
}

inline PanelSpec plot(std::string label, std::string chart) {
  PanelSpec p;
  p.label = std::move(label);
  p.kind = PanelKind::kPlot;
  p.plot = std::move(chart);
  p.closeups = false;
  return p;
}

// One figure of `paper`, numbered `figure` there, with its panels in `columns` columns; no twin
// panels (a paper's figure compares its techniques, not our legacy and modern twins).
inline FigureSpec paperFigure(std::string paper, std::string id, std::string figure,
                              std::string title, std::string caption, std::string scene,
                              int columns, std::vector<PanelSpec> panels) {
  FigureSpec f;
  f.id = std::move(id);
  f.paper = std::move(paper);
  f.paperFigure = std::move(figure);
  f.title = std::move(title);
  f.caption = std::move(caption);
  f.scene = std::move(scene);
  f.columns = columns;
  f.panels = std::move(panels);
  f.twins = false;
  return f;
}

// The entries of each paper (figure_list_PAPER.cpp), in the report's order.
std::vector<FigureSpec> brabecSeidelFigures();  // Brabec & Seidel 2001
std::vector<FigureSpec> everittFigures();       // Everitt, Rege & Cebenoyan 2001
FigureSpec gemsFigures();                       // Bunnell & Pellacini, GPU Gems ch. 11 (2004)
std::vector<FigureSpec> csmFigures();           // Annen et al. 2007 (Convolution Shadow Maps)
std::vector<FigureSpec> chanFigures();          // Chan 2004 (MIT thesis)

}  // namespace sl::figures::list
