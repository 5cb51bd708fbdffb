// core/scene/mesh_io.h — OBJ and PLY meshes through Assimp (gzip-compressed files through zlib).
//
// Loading never trusts the file: it is read (and gunzipped) into memory under the byte caps
// below, sanity-checked before Assimp sees it (a PLY header's declared counts and sizes against
// the bytes that follow it, an OBJ's vertex and face line counts against the caps), handed to
// Assimp as a buffer that ends in a newline, and the imported geometry is checked again (index
// ranges, coordinate magnitudes) before and after Assimp's post-processing. Every failure is an
// InputError that names the file (the CLI prints it and exits with status 2).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "core/scene/scene.h"

namespace sl {

// Caps on a mesh file, each checked before anything is allocated for what it bounds; a file
// over a cap is refused with a message that states the cap.
// Bytes of the file on disk, compressed or not (the full Stanford dragon is 8 MB gzipped).
constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t(256) << 20;
// Bytes of a .gz file once decompressed, counted while inflating (gzip bombs stop here; the
// full dragon is 34 MB).
constexpr std::size_t kMaxDecompressedMeshBytes = std::size_t(256) << 20;
// Vertices a file may declare (PLY `element vertex`, OBJ `v` lines) or a mesh may hold (the
// full dragon has 437,645).
constexpr std::size_t kMaxMeshVertices = 5'000'000;
// Triangles a mesh may hold after triangulation; also the most faces a file may declare.
constexpr std::size_t kMaxMeshTriangles = 10'000'000;
// Largest magnitude of a vertex coordinate (model units): keeps every extent, and the scale
// normalizeMesh derives from it, finite in single precision (3e38 would overflow to inf).
constexpr float kMaxMeshCoordinate = 1e18f;

// Loads every triangle of every mesh in an .obj, .ply, .obj.gz or .ply.gz file (triangulated,
// identical vertices joined, smooth normals generated when the file has none). Throws
// InputError naming the file and the problem for a missing, unreadable, oversized, malformed or
// truncated file, one over a cap above, one with no triangles, a non-finite or too large
// coordinate or an out-of-range index. The result has every index in range, finite positions
// and finite unit normals.
Mesh loadMesh(const std::string& path);

// Centres a mesh on the origin in x/z, puts its lowest point at y = 0 and scales it so that
// its largest extent equals `size` (models come in arbitrary units). Throws InputError naming
// `name` when `size` is not positive and finite or the mesh has a zero or non-finite extent
// (it cannot be scaled to any size).
void normalizeMesh(Mesh& mesh, float size, const std::string& name = "mesh");

}  // namespace sl
