#include "figures/figure_composite.h"

#include <stdlib.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/base/errors.h"

namespace sl::figures {
namespace fs = std::filesystem;

namespace {

constexpr const char* kLabelFont = "DejaVu-Sans";  // fonts-dejavu-core, ImageMagick's name

// One argument for sh: single-quoted, with ' written as '\''.
std::string shellQuoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// The text as ImageMagick's caption: reads it literally: '%' starts a format escape and '\' an
// escape sequence, a leading '@' names a file; an empty caption is an error.
std::string captionText(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '%')
      out += "%%";
    else if (c == '\\')
      out += "\\\\";
    else if (c == '\n' || c == '\r' || c == '\t')
      out += ' ';
    else
      out += c;
  }
  if (out.empty()) out = " ";
  if (out[0] == '@') out = "\\" + out;
  return out;
}

// Box filter by an integer factor.
Image shrink(const Image& image, int factor) {
  const Image rgb = toRgb(image);
  if (factor <= 1) return rgb;
  Image out(std::max(rgb.width / factor, 1), std::max(rgb.height / factor, 1), 3);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 3; ++c) {
        float sum = 0;
        int n = 0;
        for (int j = 0; j < factor && y * factor + j < rgb.height; ++j)
          for (int i = 0; i < factor && x * factor + i < rgb.width; ++i, ++n)
            sum += rgb.at(x * factor + i, y * factor + j, c);
        out.at(x, y, c) = sum / float(std::max(n, 1));
      }
  return out;
}

// Copies `tile` with its top-left corner at (x, y) (top-left origin) into the canvas.
void paste(Image& canvas, const Image& tile, int x, int y) {
  for (int j = 0; j < tile.height; ++j)
    for (int i = 0; i < tile.width; ++i)
      for (int c = 0; c < 3; ++c)
        canvas.at(x + i, canvas.height - 1 - (y + j), c) = tile.at(i, tile.height - 1 - j, c);
}

int rowsWidth(const std::vector<LabelledTile>& tiles, size_t columns) {
  int widest = 0;
  for (size_t i = 0; i < tiles.size(); i += columns) {
    int w = 0;
    for (size_t k = i; k < std::min(tiles.size(), i + columns); ++k)
      w += tiles[k].image.width + (k > i ? kCompositeGap : 0);
    widest = std::max(widest, w);
  }
  return widest;
}

}  // namespace

std::vector<Image> drawTextStrips(const std::vector<std::pair<std::string, int>>& texts) {
  if (texts.empty()) return {};
  std::string pattern = (fs::temp_directory_path() / "shadowlab-labels-XXXXXX").string();
  if (!mkdtemp(pattern.data())) throw InputError("cannot make a temporary folder for labels");
  const fs::path dir(pattern);
  std::ostringstream command;
  command << "convert -background white -fill black -font " << kLabelFont << " -pointsize "
          << kLabelPointSize;
  for (const auto& [text, width] : texts)
    command << " -size " << std::max(width, 1) << "x caption:" << shellQuoted(captionText(text));
  const fs::path log = dir / "convert.log";
  command << " +adjoin " << shellQuoted("PNG24:" + (dir / "label-%d.png").string()) << " >"
          << shellQuoted(log.string()) << " 2>&1";
  const int status = std::system(command.str().c_str());
  std::vector<Image> strips;
  std::string failure;
  if (status != 0) {
    std::ifstream in(log);
    std::getline(in, failure);
    if (failure.empty()) failure = "exit status " + std::to_string(status);
  } else {
    for (size_t i = 0; i < texts.size(); ++i) {
      const fs::path png = dir / ("label-" + std::to_string(i) + ".png");
      if (!fs::exists(png)) {
        failure = "no " + png.filename().string();
        break;
      }
      strips.push_back(toRgb(readPng(png.string())));
    }
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
  if (!failure.empty())
    throw InputError(
        "figure labels need ImageMagick's convert and the DejaVu fonts (Debian: "
        "imagemagick, fonts-dejavu-core): " +
        failure);
  return strips;
}

Image composeLabelled(const std::vector<LabelledTile>& panels,
                      const std::vector<LabelledTile>& closeups, int columnCount,
                      CompositeLayout* layout) {
  const size_t columns = size_t(std::max(columnCount, 1));
  const int unlabelled = std::max(rowsWidth(panels, columns), rowsWidth(closeups, columns));
  const int factor = std::max(1, (unlabelled + kCompositeMaxWidth - 1) / kCompositeMaxWidth);

  // Shrink, then draw every label at the final size in one convert run.
  std::vector<Image> tiles;
  std::vector<std::pair<std::string, int>> texts;
  for (const auto* list : {&panels, &closeups})
    for (const LabelledTile& t : *list) {
      tiles.push_back(shrink(t.image, factor));
      texts.push_back({t.label, std::max(tiles.back().width, kMinLabelWidth)});
    }
  const std::vector<Image> strips = drawTextStrips(texts);

  // Rows: panels in rows of `columns`; then the close-ups, one row per (row of panels, n-th
  // close-up of a panel), so that each sits below the panel it magnifies.
  std::vector<std::vector<size_t>> rows;
  for (size_t i = 0; i < panels.size(); i += columns) {
    rows.emplace_back();
    for (size_t k = i; k < std::min(panels.size(), i + columns); ++k) rows.back().push_back(k);
  }
  std::map<std::pair<size_t, size_t>, std::vector<size_t>> closeupRows;
  std::map<int, size_t> seen;  // close-ups already placed per panel
  for (size_t i = 0; i < closeups.size(); ++i) {
    const int under = closeups[i].under;
    const size_t panelRow = under >= 0 ? size_t(under) / columns : 0;
    closeupRows[{panelRow, seen[under]++}].push_back(panels.size() + i);
  }
  for (auto& [key, row] : closeupRows) rows.push_back(row);

  CompositeLayout placed;
  placed.shrink = factor;
  placed.tiles.resize(tiles.size());
  placed.labels.resize(tiles.size());
  int width = 0, y = 0;
  for (size_t r = 0; r < rows.size(); ++r) {
    int labelHeight = 0, tileHeight = 0, x = 0;
    for (size_t k : rows[r]) {
      labelHeight = std::max(labelHeight, strips[k].height);
      tileHeight = std::max(tileHeight, tiles[k].height);
    }
    if (r > 0) y += kCompositeGap;
    bool first = true;
    for (size_t k : rows[r]) {
      if (!first) x += kCompositeGap;
      first = false;
      const int under = k >= panels.size() ? closeups[k - panels.size()].under : -1;
      if (under >= 0 && size_t(under) < panels.size()) x = std::max(x, placed.tiles[under].x);
      placed.labels[k] = {x, y, strips[k].width, strips[k].height};
      placed.tiles[k] = {x, y + labelHeight, tiles[k].width, tiles[k].height};
      x += std::max(tiles[k].width, strips[k].width);
    }
    width = std::max(width, x);
    y += labelHeight + tileHeight;
  }
  Image canvas(std::max(width, 1), std::max(y, 1), 3, 1.0f);
  for (size_t k = 0; k < tiles.size(); ++k) {
    paste(canvas, strips[k], placed.labels[k].x, placed.labels[k].y);
    paste(canvas, tiles[k], placed.tiles[k].x, placed.tiles[k].y);
  }
  if (layout) *layout = std::move(placed);
  return canvas;
}

}  // namespace sl::figures
