// `render` has every scene-level knob a figure turns (--camera-distance for
// csm-fig1/csm-fig10, --light-radius for chan-4-9, --light-position), so that a figure's panel
// can be reproduced from the command line; bad values exit 2 with one line.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "command_util.h"
#include "core/base/image.h"

namespace sl {
namespace {
namespace fs = std::filesystem;
using test::CommandResult;

fs::path dir() { return test::testDir("scene_knobs"); }

CommandResult shadowlab(const std::string& args) {
  return test::runBinary(SHADOWLAB_BINARY, args, dir());
}

// Renders and returns {colour, mask}; fails the test on a non-zero exit.
std::pair<Image, Image> render(const std::string& name, const std::string& args) {
  const fs::path png = dir() / (name + ".png"), mask = dir() / (name + "-mask.png");
  const CommandResult r =
      shadowlab("render " + args + " --out " + png.string() + " --mask " + mask.string());
  EXPECT_EQ(r.status, 0) << r.err;
  if (r.status != 0) return {};
  return {readPng(png.string()), readPng(mask.string())};
}

long long nonBlack(const Image& image) {
  long long n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      n += image.at(x, y, 0) + image.at(x, y, 1) + image.at(x, y, 2) > 0.0f ? 1 : 0;
  return n;
}

long long fractional(const Image& mask) {
  long long n = 0;
  for (float v : mask.data) n += v > 0.0f && v < 1.0f ? 1 : 0;
  return n;
}

constexpr const char* kSmall = " --size 128x96";

TEST(SceneKnobs, CameraDistanceMovesTheCameraAway) {
  const auto near = render("near", "--scene brabec --technique modern.hw" + std::string(kSmall));
  const auto same = render(
      "same", "--scene brabec --technique modern.hw --camera-distance 1" + std::string(kSmall));
  const auto far = render(
      "far", "--scene brabec --technique modern.hw --camera-distance 3" + std::string(kSmall));
  ASSERT_FALSE(near.first.empty() || same.first.empty() || far.first.empty());
  EXPECT_EQ(near.first.data, same.first.data) << "factor 1 is the scene's own camera";
  // Farther away the scene covers fewer pixels (the background is black).
  EXPECT_LT(nonBlack(far.first), nonBlack(near.first));
}

TEST(SceneKnobs, LightRadiusWidensTheSoftReferencesPenumbra) {
  const std::string soft = "--scene cylinder --technique reference.soft" + std::string(kSmall);
  const auto small = render("r-small", soft + " --light-radius 0.02");
  const auto large = render("r-large", soft + " --light-radius 0.3");
  ASSERT_FALSE(small.second.empty() || large.second.empty());
  EXPECT_GT(fractional(large.second), 2 * fractional(small.second))
      << "a larger light, more penumbra pixels";
}

TEST(SceneKnobs, LightPositionMovesTheShadowAndIsRecorded) {
  const std::string hw = "--scene analytic --technique modern.hw" + std::string(kSmall);
  const auto base = render("light-base", hw);
  const fs::path png = dir() / "light-moved.png", mask = dir() / "light-moved-mask.png";
  const CommandResult moved = shadowlab("render " + hw + " --light-position 1.5,4,0.5 --out " +
                                        png.string() + " --mask " + mask.string());
  ASSERT_EQ(moved.status, 0) << moved.err;
  EXPECT_NE(moved.out.find("\"light_position\":[1.5,4.0,0.5]"), std::string::npos) << moved.out;
  EXPECT_NE(readPng(mask.string()).data, base.second.data) << "the shadow moved";
}

// csm-fig1's PCF panel, made by `figures`, is made again by `render` with its camera distance:
// its close-up (bottom-left origin, figures/figure_spec.h Closeup) equals the same rectangle
// cropped from render's image.
TEST(SceneKnobs, RenderReproducesAFigurePanel) {
  const fs::path figures = dir() / "figures";
  fs::remove_all(figures);
  const CommandResult made =
      shadowlab("figures --no-progress --only csm-fig1 --out " + figures.string());
  ASSERT_EQ(made.status, 0) << made.err;
  const auto alone = render("csm-fig1-pcf",
                            "--scene trees --technique modern.hw --size 512x384 --shadow-map 512 "
                            "--camera-distance 2.5");
  ASSERT_FALSE(alone.first.empty());
  // csm-fig1's close-up {0.4, 0.35, 0.2, 0.2} magnified 3x, as figures.cpp closeupOf cuts it.
  const Image& image = alone.first;
  const int x = int(0.4f * float(image.width)), y = int(0.35f * float(image.height));
  const int w = int(0.2f * float(image.width)), h = int(0.2f * float(image.height));
  constexpr int kMagnify = 3;
  const Image expected = magnifyNearest(toRgb(crop(image, x, y, w, h)), kMagnify);
  const Image closeup = readPng((figures / "csm-fig1" / "00-pcf-closeup0.png").string());
  ASSERT_EQ(closeup.width, expected.width);
  ASSERT_EQ(closeup.height, expected.height);
  EXPECT_EQ(closeup.data, expected.data) << "the same frame, the same rectangle";
}

TEST(SceneKnobs, BadValuesExitTwoWithOneLine) {
  const fs::path out = dir() / "bad.png";
  for (const std::string bad :
       {"--camera-distance 0", "--camera-distance -2", "--camera-distance x", "--light-radius -0.1",
        "--light-radius 1e13" /* beyond the scene coordinates' range */, "--light-position 1,2",
        "--light-position 1,2,3,4",
        "--light-position 0,0,0" /* the analytic light's target: no direction left */}) {
    const CommandResult r = shadowlab("render --scene analytic --technique modern.hw " + bad +
                                      " --out " + out.string());
    EXPECT_EQ(r.status, 2) << bad << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << bad << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << bad;
  }
}

}  // namespace
}  // namespace sl
