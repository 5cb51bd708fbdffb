// tests/figures/panels_test.cpp — the figures' panels (issue 14 item 3): every panel of
// figure_list.cpp names a technique, parameters and buffers that exist; figure.png holds every
// panel, buffer panels, charts and the red blocks of panels that could not be made included;
// the stencil buffer the Chan 3-1c / 3-9c panels show is the one the techniques shade from.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "registry/registry.h"
#include "core/scene_library.h"
#include "figures/figure_spec.h"
#include "figures/figures.h"
#include "figures/report.h"

namespace fs = std::filesystem;
using namespace sl;
using namespace sl::figures;

namespace {

// One 8-bit PNG step: what a value read back from figure.png may differ by.
constexpr float kPngStep = 1.0f / 255.0f;
constexpr int kGap = 6;  // pixels between tiles and rows (figures.h: composeFigure)
constexpr int kMaxCompositeWidth = 1600;

fs::path outputDir(const std::string& name) {
  const fs::path dir = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "figures" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

const Technique* lookup(const std::string& name) {
  for (const Technique& t : allTechniques())
    if (t.name == name) return &t;
  return nullptr;
}

Image solid(int w, int h, float r, float g, float b) {
  Image im(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      im.at(x, y, 0) = r;
      im.at(x, y, 1) = g;
      im.at(x, y, 2) = b;
    }
  return im;
}

// Every pixel of `tile` equals the composite's at (x0, y0) (bottom-left corner), within one
// 8-bit step; returns the number of pixels that differ.
int mismatches(const Image& composite, const Image& tile, int x0, int y0) {
  const Image rgb = toRgb(tile);
  int bad = 0;
  for (int y = 0; y < rgb.height; ++y)
    for (int x = 0; x < rgb.width; ++x)
      for (int c = 0; c < 3; ++c)
        if (std::abs(composite.at(x0 + x, y0 + y, c) - rgb.at(x, y, c)) > kPngStep) {
          ++bad;
          break;
        }
  return bad;
}

// Where each tile's bottom-left corner lies in a composite of rows of `columns` tiles,
// top-aligned, kGap apart (the layout figures.h promises), and the composite's size.
struct Layout {
  std::vector<std::pair<int, int>> corners;
  int width = 0, height = 0;
};
Layout layoutOf(const std::vector<Image>& tiles, int columns) {
  std::vector<std::pair<int, int>> topLeft;  // x, distance of the tile's top from the top
  Layout l;
  int top = 0;
  for (size_t i = 0; i < tiles.size(); i += size_t(columns)) {
    int x = 0, rowHeight = 0;
    for (size_t k = i; k < std::min(tiles.size(), i + size_t(columns)); ++k) {
      topLeft.push_back({x, top});
      x += tiles[k].width + kGap;
      rowHeight = std::max(rowHeight, tiles[k].height);
    }
    l.width = std::max(l.width, x - kGap);
    top += rowHeight + kGap;
  }
  l.height = top - kGap;
  for (size_t k = 0; k < tiles.size(); ++k)
    l.corners.push_back({topLeft[k].first, l.height - topLeft[k].second - tiles[k].height});
  return l;
}

}  // namespace

// Every panel of every figure can be made: its technique is registered, takes the parameters the
// panel passes, and (for buffer panels) captures a buffer whose name holds the panel's pattern.
// The buffers are checked by rendering each technique once, small, with capturePasses.
TEST(FigurePanels, EveryPanelNamesAnAvailableTechniqueParameterAndBuffer) {
  struct BufferUse {
    const FigureSpec* figure;
    const PanelSpec* panel;
  };
  std::map<std::string, std::vector<BufferUse>> buffers;  // technique + params -> panels
  int panels = 0;
  for (const FigureSpec& f : figureList())
    for (const PanelSpec& p : f.panels) {
      ++panels;
      for (const Closeup& c : p.ownCloseups) {
        EXPECT_TRUE(c.x >= 0 && c.y >= 0 && c.x + c.w <= 1 && c.y + c.h <= 1) << f.id;
        EXPECT_GE(c.magnify, 2) << f.id;
      }
      if (p.kind != PanelKind::kRender && p.kind != PanelKind::kIntermediates) continue;
      const Technique* t = lookup(p.technique);
      ASSERT_NE(t, nullptr) << f.id << " " << p.label << ": no technique " << p.technique;
      for (const auto& [key, value] : p.params)
        EXPECT_NE(findParam(*t, key), nullptr)
            << f.id << " " << p.label << ": " << p.technique << " has no parameter " << key;
      if (p.kind != PanelKind::kIntermediates) continue;
      std::string key = p.technique + "|" + (p.scene.empty() ? f.scene : p.scene);
      for (const auto& [k, v] : p.params) key += "|" + k + "=" + v;
      buffers[key].push_back({&f, &p});
    }
  EXPECT_GT(panels, 0);
  for (const auto& [key, uses] : buffers) {
    const FigureSpec& f = *uses.front().figure;
    const PanelSpec& p = *uses.front().panel;
    RenderParams params;
    params.width = 96;  // small: only the buffers' names matter here
    params.height = 72;
    params.shadowMapTexels = 128;
    if (p.filter) params.filter = p.filter;
    params.extra = p.params;
    params.capturePasses = true;
    const Frame frame = renderTechnique(*lookup(p.technique),
                                        loadScene(p.scene.empty() ? f.scene : p.scene), params);
    for (const BufferUse& use : uses) {
      bool found = false;
      for (const PassImage& pass : frame.intermediates)
        found = found || pass.name.find(use.panel->intermediate) != std::string::npos;
      EXPECT_TRUE(found) << use.figure->id << " " << use.panel->label << ": " << key
                         << " captures no buffer named *" << use.panel->intermediate << "*";
    }
  }
}

// composeFigure on made-up panels: a render with a close-up, a buffer panel of two images, a
// chart and a panel that could not be made, three to a row. Each must sit where the layout puts
// it, the missing one as a dark red block of the figure's panel size.
TEST(FigureComposite, HoldsRendersBuffersChartsCloseupsAndRedBlocks) {
  const fs::path dir = outputDir("composite");
  fs::create_directories(dir / "fig");
  const Image render = solid(40, 30, 0.2f, 0.4f, 0.6f);
  const Image bufferA = solid(20, 30, 0.8f, 0.8f, 0.8f);
  const Image bufferB = solid(40, 20, 0.0f, 1.0f, 0.0f);
  const Image chart = solid(50, 30, 1.0f, 1.0f, 0.0f);
  const Image closeup = solid(16, 16, 0.0f, 0.0f, 1.0f);
  const std::map<std::string, const Image*> files = {{"fig/render.png", &render},
                                                     {"fig/a.png", &bufferA},
                                                     {"fig/b.png", &bufferB},
                                                     {"fig/chart.png", &chart},
                                                     {"fig/closeup.png", &closeup}};
  for (const auto& [name, image] : files) writePng((dir / name).string(), *image);
  FigureResult fig;
  fig.spec.id = "fig";
  fig.spec.columns = 3;
  fig.spec.width = 40;
  fig.spec.height = 30;
  PanelResult p;
  p.ok = true;
  p.images = {{"fig/render.png", "render"}};
  p.closeups = {{"fig/closeup.png", "close-up"}};
  fig.panels.push_back(p);
  p = PanelResult();
  p.ok = true;
  p.spec.kind = PanelKind::kIntermediates;
  p.images = {{"fig/a.png", "buffer a"}, {"fig/b.png", "buffer b"}};
  fig.panels.push_back(p);
  p = PanelResult();
  p.ok = true;
  p.spec.kind = PanelKind::kPlot;
  p.images = {{"fig/chart.png", "chart"}};
  fig.panels.push_back(p);
  p = PanelResult();
  p.ok = false;
  p.spec.kind = PanelKind::kIntermediates;  // a buffer panel that could not be made
  p.reason = "no such buffer";
  fig.panels.push_back(p);

  const Image composite = composeFigure(fig, dir.string());
  const Image red = solid(40, 30, 0.55f, 0.0f, 0.0f);
  const std::vector<Image> tiles = {render, bufferA, bufferB, chart, red};
  const Layout panels = layoutOf(tiles, 3);
  const int closeupRow = closeup.height + kGap;  // the close-ups form the last row
  ASSERT_EQ(composite.width, std::max(panels.width, closeup.width));
  ASSERT_EQ(composite.height, panels.height + closeupRow);
  for (size_t k = 0; k < tiles.size(); ++k)
    EXPECT_EQ(mismatches(composite, tiles[k], panels.corners[k].first,
                         panels.corners[k].second + closeupRow),
              0)
        << "tile " << k;
  EXPECT_EQ(mismatches(composite, closeup, 0, 0), 0) << "close-up";
}

// A composite wider than 1600 pixels is shrunk by an integer factor; a uniform tile keeps its
// colour (a box filter of equal values).
TEST(FigureComposite, ShrinksWideFiguresByAnIntegerFactor) {
  const fs::path dir = outputDir("composite-wide");
  fs::create_directories(dir / "fig");
  const Image wide = solid(1000, 40, 0.2f, 0.6f, 1.0f);
  writePng((dir / "fig/wide.png").string(), wide);
  FigureResult fig;
  fig.spec.columns = 2;
  PanelResult p;
  p.ok = true;
  p.images = {{"fig/wide.png", "wide"}};
  fig.panels = {p, p};
  const Image composite = composeFigure(fig, dir.string());
  const int full = 2 * wide.width + kGap;
  const int factor = (full + kMaxCompositeWidth - 1) / kMaxCompositeWidth;
  ASSERT_EQ(factor, 2);
  EXPECT_EQ(composite.width, full / factor);
  EXPECT_EQ(composite.height, wide.height / factor);
  EXPECT_NEAR(composite.at(10, 10, 1), 0.6f, kPngStep);
  EXPECT_NEAR(composite.at(composite.width - 10, 10, 2), 1.0f, kPngStep);
}

// End to end: `shadowlab figures --only brabec-fig3-packing` (one buffer panel of ten buffers,
// which figure.png used to leave out) puts every buffer PNG of the panel into figure.png where
// the layout says. The expected figure is built here from the panel's PNGs (white canvas, tiles
// at the layout's corners) and shrunk by the same integer box filter; one 8-bit step of
// rounding is allowed per pixel.
TEST(FigureComposite, BufferPanelsAreInFigurePng) {
  const fs::path dir = outputDir("packing");
  const std::string command = std::string(SHADOWLAB_BINARY) + " figures --out " + dir.string() +
                              " --only brabec-fig3-packing >/dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const fs::path fig = dir / "brabec-fig3-packing";
  std::vector<Image> tiles;
  for (int k = 0; fs::exists(fig / ("00-intermediate-buffers-" + std::to_string(k) + ".png")); ++k)
    tiles.push_back(
        toRgb(readPng((fig / ("00-intermediate-buffers-" + std::to_string(k) + ".png")).string())));
  ASSERT_GT(tiles.size(), 4u) << "legacy.pcf captured too few buffers";
  const Image composite = readPng((fig / "figure.png").string());
  const Layout l = layoutOf(tiles, 4);
  Image full(l.width, l.height, 3, 1.0f);
  for (size_t k = 0; k < tiles.size(); ++k)
    for (int y = 0; y < tiles[k].height; ++y)
      for (int x = 0; x < tiles[k].width; ++x)
        for (int c = 0; c < 3; ++c)
          full.at(l.corners[k].first + x, l.corners[k].second + y, c) = tiles[k].at(x, y, c);
  const int factor = (l.width + kMaxCompositeWidth - 1) / kMaxCompositeWidth;
  ASSERT_EQ(composite.width, l.width / factor);
  ASSERT_EQ(composite.height, l.height / factor);
  int bad = 0;
  for (int y = 0; y < composite.height; ++y)
    for (int x = 0; x < composite.width; ++x)
      for (int c = 0; c < 3; ++c) {
        float sum = 0;
        for (int j = 0; j < factor; ++j)
          for (int i = 0; i < factor; ++i) sum += full.at(x * factor + i, y * factor + j, c);
        if (std::abs(composite.at(x, y, c) - sum / float(factor * factor)) > kPngStep) {
          ++bad;
          break;
        }
      }
  EXPECT_EQ(bad, 0) << "figure.png differs from its buffers laid out (factor " << factor << ")";
}

// The stencil panels (Chan Figs. 3-1c, 3-9c). modern.volumes shades from the stencil count, so
// its captured stencil is black exactly where the visibility is 0 (on a scene where every object
// receives shadows). modern.hybrid counts only at silhouette pixels: its black pixels are
// silhouette pixels in shadow, and there are some.
TEST(StencilCapture, IsTheCountTheTechniquesShadeFrom) {
  RenderParams params;
  params.width = 160;
  params.height = 120;
  params.shadowMapTexels = 256;
  params.capturePasses = true;
  const Scene scene = loadScene("cylinder");
  const auto buffer = [](const Frame& f, const std::string& name) -> const Image* {
    for (const PassImage& p : f.intermediates)
      if (p.name.find(name) != std::string::npos) return &p.image;
    return nullptr;
  };
  const Frame volumes = renderTechnique(*lookup("modern.volumes"), scene, params);
  const Image* stencil = buffer(volumes, "stencil");
  ASSERT_NE(stencil, nullptr);
  int black = 0, disagree = 0;
  for (int y = 0; y < params.height; ++y)
    for (int x = 0; x < params.width; ++x) {
      const bool inShadow = stencil->at(x, y) < 0.5f;
      black += inShadow;
      disagree += inShadow != (volumes.visibility.at(x, y) < 0.5f);
    }
  EXPECT_GT(black, params.width * params.height / 50) << "the cylinder's shadow is missing";
  EXPECT_EQ(disagree, 0);

  const Frame hybrid = renderTechnique(*lookup("modern.hybrid"), scene, params);
  const Image* hybridStencil = buffer(hybrid, "stencil");
  const Image* silhouette = buffer(hybrid, "silhouette");
  ASSERT_NE(hybridStencil, nullptr);
  ASSERT_NE(silhouette, nullptr);
  int hybridBlack = 0, outside = 0, lit = 0;
  for (int y = 0; y < params.height; ++y)
    for (int x = 0; x < params.width; ++x) {
      if (hybridStencil->at(x, y) >= 0.5f) continue;
      ++hybridBlack;
      outside += silhouette->at(x, y) < 0.5f;
      lit += hybrid.visibility.at(x, y) >= 0.5f;
    }
  EXPECT_GT(hybridBlack, 0);
  EXPECT_LT(hybridBlack, black) << "the hybrid counted volumes outside the silhouette pixels";
  EXPECT_EQ(outside, 0);
  EXPECT_EQ(lit, 0);
}
