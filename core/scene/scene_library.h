// core/scene/scene_library.h — finding scenes by name: built-in procedural scenes and JSON files.
//
// A --scene argument: a built-in name, a path when it ends in .json or holds a '/' (no such
// file: an error naming it), else assets/scenes/<name>.json. Meshes: docs/scene-files.md.
#pragma once

#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace sl {

constexpr const char* kDefaultScene = "brabec";

std::vector<std::string> builtinSceneNames();
std::vector<std::string> sceneFileNames();  // names of assets/scenes/*.json
std::string assetDirectory();               // $SHADOWLAB_ASSETS or the source tree's assets/

// Throws InputError for an unknown name or a malformed file.
Scene loadScene(const std::string& nameOrPath);
// The file a --scene argument reads: "" for a built-in scene, else the path loadScene opens
// (the argument itself, or assets/scenes/<name>.json); not checked for existence here.
std::string sceneFilePath(const std::string& nameOrPath);
Scene builtinScene(const std::string& name);  // throws InputError if unknown
// Parses a JSON scene document; `baseDir` (the scene file's folder) resolves mesh paths.
Scene parseSceneJson(const std::string& text, const std::string& sourceName,
                     const std::string& baseDir);

}  // namespace sl
