// Scene validation: primitive parameters and caps, strict scene files, mesh index
// ranges, impossible cameras and lights. Each bad input is an InputError whose one line names
// the field; the command line turns it into exit status 2 with nothing written.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/base/errors.h"
#include "core/scene/primitives.h"
#include "core/scene/scene_library.h"

namespace sl {
namespace {
namespace fs = std::filesystem;

// The InputError's message, or "" when parsing succeeded.
std::string parseError(const std::string& json) {
  try {
    parseSceneJson(json, "test.json", ".");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A scene document with `objects` and an optional extra top-level member.
std::string doc(const std::string& objects, const std::string& extra = "") {
  return "{" + extra + (extra.empty() ? "" : ",") + "\"objects\": [" + objects + "]}";
}

const std::string kGround = R"({"mesh": {"primitive": "plane"}})";

TEST(PrimitiveCaps, EveryGeneratorRefusesCountsOutsideItsCaps) {
  // Below the minimum the index formulas read outside the vertex array;
  // above the maximum the allocation is unbounded (item 3). Both refused before allocating.
  EXPECT_THROW(makeSphere(1.0f, 32, 1), InputError);
  EXPECT_THROW(makeSphere(1.0f, 32, 0), InputError);
  EXPECT_THROW(makeSphere(1.0f, 32, -4), InputError);
  EXPECT_THROW(makeSphere(1.0f, 2, 8), InputError);
  EXPECT_THROW(makeSphere(1.0f, kMaxSphereSlices + 1, 8), InputError);
  EXPECT_THROW(makeSphere(1.0f, 8, kMaxSphereStacks + 1), InputError);
  EXPECT_THROW(makeCylinder(1.0f, 1.0f, kMaxCylinderSlices + 1), InputError);
  EXPECT_THROW(makeCylinder(1.0f, 1.0f, 2), InputError);
  EXPECT_THROW(makePlane(1.0f, 1.0f, 0), InputError);
  EXPECT_THROW(makePlane(1.0f, 1.0f, kMaxPlaneDivisions + 1), InputError);
  EXPECT_THROW(makeFence(4.0f, 1.0f, 0), InputError);
  EXPECT_THROW(makeFence(4.0f, 1.0f, kMaxFencePickets + 1), InputError);
  EXPECT_THROW(makeTorus(1.0f, 0.2f, 2, 8), InputError);
  EXPECT_THROW(makeTorus(1.0f, 0.2f, 8, kMaxTorusSegments + 1), InputError);
  EXPECT_THROW(makeBranchedTree(2.0f, kMaxTreeLevels + 1, 1), InputError);
  // The smallest legal sphere is a closed double pyramid: every index in range.
  const Mesh m = makeSphere(1.0f, kMinSphereSlices, kMinSphereStacks);
  for (unsigned i : m.indices) EXPECT_LT(i, m.positions.size());
  EXPECT_TRUE(isClosedManifold(m));
}

TEST(PrimitiveCaps, LengthsMustBePositiveAndBounded) {
  EXPECT_THROW(makeSphere(0.0f), InputError);
  EXPECT_THROW(makeSphere(-1.0f), InputError);
  EXPECT_THROW(makeBox({1, 0, 1}), InputError);
  EXPECT_THROW(makePlane(2 * kMaxPrimitiveLength, 1), InputError);
  EXPECT_THROW(makeQuad(1, std::nanf("")), InputError);
}

TEST(PrimitiveCaps, TheMessageNamesTheParameterAndTheCap) {
  const std::string e = parseError(doc(R"({"mesh": {"primitive": "sphere", "slices": 1e9}})"));
  EXPECT_NE(e.find("objects[0].mesh"), std::string::npos) << e;
  EXPECT_NE(e.find("slices"), std::string::npos) << e;
  EXPECT_NE(e.find(std::to_string(kMaxSphereSlices)), std::string::npos) << e;
}

TEST(SceneFileStrictness, CountsAreIntegersInRange) {
  // 3e9 used to overflow int and become 1 divisions; 2.5 used to truncate.
  EXPECT_NE(parseError(doc(R"({"mesh": {"primitive": "plane", "divisions": 3e9}})")), "");
  EXPECT_NE(parseError(doc(R"({"mesh": {"primitive": "plane", "divisions": 2.5}})")), "");
  EXPECT_NE(parseError(doc(R"({"mesh": {"primitive": "plane", "divisions": "8"}})")), "");
  EXPECT_EQ(parseError(doc(R"({"mesh": {"primitive": "plane", "divisions": 8.0}})")), "");
}

TEST(SceneFileStrictness, WrongTypesAndUnknownKeysNameTheField) {
  const struct {
    std::string json, field;
  } cases[] = {
      {doc(kGround, R"("camera": [1, 2, 3])"), "camera"},
      {doc(kGround, R"("light": "sun")"), "light"},
      {doc(kGround, R"("camera": {"positon": [0, 1, 2]})"), "positon"},
      {doc(kGround, R"("lights": {})"), "lights"},
      {doc(R"({"mesh": {"primitive": "sphere", "stack": 4}})"), "stack"},
      {doc(R"({"mesh": {"primitive": "box"}, "casts": 1})"), "objects[0].casts"},
      {doc(R"({"mesh": {"primitive": "box"}, "name": 7})"), "objects[0].name"},
      {doc(R"({"mesh": {"primitive": 3}})"), "objects[0].mesh.primitive"},
      {doc(R"({"mesh": {"file": 3}})"), "objects[0].mesh.file"},
      {doc(R"({"mesh": {"primitive": "box"}, "translate": [3e38, 0, 0]})"), "translate"},
      {doc(R"({"mesh": {"primitive": "box"}, "scale": 1e30})"), "scale"},
  };
  for (const auto& c : cases) {
    const std::string e = parseError(c.json);
    EXPECT_NE(e.find(c.field), std::string::npos) << c.json << " -> '" << e << "'";
  }
}

TEST(SceneFileStrictness, NamesThatAreNotUtf8BecomeReadable) {
  // A name with invalid UTF-8 must not throw later in a JSON writer: inside
  // the document the JSON parser refuses it; a file name becomes U+FFFD where it is not UTF-8.
  EXPECT_THROW(parseSceneJson(doc(kGround, "\"name\": \"caf\xe9\""), "t.json", "."), InputError);
  const Scene t = parseSceneJson(doc(kGround), "/tmp/sc\xff\xfe.json", ".");
  EXPECT_NO_THROW((void)nlohmann::json(t.name).dump());
}

Scene oneBoxScene() {
  Scene s;
  s.name = "box";
  Object o;
  o.name = "box";
  o.mesh = std::make_shared<const Mesh>(makeBox({1, 1, 1}));
  s.objects.push_back(o);
  return s;
}

TEST(SceneValidation, MeshIndicesAreCheckedOnce) {
  Scene s = oneBoxScene();
  EXPECT_NO_THROW(validateScene(s));
  Mesh bad = *s.objects[0].mesh;
  bad.indices[5] = unsigned(bad.positions.size());  // one past the end
  s.objects[0].mesh = std::make_shared<const Mesh>(bad);
  EXPECT_THROW(validateScene(s), InputError);
  bad = makeBox({1, 1, 1});
  bad.indices.pop_back();  // not whole triangles
  s.objects[0].mesh = std::make_shared<const Mesh>(bad);
  EXPECT_THROW(validateScene(s), InputError);
  bad = makeBox({1, 1, 1});
  bad.normals.pop_back();  // a vertex without its normal
  s.objects[0].mesh = std::make_shared<const Mesh>(bad);
  EXPECT_THROW(validateScene(s), InputError);
}

TEST(SceneValidation, ObjectCountIsCapped) {
  Scene s = oneBoxScene();
  s.objects.resize(size_t(kMaxSceneObjects) + 1, s.objects[0]);  // one shared mesh: cheap
  try {
    validateScene(s);
    FAIL() << "accepted " << s.objects.size() << " objects";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(std::to_string(kMaxSceneObjects)), std::string::npos);
  }
}

TEST(SceneValidation, ImpossibleCamerasAndLightsAreRefused) {
  Scene s = oneBoxScene();
  s.camera.up = glm::vec3(0);  // black image, all-lit mask before
  EXPECT_THROW(validateScene(s), InputError);
  s = oneBoxScene();
  s.camera.up = glm::normalize(s.camera.target - s.camera.position);  // parallel to the view
  EXPECT_THROW(validateScene(s), InputError);
  s = oneBoxScene();
  s.light.up = glm::vec3(0);  // wrong masks before
  EXPECT_THROW(validateScene(s), InputError);
  s = oneBoxScene();
  s.light.farPlane = 0.001f;  // in front of the fitted near plane: an inverted depth range
  try {
    validateScene(s);
    FAIL() << "accepted light.far 0.001";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("light.far"), std::string::npos) << e.what();
  }
  s = oneBoxScene();
  s.light.farPlane = 20.0f;  // beyond the box: a fitted near and this far are a valid range
  EXPECT_NO_THROW(validateScene(s));
}

// The command line: exit 2, exactly one line on stderr, and no output file.
TEST(SceneValidation, TheCommandRefusesEachIssueCaseWithOneLine) {
  const fs::path dir = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "scene-validation";
  fs::create_directories(dir);
  const std::string cases[] = {
      doc(R"({"mesh": {"primitive": "sphere", "stacks": 1}})", ""),
      doc(R"({"mesh": {"primitive": "plane", "divisions": 1e9}})"),
      doc(R"({"mesh": {"primitive": "fence", "pickets": 1e9}})"),
      doc(kGround, R"("camera": {"up": [0, 0, 0]})"),
      doc(kGround, R"("light": {"far": 0.001})"),
  };
  int index = 0;
  for (const std::string& text : cases) {
    const fs::path scene = dir / ("case" + std::to_string(index++) + ".json");
    std::ofstream(scene) << text;
    const fs::path out = dir / "out.png", err = dir / "stderr.txt";
    fs::remove(out);
    const std::string command = std::string(SHADOWLAB_BINARY) + " render --scene " +
                                scene.string() + " --technique modern.hw --size 64x48 --out " +
                                out.string() + " 2> " + err.string();
    const int status = std::system(command.c_str());
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << text;
    EXPECT_FALSE(fs::exists(out)) << text;
    std::ifstream in(err);
    std::stringstream all;
    all << in.rdbuf();
    const std::string message = all.str();
    EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << message;
  }
}

}  // namespace
}  // namespace sl
