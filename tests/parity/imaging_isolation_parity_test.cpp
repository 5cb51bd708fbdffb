// Imaging isolated from the rasteriser: every legacy technique renders twice
// on the SAME reference Mesa 7.8.2 context kind, once with its native ARB_imaging and once with
// imaging/'s software emulation installed into the context's dispatch table over it
// (--imaging emulated). The rasteriser, texturing, depth test and accumulation buffer are the
// reference's in both runs, so any difference is the imaging subset's alone. Expected: the
// visibility masks and the shaded images bit for bit the same, or each differing pixel
// explained by one of the reference's measured departures from the specification
// (../shared/reference-gl/README.md, departures_test.cpp).
//
// Measured (2026-12-02, 400x300, 256^2 map, brabec and analytic): 0 of 120000 pixels differ,
// mask and image, in every one of the 18 render pairs below (docs/validation.md, "Parity with
// a real imaging implementation"). The passes use RGBA colour tables with entries in [0, 1],
// the colour matrix, an RGBA convolution filter on a copy, and read back with every stage off:
// none meets a listed departure, so none is needed to explain a difference and the test asserts
// exact equality.
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <string>

#include "../legacy_gl/legacy_test_support.h"
#include "core/base/errors.h"
#include "core/base/image.h"
#include "core/base/metrics.h"
#include "core/scene/scene_library.h"
#include "parity/parity_util.h"
#include "registry/registry.h"

namespace sl {
namespace {

// The window and map of legacy_parity_test.cpp: small, and the 256 map fits the window (the
// literal window-copy path of the paper).
constexpr int kWidth = 400;
constexpr int kHeight = 300;
constexpr int kMapTexels = 256;

struct Case {
  std::string technique;
  int filter;  // 1 for the techniques that do not filter
};

long differingPixels(const Image& a, const Image& b) {
  long n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int c = 0; c < a.channels; ++c)
        if (a.at(x, y, c) != b.at(x, y, c)) {
          ++n;
          break;
        }
  return n;
}

void writeArtefacts(const std::string& name, const Frame& native, const Frame& emulated) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "imaging_isolation";
  fs::create_directories(dir);
  writePng((dir / (name + "-native-mask.png")).string(), native.visibility, 16);
  writePng((dir / (name + "-emulated-mask.png")).string(), emulated.visibility, 16);
  writePng((dir / (name + "-mask-diff.png")).string(),
           differenceHeatMap(native.visibility, emulated.visibility), 8);
  writePng((dir / (name + "-native.png")).string(), native.color, 8);
  writePng((dir / (name + "-emulated.png")).string(), emulated.color, 8);
}

void expectSameOnOneRasteriser(const Case& c, const std::string& sceneName) {
  const Scene scene = builtinScene(sceneName);
  RenderParams p;
  p.width = kWidth;
  p.height = kHeight;
  p.shadowMapTexels = kMapTexels;
  p.filter = c.filter;
  p.backend = Backend::kReference;
  p.imaging = ImagingChoice::kNative;
  const Frame native = renderTechnique(findTechnique(c.technique), scene, p);
  p.imaging = ImagingChoice::kEmulated;
  const Frame emulated = renderTechnique(findTechnique(c.technique), scene, p);
  const std::string name = c.technique + "-" + std::to_string(c.filter) + "-" + sceneName;

  ASSERT_EQ(native.visibility.data.size(), emulated.visibility.data.size());
  ASSERT_EQ(native.color.data.size(), emulated.color.data.size());
  const long maskPixels = differingPixels(native.visibility, emulated.visibility);
  const long colorPixels = differingPixels(native.color, emulated.color);
  const MaskDifference d = compareMasks(native.visibility, emulated.visibility, 0.0);
  std::cout << name << ": native vs emulated imaging on Mesa 7.8.2: " << maskPixels
            << " mask pixels and " << colorPixels << " image pixels of " << kWidth * kHeight
            << " differ (largest mask difference " << d.maxAbs << ")\n";
  ::testing::Test::RecordProperty(name + "-mask-differing", std::to_string(maskPixels));
  ::testing::Test::RecordProperty(name + "-image-differing", std::to_string(colorPixels));
  if (maskPixels != 0 || colorPixels != 0) writeArtefacts(name, native, emulated);
  // No departure of the reference is exercised by these passes (the tables are RGBA, the
  // filters RGBA, every read-back is 8-bit or unconvolved), so nothing may differ.
  EXPECT_EQ(maskPixels, 0) << name << ": masks differ between native and emulated imaging";
  EXPECT_EQ(colorPixels, 0) << name << ": images differ between native and emulated imaging";
}

class ImagingIsolation : public ::testing::TestWithParam<Case> {};

TEST_P(ImagingIsolation, NativeAndEmulatedImagingAgreeOnOneRasteriser) {
  if (!testing::referenceAvailable())
    GTEST_SKIP() << "reference GL (../shared/reference-gl/libOSMesa.so.7.8.2) not found: set "
                    "SHADOWLAB_REFERENCE_GL";
  for (const char* scene : {"brabec", "analytic"}) expectSameOnOneRasteriser(GetParam(), scene);
}

INSTANTIATE_TEST_SUITE_P(
    EveryLegacyTechnique, ImagingIsolation,
    ::testing::Values(Case{"legacy.ramp", 1}, Case{"legacy.pcf", 2}, Case{"legacy.pcf", 3},
                      Case{"legacy.pcf", 4}, Case{"legacy.fast-pcf", 2}, Case{"legacy.fast-pcf", 4},
                      Case{"legacy.hw", 1}, Case{"legacy.woo", 1}, Case{"legacy.second-depth", 1}),
    [](const ::testing::TestParamInfo<Case>& info) {
      std::string n = info.param.technique.substr(info.param.technique.find('.') + 1) +
                      std::to_string(info.param.filter);
      for (char& ch : n)
        if (ch == '-') ch = '_';
      return n;
    });

// --imaging native exists only where the back end has native imaging.
TEST(ImagingIsolation, NativeImagingOnOsmesaIsAnInputError) {
  RenderParams p;
  p.width = 64;
  p.height = 48;
  p.shadowMapTexels = 64;
  p.filter = 2;
  p.imaging = ImagingChoice::kNative;
  EXPECT_THROW(checkRenderable(findTechnique("legacy.pcf"), p), InputError);
}

// The comparison above means something only if --imaging emulated really replaces the
// reference's imaging entries: a LUMINANCE colour table tells the two apart (the reference
// indexes G with R, departure 2; the emulation follows table 3.13).
TEST(ImagingIsolation, EmulationReplacesTheReferencesNativeImaging) {
  if (!testing::referenceAvailable())
    GTEST_SKIP() << "reference GL (../shared/reference-gl/libOSMesa.so.7.8.2) not found";
  using namespace imaging::testing;
  constexpr int kSide = 4;  // pixels; one pixel is read
  const std::vector<uint8_t> pixel = {200, 60, 120, 255};
  auto greenAfterLuminanceTable = [&](imaging::Mode mode) {
    ContextSpec spec;
    spec.backend = Backend::kReference;
    spec.width = spec.height = kSide;
    auto ctx = GlContext::create(spec);
    EXPECT_EQ(imaging::install(*ctx, mode), mode);
    EXPECT_EQ(imaging::currentMode(), mode);
    putImage(1, 1, pixel);
    std::vector<float> ramp(256);
    for (int i = 0; i < 256; ++i) ramp[i] = float(255 - i) / 255.0f;  // L_t[i] = 1 - i/255
    glColorTable(GL_COLOR_TABLE, GL_LUMINANCE, 256, GL_LUMINANCE, GL_FLOAT, ramp.data());
    glEnable(GL_COLOR_TABLE);
    return readRgbaF(0, 0, 1, 1)[1];
  };
  // Both are exact table entries read back as floats: kFloatTolerance (parity_util.h).
  EXPECT_NEAR(greenAfterLuminanceTable(imaging::Mode::kNative), 55.0f / 255.0f, kFloatTolerance);
  EXPECT_NEAR(greenAfterLuminanceTable(imaging::Mode::kEmulated), 195.0f / 255.0f, kFloatTolerance);
}

}  // namespace
}  // namespace sl
