// Bad input the shadowlab command used to take: a .jpg --out, a true/false flag, a
// missing scene file reported as an unknown scene, a user's mesh looked up in assets/. Each is
// one line on stderr naming the problem, exit status 2 and no file; the good cases run.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "command_util.h"
#include "core/base/image.h"
#include "core/technique/technique.h"
#include "figures/figure_spec.h"
#include "registry/registry.h"

namespace sl {
namespace {
namespace fs = std::filesystem;
using test::CommandResult;

constexpr const char* kSmall = " --size 64x48 --shadow-map 64";

CommandResult shadowlab(const fs::path& dir, const std::string& args) {
  return test::runBinary(SHADOWLAB_BINARY, args, dir);
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

// Exit 2, exactly `line` on stderr (after "shadowlab: "), nothing on stdout.
void expectRefused(const CommandResult& r, const std::string& line) {
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err, "shadowlab: " + line + "\n");
  EXPECT_TRUE(r.out.empty()) << r.out;
}

// Only the files the test made itself (the command's stdout/stderr captures and `keep`).
void expectNothingWritten(const fs::path& dir, std::initializer_list<const char*> keep = {}) {
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name == "stdout.txt" || name == "stderr.txt") continue;
    bool kept = false;
    for (const char* k : keep) kept = kept || name == k;
    EXPECT_TRUE(kept) << "left behind: " << e.path();
  }
}

// An image output whose name does not end in .png: PNG bytes under a .jpg name were written
// with exit 0 on main.
TEST(InputNames, ImageOutputsArePngOnly) {
  const fs::path d = test::testDir("input-names", true);
  const std::string render = "render --scene analytic --technique legacy.hw" + std::string(kSmall);
  expectRefused(shadowlab(d, render + " --out " + (d / "a.jpg").string()),
                "--out " + (d / "a.jpg").string() + ": PNG only (the name must end in .png)");
  expectRefused(shadowlab(d, render + " --out " + (d / "a.png").string() + " --mask " +
                                 (d / "m.tif").string()),
                "--mask " + (d / "m.tif").string() + ": PNG only (the name must end in .png)");
  expectRefused(shadowlab(d, "compare --scene analytic --a legacy.hw --b modern.hw" +
                                 std::string(kSmall) + " --diff " + (d / "diff").string()),
                "--diff " + (d / "diff").string() + ": PNG only (the name must end in .png)");
  expectNothingWritten(d);
  // Any case of .png is a PNG name; --help says PNG only for each of the three.
  const CommandResult upper = shadowlab(d, render + " --out " + (d / "UPPER.PNG").string());
  EXPECT_EQ(upper.status, 0) << upper.err;
  EXPECT_EQ(readPng((d / "UPPER.PNG").string()).width, 64);
  for (const char* command : {"render", "compare"}) {
    const CommandResult help = shadowlab(d, std::string(command) + " --help");
    EXPECT_EQ(help.status, 0);
    EXPECT_NE(help.out.find("PNG only"), std::string::npos) << help.out;
  }
}

// main answered "unknown scene 'missing.json' (known: ...)".
TEST(InputNames, AMissingSceneFileIsNamed) {
  const fs::path d = test::testDir("input-names", true);
  const std::string tail =
      " --technique legacy.hw" + std::string(kSmall) + " --out " + (d / "out.png").string();
  expectRefused(shadowlab(d, "render --scene missing.json" + tail),
                "scene file missing.json: no such file");
  expectRefused(shadowlab(d, "render --scene " + (d / "no" / "scene").string() + tail),
                "scene file " + (d / "no" / "scene").string() + ": no such file");
  expectNothingWritten(d);
}

// A user's scene with its mesh beside it renders (main looked for assets/table.obj); a missing
// mesh names where it looked.
TEST(InputNames, MeshesAreReadBesideTheSceneFile) {
  const fs::path d = test::testDir("input-names", true);
  write(d / "room" / "table.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  write(d / "room" / "scene.json",
        R"({"objects": [{"mesh": {"primitive": "plane"}},
                        {"mesh": {"file": "table.obj"}, "translate": [0, 1, 0]}]})");
  const std::string tail =
      " --technique legacy.hw" + std::string(kSmall) + " --out " + (d / "out.png").string();
  const CommandResult ok =
      shadowlab(d, "render --scene " + (d / "room" / "scene.json").string() + tail);
  EXPECT_EQ(ok.status, 0) << ok.err;
  EXPECT_TRUE(fs::exists(d / "out.png"));
  fs::remove(d / "out.png");
  write(d / "lost.json", R"({"objects": [{"mesh": {"file": "table.obj"}}]})");
  expectRefused(shadowlab(d, "render --scene " + (d / "lost.json").string() + tail),
                "scene file " + (d / "lost.json").string() +
                    ": objects[0].mesh.file table.obj: no such file (looked in " +
                    fs::absolute(d / "table.obj").lexically_normal().string() + ")");
  expectNothingWritten(d, {"room", "lost.json"});
}

// `shadowlab list` says on|off: main also took remap=false, plan=1.
TEST(InputNames, FlagsTakeOnOrOff) {
  const fs::path d = test::testDir("input-names", true);
  const std::string out = " --out " + (d / "out.png").string();
  expectRefused(shadowlab(d, "render --scene analytic --technique modern.smoothies" +
                                 std::string(kSmall) + " --param remap=false" + out),
                "--param remap=false: expected on or off");
  expectRefused(shadowlab(d, "render --scene analytic --technique modern.hw" + std::string(kSmall) +
                                 " --param plan=1" + out),
                "--param plan=1: expected on or off");
  expectNothingWritten(d);
  const CommandResult ok = shadowlab(d, "render --scene analytic --technique modern.smoothies" +
                                            std::string(kSmall) + " --param remap=off" + out);
  EXPECT_EQ(ok.status, 0) << ok.err;
}

// Nothing in the repository spells a flag otherwise: every figure panel's --params pass the
// checks a render makes (checkParams refuses a flag word other than on and off).
TEST(InputNames, EveryFigurePanelsParamsAreAccepted) {
  for (const figures::FigureSpec& f : figures::figureList())
    for (const figures::PanelSpec& p : f.panels) {
      if (p.technique.empty() || p.params.empty()) continue;
      RenderParams params;
      params.extra = p.params;
      EXPECT_NO_THROW(checkParams(findTechnique(p.technique), params, 0)) << f.id << " " << p.label;
    }
}

// docs/scene-files.md's minimal example through the command, at a tiny size.
TEST(InputNames, TheMinimalExampleRenders) {
  const fs::path d = test::testDir("input-names", true);
  const fs::path scene =
      fs::path(SHADOWLAB_SOURCE_DIR) / "docs" / "examples" / "minimal-scene.json";
  const CommandResult r =
      shadowlab(d, "render --scene " + scene.string() + " --technique modern.hw" +
                       std::string(kSmall) + " --out " + (d / "minimal.png").string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"scene\":\"minimal-scene\""), std::string::npos) << r.out;
  const Image image = readPng((d / "minimal.png").string());
  EXPECT_EQ(image.width, 64);
  EXPECT_EQ(image.height, 48);
}

}  // namespace
}  // namespace sl
