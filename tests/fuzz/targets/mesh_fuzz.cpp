// tests/fuzz/targets/mesh_fuzz.cpp — libFuzzer target of the mesh loaders (core/scene/mesh_io.h
// loadMesh: OBJ, PLY and their gzip-compressed forms through Assimp). loadMesh reads a path and
// picks the format by the name, so the bytes go to a per-process temporary file named by their
// content: gzip's magic number -> loaded both as .obj.gz and as .ply.gz; "ply" first -> .ply;
// anything else -> .obj. Corpus: tests/fuzz/corpus/mesh/. Run: scripts/fuzz.sh; replayed by
// tests/fuzz.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include "core/scene/mesh_io.h"
#include "fuzz/targets/fuzz_target.h"

namespace {

namespace fs = std::filesystem;

// The bytes written to `path` (truncated first).
void writeBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

// The file names the input is loaded as, per its content (see the file comment).
std::vector<std::string> meshFileNames(const std::string& bytes) {
  constexpr unsigned char kGzipMagic0 = 0x1f, kGzipMagic1 = 0x8b;
  if (bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == kGzipMagic0 &&
      static_cast<unsigned char>(bytes[1]) == kGzipMagic1)
    return {"input.obj.gz", "input.ply.gz"};
  if (bytes.rfind("ply", 0) == 0) return {"input.ply"};
  return {"input.obj"};
}

// The process's own temporary folder, removed when the process exits normally.
struct TempDir {
  fs::path path = fs::temp_directory_path() / ("shadowlab-mesh-fuzz-" + std::to_string(getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const TempDir tempDir;
  const fs::path& dir = tempDir.path;
  const std::string bytes = sl::fuzz::bytesAsString(data, size);
  for (const std::string& name : meshFileNames(bytes)) {
    const fs::path path = dir / name;
    writeBytes(path, bytes);
    sl::fuzz::acceptLoadedOrInputError([&] { sl::loadMesh(path.string()); });
    fs::remove(path);
  }
  return 0;
}
