// tests/apps/command_util.h — what the apps tests share: a per-test output folder, reading a
// file back, and running a binary with its exit status, stdout and stderr.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace sl::test {

struct CommandResult {
  int status = -1;
  std::string out;
  std::string err;
};

// build/test-output/<suite>/<test name>: one folder per test, since ctest runs the cases as
// parallel processes. `fresh` empties it first.
inline std::filesystem::path testDir(const std::string& suite, bool fresh = false) {
  std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  for (char& c : name)
    if (c == '/' || c == '.') c = '_';
  const std::filesystem::path d = std::filesystem::path(SHADOWLAB_TEST_OUTPUT_DIR) / suite / name;
  if (fresh) std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs `binary args` through the shell; its stdout and stderr go through files in `dir`.
inline CommandResult runBinary(const std::string& binary, const std::string& args,
                               const std::filesystem::path& dir) {
  const std::filesystem::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string cmd = binary + " " + args + " >" + out.string() + " 2>" + err.string();
  const int raw = std::system(cmd.c_str());
  CommandResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

}  // namespace sl::test
