// core/mesh_io.h — OBJ and PLY meshes through Assimp (gzip-compressed files through zlib).
#pragma once

#include <string>

#include "core/scene.h"

namespace sl {

// Loads every triangle of every mesh in the file (triangulated, identical vertices joined,
// smooth normals generated when the file has none). Throws InputError naming the file and the
// problem for a missing, unreadable, malformed or truncated file, or one with no triangles,
// a non-finite coordinate or an out-of-range index.
Mesh loadMesh(const std::string& path);

// Centres a mesh on the origin in x/z, puts its lowest point at y = 0 and scales it so that
// its largest extent equals `size` (models come in arbitrary units).
void normalizeMesh(Mesh& mesh, float size);

}  // namespace sl
