// The live lab's API against a server on an ephemeral loopback port:
// the JSON listings, frames that match `shadowlab render` pixel for pixel, the same one-line
// refusals as the CLI, the error against the reference, caps, rate limit and latest-wins.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "core/base/metrics.h"
#include "lab/worker.h"
#include "lab_test_util.h"

namespace sl::test {
namespace {
using json = nlohmann::json;

class LabApi : public ::testing::Test {
 protected:
  void SetUp() override {
    server_ = startLab(kTestRequestsPerSecond, kTestBurst, &port_);
    client_ = std::make_unique<httplib::Client>("127.0.0.1", port_);
    client_->set_read_timeout(120, 0);  // a first /api/scenes loads every scene
  }
  httplib::Result get(const std::string& path) { return client_->Get(path.c_str()); }

  std::unique_ptr<lab::LabServer> server_;
  std::unique_ptr<httplib::Client> client_;
  int port_ = 0;
};

// A small frame of a fast technique: the query keys are the CLI's option names.
const std::string kSmall = "scene=brabec&technique=modern.hw&size=160x120";

TEST_F(LabApi, TechniquesListEveryTechniqueWithItsParametersRangesAndDefaults) {
  auto r = get("/api/techniques");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(r->get_header_value("Content-Type"), "application/json");
  const json doc = json::parse(r->body);
  std::set<std::string> names;
  int declaredNumbers = 0;
  for (const json& t : doc["techniques"]) {
    names.insert(t["name"].get<std::string>());
    EXPECT_FALSE(t["paper"].get<std::string>().empty());
    for (const json& p : t["params"]) {
      if (p["kind"] != "number" && p["kind"] != "integer") continue;
      if (p["default"] == "auto") continue;  // derived by the technique (ParamSpec::acceptsAuto)
      ++declaredNumbers;
      const double lo = p["min"], hi = p["max"];
      const double fallback = std::stod(p["default"].get<std::string>());
      EXPECT_LE(lo, hi) << t["name"] << " " << p["key"];
      EXPECT_GE(fallback, lo) << t["name"] << " " << p["key"];
      EXPECT_LE(fallback, hi) << t["name"] << " " << p["key"];
    }
  }
  for (const char* n : {"legacy.hw", "legacy.pcf", "modern.gems16", "modern.csm", "reference.hard"})
    EXPECT_EQ(names.count(n), 1u) << n;
  EXPECT_GT(declaredNumbers, 5);  // the techniques declare numeric parameters (bias, offsets)
}

TEST_F(LabApi, ScenesListBuiltInAndAssetScenesWithTheirCameraAndLight) {
  auto r = get("/api/scenes");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const json doc = json::parse(r->body);
  EXPECT_EQ(doc["default"], "brabec");
  bool brabec = false;
  for (const json& s : doc["scenes"]) {
    EXPECT_FALSE(s.contains("error")) << s["name"] << ": " << s.value("error", "");
    if (s["name"] != "brabec") continue;
    brabec = true;
    EXPECT_TRUE(s["builtin"].get<bool>());
    EXPECT_EQ(s["light"].size(), 3u);
    EXPECT_GT(s["orbit"][2].get<double>(), 0.0);  // distance from the camera to its target
  }
  EXPECT_TRUE(brabec);
}

TEST_F(LabApi, MaskMatchesTheCommandLinePixelForPixel) {
  const auto dir = testDir("lab", true);
  // Twice through the server: the second frame comes from the worker's cached context.
  for (int i = 0; i < 2; ++i) {
    auto r = get("/api/render?" + kSmall + "&light-position=-2.5,7,3&orbit=20,30,7&view=mask");
    ASSERT_TRUE(r);
    ASSERT_EQ(r->status, 200) << r->body;
    EXPECT_EQ(r->get_header_value("Content-Type"), "image/png");
    const std::string command = r->get_header_value("X-Shadowlab-Command");
    EXPECT_NE(command.find("shadowlab render --scene brabec --technique modern.hw"),
              std::string::npos)
        << command;
    const Image served = decodePng(r->body, dir, "served.png");
    const CommandResult cli =
        runBinary(SHADOWLAB_BINARY,
                  "render --scene brabec --technique modern.hw --size 160x120 "
                  "--light-position -2.5,7,3 --orbit 20,30,7 --out " +
                      (dir / "cli.png").string() + " --mask " + (dir / "cli-mask.png").string(),
                  dir);
    ASSERT_EQ(cli.status, 0) << cli.err;
    const Image expected = readPng((dir / "cli-mask.png").string());
    ASSERT_EQ(served.width, 160);
    ASSERT_EQ(served.height, 120);
    const MaskDifference d = compareMasks(served, expected);
    EXPECT_EQ(d.mismatching, 0) << "max |difference| " << d.maxAbs;
    // The frame has both lit and shadowed pixels: the light and orbit put a shadow in view.
    float lo = 1.0f, hi = 0.0f;
    for (float v : served.data) lo = std::min(lo, v), hi = std::max(hi, v);
    EXPECT_LT(lo, 0.5f);
    EXPECT_GT(hi, 0.5f);
  }
}

TEST_F(LabApi, LightAndOrbitChangeTheFrame) {
  const auto dir = testDir("lab", true);
  auto base = get("/api/render?" + kSmall + "&view=mask");
  auto lit = get("/api/render?" + kSmall + "&light-position=2,6,-1&view=mask");
  auto orbit = get("/api/render?" + kSmall + "&orbit=60,40,8&view=mask");
  ASSERT_TRUE(base && lit && orbit);
  ASSERT_EQ(base->status, 200);
  ASSERT_EQ(lit->status, 200);
  ASSERT_EQ(orbit->status, 200);
  const Image a = decodePng(base->body, dir, "a.png"), b = decodePng(lit->body, dir, "b.png"),
              c = decodePng(orbit->body, dir, "c.png");
  EXPECT_GT(compareMasks(a, b).mismatching, 100);  // the shadow moved
  EXPECT_GT(compareMasks(a, c).mismatching, 100);  // the view moved
}

TEST_F(LabApi, ImageIsAnRgbPngOfTheRequestedSize) {
  const auto dir = testDir("lab", true);
  auto r = get("/api/render?scene=fence&technique=legacy.pcf&size=200x150&shadow-map=256&filter=3");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const Image image = decodePng(r->body, dir, "image.png");
  EXPECT_EQ(image.width, 200);
  EXPECT_EQ(image.height, 150);
  EXPECT_GE(image.channels, 3);
  EXPECT_GT(std::stod(r->get_header_value("X-Shadowlab-Frame-Ms")), 0.0);
}

// The same input is refused by the CLI (exit 2, "shadowlab: LINE" on stderr) and the API (400,
// LINE as text/plain).
TEST_F(LabApi, BadInputGetsTheCommandLinesOneLineMessage) {
  const auto dir = testDir("lab", true);
  struct Case {
    std::string query;  // after "scene=brabec&size=96x72&"
    std::string args;   // the same for `shadowlab render --scene brabec --size 96x72 ... --out`
  };
  const std::vector<Case> cases = {
      {"technique=modern.nope", "--technique modern.nope"},
      {"technique=legacy.hw&shadow-map=abc", "--technique legacy.hw --shadow-map abc"},
      {"technique=legacy.hw&shadow-map=0", "--technique legacy.hw --shadow-map 0"},
      {"technique=legacy.pcf&filter=99", "--technique legacy.pcf --filter 99"},
      {"technique=legacy.ramp&filter=2", "--technique legacy.ramp --filter 2"},
      {"technique=legacy.hw&precision=7", "--technique legacy.hw --precision 7"},
      {"technique=legacy.hw&param=nokey", "--technique legacy.hw --param nokey"},
      {"technique=legacy.hw&param=bogus=1", "--technique legacy.hw --param bogus=1"},
      {"technique=legacy.hw&light-position=1,2", "--technique legacy.hw --light-position 1,2"},
      {"technique=legacy.hw&light-position=nan,1,1",
       "--technique legacy.hw --light-position nan,1,1"},
      {"technique=legacy.hw&orbit=10,95,5", "--technique legacy.hw --orbit 10,95,5"},
      {"technique=legacy.hw&orbit=10,20,0", "--technique legacy.hw --orbit 10,20,0"},
      {"technique=legacy.hw&threshold=1", "--technique legacy.hw --threshold 1"},
      {"scene=nowhere&technique=legacy.hw", "--scene nowhere --technique legacy.hw"},
  };
  for (const Case& c : cases) {
    const std::string query =
        (c.query.rfind("scene=", 0) == 0 ? "size=96x72&" + c.query
                                         : "scene=brabec&size=96x72&" + c.query);
    auto r = get("/api/render?" + query);
    ASSERT_TRUE(r) << c.query;
    EXPECT_EQ(r->status, 400) << c.query << ": " << r->body;
    EXPECT_EQ(r->get_header_value("Content-Type"), "text/plain") << c.query;
    EXPECT_EQ(r->body.find('\n'), std::string::npos) << c.query;
    const std::string sceneArgs = c.args.rfind("--scene", 0) == 0 ? "" : "--scene brabec ";
    const CommandResult cli = runBinary(
        SHADOWLAB_BINARY,
        "render " + sceneArgs + "--size 96x72 " + c.args + " --out " + (dir / "never.png").string(),
        dir);
    EXPECT_EQ(cli.status, 2) << c.args;
    EXPECT_EQ(cli.err, "shadowlab: " + r->body + "\n") << c.query;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "never.png"));
}

TEST_F(LabApi, CapsPathsAndFilesAreRefused) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"size=4000x3000", "the lab serves --size up to"},
      {"shadow-map=8192", "the lab serves --shadow-map up to"},
      {"out=/tmp/x.png", "the lab writes no files: --out is not served"},
      {"dump-passes=/tmp/d", "the lab writes no files"},
      {"backend=reference", "--backend is not served"},
      {"view=depth", "view must be one of image, mask, passes"},
      {"lane=../x", "lane must be"},
  };
  for (const auto& [extra, message] : cases) {
    auto r = get("/api/render?scene=brabec&technique=legacy.pcf&" + extra);
    ASSERT_TRUE(r) << extra;
    EXPECT_EQ(r->status, 400) << extra;
    EXPECT_NE(r->body.find(message), std::string::npos) << extra << ": " << r->body;
  }
  // The references' Monte Carlo work is capped at their defaults (one request must not hold the
  // single worker for minutes); the default itself is served.
  for (const char* extra : {"technique=reference.soft&param=rays=100000",
                            "technique=reference.hard&param=pixel=area&param=pixel-samples=16"}) {
    auto r = get(std::string("/api/render?scene=brabec&size=64x48&") + extra);
    ASSERT_TRUE(r) << extra;
    EXPECT_EQ(r->status, 400) << extra;
    EXPECT_EQ(r->body.rfind("the lab serves --param", 0), 0u) << extra << ": " << r->body;
  }
  // A scene file path is not a served scene, however it is spelled.
  for (const char* scene : {"../../etc/passwd", "/etc/passwd.json", "assets/scenes/ball.json"}) {
    auto r = get(std::string("/api/render?technique=legacy.hw&scene=") +
                 httplib::detail::encode_query_param(scene));
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400) << scene;
    EXPECT_EQ(r->body.rfind("unknown scene", 0), 0u) << r->body;
  }
  // Only the page's own files are served.
  for (const char* path :
       {"/../CMakeLists.txt", "/etc/passwd", "/index.htm", "/api/nothing", "/lab.js/../../x"}) {
    auto r = get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 404) << path;
  }
  auto page = get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("<script src=\"/lab.js\""), std::string::npos);
  auto post = client_->Post("/api/render", "x", "text/plain");
  ASSERT_TRUE(post);
  EXPECT_EQ(post->status, 405);
  // And it still renders.
  auto r = get("/api/render?" + kSmall);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
}

TEST_F(LabApi, PassesGiveNamesMedianTimesAndFetchableImages) {
  auto r = get("/api/render?scene=brabec&technique=legacy.hw&size=128x96&view=passes");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const json doc = json::parse(r->body);
  EXPECT_EQ(doc["technique"], "legacy.hw");
  EXPECT_EQ(doc["timing_frames"], lab::kPassTimingFrames);
  ASSERT_FALSE(doc["median_timings"].empty());
  ASSERT_FALSE(doc["passes"].empty());
  // The medians are of the passes the page shows: one per timed pass of the captured frame,
  // under the same names.
  std::multiset<std::string> shown;
  for (const json& p : doc["passes"])
    for (const json& t : p.value("timings", json::array())) shown.insert(t["name"]);
  std::multiset<std::string> timed;
  for (const json& t : doc["median_timings"]) timed.insert(t["name"].get<std::string>());
  EXPECT_EQ(timed, shown);
  const double frameMs = doc["median_frame_ms"].get<double>();
  for (const json& t : doc["median_timings"]) {
    // Every timing frame ran the same passes, so each median is over all of them.
    EXPECT_EQ(t["frames"], lab::kPassTimingFrames) << t["name"];
    // A pass ends with glFinish and takes measurable time; and in every frame a pass takes at
    // most the frame's total (the sum of its passes), so its median is at most the frames'.
    EXPECT_GT(t["median_ms"].get<double>(), 0.0) << t["name"];
    EXPECT_LE(t["median_ms"].get<double>(), frameMs) << t["name"];
  }
  ASSERT_FALSE(doc["images"].empty());
  const std::string url = doc["images"][0]["url"];
  auto image = get(url);
  ASSERT_TRUE(image);
  EXPECT_EQ(image->status, 200);
  EXPECT_EQ(image->get_header_value("Content-Type"), "image/png");
  auto missing = get("/api/pass/999999/0.png");
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 404);
}

TEST_F(LabApi, ErrorAgainstTheReferenceIsZeroForTheReferenceItself) {
  const std::string q = "scene=brabec&size=96x72";
  auto self = get("/api/error?" + q + "&technique=reference.hard&param=pixel=area");
  ASSERT_TRUE(self);
  ASSERT_EQ(self->status, 200) << self->body;
  const json s = json::parse(self->body);
  EXPECT_FALSE(s["reference_cached"].get<bool>());
  EXPECT_EQ(s["rmse"].get<double>(), 0.0);
  EXPECT_GT(s["region_pixels"].get<long long>(), 0);
  auto hw = get("/api/error?" + q + "&technique=legacy.hw");
  ASSERT_TRUE(hw);
  ASSERT_EQ(hw->status, 200) << hw->body;
  const json h = json::parse(hw->body);
  EXPECT_TRUE(h["reference_cached"].get<bool>());  // same scene, size, light and camera
  EXPECT_GT(h["rmse"].get<double>(), 0.0);         // a hard map misses the partial pixels
  EXPECT_LT(h["rmse"].get<double>(), 0.5);         // ... and little else
  auto heat = get("/api/error?" + q + "&technique=legacy.hw&view=image");
  ASSERT_TRUE(heat);
  EXPECT_EQ(heat->status, 200);
  EXPECT_EQ(heat->get_header_value("Content-Type"), "image/png");
}

TEST(LabRate, RequestsAboveTheRateAreRefusedWith429) {
  int port = 0;
  auto server = startLab(/*rate=*/0.001, /*burst=*/3, &port);
  httplib::Client client("127.0.0.1", port);
  int ok = 0, limited = 0;
  for (int i = 0; i < 6; ++i) {
    auto r = client.Get("/api/render?technique=nope");
    ASSERT_TRUE(r);
    if (r->status == 429) ++limited;
    if (r->status == 400) ++ok;
  }
  EXPECT_EQ(ok, 3);  // the burst
  EXPECT_EQ(limited, 3);
  auto page = client.Get("/");  // the page itself is not rate limited
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
}

// Latest request wins: while a job runs, a second and a third in the same lane leave only the
// third to run; another lane is not affected.
TEST(LabWorker, ANewerJobInALaneDropsTheWaitingOne) {
  lab::Worker worker(4);
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<int> ran{0};
  auto job = [&](int id) {
    return [&, id] {
      released.wait();
      ran += id;
      return lab::JobResult{
          lab::JobResult::Status::kDone, 200, "text/plain", std::to_string(id), {}};
    };
  };
  std::atomic<bool> started{false};
  auto first = worker.submit("a", [&] {
    started = true;
    released.wait();
    ran += 1;
    return lab::JobResult{lab::JobResult::Status::kDone, 200, "text/plain", "1", {}};
  });
  while (!started) std::this_thread::yield();  // the worker holds the first job
  auto second = worker.submit("a", job(10));
  auto third = worker.submit("a", job(100));
  auto other = worker.submit("b", job(1000));
  EXPECT_EQ(second.get().status, lab::JobResult::Status::kSuperseded);
  release.set_value();
  EXPECT_EQ(first.get().body, "1");
  const lab::JobResult t = third.get();
  EXPECT_EQ(t.status, lab::JobResult::Status::kDone);
  EXPECT_EQ(t.body, "100");
  EXPECT_EQ(other.get().body, "1000");
  EXPECT_EQ(ran, 1101);
}

TEST(LabWorker, MoreLanesThanTheCapAreRefusedNotQueued) {
  lab::Worker worker(2);
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  auto block = [released] {
    released.wait();
    return lab::JobResult{};
  };
  std::atomic<bool> started{false};
  auto running = worker.submit("x", [&] {
    started = true;
    released.wait();
    return lab::JobResult{};
  });
  while (!started) std::this_thread::yield();  // the worker holds the first job
  auto a = worker.submit("a", block);
  auto b = worker.submit("b", block);
  auto c = worker.submit("c", block);
  EXPECT_EQ(c.get().status, lab::JobResult::Status::kBusy);
  release.set_value();
  EXPECT_EQ(a.get().status, lab::JobResult::Status::kDone);
  EXPECT_EQ(b.get().status, lab::JobResult::Status::kDone);
  running.get();
}

TEST(LabServe, ServeRefusesABadPortAndWarnsOffLoopback) {
  const auto dir = testDir("lab", true);
  const CommandResult bad = runBinary(SHADOWLAB_BINARY, "serve --port 70000", dir);
  EXPECT_EQ(bad.status, 2);
  EXPECT_EQ(bad.err, "shadowlab: --port must be a whole number in 0..65535, got '70000'\n");
  // Off loopback: a warning, then the URL; SIGTERM stops it cleanly (timeout sends it).
  const CommandResult open =
      runBinary("timeout --preserve-status -s TERM 3",
                std::string(SHADOWLAB_BINARY) + " serve --host 0.0.0.0 --port 0", dir);
  EXPECT_EQ(open.status, 0) << open.err;
  EXPECT_NE(open.err.find("warning: serving on 0.0.0.0, not loopback"), std::string::npos)
      << open.err;
  EXPECT_NE(open.out.find("the lab is at http://0.0.0.0:"), std::string::npos) << open.out;
  EXPECT_NE(open.out.find("stopped (SIGTERM)"), std::string::npos) << open.out;
  EXPECT_TRUE(lab::isLoopback("127.0.0.1"));
  EXPECT_TRUE(lab::isLoopback("::1"));
  EXPECT_FALSE(lab::isLoopback("0.0.0.0"));
}

}  // namespace
}  // namespace sl::test
