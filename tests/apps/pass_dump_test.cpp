// `shadowlab render --dump-passes DIR` (teach/pass_dump.h): every technique in
// the registry dumps its buffers in pipeline order with passes.json and index.html; a frame
// with nothing to dump is an input error, never an empty folder.
#include "teach/pass_dump.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "command_util.h"
#include "core/base/errors.h"
#include "core/base/image.h"
#include "registry/registry.h"
#include "tests/test_names.h"

namespace sl {
namespace {
namespace fs = std::filesystem;
using test::slurp;

fs::path freshDir() { return test::testDir("pass_dump", true); }

// A buffer of pass `id`, named as core/technique/passes.cpp names captures: "ID-NAME".
PassImage buffer(const std::string& id, const std::string& name, int channels = 1,
                 float value = 0.5f) {
  PassImage p(id + "-" + name, "caption of " + id + "-" + name, Image(4, 2, channels, value));
  p.passId = id;
  return p;
}

// A timed run of pass `id` (part `part`), named as core/technique/passes.cpp names it.
PassTime timed(const std::string& id, const std::string& name, double ms, int part = 0) {
  PassTime t(id + " " + name, ms);
  t.id = id;
  t.part = part;
  return t;
}

std::vector<std::string> files(const std::vector<PassDumpImage>& images) {
  std::vector<std::string> out;
  for (const PassDumpImage& i : images) out.push_back(i.file);
  return out;
}

// Zero-padded pass numbers, and letters in the order made for passes with several images:
// "5-alpha-after-colour-matrix" no longer sorts before "5-mask-after-colour-table".
TEST(PassDump, FileNamesSortInPipelineOrder) {
  Frame f;
  for (const auto& [id, name] :
       std::vector<std::pair<std::string, std::string>>{{"1", "light"},
                                                        {"3a", "projected"},
                                                        {"2", "camera"},
                                                        {"3b", "difference"},
                                                        {"5", "mask-after-colour-table"},
                                                        {"5", "alpha-after-colour-matrix"},
                                                        {"12", "last"}})
    f.intermediates.push_back(buffer(id, name));
  const std::vector<std::string> expected = {"01-light.png",
                                             "02-camera.png",
                                             "03a-projected.png",
                                             "03b-difference.png",
                                             "05a-mask-after-colour-table.png",
                                             "05b-alpha-after-colour-matrix.png",
                                             "12-last.png"};
  const std::vector<std::string> got = files(planPassDump(f, "test"));
  EXPECT_EQ(got, expected);
  std::vector<std::string> sorted = got;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, got) << "ls lists them in pipeline order";
}

// A packed map (four depths in R, G, B, A) is written opaque, then one grey PNG per channel.
TEST(PassDump, PackedMapsAreOpaqueWithOneGreyPanelPerChannel) {
  Frame f;
  f.intermediates.push_back(buffer("2", "packed", 4, 0.25f));  // alpha 0.25: transparent as is
  const std::vector<PassDumpImage> images = planPassDump(f, "test");
  ASSERT_EQ(images.size(), 5u);
  EXPECT_EQ(images[0].file, "02-packed.png");
  for (size_t i = 3; i < images[0].image.data.size(); i += 4)
    EXPECT_EQ(images[0].image.data[i], 1.0f) << "alpha forced to 1";
  const std::vector<std::string> channels = {"R", "G", "B", "A"};
  for (size_t c = 0; c < 4; ++c) {
    const PassDumpImage& panel = images[c + 1];
    EXPECT_EQ(panel.file, "02-packed-ch" + std::to_string(c + 1) + "-" + channels[c] + ".png");
    EXPECT_EQ(panel.channel, channels[c]);
    EXPECT_EQ(panel.of, "02-packed.png");
    EXPECT_EQ(panel.image.channels, 1);
    EXPECT_EQ(panel.image.data[0], 0.25f);
    EXPECT_NE(panel.caption.find("channel " + channels[c]), std::string::npos) << panel.caption;
  }
}

TEST(PassDump, NothingToDumpIsAnInputError) {
  EXPECT_THROW(requireSomethingToDump(Frame{}, "legacy.none"), InputError);
  EXPECT_THROW(planPassDump(Frame{}, "legacy.none"), InputError);
}

// passes.json pairs each pass's time with its images; index.html shows every image.
TEST(PassDump, PassesJsonAndIndexDescribeEveryImage) {
  Frame f;
  f.passes = {timed("1", "light pass", 2.0), timed("2", "camera pass (phase 1)", 1.0, 0),
              timed("2", "camera pass (phase 2)", 3.0, 1)};
  f.intermediates = {buffer("2", "shaded", 3), buffer("1", "light-depth")};
  const std::vector<PassDumpImage> images = planPassDump(f, "t");
  const nlohmann::json j = passesJson(f, {"t", "paper", "scene", {{"size", "4x2"}}, ""}, images);
  ASSERT_EQ(j["passes"].size(), 2u);
  EXPECT_EQ(j["passes"][0]["number"], 1);
  EXPECT_EQ(j["passes"][0]["name"], "light pass");
  EXPECT_EQ(j["passes"][0]["files"][0], "01-light-depth.png");
  EXPECT_DOUBLE_EQ(j["passes"][1]["milliseconds"].get<double>(), 4.0) << "phases summed";
  EXPECT_EQ(j["passes"][1]["timings"].size(), 2u);
  ASSERT_EQ(j["images"].size(), 2u);
  EXPECT_EQ(j["images"][1]["file"], "02-shaded.png");
  // A pass timed in parts is titled by what its parts share (each part is named on its own
  // "part" line of the state card), not by its first part.
  EXPECT_EQ(j["passes"][1]["name"], "camera pass");
  EXPECT_EQ(j["images"][1]["pass_name"], "camera pass");
  EXPECT_EQ(j["images"][1]["channels"], 3);
  EXPECT_EQ(j["images"][1]["width"], 4);
  EXPECT_EQ(j["images"][1]["caption"], "caption of 2-shaded");
  const std::string html = indexHtml(j);
  for (const char* s : {"01-light-depth.png", "02-shaded.png", "caption of 2-shaded",
                        "Pass 2: camera pass <span", "camera pass (phase 2)"})
    EXPECT_NE(html.find(s), std::string::npos) << s;
  // Images sized by width only: their one height rule is "height: auto" (natural aspect ratio),
  // and no <img> sets a height of its own.
  EXPECT_NE(html.find("figure img { height: auto;"), std::string::npos);
  for (size_t img = html.find("<img"); img != std::string::npos; img = html.find("<img", img + 1))
    EXPECT_EQ(html.substr(img, html.find('>', img) - img).find("height"), std::string::npos);
  EXPECT_EQ(html.find("http"), std::string::npos) << "no network";
}

// A pass's section names the paper it follows by its authors (the papers of /work/shared/papers
// and the ones they cite for a technique: Wang & Molnar, Woo, Donnelly & Lauritzen, Everitt &
// Kilgard), or starts with "ours" (our own pass, no paper's).
bool citesAPaperOrSaysOurs(const std::string& section) {
  if (section.rfind("ours", 0) == 0) return true;
  for (const char* author : {"Everitt", "Brabec & Seidel", "Bunnell & Pellacini", "Annen",
                             "Chan 2004", "Donnelly & Lauritzen"})
    if (section.find(author) != std::string::npos) return true;
  return false;
}

int run(const std::string& args, const fs::path& log) {
  const std::string cmd =
      std::string(SHADOWLAB_BINARY) + " " + args + " >" + log.string() + " 2>&1";
  const int raw = std::system(cmd.c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

// Every technique in `shadowlab list`, references included, at a small size (the whole set
// runs in about 5 s).
class EveryTechnique : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryTechnique, DumpsItsPassesWithPassesJsonAndIndex) {
  const Technique& t = findTechnique(GetParam());
  const fs::path d = freshDir();
  const fs::path dump = d / "dump";
  std::string args = "render --scene brabec --technique " + t.name + " --size 160x120 --out " +
                     (d / "image.png").string() + " --dump-passes " + dump.string();
  if (readsOption(t, CommonOption::kShadowMap)) args += " --shadow-map 128";
  ASSERT_EQ(run(args, d / "log.txt"), 0) << slurp(d / "log.txt");

  const nlohmann::json j = nlohmann::json::parse(slurp(dump / "passes.json"));
  EXPECT_EQ(j["technique"], t.name);
  EXPECT_EQ(j["scene"], "brabec");
  const std::string html = slurp(dump / "index.html");
  EXPECT_NE(html.find(t.name), std::string::npos);
  std::set<std::string> listed;
  int previousPass = -1;
  std::string previousFile;
  for (const nlohmann::json& i : j["images"]) {
    const std::string file = i["file"];
    listed.insert(file);
    // Pipeline order: pass numbers never decrease, and the names sort the same way.
    EXPECT_GE(i["pass"].get<int>(), previousPass) << file;
    EXPECT_GE(i["pass"].get<int>(), 0) << file << ": its buffer name has no pass number";
    previousPass = i["pass"].get<int>();
    if (!i.contains("of")) {
      EXPECT_LT(previousFile, file);
      previousFile = file;
    }
    EXPECT_FALSE(i["caption"].get<std::string>().empty()) << file;
    EXPECT_NE(html.find(file), std::string::npos) << file;
    const Image png = readPng((dump / file).string());
    EXPECT_EQ(png.width, i["width"].get<int>()) << file;
    EXPECT_EQ(png.height, i["height"].get<int>()) << file;
    EXPECT_EQ(png.channels, i["channels"].get<int>()) << file;
    if (png.channels == 2 || png.channels == 4) {
      for (size_t k = size_t(png.channels) - 1; k < png.data.size(); k += size_t(png.channels)) {
        ASSERT_EQ(png.data[k], 1.0f) << file << " is not opaque";
      }
    }
  }
  EXPECT_GE(listed.size(), 1u);
  // Every pass has the fields `shadowlab lesson` reads, and a state card on the page; a pass the
  // technique timed names its source function and made GL calls (the trace saw them).
  size_t cards = 0;
  for (size_t at = html.find("class=\"state-card\""); at != std::string::npos;
       at = html.find("class=\"state-card\"", at + 1))
    ++cards;
  EXPECT_EQ(cards, j["passes"].size());
  bool anyState = false;
  for (const nlohmann::json& p : j["passes"]) {
    for (const char* key : {"section", "source", "state", "glsl", "replaces"})
      EXPECT_TRUE(p.contains(key)) << key << " in pass " << p["number"];
    EXPECT_FALSE(p["section"].get<std::string>().empty()) << p["number"];
    // A timed pass declares its own section (core/technique/technique.h PassTimer; no
    // technique-wide fallback): a paper of /work/shared/papers by its authors, or "ours" where no
    // paper has it.
    if (!p["timings"].empty()) {
      EXPECT_TRUE(citesAPaperOrSaysOurs(p["section"].get<std::string>()))
          << t.name << " pass " << p["number"] << ": " << p["section"];
    }
    // A pass that runs a program names the `// @pass` markers of its GLSL (core/gl/shaders.h), and
    // the marked files are files of a program the pass uses.
    // (A program made ready before the pass's timer, "before_pass", counts for the files but
    // does not make a CPU pass a GLSL one.)
    std::string programs;
    bool usesProgram = false;
    for (const nlohmann::json& l : p["state"])
      if (l["group"] == "program" && l["text"] != "program 0 (fixed function)") {
        programs += l["text"].get<std::string>() + "\n";
        usesProgram = usesProgram || !l.value("before_pass", false);
      }
    if (usesProgram) {
      EXPECT_FALSE(p["glsl"].empty()) << t.name << " pass " << p["number"];
    }
    for (const nlohmann::json& g : p["glsl"]) {
      EXPECT_NE(programs.find(g["file"].get<std::string>()), std::string::npos)
          << t.name << " pass " << p["number"] << " names " << g["file"] << " (marker "
          << g["marker"] << ") but uses only:\n"
          << programs;
    }
    if (!p["timings"].empty()) {
      EXPECT_FALSE(p["source"]["file"].get<std::string>().empty()) << p["number"];
      EXPECT_FALSE(p["source"]["function"].get<std::string>().empty()) << p["number"];
    }
    for (const nlohmann::json& l : p["state"]) {
      EXPECT_FALSE(l["group"].get<std::string>().empty());
      EXPECT_FALSE(l["text"].get<std::string>().empty());
    }
    anyState = anyState || !p["state"].empty();
  }
  EXPECT_TRUE(anyState) << "no GL call was traced";
  std::set<std::string> onDisk;
  for (const auto& e : fs::directory_iterator(dump)) onDisk.insert(e.path().filename().string());
  listed.insert("passes.json");
  listed.insert("index.html");
  EXPECT_EQ(onDisk, listed);
}

std::vector<std::string> techniqueNames() {
  std::vector<std::string> names;
  for (const Technique& t : allTechniques()) names.push_back(t.name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(All, EveryTechnique, ::testing::ValuesIn(techniqueNames()),
                         [](const auto& info) { return testName(info.param); });

}  // namespace
}  // namespace sl
