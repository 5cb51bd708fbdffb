#include "core/base/image.h"

#include <png.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include "core/base/errors.h"
#include "core/base/png_text.h"

namespace sl {
namespace {

struct FileCloser {
  void operator()(FILE* f) const {
    if (f != nullptr) std::fclose(f);
  }
};
using File = std::unique_ptr<FILE, FileCloser>;

int pngColorType(int channels) {
  switch (channels) {
    case 1: return PNG_COLOR_TYPE_GRAY;
    case 2: return PNG_COLOR_TYPE_GRAY_ALPHA;
    case 3: return PNG_COLOR_TYPE_RGB;
    case 4: return PNG_COLOR_TYPE_RGBA;
    default: return -1;
  }
}

// The tEXt chunks of writePng. tEXt holds Latin-1; every value here is ASCII (the command line
// is shell-quoted with \xNN escapes, the parameters are JSON with \u escapes), except a
// caller's own text, whose other bytes libpng stores as they are.
void setProvenanceText(png_structp png, png_infop info, const Provenance& provenance) {
  const std::string software = softwareName();
  const std::string& command = provenance.command.empty() ? commandLine() : provenance.command;
  std::vector<std::pair<const char*, const std::string*>> entries = {{"Software", &software}};
  if (!command.empty()) entries.push_back({"shadowlab:command", &command});
  if (!provenance.parameters.empty())
    entries.push_back({"shadowlab:parameters", &provenance.parameters});
  std::vector<png_text> text(entries.size());
  for (size_t i = 0; i < entries.size(); ++i) {
    text[i].compression = PNG_TEXT_COMPRESSION_NONE;
    text[i].key = const_cast<char*>(entries[i].first);
    text[i].text = const_cast<char*>(entries[i].second->c_str());
    text[i].text_length = entries[i].second->size();
  }
  png_set_text(png, info, text.data(), int(text.size()));  // libpng copies the strings
}

// The rows of a PNG, top-down, quantised to `bitDepth` (8 or 16, big-endian).
std::vector<unsigned char> pngRows(const Image& image, int bitDepth) {
  const int bytes = bitDepth / 8;
  const size_t rowBytes = size_t(image.width) * image.channels * bytes;
  std::vector<unsigned char> pixels(rowBytes * image.height);
  const float maxValue = bitDepth == 8 ? 255.0f : 65535.0f;
  for (int y = 0; y < image.height; ++y) {
    const int srcRow = image.height - 1 - y;  // bottom-up storage -> top-down PNG
    unsigned char* out = pixels.data() + rowBytes * y;
    for (int i = 0; i < image.width * image.channels; ++i) {
      float v = image.data[size_t(srcRow) * image.width * image.channels + i];
      if (!(v >= 0.0f)) v = 0.0f;  // NaN -> 0
      v = std::min(v, 1.0f);
      const unsigned q = unsigned(std::lround(v * maxValue));
      if (bytes == 1) {
        out[i] = static_cast<unsigned char>(q);
      } else {
        out[2 * i] = static_cast<unsigned char>(q >> 8);
        out[2 * i + 1] = static_cast<unsigned char>(q & 0xff);
      }
    }
  }
  return pixels;
}

void appendToString(png_structp png, png_bytep data, png_size_t length) {
  static_cast<std::string*>(png_get_io_ptr(png))
      ->append(reinterpret_cast<const char*>(data), length);
}

}  // namespace

std::vector<unsigned char> quantizedRows(const Image& image, int bitDepth) {
  return pngRows(image, bitDepth);
}

namespace {
// zlib's default level for files; its fastest for in-memory PNGs: the live lab answers with
// those while a slider moves, on loopback, where a few more bytes cost less than the time of
// a denser deflate.
constexpr int kFilePngCompression = -1;     // Z_DEFAULT_COMPRESSION
constexpr int kInMemoryPngCompression = 1;  // Z_BEST_SPEED

// The PNG bytes of `image` with its provenance in tEXt chunks; `what` names it in errors.
std::string pngBytes(const Image& image, int bitDepth, const Provenance& provenance,
                     int compressionLevel, const std::string& what) {
  if (bitDepth != 8 && bitDepth != 16) throw InputError("PNG bit depth must be 8 or 16");
  const int colorType = pngColorType(image.channels);
  if (colorType < 0 || image.width <= 0 || image.height <= 0)
    throw InputError("cannot encode an empty or " + std::to_string(image.channels) +
                     "-channel image as " + what);
  const std::vector<unsigned char> pixels = pngRows(image, bitDepth);
  const size_t rowBytes = size_t(image.width) * image.channels * (bitDepth / 8);
  std::string out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (png == nullptr || info == nullptr) {
    png_destroy_write_struct(&png, &info);
    throw InputError("libpng could not start encoding " + what);
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw InputError("libpng failed while encoding " + what);
  }
  png_set_write_fn(png, &out, appendToString, nullptr);
  png_set_compression_level(png, compressionLevel);
  png_set_IHDR(png, info, image.width, image.height, bitDepth, colorType, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  setProvenanceText(png, info, provenance);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y)
    png_write_row(png, const_cast<unsigned char*>(pixels.data()) + rowBytes * y);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return out;
}
}  // namespace

std::string encodePng(const Image& image, int bitDepth, const Provenance& provenance) {
  return pngBytes(image, bitDepth, provenance, kInMemoryPngCompression, "a PNG");
}

void writePng(const std::string& path, const Image& image, int bitDepth,
              const Provenance& provenance) {
  const std::string bytes = pngBytes(image, bitDepth, provenance, kFilePngCompression, path);
  // A temporary name of this process alone: parallel writers of one path (ctest runs tests as
  // parallel processes) each rename a complete file into place, never a half-written one.
  const std::string temp = path + ".part-" + std::to_string(::getpid());
  File file(std::fopen(temp.c_str(), "wb"));
  if (!file) throw InputError("cannot write " + path + ": " + std::strerror(errno));
  const bool written = std::fwrite(bytes.data(), 1, bytes.size(), file.get()) == bytes.size() &&
                       std::fflush(file.get()) == 0;
  file.reset();
  if (!written || std::rename(temp.c_str(), path.c_str()) != 0) {
    std::remove(temp.c_str());
    throw InputError("cannot write " + path + ": " + std::strerror(errno));
  }
}

Image readPng(const std::string& path) {
  File file(std::fopen(path.c_str(), "rb"));
  if (!file) throw InputError("cannot open " + path + ": " + std::strerror(errno));
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (png == nullptr || info == nullptr) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw InputError("libpng could not start reading " + path);
  }
  Image image;
  std::vector<unsigned char> pixels;
  std::vector<png_bytep> rows;
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw InputError(path + " is not a valid PNG file");
  }
  png_init_io(png, file.get());
  png_read_info(png, info);
  png_set_expand(png);  // palette -> RGB, low-bit gray -> 8 bit, tRNS -> alpha
  png_set_swap(png);    // 16-bit samples in host (little-endian) order
  png_read_update_info(png, info);
  const int width = int(png_get_image_width(png, info));
  const int height = int(png_get_image_height(png, info));
  const int channels = png_get_channels(png, info);
  const int bitDepth = png_get_bit_depth(png, info);
  const size_t rowBytes = png_get_rowbytes(png, info);
  pixels.resize(rowBytes * height);
  rows.resize(height);
  for (int y = 0; y < height; ++y) rows[y] = pixels.data() + rowBytes * y;
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  image = Image(width, height, channels);
  for (int y = 0; y < height; ++y) {
    const int dstRow = height - 1 - y;
    for (int i = 0; i < width * channels; ++i) {
      float v;
      if (bitDepth == 16) {
        uint16_t s;
        std::memcpy(&s, rows[y] + 2 * i, 2);
        v = s / 65535.0f;
      } else {
        v = rows[y][i] / 255.0f;
      }
      image.data[size_t(dstRow) * width * channels + i] = v;
    }
  }
  return image;
}

std::map<std::string, std::string> readPngText(const std::string& path) {
  File file(std::fopen(path.c_str(), "rb"));
  if (!file) throw InputError("cannot open " + path + ": " + std::strerror(errno));
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (png == nullptr || info == nullptr) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw InputError("libpng could not start reading " + path);
  }
  std::map<std::string, std::string> texts;
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw InputError(path + " is not a valid PNG file");
  }
  png_init_io(png, file.get());
  // The whole file: text chunks may follow the image data (png_read_png reads them into info).
  png_read_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  png_textp text = nullptr;
  const int count = png_get_text(png, info, &text, nullptr);
  for (int i = 0; i < count; ++i)
    texts[text[i].key] = std::string(text[i].text, text[i].text ? std::strlen(text[i].text) : 0);
  png_destroy_read_struct(&png, &info, nullptr);
  return texts;
}

Image crop(const Image& image, int x, int y, int w, int h) {
  x = std::clamp(x, 0, image.width);
  y = std::clamp(y, 0, image.height);
  w = std::clamp(w, 0, image.width - x);
  h = std::clamp(h, 0, image.height - y);
  Image out(w, h, image.channels);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      for (int c = 0; c < image.channels; ++c) out.at(i, j, c) = image.at(x + i, y + j, c);
  return out;
}

Image magnifyNearest(const Image& image, int factor) {
  factor = std::max(factor, 1);
  Image out(image.width * factor, image.height * factor, image.channels);
  for (int j = 0; j < out.height; ++j)
    for (int i = 0; i < out.width; ++i)
      for (int c = 0; c < image.channels; ++c)
        out.at(i, j, c) = image.at(i / factor, j / factor, c);
  return out;
}

Image toRgb(const Image& image) {
  if (image.channels == 3) return image;
  Image out(image.width, image.height, 3);
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i)
      for (int c = 0; c < 3; ++c)
        out.at(i, j, c) = image.channels < 3 ? image.at(i, j, 0) : image.at(i, j, c);
  return out;
}

void drawFrame(Image& rgb, int x, int y, int w, int h, int thickness) {
  auto put = [&](int i, int j) {
    if (i < 0 || j < 0 || i >= rgb.width || j >= rgb.height || rgb.channels < 3) return;
    rgb.at(i, j, 0) = 1.0f;
    rgb.at(i, j, 1) = 0.0f;
    rgb.at(i, j, 2) = 0.0f;
  };
  for (int t = 0; t < thickness; ++t) {
    for (int i = x - t; i < x + w + t; ++i) {
      put(i, y - 1 - t);
      put(i, y + h + t);
    }
    for (int j = y - 1 - t; j <= y + h + t; ++j) {
      put(x - 1 - t, j);
      put(x + w + t, j);
    }
  }
}

Image differenceHeatMap(const Image& a, const Image& b, float fullScale) {
  if (a.width != b.width || a.height != b.height)
    throw InputError("cannot difference images of different sizes");
  Image out(a.width, a.height, 3);
  for (int j = 0; j < a.height; ++j)
    for (int i = 0; i < a.width; ++i) {
      const float d = std::min(std::fabs(a.at(i, j) - b.at(i, j)) / fullScale, 1.0f);
      if (!(d > 0.0f)) continue;
      // Piecewise ramp: (0,0,0.5) at tiny differences, red at 1/3, yellow at 2/3, white at 1.
      const float t = 0.15f + 0.85f * d;
      out.at(i, j, 0) = std::clamp(3.0f * t - 0.5f, 0.0f, 1.0f);
      out.at(i, j, 1) = std::clamp(3.0f * t - 1.5f, 0.0f, 1.0f);
      out.at(i, j, 2) = std::clamp(t < 0.33f ? 0.6f : 3.0f * t - 2.0f, 0.0f, 1.0f);
    }
  return out;
}

Image channel(const Image& image, int c) {
  Image out(image.width, image.height, 1);
  for (size_t p = 0; p < size_t(image.width) * image.height; ++p)
    out.data[p] = image.data[p * image.channels + c];
  return out;
}

Image sideBySide(const std::vector<Image>& images, int gap) {
  int w = 0, h = 0;
  for (const Image& im : images) {
    w += im.width + (w > 0 ? gap : 0);
    h = std::max(h, im.height);
  }
  Image out(std::max(w, 1), std::max(h, 1), 3, 1.0f);
  int x0 = 0;
  for (const Image& im : images) {
    const Image rgb = toRgb(im);
    for (int j = 0; j < rgb.height; ++j)
      for (int i = 0; i < rgb.width; ++i)
        for (int c = 0; c < 3; ++c) out.at(x0 + i, h - rgb.height + j, c) = rgb.at(i, j, c);
    x0 += im.width + gap;
  }
  return out;
}

bool allFinite(const Image& image) {
  return std::all_of(image.data.begin(), image.data.end(),
                     [](float v) { return std::isfinite(v); });
}

}  // namespace sl

namespace sl {

// core/base/png_text.h: the pixels and their format as they are, the text chunks replaced.
void addPngProvenance(const std::string& path, const Provenance& provenance) {
  File in(std::fopen(path.c_str(), "rb"));
  if (!in) throw InputError("cannot open " + path + ": " + std::strerror(errno));
  png_structp read = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop readInfo = read ? png_create_info_struct(read) : nullptr;
  if (read == nullptr || readInfo == nullptr) {
    png_destroy_read_struct(&read, &readInfo, nullptr);
    throw InputError("libpng could not start reading " + path);
  }
  if (setjmp(png_jmpbuf(read))) {
    png_destroy_read_struct(&read, &readInfo, nullptr);
    throw InputError("cannot read " + path + ": not a PNG libpng can decode");
  }
  png_init_io(read, in.get());
  png_read_png(read, readInfo, PNG_TRANSFORM_IDENTITY, nullptr);
  in.reset();
  png_uint_32 width = 0, height = 0;
  int bitDepth = 0, colorType = 0, interlace = 0, compression = 0, filter = 0;
  png_get_IHDR(read, readInfo, &width, &height, &bitDepth, &colorType, &interlace, &compression,
               &filter);
  png_bytepp rows = png_get_rows(read, readInfo);
  // Copies what the output needs from the decoded file: the palette and transparency when
  // there are any, and the text chunks whose keywords the provenance does not replace.
  png_colorp palette = nullptr;
  int paletteSize = 0;
  const bool hasPalette = png_get_PLTE(read, readInfo, &palette, &paletteSize) != 0;
  png_bytep trans = nullptr;
  int transCount = 0;
  png_color_16p transColor = nullptr;
  const bool hasTrans = png_get_tRNS(read, readInfo, &trans, &transCount, &transColor) != 0;
  const std::string temp = path + ".part-" + std::to_string(::getpid());
  File out(std::fopen(temp.c_str(), "wb"));
  if (!out) {
    png_destroy_read_struct(&read, &readInfo, nullptr);
    throw InputError("cannot write " + path + ": " + std::strerror(errno));
  }
  png_structp write = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop writeInfo = write ? png_create_info_struct(write) : nullptr;
  if (write == nullptr || writeInfo == nullptr || setjmp(png_jmpbuf(write))) {
    png_destroy_write_struct(&write, &writeInfo);
    png_destroy_read_struct(&read, &readInfo, nullptr);
    out.reset();
    std::remove(temp.c_str());
    throw InputError("libpng failed while writing " + path);
  }
  png_init_io(write, out.get());
  png_set_compression_level(write, kFilePngCompression);
  png_set_IHDR(write, writeInfo, width, height, bitDepth, colorType, interlace, compression,
               filter);
  if (hasPalette) png_set_PLTE(write, writeInfo, palette, paletteSize);
  if (hasTrans) png_set_tRNS(write, writeInfo, trans, transCount, transColor);
  setProvenanceText(write, writeInfo, provenance);
  png_set_rows(write, writeInfo, rows);
  png_write_png(write, writeInfo, PNG_TRANSFORM_IDENTITY, nullptr);
  png_destroy_write_struct(&write, &writeInfo);
  png_destroy_read_struct(&read, &readInfo, nullptr);
  const bool flushed = std::fflush(out.get()) == 0;
  out.reset();
  if (!flushed || std::rename(temp.c_str(), path.c_str()) != 0) {
    std::remove(temp.c_str());
    throw InputError("cannot write " + path + ": " + std::strerror(errno));
  }
}

}  // namespace sl
