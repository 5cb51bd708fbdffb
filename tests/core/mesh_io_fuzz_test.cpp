// A deterministic fuzz test of the mesh loader (core/scene/mesh_io.h): small valid OBJ
// and PLY files (ascii and binary, plain and gzipped) mutated by a seeded PRNG — bit flips,
// truncations, inserted and repeated bytes, edited header counts and numbers, removed or
// replaced line ends, gzip wrapping and damaged gzip streams. Every case must either load into
// a valid mesh or throw InputError: any other exception fails the test, a crash or a hang
// fails the run, and ASan (the asan preset) reports any memory error on the way.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <random>
#include <string>
#include <typeinfo>
#include <vector>

#include "core/base/errors.h"
#include "core/scene/mesh_io.h"
#include "mesh_test_files.h"

namespace sl {
namespace {
namespace fs = std::filesystem;

// Cases per seed file (five seeds): a few thousand in all, about 10 s in the release build.
constexpr int kCasesPerSeed = 600;
// The PRNG's seed: fixed, so a failure names a case that reproduces.
constexpr std::uint32_t kFuzzSeed = 17;

// Replacements for a header count or a number: edges of every integer width, the caps,
// and floats that overflow, underflow or are not numbers.
const char* const kExtremeWords[] = {"0",
                                     "1",
                                     "2",
                                     "3",
                                     "-1",
                                     "255",
                                     "256",
                                     "65535",
                                     "65536",
                                     "2147483647",
                                     "2147483648",
                                     "4294967295",
                                     "4294967296",
                                     "1000000000",
                                     "5000001",
                                     "18446744073709551615",
                                     "18446744073709551616",
                                     "99999999999999999999999",
                                     "3e38",
                                     "1e39",
                                     "-3e38",
                                     "1e-45",
                                     "nan",
                                     "-inf",
                                     "inf",
                                     "0x10",
                                     "abc",
                                     "",
                                     "1/2/3",
                                     "//",
                                     "-0"};

enum class Mutation {
  kFlipBits,
  kTruncate,
  kInsertBytes,
  kDeleteSlice,
  kRepeatSlice,
  kReplaceWord,
  kEditElementCount,
  kRemoveNewlines,
  kNewlinesToCarriageReturns,
  kNewlinesToNuls,
  kDropLastNewline,
  kCount
};

class Fuzzer {
 public:
  explicit Fuzzer(std::uint32_t seed) : rng_(seed) {}

  std::size_t below(std::size_t n) { return n == 0 ? 0 : std::size_t(rng_() % n); }

  // Applies one mutation and returns its name (for the failure message).
  std::string mutate(std::string& d, Mutation m) {
    switch (m) {
      case Mutation::kFlipBits: {
        const std::size_t flips = 1 + below(8);
        for (std::size_t i = 0; i < flips && !d.empty(); ++i)
          d[below(d.size())] ^= char(1u << below(8));
        return "flip " + std::to_string(flips) + " bits";
      }
      case Mutation::kTruncate:
        d.resize(below(d.size()));
        return "truncate to " + std::to_string(d.size());
      case Mutation::kInsertBytes: {
        const std::size_t at = below(d.size() + 1), n = 1 + below(16);
        std::string bytes;
        for (std::size_t i = 0; i < n; ++i) bytes.push_back(char(rng_()));
        d.insert(at, bytes);
        return "insert " + std::to_string(n) + " bytes at " + std::to_string(at);
      }
      case Mutation::kDeleteSlice: {
        const std::size_t at = below(d.size()), n = 1 + below(32);
        d.erase(at, n);
        return "delete " + std::to_string(n) + " bytes at " + std::to_string(at);
      }
      case Mutation::kRepeatSlice: {
        const std::size_t at = below(d.size()), n = 1 + below(64), times = 1 + below(400);
        const std::string slice = d.substr(at, n);
        std::string repeated;
        for (std::size_t i = 0; i < times; ++i) repeated += slice;
        d.insert(at, repeated);
        return "repeat " + std::to_string(n) + " bytes at " + std::to_string(at) + " x" +
               std::to_string(times);
      }
      case Mutation::kReplaceWord: {
        // A number or word, picked among the runs of non-space characters.
        const std::vector<std::pair<std::size_t, std::size_t>> words = wordsOf(d);
        if (words.empty()) return "no word";
        const auto [at, n] = words[below(words.size())];
        const std::string word = kExtremeWords[below(std::size(kExtremeWords))];
        d.replace(at, n, word);
        return "word at " + std::to_string(at) + " -> '" + word + "'";
      }
      case Mutation::kEditElementCount: {
        std::vector<std::size_t> counts;  // positions of "element NAME " counts
        for (std::size_t p = d.find("element "); p != std::string::npos;
             p = d.find("element ", p + 1)) {
          const std::size_t space = d.find(' ', p + 8);
          if (space != std::string::npos) counts.push_back(space + 1);
        }
        if (counts.empty()) return mutate(d, Mutation::kReplaceWord);
        const std::size_t at = counts[below(counts.size())];
        const std::size_t end = std::min(d.find('\n', at), d.size());
        const std::string word = kExtremeWords[below(std::size(kExtremeWords))];
        d.replace(at, end - at, word);
        return "element count at " + std::to_string(at) + " -> '" + word + "'";
      }
      case Mutation::kRemoveNewlines:
        for (char& c : d)
          if (c == '\n') c = ' ';
        return "newlines to spaces";
      case Mutation::kNewlinesToCarriageReturns:
        for (char& c : d)
          if (c == '\n') c = '\r';
        return "newlines to \\r";
      case Mutation::kNewlinesToNuls:
        for (char& c : d)
          if (c == '\n' && below(2) == 0) c = '\0';
        return "some newlines to \\0";
      case Mutation::kDropLastNewline:
        while (!d.empty() && d.back() == '\n') d.pop_back();
        return "no final newline";
      case Mutation::kCount: break;
    }
    return "none";
  }

  Mutation anyMutation() { return Mutation(below(std::size_t(Mutation::kCount))); }

 private:
  static std::vector<std::pair<std::size_t, std::size_t>> wordsOf(const std::string& d) {
    std::vector<std::pair<std::size_t, std::size_t>> words;
    std::size_t i = 0;
    while (i < d.size()) {
      while (i < d.size() && std::isspace(static_cast<unsigned char>(d[i]))) ++i;
      const std::size_t start = i;
      while (i < d.size() && !std::isspace(static_cast<unsigned char>(d[i]))) ++i;
      if (i > start) words.push_back({start, i - start});
    }
    return words;
  }

  std::mt19937 rng_;
};

// A loaded mesh is usable: whole triangles, every index in range, finite positions within
// the cap, one finite unit normal per position.
void expectValidMesh(const Mesh& m, const std::string& what) {
  ASSERT_GT(m.indices.size(), 0u) << what;
  ASSERT_EQ(m.indices.size() % 3, 0u) << what;
  ASSERT_EQ(m.normals.size(), m.positions.size()) << what;
  for (unsigned i : m.indices) ASSERT_LT(i, m.positions.size()) << what;
  for (const glm::vec3& p : m.positions)
    for (int k = 0; k < 3; ++k) {
      ASSERT_TRUE(std::isfinite(p[k])) << what;
      ASSERT_LE(std::abs(p[k]), kMaxMeshCoordinate) << what;
    }
  for (const glm::vec3& n : m.normals)
    // Unit length up to float rounding of the normalisation (a few ulps).
    ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f) << what;
}

long peakResidentKiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;  // kibibytes on Linux
}

TEST(MeshLoaderFuzz, EveryMutationLoadsOrIsAnInputError) {
  const fs::path dir = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "core-mesh-fuzz";
  fs::create_directories(dir);
  const long peakBefore = peakResidentKiB();
  Fuzzer fuzz(kFuzzSeed);
  int loaded = 0, refused = 0;
  const std::vector<testing_meshes::SeedFile>& seeds = testing_meshes::seedFiles();
  for (int c = 0; c < kCasesPerSeed * int(seeds.size()); ++c) {
    const testing_meshes::SeedFile& seed = seeds[std::size_t(c) % seeds.size()];
    std::string bytes = seed.bytes;
    std::string name = seed.name;
    std::string what = "case " + std::to_string(c) + " (" + seed.name + "):";
    // One or two mutations of the file, then (a quarter of the time) gzip it; an eighth of
    // the time the gzip stream itself is damaged afterwards.
    const std::size_t mutations = 1 + fuzz.below(2);
    for (std::size_t i = 0; i < mutations; ++i) {
      what += ' ';  // appended in place: GCC 12's -Wrestrict misfires on " " + std::string
      what += fuzz.mutate(bytes, fuzz.anyMutation());
    }
    if (fuzz.below(4) == 0) {
      bytes = testing_meshes::gzip(bytes);
      name += ".gz";
      what += ", gzipped";
      if (fuzz.below(2) == 0) {
        const Mutation onStream = fuzz.below(2) == 0 ? Mutation::kFlipBits : Mutation::kTruncate;
        what += ", stream: " + fuzz.mutate(bytes, onStream);
      }
    }
    const fs::path path = dir / name;
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
    try {
      const Mesh m = loadMesh(path.string());
      expectValidMesh(m, what);
      ++loaded;
    } catch (const InputError& e) {
      ASSERT_NE(std::string(e.what()).find(path.string()), std::string::npos)
          << what << " -> message without the file name: " << e.what();
      ++refused;
    } catch (const std::exception& e) {
      FAIL() << what << " -> " << typeid(e).name() << ": " << e.what();
    }
  }
  // Both outcomes occur: the mutations neither all break the files nor leave them all intact.
  EXPECT_GT(loaded, 0);
  EXPECT_GT(refused, 0);
  // No case allocated for what a file merely declares (up to 4e9 vertices): the process's
  // peak resident memory grew by well under the 1 GiB that even the caps would allow.
  constexpr long kMaxPeakGrowthKiB = 1024 * 1024;
  EXPECT_LT(peakResidentKiB() - peakBefore, kMaxPeakGrowthKiB);
  std::cout << "[          ] " << loaded << " cases loaded, " << refused << " refused\n";
}

}  // namespace
}  // namespace sl
