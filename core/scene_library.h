// core/scene_library.h — finding scenes by name: built-in procedural scenes and JSON files.
//
// A --scene argument is resolved in this order: a built-in name (see builtinSceneNames()),
// a file assets/scenes/<name>.json, or a path to a .json file.
#pragma once

#include <string>
#include <vector>

#include "core/scene.h"

namespace sl {

constexpr const char* kDefaultScene = "brabec";

std::vector<std::string> builtinSceneNames();
std::vector<std::string> sceneFileNames();  // names of assets/scenes/*.json
std::string assetDirectory();               // $SHADOWLAB_ASSETS or the source tree's assets/

// Throws InputError for an unknown name or a malformed file.
Scene loadScene(const std::string& nameOrPath);
Scene builtinScene(const std::string& name);  // throws InputError if unknown
// Parses a JSON scene document; `baseDir` resolves relative mesh paths.
Scene parseSceneJson(const std::string& text, const std::string& sourceName,
                     const std::string& baseDir);

}  // namespace sl
