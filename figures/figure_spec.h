// figures/figure_spec.h — one declarative entry per reproduced paper figure or table.
//
// A figure is plain data: which paper and figure number it reproduces, the scene, and a list
// of panels laid out in rows of `columns` as the paper lays them out. Each panel names a
// technique (looked up in registry/registry at run time, so techniques that land later appear
// without touching this file) or one of the figure module's own diagnostic views (the light's
// view, the depth map, texel density, plots). figures.cpp renders the entries; report.cpp
// writes report.html from the results.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "core/technique/technique.h"

namespace sl::figures {

enum class PanelKind {
  kRender,         // a technique's shaded image (or its visibility mask, see PanelSpec::mask)
  kIntermediates,  // a technique's intermediate buffers (params.capturePasses)
  kLightView,      // the scene shaded as seen from the light (Everitt Fig. 2 centre)
  kShadowMap,      // the light's depth buffer as grey levels (Everitt Fig. 2 right)
  kLightDistance,  // each eye pixel's distance from the light (Everitt Fig. 4 centre)
  kProjectedMap,   // the shadow map projected onto the scene (Everitt Fig. 4 right)
  kTexelDensity,   // shadow-map texels per eye pixel, colour coded (Everitt Fig. 6)
  kLightDensity,   // the light's view, coloured where the eye sees it as kTexelDensity
                   // (Everitt Fig. 6 right)
  kPlot,           // a gnuplot chart made from computed data or from other panels' numbers
};

// A close-up: a rectangle in fractions of the panel, magnified with nearest-neighbour sampling
// so the texels stay visible. Origin bottom-left, y up (as core/base/image.h and GL window
// coordinates): (x, y) is the rectangle's lower-left corner, x the fraction of the panel's width
// from its left edge, y the fraction of its height from its BOTTOM edge; w and h its width and
// height in the same fractions. {0.70, 0.47, 0.12, 0.12} in an 800x600 panel is the 96x72
// window whose lower-left pixel is (560, 282) counted from the bottom-left, i.e. whose top row
// is row 600 - 282 - 72 = 246 counted from the top as an image viewer counts.
// (docs/figures.md "Close-ups" and docs/user-guide.md say the same.)
struct Closeup {
  float x = 0, y = 0, w = 0, h = 0;
  int magnify = 4;
};

struct PanelSpec {
  std::string label;  // "(a) unfiltered"
  // The `figures --set` overrides that change this panel ("shadow-map=1024"), drawn in its
  // label on figure.png (figures/overrides.h applyOverrides); empty for a listed figure.
  std::vector<std::string> overridden;
  PanelKind kind = PanelKind::kRender;
  std::string technique;      // registry name; for kLightView..kTexelDensity none is needed
  std::string scene;          // empty: the figure's scene
  int width = 0, height = 0;  // 0: the figure's size
  int shadowMapTexels = 0;    // 0: the figure's
  int filter = 0;             // 0: RenderParams default
  std::map<std::string, std::string> params;  // --param key=value
  std::optional<float> lightRadius;           // overrides the scene's light radius (soft shadows)
  std::optional<glm::vec3> lightPosition;     // overrides the scene's light position
  std::optional<Precision> precision;         // RenderParams::precision; unset: its default
  float cameraDistance = 1.0f;                // > 1 moves the camera away (minification)
  bool mask = false;                          // show the visibility mask instead of colour
  std::string intermediate;   // kIntermediates: substring of the PassImage names to show
  std::string bufferCaption;  // kIntermediates: its images' caption instead of the pass's own
                              // (which may name another panel of the paper's figure)
  std::string plot;           // kPlot: which chart (see plots.h)
  std::string counter;        // Frame::counters entry a chart plots for this panel
  std::string paperNumbers;   // what the paper reports for this panel, quoted, or empty
  std::string reference;      // error against this instead of the figure's reference (a soft-shadow
                              // technique against reference.soft on error-vs-time), or empty
  bool countDepthErrors = false;      // count its leak and acne pixels (figures/measured.h
                                      // kLeakPixelsCounter) against reference.hard, legacy.hw
  bool closeups = true;               // apply the figure's close-ups to this panel
  std::vector<Closeup> ownCloseups;   // when not empty: this panel's close-ups instead of the
                                      // figure's (rows of different scenes, Chan Fig. 3-7)
  std::vector<std::string> errorsOf;  // kRender, one or two techniques: instead of its colour
                                      // the panel shows the pixels they decide lit/shadow
                                      // otherwise than its own (exact) technique, same scene,
                                      // size and map (figures/disagreement.h, Chan Fig. 3-7)
};

struct FigureSpec {
  std::string id;           // "brabec-fig7"
  std::string paper;        // "Brabec & Seidel 2001"
  std::string paperFigure;  // "Figure 7 (a-h)"
  std::string title;
  std::string caption;  // ours, with any stand-in model named
  std::string scene = "brabec";
  int width = 512, height = 384;
  int shadowMapTexels = 512;
  int columns = 4;
  std::vector<PanelSpec> panels;
  std::vector<Closeup> closeups;
  std::string reference = "reference.hard";  // error of every render panel against this
  int timingRounds = 0;  // interleaved rounds of its timed panels; 0: figures.cpp's default
  // Its timed panels round-robin in one group, every round rendering each of them once, so that
  // any two of its cells are compared round by round (CSM Table 1's trends pair cells across
  // map sizes); false: groups of figures.cpp's kInterleavedGroup, by map size.
  bool interleaveAllTimed = false;
  // Every render panel's error by both metrics of docs/error.md, side by side in the numbers
  // table: the area metric (the reference's pixel=area form, the primary truth) and the point
  // metric (its pixel-centre form); false: the area metric alone.
  bool bothMetrics = false;
  bool twins = true;         // show legacy.X beside modern.X with the difference image
  bool table = false;        // a table of numbers (CSM Table 1): panels give cells, no images
  std::string paperNumbers;  // the paper's numbers for the whole figure, quoted
  // The techniques whose lessons teach this figure where no panel renders them (a computed chart
  // such as CSM Fig. 3): with the panels' techniques, figureTechniques.
  std::vector<std::string> lessons;
  // Re-made with `figures --set` (figures/overrides.h): the listed figure's id (id then names
  // this version's folder), the overrides as typed, and their slug in every file name.
  std::string sourceId;
  std::vector<std::string> overrides;  // "shadow-map=1024"
  std::string fileSuffix;              // "--shadow-map-1024"
};

// Every figure we reproduce, in paper order.
const std::vector<FigureSpec>& figureList();

// The techniques a figure shows: its panels' (each render's technique and the ones whose errors
// it shows, PanelSpec::errorsOf) and its `lessons`, each once, in that order. The links between
// a figure and the lessons (teach/lesson.h figureShows) are made from these.
std::vector<std::string> figureTechniques(const FigureSpec& figure);

}  // namespace sl::figures
