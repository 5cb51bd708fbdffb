// lab/lab_server.h — `shadowlab serve`: the live lab. An HTTP server (cpp-httplib)
// that serves the page (lab/web/, embedded at build time) and a small API:
//
//   GET /api/techniques   names, papers, summaries, the common options each reads, and every
//                         --param key with its kind, default and range (as the technique reads
//                         it: core/technique/technique.h ParamDeclaration)
//   GET /api/scenes       built-in and asset scenes with their camera orbit and light position
//   GET /api/render?scene=S&technique=T&size=WxH&shadow-map=N&filter=K&precision=P
//                  &param=key=value(&param=...)&light=X,Y,Z&orbit=AZ,EL,DIST
//                  &view=image|mask|passes&lane=L
//                         image/mask: PNG; passes: JSON (teach/pass_dump.h passesJson, with each
//                         pass's median time over kPassTimingFrames and a URL per pass image)
//   GET /api/error?...    the same frame's visibility against reference.hard pixel=area (the
//                         pixel-integrated truth, cached per scene/size/light/camera):
//                         JSON, or a heat map PNG with view=image
//   GET /api/pass/ID/N.png  image N of a passes answer (the last kKeptPassFrames are kept)
//
// The query keys are the CLI's option names, parsed by the CLI's own parser (registry/cli.h),
// so both reject the same input with the same one line: 400 text/plain. An unknown path is 404,
// a GL failure 500; the server keeps serving. Renders run on one worker thread (lab/worker.h).
#pragma once

#include <memory>
#include <string>

#include "registry/cli.h"

namespace sl::lab {

// Caps of the served API; the CLI's own limits are wider.
constexpr int kMaxServedWidth = 1600;               // pixels
constexpr int kMaxServedHeight = 1200;              // pixels
constexpr int kMaxServedShadowMap = 4096;           // texels per side
constexpr int kMaxServedFilter = 8;                 // PCF footprint side
constexpr double kDefaultRequestsPerSecond = 60.0;  // API requests, all clients together
constexpr int kDefaultBurst = 120;                  // requests above the rate absorbed at once
constexpr int kMaxLanes = 8;                        // lanes with a waiting render
constexpr int kPassTimingFrames = 3;  // frames whose per-pass median view=passes gives
constexpr int kKeptPassFrames = 4;    // passes answers whose images stay fetchable

struct LabOptions {
  std::string host = "127.0.0.1";
  int port = 8080;  // 0: any free port (tests)
  double requestsPerSecond = kDefaultRequestsPerSecond;
  int burst = kDefaultBurst;
};

class LabServer {
 public:
  explicit LabServer(LabOptions options);
  ~LabServer();  // stop()
  LabServer(const LabServer&) = delete;
  LabServer& operator=(const LabServer&) = delete;

  // Binds and starts listening on a thread of its own. Returns the port. Throws InputError when the
  // address cannot be bound.
  int start();
  void stop();  // stops listening and joins; safe to call twice
  std::string url() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Whether `host` is a loopback address (127.0.0.0/8, ::1, localhost).
bool isLoopback(const std::string& host);

// The `serve` command: starts the lab, prints its URL, and stops cleanly on SIGINT or SIGTERM.
int runServe(const cli::Args& args);

}  // namespace sl::lab
