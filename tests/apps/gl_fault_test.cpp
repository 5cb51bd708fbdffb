// `shadowlab render` under an injected GL fault (SHADOWLAB_INJECT_GL_FAULT, core/gl/gl_fault.h):
// at any pass of legacy and modern techniques, a GL error or a missing entry point ends the run
// with exit 3, one line on stderr naming the pass and the fault, and no output at all — not the
// image, not the mask, not the pass dump, no temporary left beside them.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "apps/command_util.h"
#include "core/base/image.h"
#include "tests/test_names.h"

namespace sl::test {
namespace {

namespace fs = std::filesystem;

struct FaultCase {
  std::string technique;
  std::string options;  // render options besides --scene, --technique and the outputs
  std::string fault;    // the variable's value
  std::string pass;     // the pass the fault falls in, as the message names it
};

std::ostream& operator<<(std::ostream& os, const FaultCase& c) {
  return os << c.technique << " " << c.fault;
}

const std::string kSmall = "--size 96x72 --shadow-map 128";
// Where a pass#N or call#N trigger falls depends on the technique's pass and call order, which
// its code may change: those cases check the fault's note, not the pass it names.
const std::string kAnyPass = "*";

// Runs `shadowlab render` on the brabec scene in `dir` with every output (--out, --mask,
// --dump-passes) under the variable's value `fault` (none when empty).
CommandResult renderWithFault(const fs::path& dir, const std::string& technique,
                              const std::string& options, const std::string& fault) {
  const std::string env = fault.empty() ? "" : "SHADOWLAB_INJECT_GL_FAULT='" + fault + "' ";
  return runBinary(env + SHADOWLAB_BINARY,
                   "render --scene brabec --technique " + technique + " " + options + " --out " +
                       (dir / "x.png").string() + " --mask " + (dir / "m.png").string() +
                       " --dump-passes " + (dir / "D").string(),
                   dir);
}

// What the run left in `dir` besides runBinary's own stdout.txt and stderr.txt.
std::set<std::string> leftBehind(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name != "stdout.txt" && name != "stderr.txt") names.insert(name);
  }
  return names;
}

class RenderUnderFault : public ::testing::TestWithParam<FaultCase> {};

TEST_P(RenderUnderFault, ExitsThreeWithOneLineAndNoOutput) {
  const FaultCase& c = GetParam();
  const fs::path dir = testDir("apps", true);
  const CommandResult r = renderWithFault(dir, c.technique, c.options, c.fault);
  EXPECT_EQ(r.status, 3) << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
  EXPECT_EQ(r.err.rfind("shadowlab: GL: ", 0), 0u) << r.err;
  const std::string note = "(injected GL fault " + c.fault + ", " +
                           (c.pass == kAnyPass ? "" : "in pass '" + c.pass + "')");
  EXPECT_NE(r.err.find(note), std::string::npos) << r.err;
  const bool missing = c.fault.rfind("missing", 0) == 0;
  EXPECT_NE(r.err.find(missing ? "has no entry point gl" : "GL_INVALID_OPERATION"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(leftBehind(dir).empty()) << "left: " << ::testing::PrintToString(leftBehind(dir));
}

INSTANTIATE_TEST_SUITE_P(
    Passes, RenderUnderFault,
    ::testing::Values(
        FaultCase{"legacy.hw", kSmall, "error@pass=1", "1 depth from light"},
        FaultCase{"legacy.hw", kSmall, "missing@pass=mesh",
                  "mesh feeding: triangles split for per-vertex spotlight lighting"},
        FaultCase{"legacy.ramp", kSmall, "error@pass=3", "3 projective pass: subtract shadow map"},
        FaultCase{"legacy.pcf", kSmall + " --filter 2", "missing@pass=4",
                  "4 copy: colour table + colour matrix -> alpha"},
        FaultCase{"legacy.fast-pcf", kSmall + " --filter 2", "error@pass=2",
                  "2 copy to texture through the 3x3 packing convolution"},
        FaultCase{"legacy.fast-pcf", kSmall + " --filter 4", "missing@pass=7",
                  "7 lighting x shadow term"},
        FaultCase{"modern.hw", kSmall, "missing@pass=1", "1 depth from light"},
        FaultCase{"modern.pcf", kSmall + " --filter 3", "error@pass=2",
                  "2 camera pass = legacy passes 2-6: depth, subtract, colour table, colour "
                  "matrix, accumulate, shade (pcf_shadow.frag)"},
        FaultCase{"modern.csm", kSmall, "error@pass=5b",
                  "5b camera pass: classification (depth bounds)"},
        FaultCase{"modern.volumes", "--size 96x72", "missing@pass=3", "3 stencil volumes (z-fail)"},
        FaultCase{"legacy.hw", kSmall, "error@pass#3", kAnyPass},
        FaultCase{"legacy.hw", kSmall, "error@call#40", kAnyPass},
        FaultCase{"modern.gems16", kSmall, "missing@call#60", kAnyPass}),
    [](const auto& info) { return testName(info.param.technique + "_" + info.param.fault); });

// The same commands without the variable succeed and write every output: the cases above
// fail because of the fault, not because of their options.
TEST(RenderUnderFault, WithoutTheVariableTheSameRenderWritesEveryOutput) {
  const fs::path dir = testDir("apps", true);
  const CommandResult r = renderWithFault(dir, "legacy.fast-pcf", kSmall + " --filter 2", "");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(leftBehind(dir), (std::set<std::string>{"D", "m.png", "x.png"}));
}

// A fault whose trigger no pass meets changes nothing: exit 0 and the same pixels as a run
// without the variable (legacy.pcf --filter 2 runs fewer than 99 passes).
TEST(RenderUnderFault, AnUnmetFaultLeavesTheImageUnchanged) {
  const fs::path plain = testDir("apps", true) / "plain", armed = testDir("apps") / "armed";
  fs::create_directories(plain);
  fs::create_directories(armed);
  const std::string options = kSmall + " --filter 2";
  ASSERT_EQ(renderWithFault(plain, "legacy.pcf", options, "").status, 0);
  const CommandResult r = renderWithFault(armed, "legacy.pcf", options, "error@pass#99");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(readPng((plain / "x.png").string()).data == readPng((armed / "x.png").string()).data);
  EXPECT_TRUE(readPng((plain / "m.png").string()).data == readPng((armed / "m.png").string()).data);
}

// pass=ID names a pass-table id; one the technique does not have is an input error listing the
// ids it has (before anything is rendered or written).
TEST(RenderUnderFault, APassIdTheTechniqueLacksIsAnInputErrorListingItsIds) {
  const fs::path dir = testDir("apps", true);
  const CommandResult r = renderWithFault(dir, "legacy.ramp", kSmall, "error@pass=9z");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
  EXPECT_NE(r.err.find("legacy.ramp has no pass '9z' (its pass ids: mesh, 1, 2, 3, 4, 5)"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(leftBehind(dir).empty());
}

// A pass's display name is not its id: "pass=3 projective" is refused when the variable is read.
TEST(RenderUnderFault, APassNameInsteadOfAnIdIsAnInputError) {
  const fs::path dir = testDir("apps", true);
  const CommandResult r = renderWithFault(dir, "legacy.ramp", kSmall, "error@pass=3 projective");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("pass= takes a pass id"), std::string::npos) << r.err;
  EXPECT_TRUE(leftBehind(dir).empty());
}

TEST(RenderUnderFault, AMalformedVariableIsAnInputError) {
  const fs::path dir = testDir("apps", true);
  const CommandResult r = renderWithFault(dir, "legacy.hw", kSmall, "error@pass#zero");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
  EXPECT_NE(r.err.find("SHADOWLAB_INJECT_GL_FAULT"), std::string::npos) << r.err;
  EXPECT_TRUE(leftBehind(dir).empty());
}

}  // namespace
}  // namespace sl::test
