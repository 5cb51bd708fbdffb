// PNG round trips and the close-up helpers (core/base/image.h).
#include "core/base/image.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/base/errors.h"

namespace sl {
namespace {
namespace fs = std::filesystem;

fs::path tempDir() {
  fs::path d = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "core-image";
  fs::create_directories(d);
  return d;
}

Image ramp(int w, int h, int c) {
  Image im(w, h, c);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < c; ++k) im.at(x, y, k) = float((x * 7 + y * 13 + k * 5) % 256) / 255.0f;
  return im;
}

TEST(Png, EightBitRoundTripIsExactForEveryChannelCount) {
  for (int c = 1; c <= 4; ++c) {
    const Image a = ramp(37, 23, c);  // odd sizes: no row padding assumptions
    const std::string path = (tempDir() / ("rt8-" + std::to_string(c) + ".png")).string();
    writePng(path, a, 8);
    const Image b = readPng(path);
    ASSERT_EQ(b.width, a.width);
    ASSERT_EQ(b.height, a.height);
    ASSERT_EQ(b.channels, c);
    for (size_t i = 0; i < a.data.size(); ++i) ASSERT_FLOAT_EQ(a.data[i], b.data[i]) << i;
  }
}

TEST(Png, SixteenBitKeepsSixteenBits) {
  Image a(5, 3, 1);
  for (size_t i = 0; i < a.data.size(); ++i) a.data[i] = float(i * 4099 % 65536) / 65535.0f;
  const std::string path = (tempDir() / "rt16.png").string();
  writePng(path, a, 16);
  const Image b = readPng(path);
  for (size_t i = 0; i < a.data.size(); ++i)
    EXPECT_NEAR(a.data[i], b.data[i], 0.5f / 65535.0f) << i;  // rounding to the 16-bit grid
}

TEST(Png, RowsAreStoredBottomUp) {
  Image a(1, 2, 1);
  a.at(0, 0) = 0.0f;  // bottom row (GL convention)
  a.at(0, 1) = 1.0f;  // top row
  const std::string path = (tempDir() / "orientation.png").string();
  writePng(path, a, 8);
  const Image b = readPng(path);
  EXPECT_EQ(b.at(0, 0), 0.0f);
  EXPECT_EQ(b.at(0, 1), 1.0f);
}

TEST(Png, NanAndOutOfRangeValuesAreClampedNotWritten) {
  Image a(3, 1, 1);
  a.data = {std::nanf(""), -2.0f, 7.0f};
  const std::string path = (tempDir() / "clamp.png").string();
  writePng(path, a, 8);
  const Image b = readPng(path);
  EXPECT_EQ(b.data[0], 0.0f);
  EXPECT_EQ(b.data[1], 0.0f);
  EXPECT_EQ(b.data[2], 1.0f);
}

TEST(Png, UnwritablePathIsAnInputErrorAndLeavesNoFile) {
  const std::string path = "/nonexistent-dir/x.png";
  EXPECT_THROW(writePng(path, Image(2, 2, 1), 8), InputError);
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path + ".part-" + std::to_string(::getpid())));
}

TEST(Png, CorruptFileIsAnInputError) {
  const std::string path = (tempDir() / "corrupt.png").string();
  writePng(path, ramp(16, 16, 3), 8);
  fs::resize_file(path, 60);  // header survives, data truncated
  EXPECT_THROW(readPng(path), InputError);
  std::ofstream(tempDir() / "text.png") << "not a png";
  EXPECT_THROW(readPng((tempDir() / "text.png").string()), InputError);
  EXPECT_THROW(readPng((tempDir() / "missing.png").string()), InputError);
}

TEST(Closeup, CropMagnifyAndFrame) {
  const Image a = ramp(10, 8, 1);
  const Image c = crop(a, 2, 3, 4, 2);
  ASSERT_EQ(c.width, 4);
  ASSERT_EQ(c.height, 2);
  EXPECT_EQ(c.at(0, 0), a.at(2, 3));
  EXPECT_EQ(c.at(3, 1), a.at(5, 4));
  const Image m = magnifyNearest(c, 3);
  ASSERT_EQ(m.width, 12);
  EXPECT_EQ(m.at(11, 5), c.at(3, 1));
  Image rgb = toRgb(a);
  drawFrame(rgb, 2, 2, 4, 4);
  EXPECT_EQ(rgb.at(1, 1, 0), 1.0f);  // the corner just outside the rectangle is red
  EXPECT_EQ(rgb.at(1, 1, 1), 0.0f);
  EXPECT_EQ(rgb.at(3, 3, 0), a.at(3, 3));  // inside untouched
}

TEST(Closeup, HeatMapIsBlackWhereEqual) {
  const Image a = ramp(4, 4, 1);
  Image b = a;
  b.at(1, 1) += 0.5f;
  const Image h = differenceHeatMap(a, b);
  EXPECT_EQ(h.at(0, 0, 0) + h.at(0, 0, 1) + h.at(0, 0, 2), 0.0f);
  EXPECT_GT(h.at(1, 1, 0) + h.at(1, 1, 1) + h.at(1, 1, 2), 0.5f);
  EXPECT_THROW(differenceHeatMap(a, Image(3, 3, 1)), InputError);
}

}  // namespace
}  // namespace sl
