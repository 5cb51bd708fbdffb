// tests/apps/bench_cli_test.cpp — `shadowlab bench` runs the techniques and scenes it is given:
// repeated options and comma-separated lists both count (a repeated --technique used to keep
// only the last one, with exit status 0).
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "command_util.h"

namespace sl {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;
using test::CommandResult;

fs::path dir() { return test::testDir("bench-cli"); }

CommandResult shadowlab(const std::string& args) {
  return test::runBinary(SHADOWLAB_BINARY, args, dir());
}

// The (scene, technique) pairs of the rows bench printed for the two scenes the tests name.
std::set<std::pair<std::string, std::string>> rowsOf(const std::string& out) {
  std::set<std::pair<std::string, std::string>> rows;
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    const json row = json::parse(line);
    // The claim scenes bench derives from brabec (trees-far, brabec-light-away) are its own.
    if (row.contains("technique") && (row["scene"] == "brabec" || row["scene"] == "analytic"))
      rows.insert({row["scene"].get<std::string>(), row["technique"].get<std::string>()});
  }
  return rows;
}

// A tiny window: the references and two techniques' variants in a few seconds.
constexpr const char* kTiny = " --quick --size 48x36 --out ";

TEST(BenchCli, RepeatedAndListedTechniquesAndScenesAllRun) {
  const std::set<std::pair<std::string, std::string>> expected = {
      {"brabec", "modern.pcf"},
      {"brabec", "modern.gems16"},
      {"analytic", "modern.pcf"},
      {"analytic", "modern.gems16"}};
  const CommandResult repeated =
      shadowlab("bench --scene brabec --scene analytic --technique modern.pcf --technique "
                "modern.gems16" +
                std::string(kTiny) + (dir() / "repeated").string());
  ASSERT_EQ(repeated.status, 0) << repeated.err;
  EXPECT_EQ(rowsOf(repeated.out), expected);
  const CommandResult listed = shadowlab("bench --scene brabec,analytic --technique "
                                         "modern.pcf,modern.gems16" +
                                         std::string(kTiny) + (dir() / "listed").string());
  ASSERT_EQ(listed.status, 0) << listed.err;
  EXPECT_EQ(rowsOf(listed.out), expected);
}

TEST(BenchCli, AnUnknownOrEmptyNameInAListIsAnInputError) {
  const CommandResult unknown = shadowlab("bench --technique modern.pcf,modern.nope" +
                                          std::string(kTiny) + (dir() / "unknown").string());
  EXPECT_EQ(unknown.status, 2) << unknown.err;
  EXPECT_NE(unknown.err.find("modern.nope"), std::string::npos) << unknown.err;
  EXPECT_TRUE(unknown.out.empty());
  const CommandResult empty = shadowlab("bench --technique modern.pcf, --scene brabec" +
                                        std::string(kTiny) + (dir() / "empty").string());
  EXPECT_EQ(empty.status, 2) << empty.err;
  EXPECT_NE(empty.err.find("--technique 'modern.pcf,': an empty name"), std::string::npos)
      << empty.err;
}

}  // namespace
}  // namespace sl
