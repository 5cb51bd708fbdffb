// core/base/image.h — float images (the common currency between passes, masks, metrics and PNG).
//
// Rows are stored bottom-to-top, as glReadPixels returns them; PNG I/O flips to top-down.
// Values are linear [0,1] for colour and visibility; metrics and heat maps work on channel 0
// (visibility masks are one-channel).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/base/provenance.h"

namespace sl {

struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<float> data;  // width * height * channels, row 0 at the bottom

  Image() = default;
  Image(int w, int h, int c, float fill = 0.0f)
      : width(w), height(h), channels(c), data(size_t(w) * h * c, fill) {}
  float& at(int x, int y, int c = 0) { return data[(size_t(y) * width + x) * channels + c]; }
  float at(int x, int y, int c = 0) const { return data[(size_t(y) * width + x) * channels + c]; }
  bool empty() const { return data.empty(); }
};

// Writes 8- or 16-bit PNG (gray, gray+alpha, RGB or RGBA by channel count). Values are clamped
// to [0,1] and rounded. Writes to a temporary file first and renames it, so a failure never
// leaves a partial file. Throws InputError naming the path when it cannot write.
// tEXt chunks say what made the file (core/base/provenance.h): "Software" (shadowlab and the
// commit), "shadowlab:command" (the command line) and, when given, "shadowlab:parameters".
void writePng(const std::string& path, const Image& image, int bitDepth = 8,
              const Provenance& provenance = {});
// The same PNG in memory (the live lab's responses, lab/), deflated at zlib's fastest level.
std::string encodePng(const Image& image, int bitDepth = 8, const Provenance& provenance = {});
// The pixels as writePng stores them: rows top-down, each value clamped to [0, 1] and rounded
// to `bitDepth` (8, or 16 as big-endian byte pairs). The Python module's image arrays.
std::vector<unsigned char> quantizedRows(const Image& image, int bitDepth);
// Reads any PNG (palette, gray, RGB, with or without alpha, 8 or 16 bit) as float channels.
Image readPng(const std::string& path);
// The text chunks (tEXt, zTXt, iTXt) of a PNG, keyword -> text. Throws InputError.
std::map<std::string, std::string> readPngText(const std::string& path);

// Close-ups as the papers print them.
Image crop(const Image& image, int x, int y, int w, int h);  // (x, y) = bottom-left corner
Image magnifyNearest(const Image& image, int factor);
Image toRgb(const Image& image);  // gray -> RGB, RGBA -> RGB
// Draws a one-pixel red rectangle outline (the close-up frame) in an RGB image.
void drawFrame(Image& rgb, int x, int y, int w, int h, int thickness = 1);
// |a - b| on channel 0 as a heat map: black = equal, then blue -> red -> yellow -> white as the
// difference grows to `fullScale` (1 by default).
Image differenceHeatMap(const Image& a, const Image& b, float fullScale = 1.0f);
// One channel of an image.
Image channel(const Image& image, int c);
// Places images side by side with a gap (for figure panels); all converted to RGB.
Image sideBySide(const std::vector<Image>& images, int gap = 4);

// True when every value is finite.
bool allFinite(const Image& image);

}  // namespace sl
