// Where a scene file's names lead: a relative mesh path is read beside the scene
// file, a missing scene file is named as such, the scene files of assets/scenes/ and the two
// examples of docs/scene-files.md load.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/base/errors.h"
#include "core/scene/scene_library.h"

namespace sl {
namespace {
namespace fs = std::filesystem;

// A folder per test (ctest runs the cases as parallel processes), emptied first.
fs::path freshDir() {
  const fs::path d = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "core-scene-paths" /
                     ::testing::UnitTest::GetInstance()->current_test_info()->name();
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

// A closed tetrahedron: 4 triangles, so that a test can tell which mesh was read.
constexpr const char* kTetraObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
    "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
constexpr size_t kTetraTriangles = 4;

std::string messageOf(const std::string& scene) {
  try {
    loadScene(scene);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// The user's scene in a folder of its own with its mesh beside it, loaded from another working
// directory: the mesh is the one beside the scene file (main read it from assets/).
TEST(ScenePaths, RelativeMeshPathsAreReadBesideTheSceneFile) {
  const fs::path d = freshDir();
  write(d / "room" / "table.obj", kTetraObj);
  write(d / "room" / "parts" / "leg.obj", kTetraObj);
  write(d / "room" / "scene.json",
        R"({"objects": [{"name": "floor", "mesh": {"primitive": "plane"}},
                        {"name": "table", "mesh": {"file": "table.obj"}, "translate": [0, 1, 0]},
                        {"name": "leg", "mesh": {"file": "parts/leg.obj"}}]})");
  const fs::path previous = fs::current_path();
  fs::current_path(d);  // a relative scene path, read from its parent folder
  Scene s;
  EXPECT_NO_THROW(s = loadScene("room/scene.json"));
  fs::current_path(previous);
  ASSERT_EQ(s.objects.size(), 3u);
  EXPECT_EQ(s.objects[1].mesh->triangleCount(), kTetraTriangles);
  EXPECT_EQ(s.objects[2].mesh->triangleCount(), kTetraTriangles);
}

// A mesh that is not there: the message names the field, the path as written and the one place
// it looked (absolute), after the scene file's name.
TEST(ScenePaths, AMissingMeshNamesWhereItLooked) {
  const fs::path d = freshDir();
  const fs::path scene = d / "scene.json";
  write(scene, R"({"objects": [{"mesh": {"file": "table.obj"}}]})");
  const std::string looked = fs::absolute(d / "table.obj").lexically_normal().string();
  EXPECT_EQ(messageOf(scene.string()), "scene file " + scene.string() +
                                           ": objects[0].mesh.file table.obj: no such file "
                                           "(looked in " +
                                           looked + ")");
}

// A name that ends in .json or holds a folder is a file: when it is missing the message names
// the file, not the list of scene names (main said "unknown scene").
TEST(ScenePaths, AMissingSceneFileIsNamed) {
  EXPECT_EQ(messageOf("missing.json"), "scene file missing.json: no such file");
  EXPECT_EQ(messageOf("no/such/scene"), "scene file no/such/scene: no such file");
  // A bare name is still looked up among the scene names.
  EXPECT_EQ(messageOf("nowhere").rfind("unknown scene 'nowhere' (known: analytic, brabec", 0), 0u)
      << messageOf("nowhere");
  // A folder is not a scene file.
  const fs::path d = freshDir();
  fs::create_directories(d / "folder.json");
  EXPECT_EQ(messageOf((d / "folder.json").string()),
            "scene file " + (d / "folder.json").string() + ": not a regular file");
}

// Every scene of assets/scenes/ loads with its meshes (bunny, teapot, dragon read
// ../models/... beside themselves), by name and by path.
TEST(ScenePaths, EveryAssetSceneLoads) {
  const std::vector<std::string> names = sceneFileNames();
  ASSERT_FALSE(names.empty());
  for (const std::string& name : names) {
    Scene s;
    EXPECT_NO_THROW(s = loadScene(name)) << name;
    EXPECT_FALSE(s.objects.empty()) << name;
  }
  // The model scenes: the object named after the scene is the mesh file (a missing file is an
  // error, so this checks it is the model, not a stand-in): at least the teapot's 992 OBJ faces.
  constexpr size_t kFewestModelTriangles = 992;
  for (const char* name : {"bunny", "teapot", "dragon"}) {
    const Scene s =
        loadScene((fs::path(assetDirectory()) / "scenes" / (std::string(name) + ".json")).string());
    const Object* model = nullptr;
    for (const Object& o : s.objects)
      if (o.name == name) model = &o;
    ASSERT_NE(model, nullptr) << name;
    EXPECT_GE(model->mesh->triangleCount(), kFewestModelTriangles) << name;
  }
}

// docs/scene-files.md's two examples load as the document describes them.
TEST(ScenePaths, TheDocumentedExamplesLoad) {
  const fs::path examples = fs::path(SHADOWLAB_SOURCE_DIR) / "docs" / "examples";
  const Scene minimal = loadScene((examples / "minimal-scene.json").string());
  EXPECT_EQ(minimal.name, "minimal-scene");  // the file's stem: it has no "name"
  ASSERT_EQ(minimal.objects.size(), 2u);
  EXPECT_EQ(minimal.objects[0].name, "objects[0]");
  // The defaults the document lists.
  const Camera defaultCamera;
  const SpotLight defaultLight;
  EXPECT_EQ(minimal.camera.position, defaultCamera.position);
  EXPECT_EQ(minimal.camera.fovyDegrees, defaultCamera.fovyDegrees);
  EXPECT_EQ(minimal.light.position, defaultLight.position);
  EXPECT_EQ(minimal.light.coneDegrees, defaultLight.coneDegrees);
  EXPECT_FALSE(minimal.light.nearPlane.has_value());

  const Scene full = loadScene((examples / "full-scene.json").string());
  EXPECT_EQ(full.name, "full-example");
  EXPECT_FALSE(full.description.empty());
  ASSERT_EQ(full.objects.size(), 9u);
  EXPECT_EQ(full.objects[1].name, "pyramid");
  constexpr size_t kPyramidTriangles = 6;  // docs/examples/full-scene-pyramid.obj: 2 + 4 faces
  EXPECT_EQ(full.objects[1].mesh->triangleCount(), kPyramidTriangles);
  EXPECT_TRUE(full.objects[1].mesh->closed);
  EXPECT_FALSE(full.objects[0].castsShadow);
  EXPECT_FALSE(full.objects[6].receivesShadow);
  EXPECT_EQ(full.light.nearPlane, 2.0f);
  EXPECT_EQ(full.light.farPlane, 20.0f);
  EXPECT_EQ(full.light.radius, 0.1f);
  EXPECT_EQ(full.camera.fovyDegrees, 45.0f);
}

}  // namespace
}  // namespace sl
