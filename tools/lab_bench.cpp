// lab_bench — request latency of the live lab: a bounded load generator on
// loopback against an in-process `shadowlab serve` (lab/lab_server.h).
//
// Per technique: --warmup requests, then --requests timed ones, each from a client that keeps
// one request in flight (as the page does per panel), the light nudged every request as a
// dragged slider would; the round trip of each (HTTP + parse + render on the worker + PNG) is
// timed with the wall clock. Then a drag: --burst requests sent back to back in one lane by two
// clients at once, counting how many the server dropped as stale (409) rather than queued.
// Prints a markdown table (p50/p95/max per technique) and the load average of the machine.
// Usage: build/bin/lab_bench [--size 512x384] [--requests 20] [--technique T ...]
#include <httplib.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include "core/base/errors.h"
#include "core/base/provenance.h"
#include "lab/lab_server.h"
#include "registry/cli.h"

namespace sl::lab::bench {
namespace {
using Clock = std::chrono::steady_clock;

constexpr double kLightStep = 0.01;  // world units the light moves per request (a slow drag)

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t i = std::min(v.size() - 1, size_t(p * double(v.size() - 1) + 0.5));
  return v[i];
}

std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

int run(int argc, char** argv) {
  CLI::App app{"latency of the live lab's /api/render on loopback (p50/p95 per technique)",
               "lab_bench"};
  std::string size = "512x384", scene = "brabec";
  int requests = 20, warmup = 2, burst = 16;
  std::vector<std::string> techniques = {"legacy.hw",  "modern.hw",    "legacy.pcf",
                                         "modern.pcf", "modern.gems4", "modern.gems16",
                                         "modern.vsm"};
  app.add_option("--size", size, "frame WxH [512x384]");
  app.add_option("--scene", scene, "scene [brabec]");
  app.add_option("--requests", requests, "timed requests per technique [20]")
      ->check(CLI::Range(1, 1000));
  app.add_option("--warmup", warmup, "untimed requests first [2]")->check(CLI::Range(0, 100));
  app.add_option("--burst", burst, "requests of the drag test per client [16]")
      ->check(CLI::Range(0, 1000));
  app.add_option("--technique", techniques, "techniques [the hardware and PCF ones]");
  if (!cli::parseTool(app, argc, argv)) return 0;
  int w = 0, h = 0;
  cli::parseSize(size, w, h);

  LabOptions options;
  options.port = 0;
  options.requestsPerSecond = 1e6;  // the bench measures latency, not the rate cap
  options.burst = 1000000;
  LabServer server(options);
  const int port = server.start();
  httplib::Client client("127.0.0.1", port);
  client.set_read_timeout(300, 0);
  const std::string load0 = loadAverage();
  std::printf(
      "lab_bench %s, %s, scene %s, %d timed requests after %d warm-up; load average "
      "before: %s\n\n",
      softwareName().c_str(), size.c_str(), scene.c_str(), requests, warmup, load0.c_str());
  std::printf(
      "| technique | p50 ms | p95 ms | max ms | frame p50 ms (GL passes) | drag: rendered / "
      "dropped as stale |\n|---|---|---|---|---|---|\n");
  int failures = 0;  // techniques whose requests failed
  for (const std::string& t : techniques) {
    std::vector<double> latency, frame;
    std::string failure;
    for (int i = 0; i < warmup + requests && failure.empty(); ++i) {
      const std::string light = "-3," + std::to_string(7.0 + kLightStep * i) + ",3";
      const std::string path = "/api/render?scene=" + scene + "&technique=" + t + "&size=" + size +
                               "&light-position=" + light + "&lane=bench";
      const auto t0 = Clock::now();
      auto r = client.Get(path.c_str());
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
      if (!r || r->status != 200) {
        failure = r ? r->body : "no answer";
        break;
      }
      if (i < warmup) continue;
      latency.push_back(ms);
      frame.push_back(std::stod(r->get_header_value("X-Shadowlab-Frame-Ms")));
    }
    if (!failure.empty()) {
      std::printf("| %s | failed: %s | | | | |\n", t.c_str(), failure.c_str());
      ++failures;
      continue;
    }
    // The drag: two clients send `burst` requests each into one lane without waiting for
    // each other; the server renders the latest and drops the waiting stale ones.
    std::atomic<int> rendered{0}, dropped{0};
    auto drag = [&](int offset) {
      httplib::Client c("127.0.0.1", port);
      c.set_read_timeout(300, 0);
      for (int i = 0; i < burst; ++i) {
        const std::string path = "/api/render?scene=" + scene + "&technique=" + t +
                                 "&size=" + size + "&light-position=-3," +
                                 std::to_string(7.0 + kLightStep * (2 * i + offset)) +
                                 ",3&lane=drag";
        auto r = c.Get(path.c_str());
        if (r && r->status == 200) ++rendered;
        if (r && r->status == 409) ++dropped;
      }
    };
    std::thread a(drag, 0), b(drag, 1);
    a.join();
    b.join();
    std::printf("| %s | %.0f | %.0f | %.0f | %.0f | %d / %d |\n", t.c_str(),
                percentile(latency, 0.5), percentile(latency, 0.95), percentile(latency, 1.0),
                percentile(frame, 0.5), rendered.load(), dropped.load());
    std::fflush(stdout);
  }
  std::printf("\nload average after: %s (1, 5, 15 min; %u hardware threads)\n",
              loadAverage().c_str(), std::thread::hardware_concurrency());
  server.stop();
  // A failed technique is a failed benchmark: scripts/perf_tables.sh must not publish it.
  return failures == 0 ? 0 : 1;
}

}  // namespace
}  // namespace sl::lab::bench

int main(int argc, char** argv) {
  return sl::runProgram("lab_bench", argc, argv, sl::lab::bench::run);
}
