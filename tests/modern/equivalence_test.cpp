// Legacy/modern equivalence: every legacy_gl technique and its modern/ twin
// render the same scene with the same parameters; their visibility masks are compared pixel by
// pixel against the bound the pair states in registry/twins.cpp (bit-exact for 'faithful'
// arithmetic; otherwise <= 1/255 on 99.9% of pixels and every larger difference on the
// shadow-boundary band that core/base/metrics.h boundaryBand computes from the legacy mask), and
// their images against the image bound of registry/twins.h (judgeImages: beyond three 8-bit
// steps only on the spotlight cone's edge band or where the masks differ).
//
// Parameterised on pair x scene x back end (osmesa always; egl skips with the reason when no
// EGL context can be made). On failure both masks and the difference heat map are written to
// SHADOWLAB_TEST_OUTPUT_DIR/twins/.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <tuple>

#include "core/base/errors.h"
#include "core/gl/context.h"
#include "core/scene/scene_library.h"
#include "registry/registry.h"
#include "registry/twins.h"
#include "tests/test_names.h"

namespace sl {
namespace {
namespace fs = std::filesystem;

// Small windows keep the suite fast (common.md); the map fits in the window so the legacy
// light passes render into the window as in 2001.
constexpr int kWidth = 320;
constexpr int kHeight = 240;
constexpr int kShadowMapTexels = 256;

using Case = std::tuple<twins::TwinPair, std::string, Backend>;

std::string identifier(const std::string& text) { return testName(text); }

// Whether an EGL context can be made here; the reason when not.
std::string eglUnavailableReason() {
  static const std::string kReason = [] {
    try {
      ContextSpec spec;
      spec.backend = Backend::kEgl;
      spec.profile = Profile::kCore;
      spec.width = 16;
      spec.height = 16;
      GlContext::create(spec);
      return std::string();
    } catch (const GlError& e) {
      return std::string(e.what());
    }
  }();
  return kReason;
}

void writeFailureArtefacts(const std::string& name, const Frame& legacy, const Frame& modern) {
  const fs::path dir = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "twins";
  fs::create_directories(dir);
  writePng((dir / (name + "-legacy-mask.png")).string(), legacy.visibility, 16);
  writePng((dir / (name + "-modern-mask.png")).string(), modern.visibility, 16);
  // Full scale 1/16: one 8-bit step is visible, a flipped pixel saturates.
  writePng((dir / (name + "-difference.png")).string(),
           differenceHeatMap(legacy.visibility, modern.visibility, 1.0f / 16.0f), 8);
  writePng((dir / (name + "-legacy-image.png")).string(), legacy.color, 8);
  writePng((dir / (name + "-modern-image.png")).string(), modern.color, 8);
}

class Equivalence : public ::testing::TestWithParam<Case> {};

TEST_P(Equivalence, VisibilityMasksAgreeWithinTheStatedBound) {
  const auto& [pair, sceneName, backend] = GetParam();
  if (backend == Backend::kEgl && !eglUnavailableReason().empty())
    GTEST_SKIP() << "EGL back end unavailable on this machine: " << eglUnavailableReason();
  const RenderParams legacyParams =
      twins::paramsFor(pair, true, kWidth, kHeight, kShadowMapTexels, backend);
  if (const std::string why = twins::unavailablePrecision(pair, legacyParams); !why.empty())
    GTEST_SKIP() << why;
  const Scene scene = loadScene(sceneName);
  const Frame legacy = renderTechnique(findTechnique(pair.legacy), scene, legacyParams);
  const Frame modern =
      renderTechnique(findTechnique(pair.modern), scene,
                      twins::paramsFor(pair, false, kWidth, kHeight, kShadowMapTexels, backend));
  ASSERT_EQ(legacy.visibility.width, kWidth);
  ASSERT_EQ(modern.visibility.width, kWidth);

  // Not vacuous: the scene shows both lit and umbra pixels.
  const auto [lo, hi] =
      std::minmax_element(legacy.visibility.data.begin(), legacy.visibility.data.end());
  EXPECT_LT(*lo, 0.5f) << "no shadow in the legacy mask";
  EXPECT_GT(*hi, 0.5f) << "nothing lit in the legacy mask";

  const twins::Agreement a = twins::judge(pair, legacy.visibility, modern.visibility);
  if (!a.withinBound)
    writeFailureArtefacts(identifier(pair.label + "_" + sceneName + "_" + backendName(backend)),
                          legacy, modern);
  EXPECT_TRUE(a.withinBound) << pair.legacy << " vs " << pair.modern << " on " << sceneName << ": "
                             << a.verdict << "\nwhy this bound: " << pair.why;

  // The images agree too: the bound registry/twins.h states for judgeImages.
  const twins::ImageAgreement im =
      twins::judgeImages(legacy.color, modern.color, legacy.visibility, modern.visibility);
  if (!im.withinBound)
    writeFailureArtefacts(identifier(pair.label + "_" + sceneName + "_" + backendName(backend)),
                          legacy, modern);
  EXPECT_TRUE(im.withinBound) << pair.legacy << " vs " << pair.modern << " on " << sceneName << ": "
                              << im.verdict;
}

}  // namespace

// Readable test parameters in gtest's messages.
void PrintTo(Backend backend, std::ostream* os) { *os << backendName(backend); }
namespace twins {
void PrintTo(const TwinPair& pair, std::ostream* os) { *os << pair.label; }
}  // namespace twins

namespace {

std::string caseName(const ::testing::TestParamInfo<Case>& info) {
  const auto& [pair, scene, backend] = info.param;
  return identifier(pair.label + "_" + scene + "_" + backendName(backend));
}

INSTANTIATE_TEST_SUITE_P(Twins, Equivalence,
                         ::testing::Combine(::testing::ValuesIn(twins::twinPairs()),
                                            ::testing::ValuesIn(twins::equivalenceScenes()),
                                            ::testing::Values(Backend::kOsmesa, Backend::kEgl)),
                         caseName);

// Every planned pair is tested: twinPairs() leaves out a pair whose legacy or modern side is not
// registered, so a missing or renamed technique would silently shrink the Twins suite above.
// Every technique is built unconditionally (no build option removes one), so a missing pair is
// a defect, named here, never a skip.
TEST(Equivalence, EveryPlannedPairIsPresent) {
  const auto missing = twins::missingPairs();
  std::string list;
  for (const auto& m : missing) list += "\n  " + m;
  EXPECT_TRUE(missing.empty()) << "planned pairs not testable in this build:" << list;
}

}  // namespace
}  // namespace sl
