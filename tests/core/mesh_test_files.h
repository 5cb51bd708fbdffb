// Small valid mesh files (OBJ, ascii and binary PLY) and gzip helpers shared by the mesh loader
// tests (mesh_io_test.cpp, mesh_io_fuzz_test.cpp).
#pragma once

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace sl::testing_meshes {

struct SeedFile {
  std::string name;       // file name; its extension picks the format
  std::string bytes;      // the file's contents
  std::size_t triangles;  // what loadMesh makes of it
};

// Appends the bytes of a value in little- or big-endian order.
template <typename T>
void appendBinary(std::string& out, T value, bool bigEndian) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  for (std::size_t i = 0; i < sizeof(T); ++i)
    out.push_back(bytes[bigEndian ? sizeof(T) - 1 - i : i]);  // the host is little-endian
}

inline const std::vector<SeedFile>& seedFiles() {
  static const std::vector<SeedFile> seeds = [] {
    std::vector<SeedFile> s;
    // 0: an OBJ tetrahedron with the syntax variants the importer reads (v/vt/vn, v//vn,
    // negative indices, groups, materials, a library that is never opened).
    s.push_back({"tetra.obj",
                 "# tetrahedron\nmtllib none.mtl\no tetra\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                 "v 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 -1\nvn 1 1 1\ng sides\nusemtl red\n"
                 "f 1/1/1 3/3/1 2/2/1\nf 1/1 2/2 4/3\nf 1//2 4//2 3//2\nf -3 -2 -1\n",
                 4});
    // 1: an ascii PLY tetrahedron with a comment and per-vertex normals.
    s.push_back({"tetra.ply",
                 "ply\nformat ascii 1.0\ncomment seed\nelement vertex 4\nproperty float x\n"
                 "property float y\nproperty float z\nproperty float nx\nproperty float ny\n"
                 "property float nz\nelement face 4\nproperty list uchar int vertex_indices\n"
                 "end_header\n0 0 0 -1 -1 -1\n1 0 0 1 0 0\n0 1 0 0 1 0\n0 0 1 0 0 1\n"
                 "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n",
                 4});
    // 2: a binary little-endian PLY tetrahedron (float positions, uchar/int face lists).
    {
      std::string ply =
          "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\n"
          "property float y\nproperty float z\nelement face 4\n"
          "property list uchar int vertex_indices\nend_header\n";
      const float v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
      const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
      for (const auto& p : v)
        for (float c : p) appendBinary(ply, c, false);
      for (const auto& t : f) {
        ply.push_back(3);
        for (int i : t) appendBinary(ply, i, false);
      }
      s.push_back({"tetra_le.ply", ply, 4});
    }
    // 3: a binary big-endian PLY cube of quads (double positions, a colour, an extra element).
    {
      std::string ply =
          "ply\nformat binary_big_endian 1.0\nelement vertex 8\nproperty double x\n"
          "property double y\nproperty double z\nproperty uchar red\nelement face 6\n"
          "property list uchar uint vertex_indices\nelement extra 2\nproperty short a\n"
          "property list ushort float b\nend_header\n";
      for (int i = 0; i < 8; ++i) {
        for (int axis = 0; axis < 3; ++axis) appendBinary(ply, double((i >> axis) & 1), true);
        ply.push_back(char(200));
      }
      const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                         {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
      for (const auto& q : quads) {
        ply.push_back(4);
        for (std::uint32_t i : q) appendBinary(ply, i, true);
      }
      for (int e = 0; e < 2; ++e) {
        appendBinary(ply, std::int16_t(e), true);
        appendBinary(ply, std::uint16_t(1), true);
        appendBinary(ply, 0.5f, true);
      }
      s.push_back({"cube_be.ply", ply, 12});
    }
    // 4: an OBJ cube of quads.
    s.push_back({"cube.obj",
                 "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n"
                 "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n",
                 12});
    return s;
  }();
  return seeds;
}

// Deflates `prefix` followed by `zeros` zero bytes into one gzip member, streaming the zeros
// in chunks (a bomb needs no buffer of its decompressed size).
inline std::string gzipWithZeros(const std::string& prefix, std::size_t zeros) {
  constexpr std::size_t kChunkBytes = std::size_t(1) << 20;
  constexpr int kGzipWindowBits = 15 + 16;  // the largest window, gzip wrapper
  constexpr int kMemLevel = 8;              // zlib's default
  z_stream z{};
  if (deflateInit2(&z, Z_BEST_COMPRESSION, Z_DEFLATED, kGzipWindowBits, kMemLevel,
                   Z_DEFAULT_STRATEGY) != Z_OK)
    throw std::runtime_error("deflateInit2 failed");
  std::string out;
  std::vector<char> buffer(kChunkBytes);
  const std::string zeroChunk(kChunkBytes, '\0');
  auto feed = [&](const char* data, std::size_t bytes, int flush) {
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data));
    z.avail_in = uInt(bytes);
    do {
      z.next_out = reinterpret_cast<Bytef*>(buffer.data());
      z.avail_out = uInt(buffer.size());
      deflate(&z, flush);
      out.append(buffer.data(), buffer.size() - z.avail_out);
    } while (z.avail_out == 0 || z.avail_in > 0);
  };
  feed(prefix.data(), prefix.size(), zeros == 0 ? Z_FINISH : Z_NO_FLUSH);
  while (zeros > 0) {
    const std::size_t n = std::min(zeros, kChunkBytes);
    zeros -= n;
    feed(zeroChunk.data(), n, zeros == 0 ? Z_FINISH : Z_NO_FLUSH);
  }
  deflateEnd(&z);
  return out;
}

inline std::string gzip(const std::string& bytes) { return gzipWithZeros(bytes, 0); }

}  // namespace sl::testing_meshes
