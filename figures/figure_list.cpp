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
      "Every hard-shadow technique on the Brabec scene (512x384, 512² map): RMSE of the "
      "visibility mask against reference.hard, plotted against the measured frame time.";
  f.columns = 4;
  f.twins = false;
  f.table = true;
  for (const char* t : {"legacy.ramp", "legacy.pcf", "legacy.fast-pcf", "legacy.hw", "legacy.woo",
                        "legacy.second-depth", "modern.ramp", "modern.pcf", "modern.fast-pcf",
                        "modern.hw", "modern.gems4", "modern.gems16", "modern.csm", "modern.vsm",
                        "modern.volumes", "modern.hybrid"})
    f.panels.push_back(render(t, t));
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
