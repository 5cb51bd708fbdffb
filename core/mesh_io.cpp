#include "core/mesh_io.h"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "core/errors.h"
#include "core/primitives.h"

namespace sl {
namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string readGzip(const std::string& path) {
  gzFile f = gzopen(path.c_str(), "rb");
  if (f == nullptr) throw InputError("cannot open " + path);
  std::string data;
  constexpr int kChunkBytes = 1 << 16;
  std::vector<char> chunk(kChunkBytes);
  int n = 0;
  while ((n = gzread(f, chunk.data(), kChunkBytes)) > 0) data.append(chunk.data(), size_t(n));
  int err = 0;
  const char* message = gzerror(f, &err);
  const bool failed = n < 0 || (err != Z_OK && err != Z_STREAM_END);
  const std::string why = failed ? message : "";
  gzclose(f);
  if (failed) throw InputError(path + ": truncated or corrupt gzip data (" + why + ")");
  return data;
}

}  // namespace

Mesh loadMesh(const std::string& path) {
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw InputError("cannot open mesh file " + path);
  }
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                         aiProcess_GenSmoothNormals | aiProcess_ValidateDataStructure |
                         aiProcess_FindInvalidData;
  Assimp::Importer importer;
  const aiScene* scene = nullptr;
  if (endsWith(path, ".gz")) {
    const std::string data = readGzip(path);
    const std::string inner = path.substr(0, path.size() - 3);
    const std::string hint = inner.substr(inner.find_last_of('.') + 1);
    scene = importer.ReadFileFromMemory(data.data(), data.size(), flags, hint.c_str());
  } else {
    scene = importer.ReadFile(path, flags);
  }
  if (scene == nullptr || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0)
    throw InputError("malformed mesh file " + path + ": " + importer.GetErrorString());
  Mesh mesh;
  for (unsigned mi = 0; mi < scene->mNumMeshes; ++mi) {
    const aiMesh* m = scene->mMeshes[mi];
    if ((m->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) continue;
    const unsigned base = unsigned(mesh.positions.size());
    for (unsigned v = 0; v < m->mNumVertices; ++v) {
      const aiVector3D& p = m->mVertices[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw InputError("mesh file " + path + " has a non-finite vertex coordinate");
      mesh.positions.push_back({p.x, p.y, p.z});
      glm::vec3 n(0, 1, 0);
      if (m->mNormals != nullptr) {
        const aiVector3D& a = m->mNormals[v];
        if (std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z) &&
            (a.x != 0 || a.y != 0 || a.z != 0))
          n = glm::normalize(glm::vec3(a.x, a.y, a.z));
      }
      mesh.normals.push_back(n);
    }
    for (unsigned f = 0; f < m->mNumFaces; ++f) {
      const aiFace& face = m->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines left by the importer
      for (unsigned k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= m->mNumVertices)
          throw InputError("mesh file " + path + " has an out-of-range vertex index");
        mesh.indices.push_back(base + face.mIndices[k]);
      }
    }
  }
  if (mesh.indices.empty()) throw InputError("mesh file " + path + " contains no triangles");
  mesh.closed = isClosedManifold(mesh);
  return mesh;
}

void normalizeMesh(Mesh& mesh, float size) {
  Bounds b;
  for (const glm::vec3& p : mesh.positions) b.extend(p);
  const glm::vec3 extent = b.hi - b.lo;
  const float largest = std::max({extent.x, extent.y, extent.z, 1e-20f});
  const float s = size / largest;
  const glm::vec3 offset(b.center().x, b.lo.y, b.center().z);
  for (glm::vec3& p : mesh.positions) p = (p - offset) * s;
}

}  // namespace sl
