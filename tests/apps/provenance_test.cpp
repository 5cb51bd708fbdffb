// Outputs say what made them, and options a technique ignores are input errors: the
// JSON lines of `render` and `compare`, the text chunks of the PNGs they write,
// and the refusal of --shadow-map, --filter and --precision where the technique does not read
// them, checked against what the techniques actually do.
#include "core/base/provenance.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "command_util.h"
#include "core/base/image.h"
#include "core/scene/scene_library.h"
#include "registry/registry.h"
#include "tests/test_names.h"

namespace sl {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;
using test::CommandResult;
using test::slurp;

fs::path dir() { return test::testDir("provenance"); }

CommandResult shadowlab(const std::string& args) {
  return test::runBinary(SHADOWLAB_BINARY, args, dir());
}

int lines(const std::string& text) { return int(std::count(text.begin(), text.end(), '\n')); }

// ------------------------------------------------------------ item 2: what made an output

TEST(Provenance, RenderJsonLineAndPngsNameEveryParameterAndTheCommit) {
  const fs::path png = dir() / "pcf.png", mask = dir() / "pcf-mask.png";
  fs::remove(png);
  fs::remove(mask);
  const CommandResult r = shadowlab(
      "render --scene analytic --technique legacy.pcf --size 64x48 --shadow-map 64 --filter 3 "
      "--precision 12 --param depth-bias=3 --out " +
      png.string() + " --mask " + mask.string());
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(lines(r.out), 1) << r.out;
  const json line = json::parse(r.out);
  for (const char* key : {"technique", "scene", "size", "shadow_map", "filter", "precision",
                          "params", "backend", "command", "commit", "frame_ms", "passes"})
    EXPECT_TRUE(line.contains(key)) << key << " missing from " << r.out;
  EXPECT_EQ(line["technique"], "legacy.pcf");
  EXPECT_EQ(line["scene"], "analytic");
  EXPECT_EQ(line["size"], "64x48");
  EXPECT_EQ(line["shadow_map"], 64);
  EXPECT_EQ(line["filter"], 3);
  EXPECT_EQ(line["precision"], "12");
  EXPECT_EQ(line["backend"], "osmesa");
  EXPECT_EQ(line["imaging"], "emulated");  // Debian's OSMesa has no native imaging subset
  EXPECT_EQ(line["params"]["depth-bias"], "3");
  EXPECT_TRUE(line["scene_file"].is_null()) << "a built-in scene has no file";
  EXPECT_TRUE(line["scene_sha256"].is_null());
  EXPECT_EQ(line["commit"], buildCommit());
  const std::string command = line["command"];
  EXPECT_NE(command.find(" render --scene analytic --technique legacy.pcf"), std::string::npos)
      << command;
  EXPECT_NE(command.find("--mask " + mask.string()), std::string::npos) << command;

  // Both PNGs carry the same: the software and commit, the command, the parameters.
  for (const fs::path& file : {png, mask}) {
    const auto text = readPngText(file.string());
    ASSERT_EQ(text.count("Software"), 1u) << file;
    EXPECT_EQ(text.at("Software"), "shadowlab " + buildCommit());
    EXPECT_EQ(text.at("shadowlab:command"), command);
    const json made = json::parse(text.at("shadowlab:parameters"));
    for (const char* key : {"technique", "scene", "size", "shadow_map", "filter", "precision",
                            "params", "backend", "imaging"})
      EXPECT_EQ(made[key], line[key]) << key << " in " << file;
  }
}

// A scene from a file: the JSON line names the file and the SHA-256 of its bytes (checked
// against coreutils' sha256sum, another implementation).
TEST(Provenance, RenderNamesTheSceneFileAndItsContentHash) {
  const fs::path scene =
      fs::path(SHADOWLAB_SOURCE_DIR) / "docs" / "examples" / "minimal-scene.json";
  const fs::path png = dir() / "minimal.png";
  const CommandResult r = shadowlab("render --scene " + scene.string() +
                                    " --technique modern.hw --size 32x24 --out " + png.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const json line = json::parse(r.out);
  EXPECT_EQ(line["scene_file"], scene.string());
  const CommandResult sum = test::runBinary("/usr/bin/sha256sum", scene.string(), dir());
  ASSERT_EQ(sum.status, 0) << sum.err;
  const std::string expected = sum.out.substr(0, sum.out.find(' '));
  EXPECT_EQ(expected.size(), 64u) << sum.out;
  EXPECT_EQ(line["scene_sha256"], expected);
  const json made = json::parse(readPngText(png.string()).at("shadowlab:parameters"));
  EXPECT_EQ(made["scene_sha256"], expected) << "the PNG says the same";
}

// The --params a technique read are printed with the values it used, defaults included.
TEST(Provenance, RenderPrintsTheDefaultsTheTechniqueRead) {
  const CommandResult r = shadowlab(
      "render --scene analytic --technique modern.csm --size 48x36 "
      "--shadow-map 64 --param order=8 --out " +
      (dir() / "csm.png").string());
  ASSERT_EQ(r.status, 0) << r.err;
  const json line = json::parse(r.out);
  EXPECT_EQ(line["params"]["order"], "8");                     // given
  EXPECT_TRUE(line["params"].contains("storage")) << r.out;    // modern.csm's default
  EXPECT_TRUE(line["params"].contains("filtering")) << r.out;  // modern/prefiltered_maps.cpp
  // Options modern.csm does not read are null, not a value that did nothing.
  EXPECT_TRUE(line["filter"].is_null()) << r.out;
  EXPECT_TRUE(line["precision"].is_null()) << r.out;
  EXPECT_TRUE(line["imaging"].is_null()) << r.out;
}

TEST(Provenance, CompareJsonLineAndDiffPngNameBothTechniques) {
  const fs::path diff = dir() / "diff.png";
  fs::remove(diff);
  const CommandResult r = shadowlab(
      "compare --scene analytic --a legacy.pcf --b modern.pcf --size 48x36 "
      "--shadow-map 64 --filter 2 --diff " +
      diff.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const json line = json::parse(r.out);
  for (const char* key : {"a", "b", "scene", "size", "shadow_map", "filter", "precision",
                          "a_params", "b_params", "backend", "command", "commit", "rmse"})
    EXPECT_TRUE(line.contains(key)) << key << " missing from " << r.out;
  EXPECT_EQ(line["filter"], 2);
  EXPECT_EQ(line["commit"], buildCommit());
  EXPECT_TRUE(line["b_params"].contains("depth-bias")) << r.out;  // modern.pcf's default
  const auto text = readPngText(diff.string());
  EXPECT_EQ(text.at("Software"), "shadowlab " + buildCommit());
  EXPECT_EQ(text.at("shadowlab:command"), line["command"]);
  const json made = json::parse(text.at("shadowlab:parameters"));
  EXPECT_EQ(made["a"], "legacy.pcf");
  EXPECT_EQ(made["b"], "modern.pcf");
  EXPECT_EQ(made["a_params"], line["a_params"]);
}

// ------------------------------------------------------------ item 3: ignored options

TEST(IgnoredOptions, RenderRefusesAnOptionTheTechniqueDoesNotRead) {
  const fs::path out = dir() / "ramp.png";
  fs::remove(out);
  const CommandResult r =
      shadowlab("render --technique legacy.ramp --size 48x36 --filter 4 --out " + out.string());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("legacy.ramp does not filter: --filter has no effect on it"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("legacy.pcf"), std::string::npos) << r.err;  // who does read it
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_FALSE(fs::exists(out));
}

TEST(IgnoredOptions, PlanRefusesWhatRenderRefuses) {
  const CommandResult r = shadowlab("plan --scene analytic --technique modern.hw --precision 12");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("--precision has no effect on it"), std::string::npos) << r.err;
  EXPECT_EQ(shadowlab("plan --scene analytic --technique legacy.pcf --filter 3").status, 0);
}

TEST(IgnoredOptions, CompareWarnsWhenOneTechniqueIgnoresAnOption) {
  const CommandResult warned = shadowlab(
      "compare --scene analytic --a modern.volumes --b modern.hybrid --size 48x36 "
      "--shadow-map 64");
  EXPECT_EQ(warned.status, 0) << warned.err;
  EXPECT_EQ(lines(warned.err), 1) << warned.err;
  EXPECT_NE(warned.err.find("warning: modern.volumes"), std::string::npos) << warned.err;
  EXPECT_NE(warned.err.find("--shadow-map"), std::string::npos) << warned.err;
  EXPECT_EQ(json::parse(warned.out)["shadow_map"], 64);

  const CommandResult refused = shadowlab(
      "compare --scene analytic --a modern.volumes --b reference.hard --size 48x36 --filter 2");
  EXPECT_EQ(refused.status, 2) << refused.err;
  EXPECT_EQ(lines(refused.err), 1) << refused.err;
  EXPECT_NE(refused.err.find("neither modern.volumes nor reference.hard reads --filter"),
            std::string::npos)
      << refused.err;
}

// Every technique, every option it declares it does not read: refused before anything renders.
TEST(IgnoredOptions, EveryUndeclaredOptionIsRefused) {
  const std::map<CommonOption, std::string> given = {{CommonOption::kShadowMap, "--shadow-map 64"},
                                                     {CommonOption::kFilter, "--filter 2"},
                                                     {CommonOption::kPrecision, "--precision 8"}};
  for (const Technique& t : allTechniques())
    for (const auto& [option, text] : given) {
      if (readsOption(t, option)) continue;
      const CommandResult r = shadowlab("plan --scene analytic --technique " + t.name + " " + text);
      EXPECT_EQ(r.status, 2) << t.name << " " << text << ": " << r.err;
      EXPECT_NE(r.err.find(t.name), std::string::npos) << r.err;
    }
}

// The declarations are true: an option a technique does not declare changes nothing in what it
// renders, and one that it declares changes the image, the visibility mask
// or the technique's counters (modern.hybrid's map only finds the pixels its volumes then
// resolve: a larger map changes its counters, not its exact mask).
struct Rendered {
  Image color, visibility;
  std::map<std::string, double> counters;
};

Rendered visibility(const Technique& t, const Scene& scene, const RenderParams& p) {
  Frame f = renderTechnique(t, scene, p);
  return {std::move(f.color), std::move(f.visibility), std::move(f.counters)};
}

bool same(const Rendered& a, const Rendered& b) {
  return a.color.data == b.color.data && a.visibility.data == b.visibility.data &&
         a.counters == b.counters;
}

class Declarations : public ::testing::TestWithParam<std::string> {};

TEST_P(Declarations, MatchWhatTheTechniqueReads) {
  const Technique& t = findTechnique(GetParam());
  const Scene scene = loadScene("brabec");
  RenderParams base;
  base.width = 64;  // small: every technique renders four to six times
  base.height = 48;
  base.shadowMapTexels = 64;
  base.filter = 2;  // valid for every filtering technique (fast PCF takes 2 and 4 only)
  const Rendered reference = visibility(t, scene, base);

  RenderParams map = base;
  map.shadowMapTexels = 256;
  EXPECT_EQ(!same(reference, visibility(t, scene, map)), t.reads.shadowMap)
      << t.name << ": --shadow-map 64 against 256";
  RenderParams filter = base;
  filter.filter = 4;
  EXPECT_EQ(!same(reference, visibility(t, scene, filter)), t.reads.filter)
      << t.name << ": --filter 2 against 4";
  RenderParams precise = base;
  precise.precision = Precision::k12;  // the modern twins take float arithmetic from --param
  EXPECT_EQ(!same(reference, visibility(t, scene, precise)), t.reads.precision)
      << t.name << ": --precision 8 against 12";
}

std::vector<std::string> techniqueNames() {
  std::vector<std::string> names;
  for (const Technique& t : allTechniques()) names.push_back(t.name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(All, Declarations, ::testing::ValuesIn(techniqueNames()),
                         [](const auto& info) { return testName(info.param); });

}  // namespace
}  // namespace sl
