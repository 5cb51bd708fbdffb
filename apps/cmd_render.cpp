// apps/cmd_render.cpp — `shadowlab render` and `shadowlab compare` (apps/commands.h): the
// outputs checked before rendering, written only when the whole run succeeds.
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "apps/commands.h"
#include "core/base/errors.h"
#include "core/base/metrics.h"
#include "core/base/output_files.h"
#include "core/base/provenance.h"
#include "core/gl/gl_fault.h"
#include "core/scene/scene_library.h"
#include "registry/commands.h"
#include "registry/registry.h"
#include "registry/twins.h"
#include "teach/pass_dump.h"

namespace sl {
namespace {
namespace fs = std::filesystem;

// The files a --scene argument reads (core/scene/scene_library.cpp loadScene): the argument itself
// when it is a file, or assets/scenes/<name>.json. No output may replace them.
void addSceneInputs(OutputSet& outputs, const std::string& scene) {
  outputs.addInput(scene);
  outputs.addInput((fs::path(assetDirectory()) / "scenes" / (scene + ".json")).string());
}

// One JSON line: built before any output is committed, so that a name that is not UTF-8 (a
// scene file's name when the file has no "name" key) cannot fail after the files are written;
// invalid bytes become U+FFFD.
std::string jsonLine(const nlohmann::json& out) {
  return out.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// The PNG text of an output: the command line and the parameters (ASCII JSON).
Provenance pngProvenance(const nlohmann::json& parameters) {
  return {commandLine(), parameters.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace)};
}

// The destinations of `render`, checked before rendering (core/base/output_files.h).
struct RenderOutputs {
  OutputSet set;
  std::string image;                // temporary of --out
  std::optional<std::string> mask;  // temporary of --mask
  std::optional<std::string> dump;  // temporary directory of --dump-passes
};

// --dump-passes (teach/pass_dump.h): the buffers in pipeline order, passes.json, index.html.
void writeFrameOutputs(const Frame& frame, const PassDumpHeader& dumpHeader, RenderOutputs& outputs,
                       const Provenance& provenance) {
  if (!frame.color.empty() && !allFinite(frame.color)) throw GlError("the image has NaN or Inf");
  if (!allFinite(frame.visibility)) throw GlError("the visibility mask has NaN or Inf");
  if (outputs.dump) requireSomethingToDump(frame, dumpHeader.technique);
  outputs.set.beginWriting();
  writePng(outputs.image, frame.color, 8, provenance);
  if (outputs.mask) writePng(*outputs.mask, frame.visibility, 16, provenance);
  if (outputs.dump) writePassDump(*outputs.dump, frame, dumpHeader, provenance);
}

// SHADOWLAB_INJECT_GL_FAULT=KIND@pass=ID (core/gl/gl_fault.h) names a pass of the technique's
// pass tables: an id it has not is an input error that lists its ids, not a fault that never
// fires.
void requireFaultPassOf(const Technique& technique) {
  const std::string id = armedGlFaultPassId();
  if (id.empty()) return;
  std::string ids;
  for (const PassTable* table : allPassTables(technique))
    for (const PassSpec& pass : *table) {
      if (pass.id == id) return;
      if (ids.find(" " + pass.id + ",") == std::string::npos) ids += " " + pass.id + ",";
    }
  if (!ids.empty()) ids.pop_back();
  throw InputError(std::string(kGlFaultVariable) + ": " + technique.name + " has no pass '" + id +
                   "' (its pass ids:" + ids + ")");
}

}  // namespace

int render(const cli::Args& args) {
  RenderRequest request = prepareRender(args);
  requireFaultPassOf(*request.technique);
  RenderOutputs outputs;
  addSceneInputs(outputs.set, request.sceneName);
  outputs.image = outputs.set.addFile("--out", args.required("out"));
  if (auto mask = args.value("mask")) outputs.mask = outputs.set.addFile("--mask", *mask);
  if (auto dir = args.value("dump-passes")) {
    outputs.dump = outputs.set.addDirectory("--dump-passes", *dir);
    request.params.capturePasses = true;
  }
  const RenderRun run = runRender(request);
  const std::string line = jsonLine(run.line);
  const Technique& technique = *request.technique;
  const PassDumpHeader dumpHeader{technique.name,
                                  technique.paper,
                                  request.scene.name,
                                  run.made,
                                  twins::legacyTwinOf(technique.name),
                                  twins::legacyTwinPassesOf(technique.name)};
  writeFrameOutputs(run.frame, dumpHeader, outputs, pngProvenance(run.made));
  outputs.set.commit();
  std::cout << line << "\n";
  return 0;
}

int compare(const cli::Args& args) {
  const CompareRequest request = prepareCompare(args);
  for (const std::string& warning : request.warnings)
    std::cerr << "shadowlab: warning: " << warning << "\n";
  OutputSet outputs;
  addSceneInputs(outputs, request.sceneName);
  std::optional<std::string> diff;
  if (auto path = args.value("diff")) diff = outputs.addFile("--diff", *path);
  const CompareRun run = runCompare(request);
  const std::string line = jsonLine(run.line);
  if (diff)
    writePng(*diff, differenceHeatMap(run.a.visibility, run.b.visibility), 8,
             pngProvenance(run.made));
  outputs.commit();
  std::cout << line << "\n";
  return 0;
}

}  // namespace sl
