// Mesh loading against malformed files (core/scene/mesh_io.h): each is refused with
// an InputError that names the file (and the cap where one is exceeded), never a crash, a hang or
// an allocation of what the file merely declares.
#include "core/scene/mesh_io.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/base/errors.h"
#include "mesh_test_files.h"

namespace sl {
namespace {
namespace fs = std::filesystem;

fs::path tempDir() {
  fs::path d = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "core-mesh-io";
  fs::create_directories(d);
  return d;
}

std::string write(const std::string& name, const std::string& bytes) {
  const fs::path p = tempDir() / name;
  std::ofstream(p, std::ios::binary) << bytes;
  return p.string();
}

// The InputError's message, or "" when loading succeeded (a test failure of its own).
std::string loadError(const std::string& path) {
  try {
    loadMesh(path);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << path << " loaded";
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(MeshLoading, SeedsLoad) {
  for (const testing_meshes::SeedFile& seed : testing_meshes::seedFiles()) {
    const Mesh m = loadMesh(write(seed.name, seed.bytes));
    EXPECT_EQ(m.triangleCount(), seed.triangles) << seed.name;
    const Mesh z = loadMesh(write(seed.name + ".gz", testing_meshes::gzip(seed.bytes)));
    EXPECT_EQ(z.triangleCount(), seed.triangles) << seed.name << ".gz";
  }
}

// Text seeds (OBJ, ascii PLY) with "\r\n" line ends load as they are.
TEST(MeshLoading, WindowsLineEndsLoad) {
  for (const testing_meshes::SeedFile& seed : testing_meshes::seedFiles()) {
    if (seed.bytes.find("binary") != std::string::npos) continue;
    std::string crlf;
    for (char c : seed.bytes) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    EXPECT_EQ(loadMesh(write("crlf_" + seed.name, crlf)).triangleCount(), seed.triangles)
        << seed.name;
  }
}

// The 2 KB .ply.gz with no newline: Assimp 5.2 looped past its line cache on such
// headers (see core/scene/mesh_io.cpp). Every variant: no line end at all, '\r' or '\0' line ends,
// binary and ascii, with about 2 KB of compressed payload after the header.
TEST(MeshLoading, PlyGzWithoutNewlinesIsRefused) {
  std::string payload;
  std::uint32_t state = 12345;
  for (int i = 0; i < 4096; ++i) {
    state = state * 1664525u + 1013904223u;  // a fixed LCG: incompressible enough bytes
    payload.push_back(char(state >> 24));
  }
  for (const char* format : {"ascii", "binary_little_endian"}) {
    for (const std::string& end : {std::string(" "), std::string("\r"), std::string(1, '\0')}) {
      std::string ply = "ply" + end + "format " + format + " 1.0" + end + "element vertex 4" + end +
                        "property float x" + end + "property float y" + end + "property float z" +
                        end + "element face 4" + end + "property list uchar int vertex_indices" +
                        end + "end_header" + end + payload;
      for (char& c : ply)
        if (c == '\n') c = ' ';
      const std::string path = write("nonewline.ply.gz", testing_meshes::gzip(ply));
      EXPECT_TRUE(contains(loadError(path), path)) << format;
    }
  }
  // Lines end in '\n' but the header never ends (the binary data follows a comment).
  std::string noEnd = testing_meshes::seedFiles()[2].bytes;  // binary little endian
  noEnd.replace(noEnd.find("end_header"), 10, "comment   ");
  const std::string noEndPath = write("noend.ply.gz", testing_meshes::gzip(noEnd));
  EXPECT_TRUE(contains(loadError(noEndPath), noEndPath));
}

// The 160-byte PLY whose header claims 1e9 vertices: refused from the header, stating
// the cap, before anything is allocated for them.
TEST(MeshLoading, BillionVertexHeaderIsRefusedWithTheCap) {
  const std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty float x\n"
      "property float y\nproperty float z\nend_header\n";
  const std::string path = write("billion.ply", ply);
  const std::string message = loadError(path);
  EXPECT_TRUE(contains(message, path)) << message;
  EXPECT_TRUE(contains(message,
                       "declares 1000000000 vertices; at most " + std::to_string(kMaxMeshVertices)))
      << message;
  // Under the cap but beyond the bytes that follow the header, ascii and binary.
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 4000000\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n0 0 0\n";
  EXPECT_TRUE(contains(loadError(write("short_ascii.ply", ascii)), "bytes left"));
  std::string binary =
      "ply\nformat binary_big_endian 1.0\nelement vertex 4000000\nproperty double x\n"
      "property double y\nproperty double z\nend_header\n";
  binary += std::string(24 * 3, '\0');
  EXPECT_TRUE(contains(loadError(write("short_binary.ply", binary)), "bytes left"));
  // A face list whose count claims more indices than the file holds.
  std::string face = testing_meshes::seedFiles()[2].bytes;
  face[face.size() - 13] = char(0xff);  // the last face's uchar count: 255 indices
  EXPECT_TRUE(contains(loadError(write("longface.ply", face)), "truncated"));
}

// A binary PLY one byte short: the newline loadMesh gives every buffer must not count as the
// missing byte. A header that ends the file (no line end) declares what is not there.
TEST(MeshLoading, BinaryPlyShortByOneByteIsRefused) {
  const std::string ply = testing_meshes::seedFiles()[2].bytes;  // binary little endian
  ASSERT_NE(ply.back(), '\n');
  EXPECT_TRUE(contains(loadError(write("short1.ply", ply.substr(0, ply.size() - 1))), "truncated"));
  const std::string header = ply.substr(0, ply.find("end_header") + 10);
  EXPECT_TRUE(contains(loadError(write("headeronly.ply", header)), "bytes left"));
}

TEST(MeshLoading, ObjVerticesAndTrianglesAreCapped) {
  std::string obj;
  obj.reserve((kMaxMeshVertices + 1) * 8);
  for (std::size_t i = 0; i <= kMaxMeshVertices; ++i) obj += "v 0 0 0\n";
  const std::string message = loadError(write("many.obj", obj));
  EXPECT_TRUE(contains(message, "declares " + std::to_string(kMaxMeshVertices + 1) +
                                    " vertices; at most " + std::to_string(kMaxMeshVertices)))
      << message;
  // One polygon of kMaxMeshTriangles + 3 corners: one triangle too many after triangulation.
  std::string polygon = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf";
  for (std::size_t i = 0; i < kMaxMeshTriangles + 3; ++i) polygon += " 1";
  const std::string tooMany = loadError(write("polygon.obj", polygon + "\n"));
  EXPECT_TRUE(contains(tooMany, "more than " + std::to_string(kMaxMeshTriangles) + " triangles"))
      << tooMany;
}

// The OBJ with coordinates of 3e38: its extent overflowed to inf and normalizeMesh
// collapsed it to a point. The loader refuses coordinates beyond kMaxMeshCoordinate.
TEST(MeshLoading, HugeObjCoordinatesAreRefused) {
  const std::string path = write("huge.obj", "v -3e38 0 0\nv 3e38 0 0\nv 0 3e38 0\nf 1 2 3\n");
  const std::string message = loadError(path);
  EXPECT_TRUE(contains(message, path)) << message;
  EXPECT_TRUE(contains(message, "exceeds")) << message;
  EXPECT_NE(loadError(write("inf.obj", "v 1e39 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")), "");
  // At the cap the extent (twice the cap) and the scale stay finite.
  Mesh m = loadMesh(write("atcap.obj", "v -1e18 0 0\nv 1e18 0 0\nv 0 1e18 0\nf 1 2 3\n"));
  normalizeMesh(m, 2.0f, "atcap.obj");
  for (const glm::vec3& p : m.positions) EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y));
  // x spans [-1e18, 1e18] and becomes [-1, 1]; float rounding of the 2e18 extent is ~1e-7.
  EXPECT_NEAR(m.positions[1].x - m.positions[0].x, 2.0f, 1e-5f);
}

TEST(MeshLoading, NormalizeRefusesAZeroExtentOrSize) {
  Mesh point;  // one triangle whose corners coincide (Assimp drops it, so it is built here)
  point.positions.assign(3, glm::vec3(1.0f));
  point.normals.assign(3, glm::vec3(0, 1, 0));
  point.indices = {0, 1, 2};
  try {
    normalizeMesh(point, 1.0f, "point.obj");
    ADD_FAILURE() << "a mesh with no extent was scaled";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "point.obj")) << e.what();
  }
  Mesh tri = loadMesh(write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  EXPECT_THROW(normalizeMesh(tri, 0.0f), InputError);
  EXPECT_THROW(normalizeMesh(tri, -1.0f), InputError);
  Mesh overflow = tri;  // an extent of 1e-30 needs a scale of 1e30 * size: overflows to inf
  for (glm::vec3& p : overflow.positions) p *= 1e-30f;
  EXPECT_THROW(normalizeMesh(overflow, 1e10f), InputError);
}

TEST(MeshLoading, TruncatedAndCorruptGzipIsRefused) {
  const std::string gz = testing_meshes::gzip(testing_meshes::seedFiles()[1].bytes);
  for (std::size_t cut : {std::size_t(0), std::size_t(5), gz.size() / 2, gz.size() - 4}) {
    const std::string message = loadError(write("cut.ply.gz", gz.substr(0, cut)));
    EXPECT_TRUE(contains(message, "cut.ply.gz")) << cut << ": " << message;
  }
  std::string flipped = gz;
  flipped[gz.size() / 2] ^= 0x10;
  EXPECT_NE(loadError(write("flipped.ply.gz", flipped)), "");
  EXPECT_TRUE(contains(loadError(write("trailing.ply.gz", gz + "junk")), "gzip"));
  EXPECT_TRUE(contains(loadError(write("plain.obj.gz", "v 0 0 0\n")), "gzip"));
}

// A gzip bomb: a few hundred KB that inflate past kMaxDecompressedMeshBytes (a header, then
// gzip members of 16 MiB of zeros each, concatenated). Inflating stops at the cap, and the
// message states it, instead of filling memory.
TEST(MeshLoading, GzipBombStopsAtTheCap) {
  constexpr std::size_t kMemberZeros = std::size_t(16) << 20;
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n";
  const std::string member = testing_meshes::gzipWithZeros("", kMemberZeros);
  std::string gz = testing_meshes::gzip(header);
  for (std::size_t zeros = 0; zeros <= kMaxDecompressedMeshBytes; zeros += kMemberZeros)
    gz += member;
  EXPECT_LT(gz.size(), kMaxDecompressedMeshBytes / 100);  // it is a bomb: over 100:1
  const std::string message = loadError(write("bomb.ply.gz", gz));
  EXPECT_TRUE(contains(message, "at most " + std::to_string(kMaxDecompressedMeshBytes))) << message;
}

// A file over kMaxMeshFileBytes is refused from its size, before it is read (a sparse file:
// nothing is written to disk).
TEST(MeshLoading, OversizedFileIsRefusedUnread) {
  const std::string path = write("oversized.ply.gz", "");
  fs::resize_file(path, kMaxMeshFileBytes + 1);
  const std::string message = loadError(path);
  EXPECT_TRUE(contains(message, "at most " + std::to_string(kMaxMeshFileBytes))) << message;
  fs::remove(path);
}

TEST(MeshLoading, OnlyObjAndPlyAreRead) {
  EXPECT_TRUE(contains(loadError(write("tetra.stl", "solid x\nendsolid x\n")), ".obj or .ply"));
  EXPECT_TRUE(contains(loadError((tempDir() / "absent.ply.gz").string()), "cannot open"));
}

}  // namespace
}  // namespace sl
