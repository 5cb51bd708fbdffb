// tests/teach/exercise_cli_test.cpp — `shadowlab exercise`'s command line: PASS exits 0, FAIL 1
// (one line on stdout each), bad input 2 with one line on stderr and nothing on stdout.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "apps/command_util.h"
#include "registry/shadow_error.h"

namespace fs = std::filesystem;
using sl::test::runBinary;
using sl::test::slurp;
using sl::test::testDir;

namespace {

long lines(const std::string& s) { return long(std::count(s.begin(), s.end(), '\n')); }

void expectBadInput(const std::string& args, const std::string& word) {
  const fs::path dir = testDir("exercise_cli", true);
  const auto r = runBinary(SHADOWLAB_BINARY, args, dir);
  EXPECT_EQ(r.status, 2) << args << ": " << r.err;
  EXPECT_EQ(lines(r.err), 1) << args << ": " << r.err;
  EXPECT_NE(r.err.find(word), std::string::npos) << args << ": " << r.err;
  EXPECT_TRUE(r.out.empty()) << args << ": " << r.out;
}

TEST(ExerciseCommand, ListNamesEveryExerciseOnALine) {
  const fs::path dir = testDir("exercise_cli", true);
  const auto r = runBinary(SHADOWLAB_BINARY, "exercise list", dir);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_GE(lines(r.out), 6);
  EXPECT_NE(r.out.find("pcf-3x3  legacy  parameter file"), std::string::npos) << r.out;
}

TEST(ExerciseCommand, ShowPrintsTheTaskAndTheStartingFile) {
  const fs::path dir = testDir("exercise_cli", true);
  const auto r = runBinary(SHADOWLAB_BINARY, "exercise show pcf-3x3", dir);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("filter=2"), std::string::npos) << r.out;
}

TEST(ExerciseCommand, StartWritesTheStartingFileAndNeverOverwrites) {
  const fs::path dir = testDir("exercise_cli", true);
  const fs::path out = dir / "answer.params";
  auto r = runBinary(SHADOWLAB_BINARY, "exercise start pcf-3x3 --out " + out.string(), dir);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(slurp(out).find("filter=2"), std::string::npos);
  std::ofstream(out) << "filter=3\n";
  r = runBinary(SHADOWLAB_BINARY, "exercise start pcf-3x3 --out " + out.string(), dir);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(slurp(out), "filter=3\n");
}

TEST(ExerciseCommand, GradeExitsZeroOnPassAndOneOnFail) {
  if (!sl::haveRayTracedReferences()) GTEST_SKIP() << "built without the ray tracer";
  const fs::path dir = testDir("exercise_cli", true);
  auto r = runBinary(SHADOWLAB_BINARY, "exercise grade pcf-colour-passes 3", dir);
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(r.out.rfind("PASS pcf-colour-passes: ", 0), 0u) << r.out;
  EXPECT_EQ(lines(r.out), 1) << r.out;
  r = runBinary(SHADOWLAB_BINARY, "exercise grade pcf-colour-passes 2", dir);
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_EQ(r.out.rfind("FAIL pcf-colour-passes: ", 0), 0u) << r.out;
  EXPECT_EQ(lines(r.out), 1) << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(ExerciseCommand, BadInputIsOneLineExit2) {
  const fs::path dir = testDir("exercise_cli", true);
  expectBadInput("exercise", "subcommand");
  expectBadInput("exercise frobnicate", "frobnicate");
  expectBadInput("exercise show no-such", "no-such");
  expectBadInput("exercise grade no-such 3", "no-such");
  expectBadInput("exercise grade pcf-3x3", "usage");
  expectBadInput("exercise grade pcf-3x3 " + (dir / "missing.params").string(), "missing.params");
  expectBadInput("exercise grade ramp-acne-bias two", "two");
  expectBadInput("exercise start ramp-acne-bias --out " + (dir / "x").string(), "number");
}

}  // namespace
