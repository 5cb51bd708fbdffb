// apps/volumes_bench.cpp — frame times of modern.hw, modern.hybrid, modern.volumes and
// modern.smoothies (Chan 2004 Figures 3-10, 3-11, 4-8) with the overdraw counters; one JSON
// object per technique per line. See docs/volumes.md.
//
//   volumes_bench [--scene cubes|<built-in>] [--size WxH] [--shadow-map N] [--frames N]
//                 [--backend osmesa|egl] [--technique T ...]
#include <cstdlib>
#include <iostream>

#include "core/errors.h"
#include "core/scene_library.h"
#include "modern/volumes_bench.h"

int main(int argc, char** argv) {
  using namespace sl;
  try {
    std::string sceneName = "cubes";
    RenderParams params;
    params.width = 800;
    params.height = 600;
    params.shadowMapTexels = 1024;
    int frames = 10;
    std::vector<std::string> techniques;
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      const auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw InputError(arg + " needs a value");
        return argv[++i];
      };
      if (arg == "--scene") {
        sceneName = value();
      } else if (arg == "--size") {
        const std::string v = value();
        if (std::sscanf(v.c_str(), "%dx%d", &params.width, &params.height) != 2)
          throw InputError("--size wants WxH, got '" + v + "'");
      } else if (arg == "--shadow-map") {
        params.shadowMapTexels = std::atoi(value().c_str());
      } else if (arg == "--frames") {
        frames = std::atoi(value().c_str());
      } else if (arg == "--backend") {
        params.backend = parseBackend(value());
      } else if (arg == "--technique") {
        techniques.push_back(value());
      } else {
        throw InputError("unknown option '" + arg + "'");
      }
    }
    if (techniques.empty())
      techniques = {"modern.hw", "modern.hybrid", "modern.volumes", "modern.smoothies"};
    const Scene scene = sceneName == "cubes" ? modern::fillHeavyScene() : builtinScene(sceneName);
    for (const auto& row : modern::benchmarkShadowVolumes(scene, params, techniques, frames))
      std::cout << modern::toJson(row).dump() << std::endl;
    return 0;
  } catch (const InputError& e) {
    std::cerr << "volumes_bench: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "volumes_bench: " << e.what() << "\n";
    return 3;
  }
}
