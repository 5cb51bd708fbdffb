// registry/commands.h — the work of `shadowlab render` and `shadowlab compare` without their
// files: what they check, render and print as their JSON line. apps/cmd_render.cpp adds the
// output files (--out, --mask, --dump-passes, --diff); the Python module (python/) returns the
// same JSON fields with the buffers as arrays. One code path, so a render from Python and one
// from the command line with the same options agree field for field.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "core/technique/technique.h"
#include "registry/cli.h"
#include "registry/shadow_error.h"

namespace sl {

// A render's options as they took effect on the technique(s) rendered: size, shadow_map,
// filter, precision, backend, imaging (null: an option none of them reads).
nlohmann::json optionsJson(const std::vector<const Technique*>& techniques, const RenderParams& p);
// The --params of a render as it used them: given ones and the defaults it read.
nlohmann::json paramsJson(const RenderParams& p);
// `p` with a fresh log of the --param values its technique reads (RenderParams::readLog).
RenderParams withReadLog(RenderParams p);

// `render`: the checked request (InputError, before anything renders) and its result.
struct RenderRequest {
  std::string sceneName;  // the --scene argument (a name or a file)
  SceneAdjustments adjustments;
  Scene scene;  // loaded, adjusted and viewed (--orbit)
  const Technique* technique = nullptr;
  RenderParams params;  // with a read log; capturePasses set by the caller when it wants them
};
RenderRequest prepareRender(const cli::Args& args);
struct RenderRun {
  Frame frame;
  nlohmann::json made;  // the effective parameters (the PNGs' shadowlab:parameters)
  nlohmann::json line;  // made + command, commit, frame_ms, passes, counters
};
RenderRun runRender(const RenderRequest& request);

// `compare`: the checked request and its result.
struct CompareRequest {
  std::string sceneName;
  SceneAdjustments adjustments;
  Scene scene;
  const Technique* a = nullptr;
  const Technique* b = nullptr;
  RenderParams params;            // the options common to both sides
  RenderParams paramsA, paramsB;  // with --a-param / --b-param
  double threshold = 0.0;
  std::vector<std::string> warnings;  // an option one side ignores (checkOptionsOfPair)
};
CompareRequest prepareCompare(const cli::Args& args);
struct CompareRun {
  Frame a, b;
  nlohmann::json made;  // the effective parameters (the --diff PNG's shadowlab:parameters)
  nlohmann::json line;  // the score (docs/error.md) + made + command, commit, frame times
};
CompareRun runCompare(const CompareRequest& request);

}  // namespace sl
