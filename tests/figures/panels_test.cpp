// tests/figures/panels_test.cpp — the figures' panels: every panel of
// figure_list.cpp names a technique, parameters and buffers that exist; figure.png holds every
// panel, buffer panels, charts and the red blocks of panels that could not be made included,
// each under its label drawn as text;
// the stencil buffer the Chan 3-1c / 3-9c panels show is the one the techniques shade from.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>

#include "core/base/errors.h"
#include "core/scene/scene_library.h"
#include "figures/disagreement.h"
#include "figures/figure_spec.h"
#include "figures/figures.h"
#include "figures/plots.h"
#include "figures/report.h"
#include "registry/registry.h"

namespace fs = std::filesystem;
using namespace sl;
using namespace sl::figures;

namespace {

// One 8-bit PNG step: what a value read back from figure.png may differ by.
constexpr float kPngStep = 1.0f / 255.0f;
constexpr int kGap = 6;  // pixels between tiles and rows (figures.h: composeFigure)
constexpr int kMaxCompositeWidth = 1600;
// A label with a few characters of 13-pixel text has well over this many dark pixels; an
// empty (white) strip has none.
constexpr int kMinTextPixels = 20;

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

// A rectangle of composeFigure's layout (top-left origin) as core/base/image.h's bottom-left
// corner.
int bottomOf(const Image& composite, const TileRect& r) {
  return composite.height - r.y - r.height;
}

// Dark pixels (drawn text) inside a label strip of the composite.
int darkPixels(const Image& composite, const TileRect& r) {
  int dark = 0;
  const int y0 = bottomOf(composite, r);
  for (int y = y0; y < y0 + r.height; ++y)
    for (int x = r.x; x < r.x + r.width; ++x) dark += composite.at(x, y, 0) < 0.5f;
  return dark;
}

// Rows of `columns` tiles kGap apart, each row's tiles top-aligned under label strips of one
// height, each strip right above its tile and holding text.
void expectLabelledRows(const Image& composite, const CompositeLayout& l, size_t panels,
                        size_t columns) {
  for (size_t k = 0; k < l.tiles.size(); ++k) {
    const bool closeup = k >= panels;
    const size_t first =
        closeup ? panels + (k - panels) / columns * columns : k / columns * columns;
    EXPECT_EQ(l.tiles[k].y, l.tiles[first].y) << "tile " << k << " not top-aligned in its row";
    EXPECT_EQ(l.labels[k].x, l.tiles[k].x) << "label " << k;
    EXPECT_LE(l.labels[k].y + l.labels[k].height, l.tiles[k].y) << "label " << k << " not above";
    if (k > first) {
      EXPECT_GE(l.tiles[k].x, l.tiles[k - 1].x + l.tiles[k - 1].width + kGap) << "tile " << k;
    } else {
      EXPECT_EQ(l.tiles[k].x, 0) << "tile " << k << " does not start its row";
    }
    EXPECT_GT(darkPixels(composite, l.labels[k]), kMinTextPixels) << "label " << k << " is empty";
  }
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
      for (const std::string& name : p.errorsOf)
        EXPECT_NE(lookup(name), nullptr) << f.id << " " << p.label << ": no technique " << name;
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

  CompositeLayout layout;
  const Image composite = composeFigure(fig, dir.string(), &layout);
  const Image red = solid(40, 30, 0.55f, 0.0f, 0.0f);
  const std::vector<Image> tiles = {render, bufferA, bufferB, chart, red, closeup};
  ASSERT_EQ(layout.tiles.size(), tiles.size());
  ASSERT_EQ(layout.shrink, 1);
  for (size_t k = 0; k < tiles.size(); ++k) {
    EXPECT_EQ(layout.tiles[k].width, tiles[k].width) << "tile " << k;
    EXPECT_EQ(layout.tiles[k].height, tiles[k].height) << "tile " << k;
    EXPECT_EQ(
        mismatches(composite, tiles[k], layout.tiles[k].x, bottomOf(composite, layout.tiles[k])), 0)
        << "tile " << k;
  }
  expectLabelledRows(composite, layout, 5, 3);
  EXPECT_GT(layout.tiles[3].y, layout.tiles[0].y + 30) << "the chart starts the second row";
  EXPECT_GT(layout.tiles[5].y, layout.tiles[3].y + 30) << "the close-ups come last";
}

// Close-ups sit under the panel they magnify (Chan Fig. 3-1's close-ups of panels b-d
// were packed from column 0, one column left of their panels). Four panels in a row, the first
// without close-ups (the shadow-map view), the second a buffer panel of two images with one
// close-up each, the last a render with two close-ups: each close-up's left edge is its
// panel's, a second close-up of the same panel goes one row further down.
TEST(FigureComposite, CloseupsSitUnderTheirPanels) {
  const fs::path dir = outputDir("composite-closeups");
  fs::create_directories(dir / "fig");
  const Image view = solid(40, 30, 0.5f, 0.5f, 0.5f);
  const Image bufferA = solid(30, 30, 0.8f, 0.8f, 0.8f);
  const Image bufferB = solid(30, 30, 0.0f, 1.0f, 0.0f);
  const Image render = solid(40, 30, 0.2f, 0.4f, 0.6f);
  const Image closeA = solid(12, 12, 1.0f, 0.0f, 0.0f);
  const Image closeB = solid(12, 12, 0.0f, 0.0f, 1.0f);
  const Image closeR0 = solid(12, 12, 1.0f, 1.0f, 0.0f);
  const Image closeR1 = solid(12, 12, 0.0f, 1.0f, 1.0f);
  const std::map<std::string, const Image*> files = {
      {"fig/view.png", &view},     {"fig/a.png", &bufferA},  {"fig/b.png", &bufferB},
      {"fig/render.png", &render}, {"fig/ca.png", &closeA},  {"fig/cb.png", &closeB},
      {"fig/cr0.png", &closeR0},   {"fig/cr1.png", &closeR1}};
  for (const auto& [name, image] : files) writePng((dir / name).string(), *image);
  FigureResult fig;
  fig.spec.id = "fig";
  fig.spec.columns = 4;
  PanelResult p;
  p.ok = true;
  p.images = {{"fig/view.png", "view"}};
  fig.panels.push_back(p);
  p.spec.kind = PanelKind::kIntermediates;
  p.images = {{"fig/a.png", "a"}, {"fig/b.png", "b"}};
  p.closeups = {{"fig/ca.png", "a magnified"}, {"fig/cb.png", "b magnified"}};
  fig.panels.push_back(p);
  p.spec.kind = PanelKind::kRender;
  p.images = {{"fig/render.png", "render"}};
  p.closeups = {{"fig/cr0.png", "first"}, {"fig/cr1.png", "second"}};
  fig.panels.push_back(p);

  CompositeLayout layout;
  const Image composite = composeFigure(fig, dir.string(), &layout);
  // layout.tiles: the four panel tiles (view, a, b, render), then the close-ups in order.
  const std::vector<const Image*> tiles = {&view,   &bufferA, &bufferB, &render,
                                           &closeA, &closeB,  &closeR0, &closeR1};
  ASSERT_EQ(layout.tiles.size(), tiles.size());
  for (size_t k = 0; k < tiles.size(); ++k)
    EXPECT_EQ(
        mismatches(composite, *tiles[k], layout.tiles[k].x, bottomOf(composite, layout.tiles[k])),
        0)
        << "tile " << k;
  // The first close-up row: under tiles 1, 2 and 3, each at its panel's left edge.
  EXPECT_EQ(layout.tiles[4].x, layout.tiles[1].x) << "a's close-up";
  EXPECT_EQ(layout.tiles[5].x, layout.tiles[2].x) << "b's close-up";
  EXPECT_EQ(layout.tiles[6].x, layout.tiles[3].x) << "render's first";
  EXPECT_EQ(layout.tiles[4].y, layout.tiles[6].y) << "one row for the first close-ups";
  EXPECT_GT(layout.tiles[4].y, layout.tiles[0].y + layout.tiles[0].height);
  // The render's second close-up: the next row, under the render.
  EXPECT_EQ(layout.tiles[7].x, layout.tiles[3].x) << "render's second";
  EXPECT_GT(layout.tiles[7].y, layout.tiles[6].y + layout.tiles[6].height);
  // Nothing under the view panel: the close-up rows are white there.
  const int below = composite.height - 1 - (layout.tiles[4].y + 5);  // rows bottom-up
  EXPECT_NEAR(composite.at(layout.tiles[0].x + 5, below, 0), 1.0f, kPngStep);
  EXPECT_NEAR(composite.at(layout.tiles[0].x + 5, below, 2), 1.0f, kPngStep);
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
  CompositeLayout layout;
  const Image composite = composeFigure(fig, dir.string(), &layout);
  const int full = 2 * wide.width + kGap;
  const int factor = (full + kMaxCompositeWidth - 1) / kMaxCompositeWidth;
  ASSERT_EQ(factor, 2);
  EXPECT_EQ(layout.shrink, factor);
  // The tiles shrink; the gap and the labels keep their size (the text stays readable).
  EXPECT_EQ(composite.width, 2 * (wide.width / factor) + kGap);
  ASSERT_EQ(layout.tiles.size(), 2u);
  EXPECT_EQ(layout.tiles[1].x, wide.width / factor + kGap);
  EXPECT_EQ(layout.tiles[0].height, wide.height / factor);
  EXPECT_EQ(composite.height, layout.tiles[0].y + wide.height / factor);
  const int y = bottomOf(composite, layout.tiles[0]) + 5;
  EXPECT_NEAR(composite.at(10, y, 1), 0.6f, kPngStep);
  EXPECT_NEAR(composite.at(composite.width - 10, y, 2), 1.0f, kPngStep);
  expectLabelledRows(composite, layout, 2, 2);
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
  // Rows of four tiles shrunk by one integer factor, each under its label: a tile's x follows
  // from the widths before it in its row; its y from the label heights above, so it is found by
  // scanning its column.
  constexpr size_t kColumns = 4;
  int unlabelled = 0;
  for (size_t i = 0; i < tiles.size(); i += kColumns) {
    int w = 0;
    for (size_t k = i; k < std::min(tiles.size(), i + kColumns); ++k)
      w += tiles[k].width + (k > i ? kGap : 0);
    unlabelled = std::max(unlabelled, w);
  }
  const int factor = (unlabelled + kMaxCompositeWidth - 1) / kMaxCompositeWidth;
  int x = 0, lastTop = -1, rowFloor = 0, nextRowFloor = 0;
  for (size_t k = 0; k < tiles.size(); ++k) {
    if (k % kColumns == 0) x = 0;
    Image shrunk(tiles[k].width / factor, tiles[k].height / factor, 3);
    for (int y = 0; y < shrunk.height; ++y)
      for (int i = 0; i < shrunk.width; ++i)
        for (int c = 0; c < 3; ++c) {
          float sum = 0;
          for (int b = 0; b < factor; ++b)
            for (int a = 0; a < factor; ++a) sum += tiles[k].at(i * factor + a, y * factor + b, c);
          shrunk.at(i, y, c) = sum / float(factor * factor);
        }
    int found = -1;
    for (int y0 = composite.height - shrunk.height; y0 >= 0 && found < 0; --y0)
      if (mismatches(composite, shrunk, x, y0) == 0) found = y0;
    ASSERT_GE(found, 0) << "buffer " << k << " is not in figure.png at x = " << x;
    const int top = composite.height - found - shrunk.height;
    if (k % kColumns != 0) {
      EXPECT_EQ(top, lastTop) << "buffer " << k << " not top-aligned";
    } else if (k > 0) {
      EXPECT_GT(top, lastTop) << "buffer " << k;
    }
    // Its label: text above it, below the previous row's tiles (a row's label strips are
    // padded to its tallest, so a short label may end well above its tile).
    if (k % kColumns == 0) {
      rowFloor = nextRowFloor;
      nextRowFloor = 0;
    }
    nextRowFloor = std::max(nextRowFloor, top + shrunk.height);
    int dark = 0;
    for (int t = rowFloor; t < top; ++t)
      for (int i = x; i < x + shrunk.width; ++i)
        dark += composite.at(i, composite.height - 1 - t, 0) < 0.5f;
    EXPECT_GT(dark, kMinTextPixels) << "no label above buffer " << k;
    lastTop = top;
    x += std::max(shrunk.width, kMinLabelWidth) + kGap;
  }
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

namespace {
const FigureSpec& figureById(const std::string& id) {
  for (const FigureSpec& f : figureList())
    if (f.id == id) return f;
  throw std::runtime_error("no figure " + id);
}

std::string firstSentence(const std::string& caption) {
  return caption.substr(0, caption.find(". "));
}
}  // namespace

// Chan Fig. 4-8 times a real 16-sample bicubic PCF (modern.gems16
// --param kernel=bicubic) at every map size, beside the thesis's times, on the thesis's GPU.
TEST(ChanFigures, FourEightTimesABicubicSixteenSamplePcfAtEveryMapSize) {
  const FigureSpec& f = figureById("chan-4-8");
  std::set<int> sizes;
  for (const PanelSpec& p : f.panels) {
    const auto kernel = p.params.find("kernel");
    if (p.technique != "modern.gems16") continue;
    ASSERT_NE(kernel, p.params.end()) << p.label << ": the 16-sample column is the bicubic one";
    EXPECT_EQ(kernel->second, "bicubic") << p.label;
    EXPECT_NE(p.paperNumbers.find(" ms"), std::string::npos) << p.label << " beside the thesis";
    sizes.insert(p.shadowMapTexels);
  }
  EXPECT_EQ(sizes, (std::set<int>{256, 512, 1024}));
  // Chan §4.4: "a 2.6 GHz Pentium 4 system with an NVIDIA Geforce FX 5800 Ultra".
  EXPECT_NE(f.caption.find("GeForce FX 5800 Ultra"), std::string::npos) << f.caption;
  EXPECT_EQ(f.caption.find("5950"), std::string::npos) << "not the thesis's card";
}

// A timing figure that llvmpipe cannot reproduce says so in its first sentence.
TEST(ChanFigures, TimingCaptionsLeadWithWhatLlvmpipeCannotReproduce) {
  for (const char* id : {"chan-3-11", "chan-4-8"}) {
    const std::string first = firstSentence(figureById(id).caption);
    EXPECT_NE(first.find("llvmpipe"), std::string::npos) << id << ": " << first;
    EXPECT_TRUE(std::regex_search(first, std::regex(R"(\b(not|cannot|neither)\b)")))
        << id << ": " << first;
  }
}

// Chan Fig. 3-7 at the thesis's 1024x768 with its 1024² map, and per scene a panel of the
// pixels the shadow map and the hybrid get wrong against the volumes, with the row's close-up.
TEST(ChanFigures, ThreeSevenShowsWrongPixelsAgainstTheVolumesAtTheThesisSize) {
  const FigureSpec& f = figureById("chan-3-7");
  EXPECT_EQ(f.width, 1024);
  EXPECT_EQ(f.height, 768);
  EXPECT_EQ(f.shadowMapTexels, 1024);
  ASSERT_EQ(f.panels.size() % size_t(f.columns), 0u) << "whole rows";
  int overlays = 0;
  for (size_t row = 0; row < f.panels.size() / size_t(f.columns); ++row) {
    const PanelSpec& last = f.panels[row * size_t(f.columns) + size_t(f.columns) - 1];
    EXPECT_EQ(last.technique, "modern.volumes") << last.label;
    EXPECT_EQ(last.errorsOf, (std::vector<std::string>{"modern.hw", "modern.hybrid"}))
        << last.label;
    for (int c = 0; c < f.columns; ++c) {
      const PanelSpec& p = f.panels[row * size_t(f.columns) + size_t(c)];
      EXPECT_EQ(p.scene, last.scene) << "one scene per row";
      // Two windows per scene (the most wrong pixels, a long ground shadow edge), the same in
      // every column of the row, magnified enough to survive figure.png's shrinking.
      ASSERT_EQ(p.ownCloseups.size(), 2u) << p.label;
      for (size_t k = 0; k < 2; ++k) {
        EXPECT_EQ(p.ownCloseups[k].x, last.ownCloseups[k].x) << "one window per row";
        EXPECT_EQ(p.ownCloseups[k].y, last.ownCloseups[k].y) << "one window per row";
        EXPECT_GE(p.ownCloseups[k].magnify, 6) << p.label;
      }
    }
    overlays += last.errorsOf.empty() ? 0 : 1;
  }
  EXPECT_EQ(overlays, 3);
}

// The overlay: grey where both techniques agree with the exact one, magenta / yellow / cyan
// where the first only, both, the second only decide lit or shadow otherwise; counted.
TEST(Disagreement, ColoursAndCountsEachTechniquesWrongPixels) {
  // Five pixels in a row: exact lit, lit, shadow, shadow, lit.
  Image exact(5, 1, 1), first(5, 1, 1), second(5, 1, 1);
  const float e[] = {1, 1, 0, 0, 0.6f}, a[] = {1, 0, 0, 1, 0.4f}, b[] = {1, 1, 1, 1, 0.6f};
  for (int x = 0; x < 5; ++x) {
    exact.at(x, 0) = e[x];
    first.at(x, 0) = a[x];
    second.at(x, 0) = b[x];
  }
  const Image colour = solid(5, 1, 1.0f, 1.0f, 1.0f);
  const Disagreement d = disagreementOverlay(colour, exact, first, second);
  EXPECT_EQ(d.pixels, 5);
  EXPECT_EQ(d.firstWrong, 3);   // pixels 1, 3, 4
  EXPECT_EQ(d.secondWrong, 2);  // pixels 2, 3
  EXPECT_EQ(d.bothWrong, 1);    // pixel 3
  auto rgb = [&](int x) {
    return std::array<float, 3>{d.overlay.at(x, 0, 0), d.overlay.at(x, 0, 1),
                                d.overlay.at(x, 0, 2)};
  };
  const float grey = kOverlayBackgroundShare;  // white under the share (luma weights sum to 1)
  constexpr float kLumaRoundoff = 1e-6f;       // three float products summed
  for (float c : rgb(0)) EXPECT_NEAR(c, grey, kLumaRoundoff);
  EXPECT_EQ(rgb(1),
            (std::array<float, 3>{kFirstOnlyWrong[0], kFirstOnlyWrong[1], kFirstOnlyWrong[2]}));
  EXPECT_EQ(rgb(2),
            (std::array<float, 3>{kSecondOnlyWrong[0], kSecondOnlyWrong[1], kSecondOnlyWrong[2]}));
  EXPECT_EQ(rgb(3), (std::array<float, 3>{kBothWrong[0], kBothWrong[1], kBothWrong[2]}));
  EXPECT_THROW(disagreementOverlay(colour, exact, Image(4, 1, 1), second), InputError);
}

// Chan Fig. 3-11's chart has a dozen passes: each stack segment gets its own colour (gnuplot's
// default cycle repeats after eight).
TEST(Plots, StackSegmentsHaveOneColourEach) {
  static const std::regex hex("#[0-9a-f]{6}");
  for (size_t n : {1u, 8u, 12u, 20u, 33u}) {
    const std::vector<std::string> colours = segmentColours(n);
    ASSERT_EQ(colours.size(), n);
    for (const std::string& c : colours) EXPECT_TRUE(std::regex_match(c, hex)) << c;
    EXPECT_EQ(std::set<std::string>(colours.begin(), colours.end()).size(), n) << n << " segments";
  }
  // The chart's script (kept beside the PNG) gives each of twelve segments its colour.
  std::string why;
  if (!gnuplotAvailable(&why)) GTEST_SKIP() << why;
  const fs::path dir = outputDir("stacked-colours");
  std::vector<std::string> columns;
  for (int c = 0; c < 12; ++c) columns.push_back("pass " + std::to_string(c));
  plotStackedBars("t", "ms", {"a", "b"}, columns,
                  {std::vector<double>(12, 1.0), std::vector<double>(12, 2.0)},
                  (dir / "chart.png").string(), 400, 300);
  std::ifstream gp(dir / "chart.gp");
  const std::string script((std::istreambuf_iterator<char>(gp)), std::istreambuf_iterator<char>());
  std::set<std::string> used;
  static const std::regex lc(R"re(lc rgb "(#[0-9a-f]{6})")re");
  for (auto it = std::sregex_iterator(script.begin(), script.end(), lc);
       it != std::sregex_iterator(); ++it)
    used.insert((*it)[1]);
  EXPECT_EQ(used.size(), 12u) << script;
}
