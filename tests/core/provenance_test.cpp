// What made an output: the PNG text chunks written by writePng and read back
// through libpng, the shell quoting of the recorded command line, and the effective --params
// a render reads (core/base/provenance.h, core/base/image.h, core/technique/technique.h).
#include "core/base/provenance.h"

#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>

#include "core/base/image.h"
#include "core/technique/technique.h"

namespace sl {
namespace {
namespace fs = std::filesystem;

fs::path tempDir() {
  fs::path d = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "core-provenance";
  fs::create_directories(d);
  return d;
}

TEST(Provenance, BuildCommitIsAHashOrUnknown) {
  const std::string& commit = buildCommit();
  ASSERT_FALSE(commit.empty());
  if (commit == "unknown") GTEST_SKIP() << "built without git: the commit is 'unknown'";
  const std::string hash = commit.substr(0, commit.find('-'));
  EXPECT_GE(hash.size(), 7u) << commit;  // git's shortest abbreviation
  for (char c : hash) EXPECT_TRUE(std::isxdigit(static_cast<unsigned char>(c))) << commit;
  const std::string rest = commit.substr(hash.size());
  EXPECT_TRUE(rest.empty() || rest == "-dirty") << commit;
  EXPECT_EQ(softwareName(), "shadowlab " + commit);
}

TEST(Provenance, PngCarriesSoftwareCommandAndParametersAsText) {
  const std::string path = (tempDir() / "made.png").string();
  const Provenance made{"shadowlab render --scene brabec --out made.png",
                        R"({"technique":"legacy.pcf","filter":3})"};
  const Image image(9, 5, 3, 0.25f);
  writePng(path, image, 8, made);
  const auto text = readPngText(path);
  ASSERT_EQ(text.count("Software"), 1u);
  EXPECT_EQ(text.at("Software"), "shadowlab " + buildCommit());
  EXPECT_EQ(text.at("shadowlab:command"), made.command);
  EXPECT_EQ(text.at("shadowlab:parameters"), made.parameters);
  // The pixels are unchanged by the text.
  const Image back = readPng(path);
  ASSERT_EQ(back.data.size(), image.data.size());
  for (size_t i = 0; i < image.data.size(); ++i)
    EXPECT_NEAR(back.data[i], image.data[i], 0.5f / 255.0f) << i;  // the 8-bit grid
}

TEST(Provenance, SixteenBitPngWithoutProvenanceStillNamesTheSoftware) {
  const std::string path = (tempDir() / "plain16.png").string();
  writePng(path, Image(4, 4, 1, 0.5f), 16);
  const auto text = readPngText(path);
  EXPECT_EQ(text.at("Software"), "shadowlab " + buildCommit());
  EXPECT_EQ(text.count("shadowlab:parameters"), 0u);
  // This test binary records no command line, so there is none to write.
  EXPECT_EQ(text.count("shadowlab:command"), commandLine().empty() ? 0u : 1u);
}

TEST(Provenance, ShellQuotingReadsBackAsTheArguments) {
  EXPECT_EQ(shellQuote("--size=64x48"), "--size=64x48");
  EXPECT_EQ(shellQuote("a b"), "'a b'");
  EXPECT_EQ(shellQuote("it's"), "'it'\\''s'");
  EXPECT_EQ(shellQuote(""), "''");
  EXPECT_EQ(shellQuote("sc\xff\n"), "$'sc\\xff\\x0a'");  // always printable ASCII
  EXPECT_EQ(shellJoin({"shadowlab", "render", "--out", "my image.png"}),
            "shadowlab render --out 'my image.png'");
  const char* argv[] = {"shadowlab", "list"};
  recordCommandLine(2, argv);
  EXPECT_EQ(commandLine(), "shadowlab list");
}

TEST(EffectiveParams, DefaultsReadByTheTechniqueJoinTheGivenValues) {
  RenderParams p;
  p.extra["order"] = "8";
  p.extra["offset"] = "auto";  // read through `extra` only: kept as given
  p.readLog = std::make_shared<ParamReadLog>();
  EXPECT_EQ(p.integer("order", 4, 1, 16), 8);
  EXPECT_DOUBLE_EQ(p.number("alpha", 0.5, 0, 1), 0.5);
  EXPECT_EQ(p.text("storage", "8", {"8", "float"}), "8");
  EXPECT_FALSE(p.flag("remap", false));
  const auto values = effectiveParams(p);
  const std::map<std::string, std::string> expected = {
      {"order", "8"}, {"offset", "auto"}, {"alpha", "0.5"}, {"storage", "8"}, {"remap", "off"}};
  EXPECT_EQ(values, expected);
  // Without a log, the given keys only.
  RenderParams plain;
  plain.extra["order"] = "8";
  EXPECT_DOUBLE_EQ(plain.number("alpha", 0.5, 0, 1), 0.5);
  EXPECT_EQ(effectiveParams(plain), (std::map<std::string, std::string>{{"order", "8"}}));
}

}  // namespace
}  // namespace sl
