// tests/fuzz/targets/scene_file_fuzz.cpp — libFuzzer target of the scene-file loader
// (core/scene/scene_library.h parseSceneJson, what loadScene does with a file's text): the bytes
// are a scene JSON document, parsed from memory. Relative mesh paths resolve in
// tests/fuzz/scene_meshes/ (two tiny meshes), so that the seeds' mesh objects load quickly.
// Corpus: tests/fuzz/corpus/scene_file/. Run: scripts/fuzz.sh; replayed by tests/fuzz.
#include "core/scene/scene_library.h"
#include "fuzz/targets/fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return sl::fuzz::acceptLoadedOrInputError([&] {
    sl::parseSceneJson(sl::fuzz::bytesAsString(data, size), "fuzz.json",
                       SHADOWLAB_SOURCE_DIR "/tests/fuzz/scene_meshes");
  });
}
