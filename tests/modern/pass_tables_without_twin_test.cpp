// The pass tables (core/technique/pass_table.h) of the modern techniques without a legacy twin:
// each table well formed, and a frame's passes and dumped buffers exactly those the table declares,
// with the table's names, paper references and shaders.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "core/scene/scene_library.h"
#include "core/technique/pass_table.h"
#include "filtered_shadows_util.h"
#include "test_names.h"

namespace sl {
namespace {
using namespace sl::testing_filtered;

// Small enough for the whole suite to stay within seconds; a map of more than one texel, so
// that modern.csm classifies.
constexpr int kWidth = 160;
constexpr int kHeight = 120;
constexpr int kMapTexels = 64;

class PassTablesWithoutTwin : public ::testing::TestWithParam<std::string> {};

TEST_P(PassTablesWithoutTwin, FramePassesAndBuffersAreTheDeclaredOnes) {
  const Technique t = findTechnique(GetParam());
  EXPECT_TRUE(passTableProblems(t.passes).empty()) << GetParam();
  RenderParams p = smallParams(kWidth, kHeight, kMapTexels);
  // modern.csm's declared table is the one with the mip chain (pass 4 "mip-maps"); at this
  // size mipmaps=auto would leave the chain out and run the table whose pass 4 says so.
  if (GetParam() == "modern.csm") p.extra["mipmaps"] = "always";
  p.capturePasses = true;
  const Frame f = renderTechnique(t, builtinScene("brabec"), p);
  ASSERT_FALSE(f.passes.empty());
  for (const PassTime& pass : f.passes) {
    const auto spec = std::find_if(t.passes.begin(), t.passes.end(),
                                   [&](const PassSpec& s) { return s.id == pass.id; });
    ASSERT_NE(spec, t.passes.end()) << GetParam() << ": pass " << pass.name;
    // The display name: the id, the declared name and possibly a suffix ("3x3").
    EXPECT_EQ(pass.name.rfind(spec->id + " " + spec->name, 0), 0u) << pass.name;
    EXPECT_EQ(pass.section, spec->reference) << pass.name;
    EXPECT_EQ(pass.glsl, spec->shaders) << pass.name;
  }
  ASSERT_FALSE(f.intermediates.empty());
  for (const PassImage& image : f.intermediates) {
    const auto spec = std::find_if(t.passes.begin(), t.passes.end(),
                                   [&](const PassSpec& s) { return s.id == image.passId; });
    ASSERT_NE(spec, t.passes.end()) << GetParam() << ": buffer " << image.name;
    EXPECT_EQ(image.name.rfind(spec->id + "-", 0), 0u) << image.name;
    EXPECT_FALSE(image.caption.empty()) << image.name;
    EXPECT_EQ(image.caption.find('{'), std::string::npos) << image.caption;  // words filled in
  }
}

INSTANTIATE_TEST_SUITE_P(Modern, PassTablesWithoutTwin,
                         ::testing::Values("modern.gems16", "modern.gems4", "modern.csm",
                                           "modern.vsm", "modern.esm", "modern.evsm2",
                                           "modern.evsm4", "modern.msm", "modern.volumes",
                                           "modern.hybrid", "modern.smoothies", "modern.pcss"),
                         [](const auto& info) { return testName(info.param); });

// modern.gems16 with the bicubic kernel runs its own variant's passes: the same ids, the
// names, references and shaders of Chan 2004 Fig. 4-8.
TEST(PassTablesWithoutTwinGems, BicubicKernelRunsItsOwnVariant) {
  const Frame f = renderByName("modern.gems16", builtinScene("brabec"),
                               smallParams(kWidth, kHeight, kMapTexels, {{"kernel", "bicubic"}}));
  ASSERT_EQ(f.passes.size(), 2u);
  EXPECT_EQ(f.passes[0].id, "1");
  EXPECT_EQ(f.passes[1].id, "2");
  EXPECT_EQ(f.passes[1].name, "2 camera pass, 16-sample bicubic PCF");
  EXPECT_EQ(f.passes[1].glsl, (std::vector<std::string>{"bicubic-weights", "bicubic-region"}));
  EXPECT_EQ(f.passes[0].section.rfind("Chan 2004 §4.4, Fig. 4-8", 0), 0u);
}

}  // namespace
}  // namespace sl
