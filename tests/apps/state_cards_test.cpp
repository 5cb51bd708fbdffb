// The GL state cards and twin links of `render --dump-passes`, as the
// issue's done-when names them: legacy.hw shows its EYE_LINEAR planes and compare mode,
// legacy.fast-pcf the Eq. (1) kernel, the colour table and the colour matrix, and modern.fast-pcf
// links its packing pass to the GLSL lines that do it.
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>

#include "command_util.h"
#include "registry/twins.h"
#include "tests/test_names.h"

namespace sl {
namespace {
namespace fs = std::filesystem;
using test::slurp;

// Renders `technique` on the brabec scene with a dump; returns passes.json. `tag` keeps the
// folders of tests that may run at once (ctest -j) apart.
nlohmann::json dumpOf(const std::string& technique, const std::string& extra = "",
                      const std::string& tag = "") {
  const fs::path d = test::testDir("state_cards_" + tag + technique, true);
  const test::CommandResult r =
      test::runBinary(SHADOWLAB_BINARY,
                      "render --scene brabec --technique " + technique +
                          " --size 160x120 --shadow-map 128 " + extra + " --out " +
                          (d / "image.png").string() + " --dump-passes " + (d / "dump").string(),
                      d);
  EXPECT_EQ(r.status, 0) << r.err;
  return nlohmann::json::parse(slurp(d / "dump" / "passes.json"));
}

const nlohmann::json& pass(const nlohmann::json& dump, int number) {
  for (const nlohmann::json& p : dump["passes"])
    if (p["number"] == number) return p;
  throw std::runtime_error("no pass " + std::to_string(number));
}

// The pass with id `id` of the technique's pass table ("6a").
const nlohmann::json& passWithId(const nlohmann::json& dump, const std::string& id) {
  for (const nlohmann::json& p : dump["passes"])
    if (p["id"] == id) return p;
  throw std::runtime_error("no pass with id " + id);
}

// True when some line of the pass (group `group`) contains every one of `parts`.
bool hasLine(const nlohmann::json& p, const std::string& group,
             const std::vector<std::string>& parts) {
  for (const nlohmann::json& l : p["state"]) {
    if (l["group"] != group) continue;
    const std::string text = l["text"];
    bool all = true;
    for (const std::string& part : parts) all = all && text.find(part) != std::string::npos;
    if (all) return true;
  }
  return false;
}

std::string lines(const nlohmann::json& p) {
  std::string out;
  for (const nlohmann::json& l : p["state"])
    out += l["group"].get<std::string>() + ": " + l["text"].get<std::string>() + "\n";
  return out;
}

TEST(StateCards, HardwareShadowMapShowsEyeLinearPlanesAndCompareMode) {
  const nlohmann::json d = dumpOf("legacy.hw");
  const nlohmann::json& depth = pass(d, 1);
  EXPECT_EQ(depth["source"]["file"], "legacy_gl/hardware_shadow_map.cpp");
  EXPECT_TRUE(hasLine(depth, "texture", {"GL_TEXTURE_COMPARE_MODE", "GL_COMPARE_R_TO_TEXTURE"}))
      << lines(depth);
  EXPECT_TRUE(hasLine(depth, "polygon offset", {"glPolygonOffset("})) << lines(depth);
  const nlohmann::json& planes = pass(d, 2);
  for (const char* coord : {"GL_S", "GL_T", "GL_R", "GL_Q"}) {
    EXPECT_TRUE(
        hasLine(planes, "texgen", {std::string(coord) + ": GL_TEXTURE_GEN_MODE = GL_EYE_LINEAR"}))
        << coord << "\n"
        << lines(planes);
    EXPECT_TRUE(hasLine(planes, "texgen", {std::string(coord) + ": GL_EYE_PLANE = ("})) << coord;
  }
}

TEST(StateCards, FastPcfShowsKernelColourTableAndColourMatrix) {
  const nlohmann::json d = dumpOf("legacy.fast-pcf");
  const nlohmann::json& pack = pass(d, 2);
  EXPECT_NE(pack["section"].get<std::string>().find("Eq. (1)"), std::string::npos);
  EXPECT_EQ(pack["source"]["file"], "legacy_gl/fast_pcf.cpp");
  EXPECT_EQ(pack["source"]["function"], "packNeighboursByConvolution");
  // Eq. (1): R takes the lower left, G the lower middle, B the middle left, A the centre
  // (rows printed top to bottom).
  EXPECT_TRUE(hasLine(pack, "convolution",
                      {"3x3 kernel", "R: [0 0 0 / 0 0 0 / 1 0 0]", "G: [0 0 0 / 0 0 0 / 0 1 0]",
                       "B: [0 0 0 / 1 0 0 / 0 0 0]", "A: [0 0 0 / 0 1 0 / 0 0 0]"}))
      << lines(pack);
  EXPECT_TRUE(hasLine(pack, "pixels", {"glCopyTexSubImage2D"})) << lines(pack);
  const nlohmann::json& subtract = pass(d, 4);
  EXPECT_TRUE(hasLine(subtract, "blend", {"GL_FUNC_REVERSE_SUBTRACT"})) << lines(subtract);
  const nlohmann::json& count = pass(d, 5);
  // 8 bits: index 0 (no depth difference) -> 0, every other index -> 64/255 (63 in alpha).
  EXPECT_TRUE(hasLine(count, "colour table", {"256 entries", "0 -> 0, 1..255 -> 0.251 (64/255)"}))
      << lines(count);
  EXPECT_TRUE(hasLine(count, "colour matrix", {"load [0 0 0 0; 0 0 0 0; 0 0 0 0; 1 1 1 1]"}))
      << lines(count);
  EXPECT_TRUE(hasLine(count, "pixels", {"glCopyPixels 160x120"})) << lines(count);
}

// 4x4: four phases; the camera pass is the same in each, so it is written once, and the
// accumulation buffer shows up as glAccum lines.
TEST(StateCards, FastPcf4x4WritesOneCameraPassAndShowsTheAccumulation) {
  const nlohmann::json d = dumpOf("legacy.fast-pcf", "--filter 4");
  int cameraFiles = 0;
  for (const nlohmann::json& i : d["images"])
    if (i["pass"] == 3) ++cameraFiles;
  EXPECT_EQ(cameraFiles, 1);
  // Pass 6a sums the phases, pass 6b returns the sum (two passes of the table).
  const nlohmann::json& accumulate = passWithId(d, "6a");
  EXPECT_TRUE(hasLine(accumulate, "accum", {"glAccum(GL_LOAD"})) << lines(accumulate);
  EXPECT_TRUE(hasLine(accumulate, "accum", {"glAccum(GL_ACCUM"})) << lines(accumulate);
  const nlohmann::json& back = passWithId(d, "6b");
  EXPECT_TRUE(hasLine(back, "accum", {"glAccum(GL_RETURN"})) << lines(back);
}

// The packed map gets a "channel minus centre" view per neighbour on a diverging legend.
TEST(StateCards, PackedMapHasMinusCentreViewsWithLegends) {
  const nlohmann::json d = dumpOf("legacy.fast-pcf");
  int views = 0;
  for (const nlohmann::json& i : d["images"]) {
    if (i.value("view", "") == "minus centre") {
      ++views;
      EXPECT_EQ(i["legend"]["kind"], "diverging");
      EXPECT_LT(i["legend"]["low"].get<double>(), 0.0);
      EXPECT_GT(i["legend"]["high"].get<double>(), 0.0) << "the neighbours differ somewhere";
    }
    if (i.value("view", "") == "channel") {
      EXPECT_EQ(i["legend"]["kind"], "grey");
    }
  }
  EXPECT_EQ(views, 3) << "R, G and B minus A";
}

// modern.fast-pcf: numbered like its twin; its packing pass names legacy pass 2 and the lines
// of fast_pcf_pack.frag that do it, and those lines are the packing code.
TEST(StateCards, ModernFastPcfLinksItsPackPassToItsGlslLines) {
  const nlohmann::json modern = dumpOf("modern.fast-pcf");
  const nlohmann::json legacy = dumpOf("legacy.fast-pcf");
  const nlohmann::json& pack = pass(modern, 2);
  ASSERT_EQ(pack["replaces"].size(), 1u) << pack.dump();
  const nlohmann::json packing = {{"technique", "legacy.fast-pcf"},
                                  {"pass", "2"},
                                  {"name", pass(legacy, 2)["name"].get<std::string>()}};
  EXPECT_EQ(pack["replaces"][0], packing)
      << "the replaced pass by its id, named as the legacy dump names it";
  ASSERT_EQ(pack["glsl"].size(), 1u);
  const nlohmann::json& where = pack["glsl"][0];
  EXPECT_EQ(where["file"], "fast_pcf_pack.frag.glsl");
  std::ifstream in(fs::path(SHADOWLAB_SOURCE_DIR) / "modern" / "shaders" /
                   where["file"].get<std::string>());
  std::string line, code;
  for (int n = 1; std::getline(in, line); ++n)
    if (n >= where["first_line"].get<int>() && n <= where["last_line"].get<int>())
      code += line + "\n";
  EXPECT_NE(code.find("texelFetch(uEncodedDepth"), std::string::npos) << code;
  EXPECT_NE(code.find("oPacked = vec4(sampleAt(o, 0)"), std::string::npos) << code;
  EXPECT_EQ(code.find("@pass"), std::string::npos) << "the marker lines are not the code";
  EXPECT_TRUE(hasLine(pack, "program", {"fast_pcf_pack.frag.glsl"})) << lines(pack);
  EXPECT_TRUE(hasLine(pack, "uniforms", {"uRegionOrigin = (-1, -1)"})) << lines(pack);
  EXPECT_TRUE(hasLine(pack, "draw", {"glDrawArrays(GL_TRIANGLES), 3 vertices"})) << lines(pack);
  // The camera pass replaces legacy passes 3 to 7, each named by its id (passes 6a and 6b, the
  // accumulation and its return, exist in the 4x4 footprint only).
  const nlohmann::json& camera = pass(modern, 3);
  const auto replaces = [&](const nlohmann::json& id) {
    return std::find(camera["replaces"].begin(), camera["replaces"].end(), id) !=
           camera["replaces"].end();
  };
  for (const auto& [accumulation, name] :
       {std::pair{"6a", "accumulate"}, std::pair{"6b", "accumulation return"}}) {
    const nlohmann::json id = {
        {"technique", "legacy.fast-pcf"}, {"pass", accumulation}, {"name", name}};
    EXPECT_TRUE(replaces(id)) << id << " in " << camera["replaces"].dump();
  }
  for (const char* legacyPass : {"3", "4", "5", "7"}) {
    const nlohmann::json id = {{"technique", "legacy.fast-pcf"},
                               {"pass", legacyPass},
                               {"name", passWithId(legacy, legacyPass)["name"]}};
    EXPECT_TRUE(replaces(id)) << id << " in " << camera["replaces"].dump();
  }
}

// Every modern twin (registry/twins.h) is linked pass by pass, from the `// @replaces` lines of
// its shaders: each of its passes names at least one legacy pass and its GLSL lines, each named
// legacy pass exists under that id and name in the legacy dump (markers name pass ids of the
// legacy pass table, and they cannot name a pass that is not there), and every numbered legacy
// pass is replaced by some modern pass. Passes the default run does not make (the accumulation
// of footprints above 2x2) are only checked where they exist; tests/modern/
// twin_pass_links_test.cpp checks the tables themselves.
class TwinLinks : public ::testing::TestWithParam<const char*> {};

TEST_P(TwinLinks, EveryModernPassNamesTheLegacyPassesItReplaces) {
  const std::string modernName = GetParam();
  const std::string legacyName = twins::legacyTwinOf(modernName);
  const nlohmann::json modern = dumpOf(modernName, "", "twin_links_");
  const nlohmann::json legacy = dumpOf(legacyName, "", "twin_links_of_" + modernName + "_");
  std::map<std::string, std::string> legacyPasses;  // id -> name, the numbered ones
  for (const nlohmann::json& p : legacy["passes"])
    if (p["number"].get<int>() >= 1) legacyPasses[p["id"].get<std::string>()] = p["name"];
  std::set<std::string> replaced;
  for (const nlohmann::json& p : modern["passes"]) {
    EXPECT_FALSE(p["replaces"].empty()) << modernName << " pass " << p["id"];
    EXPECT_FALSE(p["glsl"].empty()) << modernName << " pass " << p["id"];
    for (const nlohmann::json& r : p["replaces"]) {
      ASSERT_TRUE(r.is_object() && r.contains("technique") && r.contains("pass")) << r;
      EXPECT_EQ(r["technique"], legacyName) << r;
      const std::string id = r["pass"];
      if (!legacyPasses.count(id)) continue;
      EXPECT_EQ(r.value("name", ""), legacyPasses[id]) << "the legacy dump names pass " << id;
      replaced.insert(id);
    }
  }
  for (const auto& [id, name] : legacyPasses)
    EXPECT_TRUE(replaced.count(id)) << legacyName << " pass " << id << " " << name
                                    << " is replaced by no pass of " << modernName;
}

INSTANTIATE_TEST_SUITE_P(Twins, TwinLinks,
                         ::testing::Values("modern.hw", "modern.woo", "modern.second-depth",
                                           "modern.ramp", "modern.pcf", "modern.fast-pcf"),
                         [](const auto& info) { return testName(info.param); });

}  // namespace
}  // namespace sl
