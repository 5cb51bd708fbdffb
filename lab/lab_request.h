// lab/lab_request.h — a query of the lab's /api/render and /api/error parsed as `shadowlab render`
// parses its command line (registry/cli.h), with the API's own keys (view, lane) and caps
// (lab/lab_server.h kMaxServed*).
#pragma once

#include <httplib.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/technique/technique.h"
#include "registry/cli.h"

namespace sl::lab {

constexpr const char* kDefaultLane = "main";

// One line: the CLI prints its InputError on one line; a value with a line break would not be.
std::string oneLine(std::string text);

// The scenes the lab serves: the built-in ones, then the scene files.
std::vector<std::string> servedSceneNames();

// A parsed /api/render or /api/error query: the CLI's Args of `shadowlab render` with the two
// keys of the API alone (view, lane).
struct LabRequest {
  cli::Args args;
  std::string view;
  std::string lane = kDefaultLane;
  std::string sceneName;
  const Technique* technique = nullptr;
  RenderParams params;
  std::string command;        // the `shadowlab render ...` line that reproduces the frame
  nlohmann::json parameters;  // the query as it took effect, for the PNG's provenance
};

// The request's query as `shadowlab render` options; `views`: the view names this path accepts,
// the first the default. InputError (the CLI's one line) for anything the CLI or the caps refuse.
LabRequest parseRequest(const httplib::Request& req, const std::vector<std::string>& views);

}  // namespace sl::lab
