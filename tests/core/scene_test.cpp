// Scenes: built-ins, JSON files, meshes through Assimp, primitives (core/scene*.h, mesh_io.h).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>

#include "core/base/errors.h"
#include "core/scene/mesh_io.h"
#include "core/scene/primitives.h"
#include "core/scene/scene_library.h"

namespace sl {
namespace {
namespace fs = std::filesystem;

fs::path tempDir() {
  fs::path d = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "core-scene";
  fs::create_directories(d);
  return d;
}

std::string write(const std::string& name, const std::string& text) {
  const fs::path p = tempDir() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

// Every triangle's normal (from its winding) points away from the mesh centre: the
// primitives are wound counter-clockwise seen from outside, as OpenGL's front faces.
void expectOutwardWinding(const Mesh& m, const glm::vec3& centre) {
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                    c = m.positions[m.indices[t + 2]];
    const glm::vec3 n = glm::cross(b - a, c - a);
    if (glm::length(n) < 1e-9f) continue;
    EXPECT_GT(glm::dot(n, (a + b + c) / 3.0f - centre), 0.0f) << "triangle " << t / 3;
  }
}

TEST(Primitives, ClosedMeshesAreClosedAndWoundOutward) {
  const Mesh closed[] = {makeBox({1, 2, 3}), makeSphere(1.0f, 12, 6), makeCylinder(0.5f, 2.0f, 10),
                         makeTorus(1.0f, 0.3f, 12, 8)};
  for (const Mesh& m : closed) {
    EXPECT_TRUE(m.closed);
    EXPECT_TRUE(isClosedManifold(m));
    EXPECT_EQ(m.positions.size(), m.normals.size());
  }
  expectOutwardWinding(makeBox({1, 2, 3}), glm::vec3(0));
  expectOutwardWinding(makeSphere(1.0f, 12, 6), glm::vec3(0));
  expectOutwardWinding(makeCylinder(0.5f, 2.0f, 10), glm::vec3(0));
  EXPECT_FALSE(isClosedManifold(makePlane(2, 2, 3)));
  EXPECT_FALSE(isClosedManifold(makeQuad(1, 1)));
}

TEST(Primitives, PlaneFacesUp) {
  const Mesh p = makePlane(2, 2, 2);
  for (size_t t = 0; t < p.indices.size(); t += 3) {
    const glm::vec3 a = p.positions[p.indices[t]], b = p.positions[p.indices[t + 1]],
                    c = p.positions[p.indices[t + 2]];
    EXPECT_GT(glm::cross(b - a, c - a).y, 0.0f);
  }
}

TEST(Scenes, EveryBuiltinLoadsAndValidates) {
  for (const std::string& name : builtinSceneNames()) {
    const Scene s = loadScene(name);
    EXPECT_EQ(s.name, name);
    EXPECT_FALSE(s.objects.empty());
    const DepthRange r = lightDepthRange(s);
    EXPECT_GT(r.nearPlane, 0.0f) << name;
    EXPECT_GT(r.farPlane, r.nearPlane) << name;
  }
}

TEST(Scenes, BrabecSceneHasAboutSevenThousandPolygons) {
  // Brabec & Seidel §5: "The scene consists of about 7000 polygons".
  size_t triangles = 0;
  for (const Object& o : loadScene("brabec").objects) triangles += o.mesh->triangleCount();
  EXPECT_GT(triangles, 6000u);
  EXPECT_LT(triangles, 8500u);
}

TEST(Scenes, LightDepthRangeIsFittedToTheScene) {
  const Scene s = loadScene("analytic");
  const DepthRange r = lightDepthRange(s);
  // Occluder top at y = 1.01, ground at y = 0, light at y = 4 looking down; the ground's far
  // corners lie at distance 4 along the axis (the axis is vertical). Fitted with 2% margins.
  EXPECT_NEAR(r.nearPlane, 4.0f - 1.01f - 0.02f * (4.0f - 2.99f), 1e-3f);
  EXPECT_NEAR(r.farPlane, 4.0f + 0.02f * (4.0f - 2.99f), 1e-3f);
}

TEST(Scenes, UnknownSceneNamesTheKnownOnes) {
  try {
    loadScene("no-such-scene");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("brabec"), std::string::npos);
  }
}

TEST(SceneFiles, ParsesPrimitivesTransformsAndFlags) {
  const std::string text = R"({
    "name": "t", "camera": {"position": [0, 3, 5], "target": [0, 0, 0]},
    "light": {"position": [0, 5, 0], "target": [0, 0, 0], "cone": 50, "radius": 0.1},
    "objects": [
      {"name": "floor", "mesh": {"primitive": "plane", "width": 4, "depth": 4}, "casts": false},
      {"name": "ball", "mesh": {"primitive": "sphere", "radius": 0.5}, "translate": [0, 1, 0],
       "scale": 2, "diffuse": [1, 0, 0]}
    ]})";
  const Scene s = parseSceneJson(text, "t.json", tempDir().string());
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_FALSE(s.objects[0].castsShadow);
  EXPECT_TRUE(s.objects[1].mesh->closed);
  EXPECT_EQ(s.objects[1].diffuse, glm::vec3(1, 0, 0));
  const Bounds b = worldBounds(s.objects[1]);
  EXPECT_NEAR(b.hi.y, 2.0f, 1e-5f);  // radius 0.5 scaled by 2, centred at y = 1
  EXPECT_FLOAT_EQ(s.light.coneDegrees, 50.0f);
}

TEST(SceneFiles, MalformedDocumentsAreInputErrors) {
  const char* bad[] = {
      "{",                                                  // truncated JSON
      "[]",                                                 // not an object
      R"({"objects": 3})",                                  // objects not an array
      R"({"objects": []})",                                 // nothing to render
      R"({"objects": [{"mesh": {"primitive": "blob"}}]})",  // unknown primitive
      R"({"objects": [{"mesh": {"primitive": "box"}, "translate": [1, 2]}]})",
      R"({"objects": [{"mesh": {"primitive": "box"}}], "camera": {"fovy": 0}})",
      R"({"objects": [{"mesh": {"primitive": "box"}}], "light": {"position": [0,0,0], "target": [0,0,0]}})",
      R"({"objects": [{"mesh": {"primitive": "box"}, "scale": 0}]})",
      R"({"objects": [{"mesh": {"file": "missing.obj"}}]})",
  };
  for (const char* text : bad)
    EXPECT_THROW(parseSceneJson(text, "bad.json", tempDir().string()), InputError) << text;
}

const char* kTetraObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
    "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

TEST(Meshes, ObjLoadsAndClosednessIsDetected) {
  const Mesh m = loadMesh(write("tetra.obj", kTetraObj));
  EXPECT_EQ(m.triangleCount(), 4u);
  EXPECT_TRUE(m.closed);
  for (const glm::vec3& n : m.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-4f);
  const Mesh open = loadMesh(write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  EXPECT_FALSE(open.closed);
}

TEST(Meshes, PlyLoads) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const Mesh m = loadMesh(write("tetra.ply", ply));
  EXPECT_EQ(m.triangleCount(), 4u);
  EXPECT_TRUE(m.closed);
}

TEST(Meshes, BadMeshFilesAreInputErrors) {
  EXPECT_THROW(loadMesh((tempDir() / "absent.obj").string()), InputError);
  EXPECT_THROW(loadMesh(write("empty.obj", "")), InputError);
  EXPECT_THROW(loadMesh(write("garbage.obj", "this is not a mesh\n\x01\x02")), InputError);
  EXPECT_THROW(loadMesh(write("badindex.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n")), InputError);
  // A binary PLY cut off in the middle of its vertex data.
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 100\nproperty float x\n"
      "property float y\nproperty float z\nelement face 50\n"
      "property list uchar int vertex_indices\nend_header\n";
  ply += std::string(40, '\0');
  EXPECT_THROW(loadMesh(write("truncated.ply", ply)), InputError);
  EXPECT_THROW(loadMesh(write("notgzip.ply.gz", "plain text")), InputError);
}

TEST(Meshes, NormalizeFitsTheLargestExtent) {
  Mesh m = loadMesh(write("tetra2.obj", kTetraObj));
  normalizeMesh(m, 3.0f);
  Bounds b;
  for (const glm::vec3& p : m.positions) b.extend(p);
  EXPECT_NEAR(b.lo.y, 0.0f, 1e-6f);
  EXPECT_NEAR(std::max({b.hi.x - b.lo.x, b.hi.y - b.lo.y, b.hi.z - b.lo.z}), 3.0f, 1e-5f);
}

}  // namespace
}  // namespace sl
