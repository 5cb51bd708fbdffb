// measure/roofline.h: every pass of every Brabec & Seidel variant of
// legacy_bench has a floor rule, the floors measure real GL work, and running them between two
// frames in one context leaves the frames unchanged (the floors restore the state they touch).
#include "measure/roofline.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <regex>

#include "core/scene/scene_library.h"
#include "measure/legacy_benchmark.h"
#include "registry/registry.h"

namespace sl::legacy {
namespace {

constexpr int kWidth = 160, kHeight = 120, kMap = 64;  // small: the rules, not the speed

RenderParams smallParams(const BenchmarkVariant& v) {
  RenderParams p;
  p.width = kWidth;
  p.height = kHeight;
  p.shadowMapTexels = kMap;
  p.filter = v.filter;
  return p;
}

TEST(Roofline, EveryPassOfEveryPaperVariantHasAFloor) {
  const Scene scene = builtinScene("brabec");
  for (const BenchmarkVariant& v : paperVariants()) {
    const RenderParams p = smallParams(v);
    const Frame frame = renderTechnique(findTechnique(v.technique), scene, p);
    ASSERT_FALSE(frame.passes.empty()) << v.label;
    for (const PassTime& pass : frame.passes) {
      const auto terms = passFloor(pass, p);
      ASSERT_TRUE(terms.has_value()) << v.label << ": pass '" << pass.name
                                     << "' declares no floor in its technique's pass table";
      // No GL work: the mesh feeding; legacy.hw's texgen planes (state only, nothing drawn).
      const bool noGlWork = pass.id == "mesh" || (v.technique == "legacy.hw" && pass.id == "2");
      EXPECT_EQ(terms->empty(), noGlWork) << v.label << ": " << pass.name;
      for (const FloorTerm& t : *terms) {
        EXPECT_GT(t.count, 0) << pass.name;
        EXPECT_TRUE((t.width == kWidth && t.height == kHeight) ||
                    (t.width == kMap && t.height == kMap))
            << pass.name << ": a floor of the window's or the map's size";
      }
    }
  }
  EXPECT_FALSE(passFloor(PassFloor::kNone, 0, smallParams(paperVariants().front())).has_value());
}

// §3: four jittered samples per map; a 4x4 footprint has four groups of four, 3x3 ends with one.
TEST(Roofline, JitteredLightPassFloorCountsTheGroupsSamples) {
  RenderParams p;
  p.filter = 3;
  auto samples = [&](int part) {
    return passFloor(PassFloor::kJitteredLightGroup, part, p)->front().count;
  };
  EXPECT_EQ(samples(0), 4);  // group 1
  EXPECT_EQ(samples(2), 1);  // group 3
  p.filter = 2;
  EXPECT_EQ(samples(0), 4);
}

// The floors of one variant run between two of its frames in one context; the second frame is
// bit-identical to the first (the floors restore the state they touch).
void expectFloorsLeaveFramesUnchanged(const BenchmarkVariant& v) {
  const Scene scene = builtinScene("brabec");
  const Technique& t = findTechnique(v.technique);
  const RenderParams p = smallParams(v);
  auto context = makeRenderContext(t, p);
  const Frame before = t.render(*context, scene, p);
  std::vector<FloorTerm> terms;
  for (const PassTime& pass : before.passes) {
    const auto passTerms = passFloor(pass, p);
    ASSERT_TRUE(passTerms.has_value()) << pass.name;
    terms.insert(terms.end(), passTerms->begin(), passTerms->end());
  }
  auto resources = makeFloorResources(p.shadowMapTexels, p.width, p.height);
  const Frame floors = renderFloors(*resources, terms);
  ASSERT_EQ(floors.passes.size(), terms.size());
  for (size_t i = 0; i < terms.size(); ++i) EXPECT_EQ(floors.passes[i].name, floorName(terms[i]));
  const Frame after = t.render(*context, scene, p);
  EXPECT_EQ(after.visibility.data, before.visibility.data) << v.label;
  EXPECT_EQ(after.color.data, before.color.data) << v.label;
}

TEST(Roofline, FloorsBetweenFramesLeaveTheFramesUnchanged) {
  expectFloorsLeaveFramesUnchanged(paperVariants()[2]);  // fast PCF 2x2: table, matrix, convolution
}

// legacy_bench times legacy.hw: its floors touch three texture units, the alpha test, polygon
// offset and the depth texture's comparison, and leave its frames unchanged.
TEST(Roofline, HardwareShadowMapIsBenchedAndItsFloorsLeaveTheFramesUnchanged) {
  const std::vector<BenchmarkVariant> variants = paperVariants();
  const auto hw = std::find_if(variants.begin(), variants.end(), [](const BenchmarkVariant& v) {
    return v.technique == "legacy.hw";
  });
  ASSERT_NE(hw, variants.end()) << "legacy_bench does not time legacy.hw";
  const PassTable& table = findTechnique("legacy.hw").passes;
  EXPECT_EQ(findPassSpec(table, "1").floor, PassFloor::kDepthFromLight);
  EXPECT_EQ(findPassSpec(table, "4").floor, PassFloor::kShadowedDirectLight);
  expectFloorsLeaveFramesUnchanged(*hw);
}

// The lighting pass draws its direct layer through the projected cone (texture + alpha test,
// legacy_gl/projected_spotlight.h) after clearing the colour with alpha kept: so does its floor.
TEST(Roofline, LightingFloorLooksUpTheConeAndKeepsAlpha) {
  const auto terms = passFloor(PassFloor::kLighting, 0, smallParams(paperVariants().front()));
  ASSERT_TRUE(terms.has_value());
  std::vector<FloorWork> works;
  for (const FloorTerm& t : *terms) works.push_back(t.work);
  EXPECT_EQ(works,
            (std::vector<FloorWork>{FloorWork::kClearColourKeepAlpha,
                                    FloorWork::kLitBlendedConeFill, FloorWork::kLitBlendedFill}));
}

// fast PCF 4x4: its accumulate floor is glAccum(GL_ACCUM) into the frame's own accumulation
// buffer, which each frame starts with GL_LOAD.
TEST(Roofline, AccumulateFloorIsGlAccumAndLeavesTheFramesUnchanged) {
  const BenchmarkVariant v = paperVariants()[3];
  ASSERT_EQ(v.technique, "legacy.fast-pcf");
  ASSERT_EQ(v.filter, 4);
  const auto terms = passFloor(findPassSpec(findTechnique("legacy.fast-pcf").passes, "6a").floor, 1,
                               smallParams(v));
  ASSERT_TRUE(terms.has_value());
  ASSERT_EQ(terms->size(), 1u);
  EXPECT_EQ(terms->front().work, FloorWork::kAccumulate);
  expectFloorsLeaveFramesUnchanged(v);
}

// legacy_bench --split-cost: the camera pass's draw of brabec's own meshes and of the split
// meshes the camera passes draw, beside the floor; the split has more triangles.
TEST(Roofline, SplitCostTimesTheOwnAndTheSplitMeshes) {
  BenchmarkOptions options;
  options.width = kWidth;
  options.height = kHeight;
  options.shadowMapTexels = kMap;
  options.frames = {1, 1};  // one warm-up round, one timed: the table, not the speed
  const Scene scene = builtinScene("brabec");
  const std::string table = splitCostMarkdown(scene, options);
  size_t own = 0;
  for (const Object& o : scene.objects) own += o.mesh->triangleCount();
  std::smatch m;
  ASSERT_TRUE(std::regex_search(table, m, std::regex(R"(\| the scene's own meshes \| (\d+) \|)")))
      << table;
  EXPECT_EQ(std::stoul(m[1].str()), own);
  ASSERT_TRUE(std::regex_search(
      table, m, std::regex(R"(\| the split meshes, both faces \| (\d+) \| (\d+|-) \| [\d.]+ \|)")))
      << table;
  EXPECT_GT(std::stoul(m[1].str()), own);
  const std::string splitFragments = m[2].str();
  ASSERT_TRUE(std::regex_search(
      table, m,
      std::regex(R"(\| floor: clear \+ one ramp-textured full-window quad \| 2 \| (\d+|-) \|)")))
      << table;
  const std::string floorFragments = m[1].str();
  ASSERT_TRUE(std::regex_search(
      table, m,
      std::regex(R"(\| the split meshes, one pixel drawn \(scissor\)[^|]*\| \d+ \| (\d+|-) \|)")))
      << table;
  const std::string onePixelFragments = m[1].str();
  ASSERT_TRUE(std::regex_search(
      table, m,
      std::regex(R"(\| the split meshes, hidden back faces culled[^|]*\| \d+ \| (\d+|-) \|)")))
      << table;
  const std::string culledFragments = m[1].str();
  if (floorFragments == "-") GTEST_SKIP() << "no GL_ARB_pipeline_statistics_query here";
  // brabec's torus and boxes are closed and seen from outside: culling their back faces saves
  // fragments.
  EXPECT_LT(std::stoul(culledFragments), std::stoul(splitFragments));
  // The full-window quad shades every pixel; the scene shades its surfaces, hidden ones too.
  EXPECT_GE(std::stoul(floorFragments), size_t(kWidth) * kHeight);
  EXPECT_GT(std::stoul(splitFragments), 0u);
  // One pixel drawn: at most one 4x4 block per triangle that covers it (a handful), never the
  // window.
  EXPECT_LT(std::stoul(onePixelFragments), std::stoul(floorFragments) / 100);
}

}  // namespace
}  // namespace sl::legacy
