// figures/figure_composite.h — figure.png as a slide: the figure's tiles in rows, each under
// its label (panel letter, label, technique; a buffer's caption with its channel names), drawn
// as text by ImageMagick's `convert` (Debian: imagemagick) in DejaVu Sans (fonts-dejavu-core).
#pragma once

#include <string>
#include <vector>

#include "core/base/image.h"

namespace sl::figures {

constexpr int kCompositeMaxWidth = 1600;  // the one-PNG version of a figure, in pixels
constexpr int kCompositeGap = 6;          // pixels between its tiles and rows
constexpr int kLabelPointSize = 13;       // label text height, pixels (at the final size)
constexpr int kMinLabelWidth = 128;       // a narrower tile gets a label this wide (pixels)

struct LabelledTile {
  Image image;
  std::string label;
  int under = -1;  // a close-up: the index of the panel tile it magnifies (it sits below it)
};

// Where composeLabelled put one tile and its label (pixels, top-left origin, as a PNG viewer
// shows them).
struct TileRect {
  int x = 0, y = 0, width = 0, height = 0;
};
struct CompositeLayout {
  std::vector<TileRect> tiles;   // panels then close-ups, in order
  std::vector<TileRect> labels;  // the text strip above each tile
  int shrink = 1;                // the integer factor every tile was shrunk by
};

// Draws each text black on white, wrapped to its width (pixels), in one `convert` run; each
// strip is as tall as its wrapped text. Throws InputError when convert is missing or fails.
std::vector<Image> drawTextStrips(const std::vector<std::pair<std::string, int>>& texts);

// Rows of `columns` panel tiles, then the close-ups: one row per row of panels and close-up
// number, each close-up starting under the left edge of the panel it magnifies (`under`; or just
// right of the close-up before it where that one is wider), each tile under its label
// strip (a row's strips padded to the row's tallest), tiles and rows kCompositeGap apart. When
// the unlabelled layout is wider than kCompositeMaxWidth every tile is first shrunk by the
// smallest integer factor that fits (box filter), so the text keeps its size. RGB.
Image composeLabelled(const std::vector<LabelledTile>& panels,
                      const std::vector<LabelledTile>& closeups, int columns,
                      CompositeLayout* layout = nullptr);

}  // namespace sl::figures
