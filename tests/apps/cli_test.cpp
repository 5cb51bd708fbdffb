// The shadowlab command as a user runs it: outputs on success, and for every kind of bad
// input one line on stderr, exit status 2, and no output file (docs/design.md, CLI).
#include "registry/cli.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "command_util.h"
#include "core/base/errors.h"
#include "core/base/image.h"
#include "core/base/provenance.h"
#include "tests/test_names.h"

namespace sl {
namespace {
namespace fs = std::filesystem;
using test::CommandResult;
using test::slurp;

fs::path dir() { return test::testDir("cli"); }

CommandResult runBinary(const std::string& binary, const std::string& args) {
  return test::runBinary(binary, args, dir());
}

CommandResult shadowlab(const std::string& args) { return runBinary(SHADOWLAB_BINARY, args); }

// Input files are written while the test list is built (before any test runs), into a
// directory per process, since every ctest process builds the list anew.
std::string write(const std::string& name, const std::string& text) {
  const fs::path d =
      fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "cli" / ("inputs-" + std::to_string(::getpid()));
  fs::create_directories(d);
  const fs::path p = d / name;
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

constexpr const char* kSmall = " --size 96x72 --shadow-map 64";

TEST(Cli, RenderWritesImageAndSixteenBitMask) {
  const fs::path png = dir() / "ok.png", mask = dir() / "ok-mask.png";
  fs::remove(png);
  fs::remove(mask);
  const CommandResult r =
      shadowlab("render --scene analytic --technique legacy.hw" + std::string(kSmall) + " --out " +
                png.string() + " --mask " + mask.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const Image image = readPng(png.string());
  EXPECT_EQ(image.width, 96);
  EXPECT_EQ(image.height, 72);
  const Image m = readPng(mask.string());
  EXPECT_EQ(m.channels, 1);
  // The analytic scene has both lit ground and the occluder's umbra in view.
  float lo = 1, hi = 0;
  for (float v : m.data) lo = std::min(lo, v), hi = std::max(hi, v);
  EXPECT_EQ(lo, 0.0f);
  EXPECT_EQ(hi, 1.0f);
  EXPECT_NE(r.out.find("\"frame_ms\""), std::string::npos);
}

TEST(Cli, ListAndHelp) {
  const CommandResult list = shadowlab("list");
  EXPECT_EQ(list.status, 0);
  EXPECT_NE(list.out.find("legacy.hw"), std::string::npos);
  EXPECT_NE(list.out.find("brabec"), std::string::npos);
  const CommandResult help = shadowlab("--help");
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.out.find("render"), std::string::npos);
  EXPECT_NE(help.out.find("--version"), std::string::npos);
}

// `shadowlab --version` prints the commit the binary was built from (core/base/provenance.h), the
// same "shadowlab <commit>" its PNGs carry as "Software"; anything after it is bad input.
TEST(Cli, VersionPrintsTheBuildCommit) {
  const CommandResult r = shadowlab("--version");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_EQ(r.out, "shadowlab " + buildCommit() + "\n");
  const CommandResult extra = shadowlab("--version list");
  EXPECT_EQ(extra.status, 2) << extra.err;
  EXPECT_EQ(std::count(extra.err.begin(), extra.err.end(), '\n'), 1) << extra.err;
  EXPECT_NE(extra.err.find("--version"), std::string::npos) << extra.err;
  EXPECT_TRUE(extra.out.empty()) << extra.out;
}

// Every command answers --help with its own options on stdout and exit status 0, and
// runs nothing: no output file appears.
TEST(Cli, EveryCommandHasHelp) {
  const std::map<std::string, std::vector<std::string>> expected = {
      {"list", {}},
      {"render",
       {"--technique", "--out", "--mask", "--dump-passes", "--param", "--backend",
        "--light-position", "--orbit"}},
      {"compare", {"--a", "--b", "--diff", "--threshold", "--size"}},
      {"bench", {"--quick", "--scene", "--technique", "--csv", "--repeat", "--out"}},
      {"plan", {"--technique", "--shadow-map", "--param"}},
      {"figures", {"--out", "--only", "--no-progress"}},
      {"serve", {"--host", "--port"}},
  };
  for (const auto& [command, options] : expected) {
    for (const char* flag : {" --help", " -h"}) {
      const CommandResult r = shadowlab(command + flag);
      EXPECT_EQ(r.status, 0) << command << flag << ": " << r.err;
      EXPECT_TRUE(r.err.empty()) << command << flag << ": " << r.err;
      EXPECT_NE(r.out.find(command), std::string::npos) << command << flag << ": " << r.out;
      for (const std::string& option : options)
        EXPECT_NE(r.out.find(option), std::string::npos) << command << " lacks " << option;
    }
  }
  // --help wins over other arguments and renders nothing.
  const fs::path png = dir() / "not-written.png";
  fs::remove(png);
  const CommandResult r =
      shadowlab("render --scene analytic --technique legacy.hw --out " + png.string() + " --help");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(fs::exists(png));
}

// Repeated --param options accumulate; a repeated single-valued option keeps its last value
// (as before the move to CLI11); --key=value works like --key value.
cli::Args parseLine(std::vector<std::string> words) {
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  return cli::parse(int(argv.size()), argv.data());
}

TEST(Cli, RepeatedAndInlineOptions) {
  const cli::Args a = parseLine({"shadowlab", "plan", "--technique", "modern.csm", "--param",
                                 "order=8", "--param=blur=3", "--size=64x48", "--size", "96x72"});
  EXPECT_EQ(a.command, "plan");
  const RenderParams p = cli::renderParams(a);
  EXPECT_EQ(p.extra.at("order"), "8");
  EXPECT_EQ(p.extra.at("blur"), "3");
  EXPECT_EQ(p.width, 96);
  EXPECT_EQ(p.height, 72);
  const cli::Args b = parseLine({"shadowlab", "bench", "--quick", "--scene", "fence"});
  EXPECT_TRUE(b.has("quick"));
  EXPECT_FALSE(b.has("csv"));
  EXPECT_EQ(b.value("scene").value_or(""), "fence");
  EXPECT_THROW(parseLine({"shadowlab", "plan", "--param"}), InputError);
  EXPECT_THROW(parseLine({"shadowlab", "plan", "--quick"}), InputError);
  EXPECT_THROW(parseLine({"shadowlab", "bench", "stray"}), InputError);
  EXPECT_THROW(parseLine({"shadowlab", "bench", "--help"}), cli::HelpRequested);
}

TEST(Cli, CompareReportsStatisticsAsJson) {
  const fs::path diff = dir() / "diff.png";
  const CommandResult r = shadowlab("compare --scene analytic --a legacy.hw --b modern.hw" +
                                    std::string(kSmall) + " --diff " + diff.string());
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* key : {"\"mismatching\"", "\"max_abs\"", "\"rmse\"", "\"a_frame_ms\""})
    EXPECT_NE(r.out.find(key), std::string::npos) << key;
  EXPECT_TRUE(fs::exists(diff));
}

// No temporary of core/base/output_files.h (".tmp-", ".old-") or of writePng (".part-") is left.
void expectNoTemporaries(const fs::path& directory) {
  for (const auto& entry : fs::directory_iterator(directory))
    for (const char* mark : {".tmp-", ".old-", ".part-"})
      EXPECT_EQ(entry.path().filename().string().find(mark), std::string::npos) << entry.path();
}

struct BadInput {
  const char* what;
  std::string args;
};

class CliBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(CliBadInput, OneLineOnStderrExitTwoNoOutput) {
  const fs::path out = dir() / "bad.png", mask = dir() / "bad-mask.png";
  fs::remove(out);
  fs::remove(mask);
  std::string args = GetParam().args;
  for (auto [key, value] : {std::pair{std::string("@OUT"), out.string()},
                            std::pair{std::string("@MASK"), mask.string()}})
    for (size_t p; (p = args.find(key)) != std::string::npos;) args.replace(p, key.size(), value);
  const CommandResult r = shadowlab(args);
  EXPECT_EQ(r.status, 2) << GetParam().what << ": " << r.err;
  EXPECT_FALSE(r.err.empty());
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.find("terminate"), std::string::npos);
  EXPECT_FALSE(fs::exists(out)) << GetParam().what;
  EXPECT_FALSE(fs::exists(mask)) << GetParam().what;
  expectNoTemporaries(out.parent_path());
}

std::vector<BadInput> badInputs() {
  const std::string base = "render --technique legacy.hw --size 64x48 --out @OUT --mask @MASK ";
  const std::string malformedJson = write("malformed.json", "{\"objects\": [ {\"mesh\": ");
  const std::string badObjScene =
      write("badobj.json", "{\"objects\": [{\"mesh\": {\"file\": \"" +
                               write("broken.obj", "v 1 2\nf 1 2 7\n") + "\"}}]}");
  const std::string truncatedPly =
      write("truncated.ply",
            "ply\nformat binary_little_endian 1.0\nelement vertex 50\nproperty float x\n"
            "property float y\nproperty float z\nelement face 10\n"
            "property list uchar int vertex_indices\nend_header\n" +
                std::string(17, '\0'));
  const std::string badPlyScene =
      write("badply.json", "{\"objects\": [{\"mesh\": {\"file\": \"" + truncatedPly + "\"}}]}");
  return {
      {"unknown scene", base + "--scene nowhere"},
      {"unknown technique", "render --scene analytic --technique legacy.nothing --out @OUT"},
      {"malformed JSON", base + "--scene " + malformedJson},
      {"malformed OBJ", base + "--scene " + badObjScene},
      {"truncated PLY", base + "--scene " + badPlyScene},
      {"missing scene file", base + "--scene /no/such/file.json"},
      {"NaN size", "render --scene analytic --technique legacy.hw --size nanxnan --out @OUT"},
      {"negative size", "render --scene analytic --technique legacy.hw --size -4x30 --out @OUT"},
      {"zero-area window", "render --scene analytic --technique legacy.hw --size 0x0 --out @OUT"},
      {"shadow map 0", base + "--scene analytic --shadow-map 0"},
      {"shadow map above GL max", base + "--scene analytic --shadow-map 60000"},
      {"NaN parameter", base + "--scene analytic --param offset-factor=nan"},
      {"unknown parameter", base + "--scene analytic --param wobble=3"},
      {"bad precision", base + "--scene analytic --precision 9"},
      {"bad backend", base + "--scene analytic --backend vulkan"},
      // Debian's OSMesa has no native ARB_imaging: only the emulation exists there.
      {"native imaging on osmesa", base + "--scene analytic --imaging native"},
      {"bad imaging", base + "--scene analytic --imaging both"},
      {"imaging on a modern technique",
       "render --scene analytic --technique modern.hw --size 64x48 --out @OUT --imaging emulated"},
      {"unwritable output",
       "render --scene analytic --technique legacy.hw --size 64x48 --out "
       "/proc/nonexistent/x.png"},
      {"mask in missing dir",
       "render --scene analytic --technique legacy.hw --size 64x48 --out "
       "@OUT --mask /nonexistent-dir/m.png"},
      {"missing --out", "render --scene analytic --technique legacy.hw"},
      {"unknown option", "render --scene analytic --technique legacy.hw --out @OUT --colour red"},
      {"unknown command", "paint"},
      {"stray argument", "render --scene analytic --technique legacy.hw --out @OUT extra"},
      {"option without its value", "render --scene analytic --technique legacy.hw --out"},
      {"bench option on render",
       "render --scene analytic --technique legacy.hw --out @OUT --quick"},
      // Strict decimal numbers: no trailing characters, hex, inf or spaces.
      {"threshold with trailing junk",
       "compare --scene analytic --a legacy.hw --b modern.hw --size 64x48 --threshold 0.5abc"},
      {"hexadecimal threshold",
       "compare --scene analytic --a legacy.hw --b modern.hw --size 64x48 --threshold 0x0.8"},
      {"infinite threshold",
       "compare --scene analytic --a legacy.hw --b modern.hw --size 64x48 --threshold inf"},
      {"hexadecimal parameter", base + "--scene analytic --param offset-factor=0x10"},
      {"parameter with a space", base + "--scene analytic --param 'offset-factor= 2'"},
      {"size with a space",
       "render --scene analytic --technique legacy.hw --size '64x 48' --out @OUT"},
      // plan refuses what render refuses: the GL's largest texture included.
      {"plan shadow map above GL max",
       "plan --scene analytic --technique legacy.hw --shadow-map 65536"},
      // Destinations are checked before the bench runs (it would take minutes otherwise).
      {"bench plots in an unwritable folder",
       "bench --quick --technique legacy.hw --scene analytic --out /proc/nonexistent/bench"},
      {"bench CSV in /proc", "bench --quick --technique legacy.hw --csv /proc/bench.csv"},
      {"compare diff in /proc",
       "compare --scene analytic --a legacy.hw --b modern.hw --size 64x48 --diff /proc/d.png"},
      {"dump into an existing file",
       "render --scene analytic --technique legacy.hw --size 64x48 --out @OUT --dump-passes " +
           write("not-a-directory.txt", "text")},
  };
}

INSTANTIATE_TEST_SUITE_P(All, CliBadInput, ::testing::ValuesIn(badInputs()),
                         [](const auto& info) { return testName(info.param.what); });

// The developer tools parse their command lines with CLI11 as the shadowlab command does:
// --help lists every option, and bad input is one line on stderr with exit status
// 2, found before any benchmark runs (these cases take milliseconds, not the benchmark's minutes).
struct Tool {
  const char* name;
  const char* binary;
  std::vector<std::string> options;  // every option the tool's header comment documents
};

const std::vector<Tool>& tools() {
  static const std::vector<Tool> kTools = {
      {"legacy_bench",
       LEGACY_BENCH_BINARY,
       {"--backend", "--frames", "--quick", "--technique", "--trace-overhead", "--split-cost"}},
      {"volumes_bench",
       VOLUMES_BENCH_BINARY,
       {"--scene", "--size", "--shadow-map", "--frames", "--backend", "--technique",
        "--doc-images"}},
      {"shadowlab-twins",
       TWINS_BINARY,
       {"--size", "--shadow-map", "--backend", "--scenes", "--bench-size", "--bench-shadow-map",
        "--bench-scene", "--frames", "--no-agreement", "--no-bench"}},
      {"csm_bench",
       CSM_BENCH_BINARY,
       {"--quick", "--size", "--repeat", "--warmup", "--scene", "--backend", "--part", "--csv",
        "--param"}},
      {"imaging_bench", IMAGING_BENCH_BINARY, {"--quick", "--cpu", "--only"}},
      {"imaging_fuzz", IMAGING_FUZZ_BINARY, {"--sequences", "--seed", "--out", "--print"}},
      {"bias_table", BIAS_TABLE_BINARY, {"--progress"}},
  };
  return kTools;
}

TEST(ToolCli, EveryToolHasHelp) {
  for (const Tool& tool : tools())
    for (const char* flag : {"--help", "-h"}) {
      const CommandResult r = runBinary(tool.binary, flag);
      EXPECT_EQ(r.status, 0) << tool.name << " " << flag << ": " << r.err;
      EXPECT_TRUE(r.err.empty()) << tool.name << " " << flag << ": " << r.err;
      EXPECT_NE(r.out.find(tool.name), std::string::npos) << tool.name << ": " << r.out;
      for (const std::string& option : tool.options) {
        const size_t at = r.out.find("  " + option + " ");  // "--size", not "--bench-size"
        EXPECT_NE(at, std::string::npos) << tool.name << " --help lacks " << option;
        if (at == std::string::npos) continue;
        // One help line per option: the option's line carries its description.
        const size_t eol = r.out.find('\n', at);
        const std::string line = r.out.substr(at, eol - at);
        EXPECT_GT(line.size(), option.size() + 10) << tool.name << ": '" << line << "'";
      }
    }
  // --help wins over the other arguments: nothing is benchmarked (this would take minutes).
  const CommandResult r = runBinary(LEGACY_BENCH_BINARY, "--technique legacy.pcf --help");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.find("| variant"), std::string::npos) << r.out;
}

struct BadToolInput {
  const char* what;
  const char* binary;
  std::string args;
};

class ToolBadInput : public ::testing::TestWithParam<BadToolInput> {};

TEST_P(ToolBadInput, OneLineOnStderrExitTwoNothingOnStdout) {
  const CommandResult r = runBinary(GetParam().binary, GetParam().args);
  EXPECT_EQ(r.status, 2) << GetParam().what << ": " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.find("terminate"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << GetParam().what << ": " << r.out;
}

std::vector<BadToolInput> badToolInputs() {
  return {
      {"fuzz sequences not a number", IMAGING_FUZZ_BINARY, "--sequences many"},
      {"fuzz sequences zero", IMAGING_FUZZ_BINARY, "--sequences 0"},
      {"fuzz sequences missing", IMAGING_FUZZ_BINARY, "--seed 3"},
      {"fuzz negative seed", IMAGING_FUZZ_BINARY, "--sequences 1 --seed -1"},
      {"fuzz unknown option", IMAGING_FUZZ_BINARY, "--sequences 1 --fast"},
      {"bias table unknown option", BIAS_TABLE_BINARY, "--scene brabec"},
      {"bias table stray argument", BIAS_TABLE_BINARY, "extra"},
      {"legacy frames not a number", LEGACY_BENCH_BINARY, "--frames five"},
      {"legacy frames zero", LEGACY_BENCH_BINARY, "--frames 0"},
      {"legacy frames trailing junk", LEGACY_BENCH_BINARY, "--frames 3x"},
      {"legacy unknown option", LEGACY_BENCH_BINARY, "--fast"},
      {"legacy stray argument", LEGACY_BENCH_BINARY, "--quick extra"},
      {"legacy missing value", LEGACY_BENCH_BINARY, "--frames"},
      {"legacy bad backend", LEGACY_BENCH_BINARY, "--backend vulkan"},
      {"legacy bad imaging", LEGACY_BENCH_BINARY, "--imaging both"},
      {"legacy native imaging on osmesa", LEGACY_BENCH_BINARY, "--quick --imaging native"},
      {"legacy unknown technique", LEGACY_BENCH_BINARY, "--technique legacy.nothing"},
      {"volumes frames not a number", VOLUMES_BENCH_BINARY, "--frames many"},
      {"volumes shadow map zero", VOLUMES_BENCH_BINARY, "--shadow-map 0"},
      {"volumes malformed size", VOLUMES_BENCH_BINARY, "--size 800by600"},
      {"volumes unknown option", VOLUMES_BENCH_BINARY, "--colour red"},
      {"volumes stray argument", VOLUMES_BENCH_BINARY, "--technique modern.hw extra"},
      {"twins frames not a number", TWINS_BINARY, "--frames 1.5"},
      {"twins frames out of range", TWINS_BINARY, "--frames 100000"},
      {"twins negative shadow map", TWINS_BINARY, "--bench-shadow-map -512"},
      {"twins unknown option", TWINS_BINARY, "--no-table"},
      {"twins stray argument", TWINS_BINARY, "--no-bench brabec"},
      {"csm repeat not a number", CSM_BENCH_BINARY, "--repeat ten"},
      {"csm negative warmup", CSM_BENCH_BINARY, "--warmup -1"},
      {"csm malformed size", CSM_BENCH_BINARY, "--size 0x768"},
      {"csm unknown part", CSM_BENCH_BINARY, "--part figures"},
      {"csm reference backend", CSM_BENCH_BINARY, "--backend reference"},
      {"csm malformed param", CSM_BENCH_BINARY, "--param order"},
      {"csm unknown option", CSM_BENCH_BINARY, "--order 8"},
      {"csm stray argument", CSM_BENCH_BINARY, "--quick table1"},
      {"imaging unknown option", IMAGING_BENCH_BINARY, "--fast"},
      {"imaging stray argument", IMAGING_BENCH_BINARY, "--quick extra"},
      {"imaging missing value", IMAGING_BENCH_BINARY, "--only"},
      // Found before any work, exit 2, nothing on stdout.
      {"csm csv in /proc", CSM_BENCH_BINARY, "--csv /proc/x.csv"},
      {"csm csv with the ratio part", CSM_BENCH_BINARY, "--part ratio --csv /tmp/ratio.csv"},
      {"csm param with the techniques part", CSM_BENCH_BINARY, "--part techniques --param order=4"},
      {"csm hexadecimal repeat", CSM_BENCH_BINARY, "--repeat 0x3"},
      {"csm shadow map with the table1 part", CSM_BENCH_BINARY, "--part table1 --shadow-map 256"},
      {"csm shadow map zero", CSM_BENCH_BINARY, "--part ratio --shadow-map 0"},
      {"twins empty scene list", TWINS_BINARY, "--scenes ''"},
      {"twins scene list of commas", TWINS_BINARY, "--scenes ,,"},
      {"twins unknown scene", TWINS_BINARY, "--scenes nowhere --no-bench"},
      {"imaging only matches nothing", IMAGING_BENCH_BINARY, "--only nomatch"},
      {"volumes doc images in /proc", VOLUMES_BENCH_BINARY, "--doc-images /proc/docs"},
  };
}

INSTANTIATE_TEST_SUITE_P(All, ToolBadInput, ::testing::ValuesIn(badToolInputs()),
                         [](const auto& info) { return testName(info.param.what); });

// csm_bench --part ratio measures the --size and --scene it is given, not
// the bench sizes and scenes.
TEST(ToolCli, CsmRatioTakesSizeAndScene) {
  const CommandResult r =
      runBinary(CSM_BENCH_BINARY, "--part ratio --size 48x36 --scene fence --repeat 1 --warmup 0");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("| fence | 48x36 |"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("256x192"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("| brabec |"), std::string::npos) << r.out;
}

// ... and the --shadow-map it is given (the per-pass costs at Table 1's sizes).
TEST(ToolCli, CsmRatioTakesShadowMap) {
  const CommandResult r =
      runBinary(CSM_BENCH_BINARY,
                "--part ratio --size 48x36 --scene fence --shadow-map 64 --repeat 1 --warmup 0");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("map 64,"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("map 512"), std::string::npos) << r.out;
}

// Numbers on the command line are strict decimals (core/base/decimal.h, one parser for all).
TEST(Cli, StrictDecimalNumbers) {
  for (const char* good : {"0.5", "-0.5", "+2", ".5", "2.", "1e-3", "3E2"})
    EXPECT_NO_THROW(cli::parseNumber("--x", good)) << good;
  EXPECT_EQ(cli::parseNumber("--x", "1e-3"), 1e-3);
  for (const char* bad : {"", "0.5abc", "0x0.8", "0x10", "inf", "-inf", "nan", " 0.5", "0.5 ", "1e",
                          "e5", ".", "-", "1e999", "1,5", "0.5\n"})
    EXPECT_THROW(cli::parseNumber("--x", bad), InputError) << "'" << bad << "'";
  EXPECT_EQ(cli::parsePositiveInt("--n", "42", 100), 42);
  for (const char* bad : {"0x10", " 4", "4 ", "4.0", "1e2", "+-4", "99999999999999999999", "0"})
    EXPECT_THROW(cli::parsePositiveInt("--n", bad, 100), InputError) << "'" << bad << "'";
}

// A run writes all its outputs or none: every destination is checked before
// rendering, and an existing --out survives a run that fails.
struct FailingRun {
  const char* what;
  std::string extra;  // @OUT: the existing output; @DIR: the test's directory
};

class CliOutputsAllOrNone : public ::testing::TestWithParam<FailingRun> {};

TEST_P(CliOutputsAllOrNone, ExistingOutputSurvives) {
  const fs::path d = dir();
  const fs::path out = d / "existing.png";
  std::ofstream(out) << "an earlier result";
  const fs::path scene = d / "scene.json";
  std::ofstream(scene) << slurp(fs::path(SHADOWLAB_SOURCE_DIR) / "assets/scenes/squares.json");
  std::string args = "render --scene " + scene.string() +
                     " --technique legacy.hw --size 64x48 --out " + out.string() + " " +
                     GetParam().extra;
  for (auto [key, value] :
       {std::pair{std::string("@OUT"), out.string()}, std::pair{std::string("@DIR"), d.string()},
        std::pair{std::string("@SCENE"), scene.string()}})
    for (size_t p; (p = args.find(key)) != std::string::npos;) args.replace(p, key.size(), value);
  const CommandResult r = shadowlab(args);
  EXPECT_EQ(r.status, 2) << GetParam().what << ": " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_EQ(slurp(out), "an earlier result") << GetParam().what;
  EXPECT_NE(slurp(scene).find("\"squares\""), std::string::npos) << "the scene was replaced";
  EXPECT_FALSE(fs::exists(d / "dump")) << GetParam().what;
  EXPECT_FALSE(fs::exists(d / "mask.png")) << GetParam().what;
  expectNoTemporaries(d);
}

INSTANTIATE_TEST_SUITE_P(
    All, CliOutputsAllOrNone,
    ::testing::ValuesIn(std::vector<FailingRun>{
        {"mask name too long", "--mask @DIR/" + std::string(300, 'm') + ".png"},
        {"mask in proc", "--mask /proc/mask.png"},
        {"mask in a missing folder", "--mask @DIR/missing/mask.png"},
        {"mask equal to out", "--mask @OUT"},
        {"mask equal to out by another spelling", "--mask @DIR/./existing.png"},
        {"out equal to the scene file", "--mask @DIR/mask.png --out @SCENE"},
        {"dump directory holding the out", "--dump-passes @DIR --mask @DIR/mask.png"},
        {"dump directory name too long", "--dump-passes @DIR/" + std::string(300, 'd')},
        // Rejected after the destinations were checked: nothing is created, not even the
        // dump directory.
        {"unknown parameter", "--mask @DIR/mask.png --dump-passes @DIR/dump --param wobble=3"},
        {"shadow map above GL max",
         "--mask @DIR/mask.png --dump-passes @DIR/dump --shadow-map 60000"},
    }),
    [](const auto& info) { return testName(info.param.what); });

// A rejected scene leaves no dump directory.
TEST(Cli, RejectedSceneCreatesNoDumpDirectory) {
  const fs::path dump = dir() / "dump";
  fs::remove_all(dump);
  const CommandResult r = shadowlab("render --scene nowhere --technique legacy.hw --out " +
                                    (dir() / "x.png").string() + " --dump-passes " + dump.string());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_FALSE(fs::exists(dump));
  expectNoTemporaries(dir());
}

// --dump-passes: a new directory (missing parents made), replaced as a whole by a later dump,
// and an existing directory holding anything else than a dump's files is refused untouched.
TEST(Cli, DumpPassesDirectoryIsReplacedAsAWhole) {
  const fs::path d = dir();
  fs::remove_all(d / "nested");
  const fs::path dump = d / "nested" / "dump";
  const std::string render = "render --scene analytic --size 64x48 --shadow-map 64 --out " +
                             (d / "image.png").string() + " --dump-passes " + dump.string();
  CommandResult r = shadowlab(render + " --technique legacy.pcf");
  ASSERT_EQ(r.status, 0) << r.err;
  std::set<std::string> first;
  for (const auto& e : fs::directory_iterator(dump)) first.insert(e.path().filename().string());
  EXPECT_FALSE(first.empty());
  r = shadowlab(render + " --technique modern.csm");
  ASSERT_EQ(r.status, 0) << r.err;
  std::set<std::string> second;
  for (const auto& e : fs::directory_iterator(dump)) second.insert(e.path().filename().string());
  EXPECT_FALSE(second.empty());
  EXPECT_TRUE(second.count("passes.json") && second.count("index.html"));
  for (const std::string& name : second) {
    if (name != "passes.json" && name != "index.html") {
      EXPECT_EQ(first.count(name), 0u) << name;
    }
  }
  expectNoTemporaries(d);
  expectNoTemporaries(d / "nested");
  std::ofstream(dump / "notes.txt") << "mine";
  r = shadowlab(render + " --technique legacy.pcf");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("notes.txt"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(dump / "notes.txt"), "mine");
  EXPECT_EQ(fs::exists(dump / *second.begin()), true);
}

// A scene file named in bytes that are not UTF-8, without a "name" key: the JSON line is
// built before any file is committed and prints the name with U+FFFD.
TEST(Cli, NonUtf8SceneNameStillGivesOneJsonLine) {
  const fs::path d = dir();
  const fs::path scene = d / "sc\xff\xfe.json";
  std::string text = slurp(fs::path(SHADOWLAB_SOURCE_DIR) / "assets/scenes/squares.json");
  text.replace(text.find("\"name\": \"squares\","), std::string("\"name\": \"squares\",").size(),
               "");
  std::ofstream(scene) << text;
  const fs::path out = d / "u.png", mask = d / "u-mask.png";
  fs::remove(out);
  fs::remove(mask);
  const CommandResult r = shadowlab("render --scene '" + scene.string() +
                                    "' --technique legacy.hw --size 64x48 --out " + out.string() +
                                    " --mask " + mask.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"scene\":\"sc\xef\xbf\xbd\xef\xbf\xbd\""), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(out));
  EXPECT_TRUE(fs::exists(mask));
  expectNoTemporaries(d);
}

}  // namespace
}  // namespace sl
