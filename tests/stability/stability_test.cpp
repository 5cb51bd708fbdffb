// Stability suite: stiff and extreme cases, each run over allTechniques() so
// that every technique a colleague adds is covered without touching this file.
//
// Every (case, technique) test asserts:
//   1. the render succeeds, or refuses with sl::InputError (one clear line) where the case is
//      declared to be refused (measure/stability.cpp expectedRefusals, with the expected
//      message); any other refusal, a declared refusal that renders, a GlError or any other
//      exception fails the test;
//   2. no NaN or Inf in any buffer (colour, visibility, every captured intermediate);
//   3. visibility within [0, 1];
//   4. the case's error bound against the ray-traced reference (reference.soft for techniques
//      that approximate area lights, reference.hard otherwise): the share of pixels that differ
//      by more than 0.5 outside the reference's shadow-boundary band. Each case states its
//      bound and why it is right. A documented limitation that predicts its failure (knownIssues,
//      selfShadowedAtLeast) asserts the prediction instead: the lit pixels shadow themselves at
//      least that much, and the pixels lit where the reference is in shadow stay within bound.
// Small windows (160x120) keep the whole suite within about 3 minutes on two cores.
#include "measure/stability.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <iostream>
#include <map>
#include <mutex>
#include <tuple>

#include "core/base/errors.h"
#include "core/base/metrics.h"
#include "core/scene/primitives.h"
#include "core/scene/scene_library.h"
#include "reference/reference.h"
#include "registry/registry.h"
#include "tests/test_names.h"

namespace sl {
namespace {

using namespace figures::stability;  // the cases, bounds and measurement (measure/stability.h)

std::filesystem::path outputDir() {
  const std::filesystem::path dir = std::filesystem::path(SHADOWLAB_TEST_OUTPUT_DIR) / "stability";
  std::filesystem::create_directories(dir);
  return dir;
}

void expectFiniteBuffers(const Frame& f) {
  EXPECT_TRUE(allFinite(f.visibility)) << "visibility has NaN/Inf";
  EXPECT_TRUE(f.color.empty() || allFinite(f.color)) << "colour has NaN/Inf";
  for (const PassImage& p : f.intermediates)
    EXPECT_TRUE(allFinite(p.image)) << p.name << " has NaN/Inf";
}

using Param = std::tuple<std::string, std::string>;  // case, technique

class Stability : public ::testing::TestWithParam<Param> {};

TEST_P(Stability, FiniteBoundedAndWithinErrorBound) {
  const Case& c = findCase(std::get<0>(GetParam()));
  const Technique& t = findTechnique(std::get<1>(GetParam()));
  const Outcome o = evaluate(c, t);  // a GlError or any other exception fails the test
  switch (o.kind) {
    case Outcome::Kind::kNotApplicable: GTEST_SKIP() << o.note;
    case Outcome::Kind::kRefused:
      std::cout << "[stability] " << c.name << " " << t.name << ": InputError: " << o.note << "\n";
      EXPECT_FALSE(o.expectedRefusal.empty())
          << "refused, but not declared in measure/stability.cpp expectedRefusals(): " << o.note;
      EXPECT_TRUE(o.expectedRefusal.empty() || o.refusedAsExpected())
          << "refused with \"" << o.note << "\", expected a message containing \""
          << o.expectedRefusal << "\"";
      return;
    case Outcome::Kind::kMeasured: break;
  }
  EXPECT_TRUE(o.expectedRefusal.empty())
      << "declared to refuse (\"" << o.expectedRefusal << "\", measure/stability.cpp "
      << "expectedRefusals) but rendered";
  ASSERT_EQ(o.frame.visibility.width, kWidth);
  ASSERT_EQ(o.frame.visibility.height, kHeight);
  expectFiniteBuffers(o.frame);
  EXPECT_GE(o.lowest, 0.0f);
  EXPECT_LE(o.highest, 1.0f);
  std::cout << "[stability] " << c.name << " " << t.name << ": wrong where it matters "
            << 100.0 * o.error.shareAboveHalf << "% (bound " << 100.0 * o.bound << "%), rmse "
            << o.error.rmse << "; lit where the reference is shadowed "
            << 100.0 * o.wronglyLit.shareAboveHalf << "%, shadowed where it is lit "
            << 100.0 * o.wronglyShadowed.shareAboveHalf << "% = " << 100.0 * o.selfShadowed()
            << "% of its lit " << 100.0 * o.referenceLit << "%\n";
  if (o.predictsSelfShadowing()) {
    // The documented limitation, asserted as it predicts (knownIssues): the lit receiver
    // shadows itself, and nothing the reference shadows is lit.
    EXPECT_GE(o.selfShadowed(), o.selfShadowedAtLeast)
        << "the documented limitation no longer shows (fixed? then remove its knownIssues "
           "entry): "
        << o.why;
    EXPECT_LE(o.wronglyLit.shareAboveHalf, o.bound) << o.why;
  } else {
    EXPECT_LE(o.error.shareAboveHalf, o.bound) << o.why;
  }
  if (!o.withinBound()) {  // failure artefacts, one name per test (ctest runs in parallel)
    writePng((outputDir() / (c.name + "-" + t.name + ".png")).string(), o.frame.color);
    writePng((outputDir() / (c.name + "-" + t.name + "-reference.png")).string(),
             o.reference->color);
  }
}

std::vector<Param> allParams() {
  std::vector<Param> out;
  for (const Case& c : cases())
    for (const Technique& t : allTechniques()) out.emplace_back(c.name, t.name);
  return out;
}

std::string paramName(const ::testing::TestParamInfo<Param>& info) {
  return testName(std::get<0>(info.param) + "__" + std::get<1>(info.param));
}

INSTANTIATE_TEST_SUITE_P(Cases, Stability, ::testing::ValuesIn(allParams()), paramName);

std::vector<std::string> techniqueNames() {
  std::vector<std::string> out;
  for (const Technique& t : allTechniques()) out.push_back(t.name);
  return out;
}

// Mirroring by the model matrix must change no technique's mask. The mirrored
// stage is the same geometry with three objects' windings reversed; front faces (gl_FrontFacing,
// the second-depth map's culling, hybrid's back-face test), the volumes' two-sided stencil counts
// and the smoothies' silhouette orientation all depend on the winding.
class StabilityMirroring : public ::testing::TestWithParam<std::string> {};

// The mirrored box and ground split each face along the other diagonal, so depths interpolate
// from other triangles and differ in the last bits: a shadow-map compare or a sample at a
// silhouette may turn over on a few edge pixels. 0.3% of 160x120 is 57 pixels, well below the
// length of one shadow outline (~300 pixels); a winding error turns whole faces (>5%).
constexpr double kMirroringShare = 0.003;

TEST_P(StabilityMirroring, MirroredObjectsGiveTheUnmirroredMask) {
  const Technique& t = findTechnique(GetParam());
  RenderParams p = baseParams();
  p.capturePasses = false;
  const Frame plain = renderTechnique(t, mirroringStage(false), p);
  const Frame mirrored = renderTechnique(t, mirroringStage(true), p);
  const MaskDifference d = compareMasks(plain.visibility, mirrored.visibility);
  std::cout << "[stability] mirrored " << t.name << ": " << 100.0 * d.shareAboveHalf
            << "% of pixels differ by > 0.5, max " << d.maxAbs << "\n";
  EXPECT_LE(d.shareAboveHalf, kMirroringShare);
}

INSTANTIATE_TEST_SUITE_P(Techniques, StabilityMirroring, ::testing::ValuesIn(techniqueNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return testName(info.param);
                         });

// Stiff light cones and depth ranges through the command line, as a user meets them: a light cone
// or a camera depth range that no technique can render right is refused with exit 2 and one line
// naming the field, and no output file; the bound itself still renders.
struct CommandResult {
  int status = -1;
  std::string err;
};

CommandResult renderSceneFile(const std::string& name, double cameraNear, double cone,
                              const std::filesystem::path& image, double boxX = -0.6) {
  const std::filesystem::path dir = outputDir() / ("stiff-" + name);
  std::filesystem::create_directories(dir);
  const std::filesystem::path scene = dir / "scene.json", err = dir / "stderr.txt";
  std::ofstream(scene) << "{\"camera\": {\"position\": [0, 3.2, 2.6], \"target\": [0, 0, -0.2], "
                          "\"near\": "
                       << cameraNear
                       << ", \"far\": 20}, \"light\": {\"position\": [1.5, 3.5, -2], "
                          "\"target\": [0, 0, 0], \"up\": [0, 1, 0], \"cone\": "
                       << cone
                       << "}, \"objects\": [{\"mesh\": {\"primitive\": \"plane\", "
                          "\"width\": 4, \"depth\": 4}, \"casts\": false}, {\"mesh\": "
                          "{\"primitive\": \"box\", \"extent\": [0.8, 0.8, 0.8]}, "
                          "\"translate\": ["
                       << boxX << ", 0.8, -0.2]}]}";
  std::filesystem::remove(image);
  const std::string command = std::string(SHADOWLAB_BINARY) + " render --scene " + scene.string() +
                              " --technique modern.hw --size 64x48 --out " + image.string() +
                              " >/dev/null 2>" + err.string();
  const int raw = std::system(command.c_str());
  CommandResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  std::ifstream in(err);
  std::getline(in, r.err, '\0');
  return r;
}

void expectRefusedNaming(const CommandResult& r, const std::string& field,
                         const std::filesystem::path& image) {
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find(field), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
  EXPECT_FALSE(std::filesystem::exists(image));
}

constexpr double kStageCameraNear = 0.5;
constexpr double kStageCone = 70;

TEST(StabilityStiffRanges, LightConeNear180IsRefusedNamingTheField) {
  const std::filesystem::path image = outputDir() / "stiff-cone.png";
  // 179.9 degrees (every shadow-map technique drew an all-lit mask) and 170.
  for (double cone : {179.9, 170.0})
    expectRefusedNaming(renderSceneFile("cone", kStageCameraNear, cone, image), "light.cone",
                        image);
  const CommandResult widest = renderSceneFile("cone", kStageCameraNear, 160.0, image);
  EXPECT_EQ(widest.status, 0) << widest.err;
  EXPECT_TRUE(std::filesystem::exists(image));
}

TEST(StabilityStiffRanges, CameraNearFarBelowBoundIsRefusedNamingTheField) {
  const std::filesystem::path image = outputDir() / "stiff-camera.png";
  // near 1e-12 (modern.volumes streaked) and 1e-6, far 20.
  for (double cameraNear : {1e-12, 1e-6})
    expectRefusedNaming(renderSceneFile("camera", cameraNear, kStageCone, image), "camera.near/far",
                        image);
  const CommandResult stiffest = renderSceneFile("camera", 20 * 1e-5, kStageCone, image);
  EXPECT_EQ(stiffest.status, 0) << stiffest.err;
  EXPECT_TRUE(std::filesystem::exists(image));
}

// Beyond the scale 1e6 it reports (fixed): world coordinates beyond 1e12 are
// refused (products of coordinates overflow float in ray and shadow-volume tests from ~2e13).
TEST(StabilityStiffRanges, WorldCoordinatesBeyondBoundAreRefusedNamingTheObject) {
  const std::filesystem::path image = outputDir() / "stiff-coordinates.png";
  expectRefusedNaming(renderSceneFile("coordinates", kStageCameraNear, kStageCone, image, 2e12),
                      "objects[1].translate", image);
}

// A given light range with near/far below 1e-4 is narrowed to the geometry
// (core/scene/scene.cpp lightDepthRange); a range that clips geometry keeps its clipping plane.
TEST(StabilityStiffRanges, StiffLightRangeIsNarrowedToTheGeometry) {
  Scene fitted = stage();
  const DepthRange fit = lightDepthRange(fitted);
  Scene given = stage();
  given.light.nearPlane = 8e-7f;
  given.light.farPlane = 8.0f;
  const DepthRange narrowed = lightDepthRange(given);
  EXPECT_EQ(narrowed.nearPlane, fit.nearPlane);
  EXPECT_EQ(narrowed.farPlane, fit.farPlane);
  // A far plane inside the geometry stays where it was given.
  given.light.farPlane = 0.5f * (fit.nearPlane + fit.farPlane);
  given.light.nearPlane = *given.light.farPlane * 1e-7f;
  const DepthRange clipped = lightDepthRange(given);
  EXPECT_EQ(clipped.nearPlane, fit.nearPlane);
  EXPECT_EQ(clipped.farPlane, *given.light.farPlane);
  // A well-conditioned given range is left as given.
  given.light.nearPlane = 0.01f;
  given.light.farPlane = 8.0f;
  const DepthRange kept = lightDepthRange(given);
  EXPECT_EQ(kept.nearPlane, 0.01f);
  EXPECT_EQ(kept.farPlane, 8.0f);
}

// The GL maximum: GL_MAX_TEXTURE_SIZE + 1 is refused with an InputError by every technique;
// the maximum itself renders (16384^2 depth = 1 GiB on llvmpipe, ~10 s per technique), so it
// runs for the two hardware-compare techniques here and for all with SHADOWLAB_STABILITY_FULL=1.
class StabilityMaxMap : public ::testing::TestWithParam<std::string> {};

int maxTextureSize() {
  ContextSpec spec;
  spec.width = 16;
  spec.height = 16;
  return GlContext::create(spec)->caps().maxTextureSize;
}

TEST_P(StabilityMaxMap, BeyondMaximumIsInputError) {
  const Technique& t = findTechnique(GetParam());
  if (isReference(t)) GTEST_SKIP() << "no shadow map";
  RenderParams p = baseParams();
  p.shadowMapTexels = maxTextureSize() + 1;
  EXPECT_THROW(renderTechnique(t, stage(), p), InputError);
}

TEST_P(StabilityMaxMap, MaximumRendersOrRefuses) {
  const Technique& t = findTechnique(GetParam());
  if (isReference(t)) GTEST_SKIP() << "no shadow map";
  const bool full = std::getenv("SHADOWLAB_STABILITY_FULL") != nullptr;
  if (!full && t.name != "legacy.hw" && t.name != "modern.hw")
    GTEST_SKIP() << "GL maximum map is ~10 s per technique: set SHADOWLAB_STABILITY_FULL=1";
  RenderParams p = baseParams();
  p.capturePasses = false;
  p.shadowMapTexels = maxTextureSize();
  try {
    const Frame f = renderTechnique(t, stage(), p);
    expectFiniteBuffers(f);
    const MaskDifference d = errorWhereItMatters(f.visibility, referenceFor(cases()[0], false));
    // The largest map only sharpens the baseline: the well-conditioned bound applies.
    EXPECT_LE(d.shareAboveHalf, kWellConditioned);
  } catch (const InputError& e) {
    std::cout << "[stability] max map " << t.name << ": InputError: " << e.what() << "\n";
  }
}

INSTANTIATE_TEST_SUITE_P(Techniques, StabilityMaxMap, ::testing::ValuesIn(techniqueNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return testName(info.param);
                         });

}  // namespace
}  // namespace sl
