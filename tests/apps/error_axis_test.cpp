// tests/apps/error_axis_test.cpp — the one error definition (docs/error.md) seen from the
// command line: compare scores against either truth with --a-param / --b-param, names its
// metric and truth, and prints the number bench prints for the same pair.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "command_util.h"

namespace sl {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;
using test::CommandResult;

fs::path dir() { return test::testDir("error-axis"); }

CommandResult shadowlab(const std::string& args) {
  return test::runBinary(SHADOWLAB_BINARY, args, dir());
}

int lines(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

// The bench's quick window is 256x192; this small one keeps both runs within seconds.
constexpr const char* kSize = "64x48";

TEST(ErrorAxis, CompareAndBenchPrintTheSameNumberForTheSamePair) {
  const CommandResult c = shadowlab(std::string("compare --scene brabec --size ") + kSize +
                                    " --a modern.hw --b reference.hard --b-param pixel=area");
  ASSERT_EQ(c.status, 0) << c.err;
  const json compared = json::parse(c.out);
  EXPECT_EQ(compared["metric"], "area");
  EXPECT_EQ(compared["truth"], "reference.hard pixel=area");
  EXPECT_EQ(compared["b_params"]["pixel"], "area");
  EXPECT_TRUE(compared["a_params"].find("pixel") == compared["a_params"].end())
      << "--b-param goes to B only";

  const fs::path out = dir() / "bench";
  const CommandResult b = shadowlab(std::string("bench --quick --scene brabec --technique ") +
                                    "modern.hw --size " + kSize + " --out " + out.string());
  ASSERT_EQ(b.status, 0) << b.err;
  std::istringstream rows(b.out);
  bool found = false;
  for (std::string line; std::getline(rows, line);) {
    const json row = json::parse(line);
    if (row.value("scene", "") != "brabec" || row.value("technique", "") != "modern.hw" ||
        row.value("variant", "") != "default")
      continue;
    found = true;
    EXPECT_EQ(row["error"]["metric"], "area");
    EXPECT_EQ(row["error"]["truth"], "reference.hard pixel=area");
    // One definition, one number: the same renders and the same arithmetic (bit for bit up to
    // the JSON's shortest round-trip printing).
    EXPECT_DOUBLE_EQ(row["error"]["rmse"].get<double>(), compared["rmse"].get<double>());
    EXPECT_EQ(row["error"]["scored_pixels"], compared["scored_pixels"]);
    EXPECT_DOUBLE_EQ(row["error"]["left_out"]["share"].get<double>(),
                     compared["left_out"]["share"].get<double>());
  }
  EXPECT_TRUE(found) << b.out;

  // The point metric is the other truth: compare without --b-param, bench's centre column.
  const CommandResult p = shadowlab(std::string("compare --scene brabec --size ") + kSize +
                                    " --a modern.hw --b reference.hard");
  ASSERT_EQ(p.status, 0) << p.err;
  EXPECT_EQ(json::parse(p.out)["metric"], "point");
}

double areaRmse(const std::string& scene, const std::string& technique) {
  const CommandResult r = shadowlab("compare --scene " + scene + " --size 256x192 --a " +
                                    technique + " --b reference.hard --b-param pixel=area");
  EXPECT_EQ(r.status, 0) << r.err;
  return r.status == 0 ? json::parse(r.out)["rmse"].get<double>() : -1.0;
}

// An exact technique is not ranked below an approximate one of the same kind: against the area
// truth the binary shadow volumes beat the binary (nearest-compare) 512² map on both quick
// bench scenes. (Against the bilinear 2x2 compare they lose in windows this small, where its
// one-texel blur is close to the pixel's box filter: real antialiasing, docs/error.md.)
TEST(ErrorAxis, ExactVolumesBeatAnUnfilteredMapByTheAreaMetric) {
  for (const char* scene : {"brabec", "fence"}) {
    const double volumes = areaRmse(scene, "modern.volumes");
    const double map = areaRmse(scene, "modern.hw --a-param compare=nearest");
    EXPECT_GT(volumes, 0.0) << scene;
    EXPECT_LT(volumes, map) << scene;
  }
}

TEST(ErrorAxis, EitherSideCanBeTheTruth) {
  const CommandResult ab = shadowlab(std::string("compare --scene fence --size ") + kSize +
                                     " --a modern.pcf --b reference.hard --b-param pixel=area");
  const CommandResult ba = shadowlab(std::string("compare --scene fence --size ") + kSize +
                                     " --a reference.hard --a-param pixel=area --b modern.pcf");
  ASSERT_EQ(ab.status, 0) << ab.err;
  ASSERT_EQ(ba.status, 0) << ba.err;
  EXPECT_EQ(json::parse(ab.out)["truth_side"], "b");
  EXPECT_EQ(json::parse(ba.out)["truth_side"], "a");
  EXPECT_DOUBLE_EQ(json::parse(ab.out)["rmse"].get<double>(),
                   json::parse(ba.out)["rmse"].get<double>());
}

TEST(ErrorAxis, TwoTechniquesCompareOverTheScoredPixelsWithAllPixelsBeside) {
  const CommandResult r = shadowlab(std::string("compare --scene brabec --size ") + kSize +
                                    " --a legacy.hw --b modern.hw");
  ASSERT_EQ(r.status, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["metric"], "mask difference");
  EXPECT_TRUE(j["truth"].is_null());
  EXPECT_LT(j["scored_pixels"].get<long long>(), j["all_pixels"]["pixels"].get<long long>());
  EXPECT_GT(j["left_out"]["share"].get<double>(), 0.0);
}

TEST(ErrorAxis, SideParamsNamingAnUndeclaredKeyAreInputErrors) {
  const CommandResult r = shadowlab(std::string("compare --scene brabec --size ") + kSize +
                                    " --a modern.pcf --a-param pixel=area --b reference.hard");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("--a-param pixel: technique modern.pcf has no parameter 'pixel'"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("depth-bias"), std::string::npos) << "names A's keys: " << r.err;
  EXPECT_TRUE(r.out.empty());

  const CommandResult malformed = shadowlab(std::string("compare --scene brabec --size ") + kSize +
                                            " --a modern.pcf --b reference.hard "
                                            "--b-param pixel");
  EXPECT_EQ(malformed.status, 2) << malformed.err;
  EXPECT_NE(malformed.err.find("--b-param must look like key=value"), std::string::npos)
      << malformed.err;
}

}  // namespace
}  // namespace sl
