// tests/fuzz/replay_test.cpp — the fuzz targets (tests/fuzz/targets/*.cpp) replayed on their
// corpora in the ordinary build: every file under tests/fuzz/corpus/<target>/ (the seeds, the
// inputs libFuzzer's runs kept, and the inputs of past findings) goes through the target's
// LLVMFuzzerTestOneInput, which returns for an input that loads or is an InputError and aborts
// on anything else. The coverage-guided runs themselves: scripts/fuzz.sh (docs/validation.md
// "Fuzzing").
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

// Each target's LLVMFuzzerTestOneInput, renamed per target when compiled into this test
// (tests/CMakeLists.txt): one executable holds them all.
extern "C" int sl_fuzz_scene_file(const std::uint8_t* data, std::size_t size);
extern "C" int sl_fuzz_mesh(const std::uint8_t* data, std::size_t size);
extern "C" int sl_fuzz_lab_request(const std::uint8_t* data, std::size_t size);

namespace {

namespace fs = std::filesystem;
using Target = int (*)(const std::uint8_t*, std::size_t);

// The corpus files of `target`, sorted (a stable order for the log).
std::vector<fs::path> corpusFiles(const std::string& target) {
  std::vector<fs::path> files;
  for (const auto& e :
       fs::directory_iterator(fs::path(SHADOWLAB_SOURCE_DIR) / "tests/fuzz/corpus" / target))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

void replay(const std::string& target, Target run) {
  const std::vector<fs::path> files = corpusFiles(target);
  ASSERT_FALSE(files.empty()) << "no corpus for " << target;
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // libFuzzer's contract: the target returns 0 for every input it does not abort on. An
    // exception other than InputError leaves the target (libFuzzer: a crash): a finding here.
    try {
      EXPECT_EQ(run(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()), 0);
    } catch (const std::exception& e) {
      ADD_FAILURE() << file.string() << " threw (not an InputError): " << e.what();
    }
  }
}

}  // namespace

TEST(FuzzReplay, SceneFileCorpus) { replay("scene_file", sl_fuzz_scene_file); }
TEST(FuzzReplay, MeshCorpus) { replay("mesh", sl_fuzz_mesh); }
TEST(FuzzReplay, LabRequestCorpus) { replay("lab_request", sl_fuzz_lab_request); }
