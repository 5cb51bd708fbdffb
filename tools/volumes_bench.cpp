// tools/volumes_bench.cpp — frame times of modern.hw, modern.hybrid, modern.volumes and
// modern.smoothies (Chan 2004 Figures 3-10, 3-11, 4-8) with the overdraw counters; one JSON
// object per technique per line. See docs/volumes.md.
//
//   volumes_bench [--scene S] [--size WxH] [--shadow-map N] [--frames N]
//                 [--backend osmesa|egl] [--technique T[:key=value,...] ...]
//   (T:key=value passes --param values to that technique only, e.g. modern.hybrid:mask=stencil;
//    the row's "technique" is the whole spelling)
//   volumes_bench --doc-images DIR     the three images of docs/volumes.md
//
// S: cubes (the default, assets/scenes/cubes.json), a built-in scene or a scene file.
#include "measure/volumes_bench.h"

#include <CLI/CLI.hpp>
#include <iostream>

#include "core/base/errors.h"
#include "core/base/provenance.h"
#include "core/scene/scene_library.h"
#include "registry/cli.h"
#include "registry/registry.h"

namespace {
using namespace sl;

constexpr int kMaxShadowMap = 1 << 16;  // texels; the GL maximum is checked once a context exists
constexpr int kMaxFrames = 1000;        // timed frames: more would take hours on llvmpipe
}  // namespace

int main(int argc, char** argv) {
  sl::recordCommandLine(argc, argv);  // PNG text chunks name the command (core/base/provenance.h)
  using namespace sl;
  try {
    std::string sceneName = "cubes";
    RenderParams params;
    params.width = 800;
    params.height = 600;
    params.shadowMapTexels = 1024;
    int frames = kTimedFrames;  // after kWarmupFrames (core/technique/frame_timing.h)
    std::vector<std::string> techniques;
    std::string size, shadowMap, framesText, backend, docImages;
    CLI::App app{"frame times and overdraw counters of the shadow-volume techniques (JSON lines)",
                 "volumes_bench"};
    app.add_option("--scene", sceneName, "cubes, a built-in scene or a scene file [cubes]")
        ->type_name("S");
    app.add_option("--size", size, "window WxH [800x600]")->type_name("WxH");
    app.add_option("--shadow-map", shadowMap, "shadow map side in texels [1024]")->type_name("N");
    app.add_option("--frames", framesText, "timed frames per technique, after the warm-up")
        ->type_name("N");
    app.add_option("--backend", backend, "osmesa or egl [osmesa]")->type_name("NAME");
    app.add_option("--technique", techniques,
                   "T or T:key=value,... (repeatable) [hw, hybrid, volumes, smoothies]")
        ->type_name("T")
        ->type_size(1)
        ->allow_extra_args(false)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    app.add_option("--doc-images", docImages, "write the three images of docs/volumes.md to DIR")
        ->type_name("DIR");
    if (!cli::parseTool(app, argc, argv)) return 0;
    if (!size.empty()) cli::parseSize(size, params.width, params.height);
    if (!shadowMap.empty())
      params.shadowMapTexels = cli::parsePositiveInt("--shadow-map", shadowMap, kMaxShadowMap);
    if (!framesText.empty()) frames = cli::parsePositiveInt("--frames", framesText, kMaxFrames);
    if (!backend.empty()) params.backend = parseBackend(backend);
    if (!docImages.empty()) {
      modern::writeVolumesDocImages(docImages);
      return 0;
    }
    if (techniques.empty())
      techniques = {"modern.hw", "modern.hybrid", "modern.volumes", "modern.smoothies"};
    const Scene scene = loadScene(sceneName);
    for (const std::string& spelling : techniques) {
      // "T:key=value,key=value": the technique's own --param values.
      RenderParams own = params;
      const size_t colon = spelling.find(':');
      const std::string name = spelling.substr(0, colon);
      if (colon != std::string::npos) {
        std::string rest = spelling.substr(colon + 1);
        while (!rest.empty()) {
          const size_t comma = rest.find(',');
          const std::string pair = rest.substr(0, comma);
          const size_t eq = pair.find('=');
          if (eq == std::string::npos || eq == 0)
            throw InputError("--technique " + spelling + ": want T:key=value, got '" + pair + "'");
          own.extra[pair.substr(0, eq)] = pair.substr(eq + 1);
          rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
        }
      }
      for (auto row : modern::benchmarkShadowVolumes(scene, own, {name}, frames)) {
        row.technique = spelling;
        // Invalid UTF-8 (a scene file named in other bytes) becomes U+FFFD, never a throw.
        std::cout << modern::toJson(row).dump(-1, ' ', false,
                                              nlohmann::json::error_handler_t::replace)
                  << std::endl;
      }
    }
    return 0;
  } catch (const InputError& e) {
    std::cerr << "volumes_bench: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "volumes_bench: " << e.what() << "\n";
    return 3;
  }
}
