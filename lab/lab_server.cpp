// lab/lab_server.cpp — `shadowlab serve`: the HTTP server, its routes and the serve command
// (lab/lab_server.h). A query is parsed in lab_request.cpp and rendered on the worker thread
// (lab/worker.h) with the caches of lab_engine.cpp.
#include "lab/lab_server.h"

#include <httplib.h>
#include <pthread.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <deque>
#include <iostream>
#include <list>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "core/base/decimal.h"
#include "core/base/errors.h"
#include "core/base/metrics.h"
#include "core/base/provenance.h"
#include "core/scene/scene_library.h"
#include "core/technique/pass_run_key.h"
#include "lab/lab_engine.h"
#include "lab/lab_request.h"
#include "lab/web_files.h"
#include "lab/worker.h"
#include "registry/registry.h"
#include "registry/shadow_error.h"
#include "teach/pass_dump.h"

namespace sl::lab {
namespace {
using json = nlohmann::json;

constexpr time_t kSocketTimeoutSeconds = 5;  // read/write timeout of a connection
constexpr size_t kMaxPayloadBytes = 1024;    // request bodies (the API is GET only)

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

bool isLoopback(const std::string& host) {
  return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

// ------------------------------------------------------------------ the server

struct LabServer::Impl {
  LabOptions options;
  Engine engine;             // the worker thread's alone
  Worker worker{kMaxLanes};  // after `engine`: its thread stops before the engine goes
  httplib::Server server;
  std::thread listener;
  int port = 0;

  std::mutex initMutex;  // lazily built answers of /api/techniques and /api/scenes
  std::optional<std::string> techniquesJson, scenesJson;

  std::mutex rateMutex;  // token bucket over every /api request
  double tokens = 0.0;
  std::chrono::steady_clock::time_point refilled = std::chrono::steady_clock::now();

  std::mutex passesMutex;  // images of the last kKeptPassFrames passes answers
  std::deque<std::pair<unsigned long long, std::vector<PassDumpImage>>> keptPasses;
  unsigned long long nextPassesId = 1;

  // The GL contexts are released on the thread that made them current.
  ~Impl() {
    worker.runNow([this] {
      engine.clear();
      return JobResult{};
    });
  }

  bool allowRequest() {
    std::lock_guard<std::mutex> lock(rateMutex);
    const auto now = std::chrono::steady_clock::now();
    tokens = std::min(
        double(options.burst),
        tokens + options.requestsPerSecond * std::chrono::duration<double>(now - refilled).count());
    refilled = now;
    if (tokens < 1.0) return false;
    tokens -= 1.0;
    return true;
  }

  // /api/techniques: every technique with its --params as it declares them
  // (core/technique/technique.h ParamSpec), so the page builds its controls from the declarations.
  static std::string buildTechniques() {
    json out = json::array();
    for (const Technique& t : allTechniques()) {
      json params = json::array();
      for (const ParamSpec& p : t.params) {
        json entry = {{"key", p.key},
                      {"kind", paramKindName(p.kind)},
                      {"default", p.defaultText()},
                      {"meaning", p.meaning}};
        if (p.kind == ParamSpec::Kind::kNumber || p.kind == ParamSpec::Kind::kInteger) {
          entry["min"] = p.lo;
          entry["max"] = p.hi;
        }
        if (p.kind == ParamSpec::Kind::kChoice) entry["values"] = p.choices;
        if (p.acceptsAuto) entry["auto"] = true;
        params.push_back(entry);
      }
      json reads = {{"shadow-map", t.reads.shadowMap},
                    {"filter", t.reads.filter},
                    {"precision", t.reads.precision},
                    {"imaging", readsOption(t, CommonOption::kImaging)}};
      out.push_back({{"name", t.name},
                     {"paper", t.paper},
                     {"summary", t.summary},
                     {"status", t.status},
                     {"reads", reads},
                     {"params", params}});
    }
    json doc = {
        {"techniques", out},
        {"defaults", {{"size", "800x600"}, {"shadow-map", 512}, {"filter", 2}, {"precision", "8"}}},
        {"caps",
         {{"width", kMaxServedWidth},
          {"height", kMaxServedHeight},
          {"shadow-map", kMaxServedShadowMap},
          {"filter", kMaxServedFilter}}},
        {"commit", buildCommit()}};
    return doc.dump(-1, ' ', false, json::error_handler_t::replace);
  }

  std::string buildScenes() {
    json out = json::array();
    const std::vector<std::string> builtins = builtinSceneNames();
    for (const std::string& name : servedSceneNames()) {
      json entry = {
          {"name", name},
          {"builtin", std::find(builtins.begin(), builtins.end(), name) != builtins.end()}};
      const JobResult loaded = worker.runNow([&] {
        return guarded([&] {
          const Scene& s = engine.scene(name);
          const cli::ViewPose pose = cli::viewPose(s);
          const Bounds b = sceneBounds(s);
          entry["description"] = s.description;
          entry["orbit"] = {pose.azimuthDegrees, pose.elevationDegrees, pose.distance};
          entry["light"] = {pose.light.x, pose.light.y, pose.light.z};
          entry["light_target"] = {s.light.target.x, s.light.target.y, s.light.target.z};
          entry["bounds"] = {{b.lo.x, b.lo.y, b.lo.z}, {b.hi.x, b.hi.y, b.hi.z}};
          return JobResult{};
        });
      });
      if (loaded.httpStatus != 200) entry["error"] = loaded.body;
      out.push_back(entry);
    }
    return json{{"scenes", out}, {"default", kDefaultScene}}.dump(-1, ' ', false,
                                                                  json::error_handler_t::replace);
  }

  static void answer(httplib::Response& res, const JobResult& r) {
    res.status = r.httpStatus;
    res.set_header("Cache-Control", "no-store");
    for (const auto& [name, value] : r.headers) res.set_header(name.c_str(), value);
    res.set_content(r.body, r.contentType.empty() ? "text/plain" : r.contentType.c_str());
  }

  static void answerNotGet(httplib::Response& res) {
    res.status = 405;
    res.set_header("Allow", "GET");
    res.set_content("the lab answers GET only", "text/plain");
  }

  static void badRequest(httplib::Response& res, const std::string& message) {
    answer(res, JobResult{JobResult::Status::kDone, 400, "text/plain", oneLine(message), {}});
  }

  // The request's scene as every command sees it (cli::viewScene: scene knobs, then orbit).
  Scene requestScene(const LabRequest& r) {
    Scene scene = engine.scene(r.sceneName);
    cli::viewScene(r.args, scene);
    return scene;
  }

  void handleRender(const httplib::Request& req, httplib::Response& res) {
    LabRequest r;
    try {
      r = parseRequest(req, {"image", "mask", "passes"});
    } catch (const InputError& e) {
      return badRequest(res, e.what());
    }
    auto future = worker.submit(r.lane, [this, r]() {
      return guarded([&] {
        const Scene scene = requestScene(r);
        if (r.view != "passes") {
          const Frame f = engine.render(*r.technique, scene, r.params);
          JobResult out =
              r.view == "mask" ? pngResult(f.visibility, 16, r) : pngResult(f.color, 8, r);
          out.headers = {{"X-Shadowlab-Command", r.command},
                         {"X-Shadowlab-Frame-Ms", formatNumber(f.totalMilliseconds())}};
          return out;
        }
        return passes(r, scene);
      });
    });
    answer(res, future.get());
  }

  JobResult passes(const LabRequest& r, const Scene& scene) {
    // The per-pass medians over kPassTimingFrames plain frames, then one frame with capture.
    std::vector<Frame> timed;
    for (int i = 0; i < kPassTimingFrames; ++i)
      timed.push_back(engine.render(*r.technique, scene, r.params));
    RenderParams captured = r.params;
    captured.capturePasses = true;
    const Frame frame = engine.render(*r.technique, scene, captured);
    std::vector<PassDumpImage> images;
    if (!frame.intermediates.empty()) images = planPassDump(frame, r.technique->name);
    json parameters = r.parameters;
    parameters["params"] = effectiveParams(r.params);
    const PassDumpHeader header{r.technique->name, r.technique->paper, scene.name, parameters, ""};
    json doc = passesJson(frame, header, images);
    json medians = json::array();
    std::vector<double> frameTimes;
    for (const Frame& f : timed) frameTimes.push_back(f.totalMilliseconds());
    for (size_t i = 0; i < timed.front().passes.size(); ++i) {
      std::vector<double> times;
      for (const Frame& f : timed)
        if (i < f.passes.size() && passRunKey(f.passes[i]) == passRunKey(timed.front().passes[i]))
          times.push_back(f.passes[i].milliseconds);
      medians.push_back({{"name", timed.front().passes[i].name},
                         {"median_ms", median(times)},
                         {"frames", times.size()}});
    }
    doc["median_timings"] = medians;
    doc["median_frame_ms"] = median(frameTimes);
    doc["timing_frames"] = kPassTimingFrames;
    doc["command"] = r.command;
    std::lock_guard<std::mutex> lock(passesMutex);
    const unsigned long long id = nextPassesId++;
    for (size_t i = 0; i < images.size() && i < doc["images"].size(); ++i)
      doc["images"][i]["url"] =
          "/api/pass/" + std::to_string(id) + "/" + std::to_string(i) + ".png";
    keptPasses.emplace_back(id, std::move(images));
    while (keptPasses.size() > size_t(kKeptPassFrames)) keptPasses.pop_front();
    return jsonResult(doc);
  }

  void handleError(const httplib::Request& req, httplib::Response& res) {
    LabRequest r;
    try {
      r = parseRequest(req, {"json", "image"});
    } catch (const InputError& e) {
      return badRequest(res, e.what());
    }
    auto future = worker.submit(r.lane, [this, r]() {
      return guarded([&] {
        const Scene scene = requestScene(r);
        const Frame f = engine.render(*r.technique, scene, r.params);
        bool cached = false;
        const Engine::Reference& ref = engine.reference(scene, r.params, cached);
        if (r.view == "image") {
          JobResult out = pngResult(errorHeatMap(f.visibility, ref.truth), 8, r);
          out.headers = {{"X-Shadowlab-Command", r.command}};
          return out;
        }
        const MaskDifference all = compareMasks(f.visibility, ref.truth.visibility);
        const ShadowError score = scoreShadow(f.visibility, ref.truth);
        json doc = toJson(score);  // the fields bench and compare print for the same pair
        doc.update(json{{"technique", r.technique->name},
                        {"scene", scene.name},
                        {"reference", score.truth},
                        {"reference_cached", cached},
                        {"reference_ms", ref.milliseconds},
                        {"frame_ms", f.totalMilliseconds()},
                        {"all_pixels", toJson(all)},
                        {"region_pixels", score.all.pixels},
                        {"left_out_text", describeLeftOut(score.counts)},
                        {"params", effectiveParams(r.params)},
                        {"command", r.command},
                        {"commit", buildCommit()}});
        return jsonResult(doc);
      });
    });
    answer(res, future.get());
  }

  void handlePass(const httplib::Request& req, httplib::Response& res) {
    const std::optional<long long> id = parseWholeNumber(req.matches[1].str());
    const std::optional<long long> index = parseWholeNumber(req.matches[2].str());
    std::lock_guard<std::mutex> lock(passesMutex);
    for (const auto& [keptId, images] : keptPasses)
      if (id && index && (long long)keptId == *id && *index >= 0 &&
          *index < (long long)images.size()) {
        res.set_header("Cache-Control", "no-store");
        res.set_content(encodePng(images[size_t(*index)].image, 8), "image/png");
        return;
      }
    res.status = 404;
    res.set_content("no such pass image (only the last " + std::to_string(kKeptPassFrames) +
                        " passes answers are kept)",
                    "text/plain");
  }

  void routes() {
    server.set_read_timeout(kSocketTimeoutSeconds, 0);
    server.set_write_timeout(kSocketTimeoutSeconds, 0);
    server.set_keep_alive_timeout(kSocketTimeoutSeconds);
    server.set_payload_max_length(kMaxPayloadBytes);
    server.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
      // A request of another method without Content-Length or Transfer-Encoding has no body
      // (RFC 9112 §6.3), but httplib would wait for one until the read timeout and answer 400:
      // it gets its 405 at once. (With a body, the routes below answer 405 once it is read.)
      if (req.method != "GET" && req.method != "HEAD" && !req.has_header("Content-Length") &&
          !req.has_header("Transfer-Encoding")) {
        answerNotGet(res);
        return httplib::Server::HandlerResponse::Handled;
      }
      if (req.path.rfind("/api/", 0) == 0 && !allowRequest()) {
        res.status = 429;
        res.set_content("too many requests: the lab answers at most " +
                            formatNumber(options.requestsPerSecond) + " API requests a second",
                        "text/plain");
        return httplib::Server::HandlerResponse::Handled;
      }
      return httplib::Server::HandlerResponse::Unhandled;
    });
    server.Get("/api/techniques", [this](const httplib::Request&, httplib::Response& res) {
      std::lock_guard<std::mutex> lock(initMutex);
      if (!techniquesJson) techniquesJson = buildTechniques();
      answer(res,
             JobResult{JobResult::Status::kDone, 200, "application/json", *techniquesJson, {}});
    });
    server.Get("/api/scenes", [this](const httplib::Request&, httplib::Response& res) {
      std::lock_guard<std::mutex> lock(initMutex);
      if (!scenesJson) scenesJson = buildScenes();
      answer(res, JobResult{JobResult::Status::kDone, 200, "application/json", *scenesJson, {}});
    });
    server.Get("/api/render", [this](const httplib::Request& req, httplib::Response& res) {
      handleRender(req, res);
    });
    server.Get("/api/error", [this](const httplib::Request& req, httplib::Response& res) {
      handleError(req, res);
    });
    server.Get(
        R"(/api/pass/([0-9]{1,12})/([0-9]{1,6})\.png)",
        [this](const httplib::Request& req, httplib::Response& res) { handlePass(req, res); });
    server.Get(R"(/|/[a-z_-]+\.(html|js|css))",
               [](const httplib::Request& req, httplib::Response& res) {
                 const std::string path = req.path == "/" ? "/index.html" : req.path;
                 auto it = webFiles().find(path);
                 if (it == webFiles().end()) {
                   res.status = 404;
                   res.set_content("not found: " + oneLine(req.path), "text/plain");
                   return;
                 }
                 res.set_header("Content-Security-Policy",
                                "default-src 'self'; img-src 'self' blob: data:; style-src 'self'");
                 res.set_content(it->second.text, it->second.contentType.c_str());
               });
    const auto notGet = [](const httplib::Request&, httplib::Response& res) { answerNotGet(res); };
    server.Post(".*", notGet);
    server.Put(".*", notGet);
    server.Delete(".*", notGet);
    server.Patch(".*", notGet);
    server.Options(".*", notGet);
    server.set_error_handler(httplib::Server::HandlerWithResponse(
        [](const httplib::Request& req, httplib::Response& res) {
          if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
          res.set_content(res.status == 404 ? "not found: " + oneLine(req.path)
                                            : "HTTP " + std::to_string(res.status),
                          "text/plain");
          return httplib::Server::HandlerResponse::Handled;
        }));
    server.set_exception_handler(
        [](const httplib::Request&, httplib::Response& res, std::exception_ptr ep) {
          std::string what = "internal error";
          try {
            std::rethrow_exception(ep);
          } catch (const std::exception& e) {
            what = e.what();
          } catch (...) {}
          res.status = 500;
          res.set_content(oneLine(what), "text/plain");
        });
  }
};

LabServer::LabServer(LabOptions options) : impl_(std::make_unique<Impl>()) {
  impl_->options = std::move(options);
  impl_->tokens = impl_->options.burst;
  impl_->routes();
}

LabServer::~LabServer() { stop(); }

int LabServer::start() {
  Impl& i = *impl_;
  if (i.options.port == 0) {
    i.port = i.server.bind_to_any_port(i.options.host.c_str());
    if (i.port <= 0) throw InputError("cannot listen on " + i.options.host + " (any port)");
  } else {
    if (!i.server.bind_to_port(i.options.host.c_str(), i.options.port))
      throw InputError("cannot listen on " + i.options.host + ":" + std::to_string(i.options.port) +
                       " (in use, or not an address of this "
                       "machine)");
    i.port = i.options.port;
  }
  i.listener = std::thread([&i] { i.server.listen_after_bind(); });
  return i.port;
}

void LabServer::stop() {
  if (!impl_) return;
  impl_->server.stop();
  if (impl_->listener.joinable()) impl_->listener.join();
}

std::string LabServer::url() const {
  const std::string& host = impl_->options.host;
  const bool v6 = host.find(':') != std::string::npos;
  return "http://" + (v6 ? "[" + host + "]" : host) + ":" + std::to_string(impl_->port) + "/";
}

int runServe(const cli::Args& args) {
  LabOptions options;
  if (auto h = args.value("host")) {
    if (h->empty()) throw InputError("--host must name an address, got ''");
    options.host = *h;
  }
  if (auto p = args.value("port")) {
    constexpr long long kMaxPort = 65535;
    const std::optional<long long> port = parseWholeNumber(*p);
    if (!port || *port < 0 || *port > kMaxPort)
      throw InputError("--port must be a whole number in 0..65535, got '" + *p + "'");
    options.port = int(*port);
  }
  if (!isLoopback(options.host))
    std::cerr << "shadowlab: warning: serving on " << options.host
              << ", not loopback: anyone who reaches this address can use the lab and its CPU\n";
  // Ctrl-C and SIGTERM are received by sigwait below, never by the server's threads: block
  // them before any thread starts (threads inherit the mask).
  // A shell's background job starts with SIGINT ignored, and an ignored signal is discarded,
  // never pending: restore the default action first (it never runs while the signal is blocked).
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  sigset_t stopSignals;
  sigemptyset(&stopSignals);
  sigaddset(&stopSignals, SIGINT);
  sigaddset(&stopSignals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stopSignals, nullptr);
  LabServer server(options);
  server.start();
  std::cout << "shadowlab: the lab is at " << server.url() << " (Ctrl-C stops it)" << std::endl;
  int signal = 0;
  sigwait(&stopSignals, &signal);
  server.stop();
  std::cout << "shadowlab: stopped (" << (signal == SIGINT ? "SIGINT" : "SIGTERM") << ")"
            << std::endl;
  return 0;
}

}  // namespace sl::lab
