// tests/apps/course_cli_test.cpp — `shadowlab course`'s bad input: one line on stderr, exit 2,
// nothing written (the course itself: tests/figures/course_test.cpp, tests/browser).
#include <gtest/gtest.h>

#include <filesystem>

#include "command_util.h"

namespace fs = std::filesystem;
using sl::test::runBinary;
using sl::test::testDir;

TEST(CourseCommand, WithoutOutIsOneLineExit2) {
  const fs::path dir = testDir("course_cli", true);
  const auto r = runBinary(SHADOWLAB_BINARY, "course", dir);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("--out"), std::string::npos) << r.err;
}

TEST(CourseCommand, ALabAddressThatIsNotHttpIsExit2AndWritesNothing) {
  const fs::path dir = testDir("course_cli", true);
  const auto r = runBinary(SHADOWLAB_BINARY,
                           "course --out " + (dir / "c").string() + " --lab ftp://host/", dir);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("--lab"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "c"));
}
