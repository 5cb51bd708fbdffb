#include "core/scene/scene_library.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/base/errors.h"
#include "core/scene/mesh_io.h"
#include "core/scene/primitives.h"

#ifndef SHADOWLAB_ASSET_DIR
#define SHADOWLAB_ASSET_DIR "assets"
#endif

namespace sl {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::shared_ptr<const Mesh> share(Mesh m) { return std::make_shared<const Mesh>(std::move(m)); }

Object object(std::string name, Mesh mesh, glm::mat4 model, glm::vec3 diffuse, bool casts = true,
              bool receives = true) {
  Object o;
  o.name = std::move(name);
  o.mesh = share(std::move(mesh));
  o.model = model;
  o.diffuse = diffuse;
  o.castsShadow = casts;
  o.receivesShadow = receives;
  return o;
}

glm::mat4 at(glm::vec3 p) { return glm::translate(glm::mat4(1.0f), p); }

constexpr glm::vec3 kGround{0.75f, 0.75f, 0.72f};
// Fixed-function lighting is evaluated per vertex (glspec121 §2.13): ground planes are
// tessellated so that the spotlight cone reads as a circle in the legacy images too.
constexpr int kGroundDivisions = 48;
constexpr int kBrabecGroundDivisions = 32;  // keeps the scene near its 7000 polygons

// A square occluder parallel to a ground plane, a point-like spotlight straight above: the
// geometric shadow is a square whose edges follow from similar triangles (tests use it).
Scene analyticScene() {
  Scene s;
  s.name = "analytic";
  s.description =
      "unit square occluder 1 unit above a plane, light 4 units above (exact shadow known)";
  s.objects.push_back(
      object("ground", makePlane(6, 6, kGroundDivisions), glm::mat4(1), kGround, false, true));
  Mesh square = makeBox({1.0f, 0.02f, 1.0f});
  s.objects.push_back(
      object("occluder", square, at({0, 1.0f, 0}), {0.8f, 0.3f, 0.2f}, true, false));
  s.camera.position = {0, 6.5f, 3.2f};
  s.camera.target = {0, 0, 0.3f};
  s.camera.fovyDegrees = 40;
  s.camera.nearPlane = 0.5f;
  s.camera.farPlane = 20;
  s.light.position = {0, 4.0f, 0};
  s.light.target = {0, 0, 0};
  s.light.up = {0, 0, -1};
  s.light.coneDegrees = 70;
  return s;
}

// The Brabec–Seidel test scene as their §5 describes it: about 7000 polygons, one light,
// 800x600, OpenGL lighting (their exact model is not published; these are our primitives).
Scene brabecScene() {
  Scene s;
  s.name = "brabec";
  s.description =
      "torus, spheres, boxes and a cylinder on a ground plane, ~7000 triangles (Brabec–Seidel §5)";
  s.objects.push_back(object("ground", makePlane(12, 12, kBrabecGroundDivisions), glm::mat4(1),
                             kGround, true, true));
  s.objects.push_back(object("torus", makeTorus(0.8f, 0.25f, 48, 24),
                             glm::rotate(at({-1.3f, 1.1f, 0.2f}), glm::radians(60.0f), {1, 0, 0}),
                             {0.85f, 0.35f, 0.25f}));
  s.objects.push_back(
      object("sphere", makeSphere(0.6f, 48, 24), at({1.3f, 0.9f, -0.6f}), {0.3f, 0.5f, 0.85f}));
  s.objects.push_back(
      object("small sphere", makeSphere(0.3f, 32, 16), at({0.4f, 0.3f, 1.3f}), {0.9f, 0.8f, 0.3f}));
  s.objects.push_back(object("box", makeBox({0.8f, 0.8f, 0.8f}),
                             glm::rotate(at({0.2f, 0.4f, -1.8f}), glm::radians(30.0f), {0, 1, 0}),
                             {0.4f, 0.75f, 0.4f}));
  s.objects.push_back(object("pillar", makeCylinder(0.2f, 2.0f, 48), at({-0.2f, 1.0f, -0.5f}),
                             {0.7f, 0.7f, 0.75f}));
  s.camera.position = {0.5f, 4.0f, 6.5f};
  s.camera.target = {0, 0.4f, 0};
  s.camera.fovyDegrees = 45;
  s.camera.nearPlane = 0.5f;
  s.camera.farPlane = 30;
  s.light.position = {-3.0f, 7.0f, 3.0f};
  s.light.target = {0, 0, 0};
  s.light.up = {0, 1, 0};
  s.light.coneDegrees = 55;
  return s;
}

// A picket fence in front of objects (Annen et al. Fig. 9: where VSM leaks light).
Scene fenceScene() {
  Scene s;
  s.name = "fence";
  s.description = "a picket fence casting onto objects and ground (Annen et al. Fig. 9)";
  s.objects.push_back(
      object("ground", makePlane(12, 12, kGroundDivisions), glm::mat4(1), kGround, false, true));
  s.objects.push_back(
      object("fence", makeFence(4.0f, 1.2f, 12), at({0, 0, 0.8f}), {0.65f, 0.5f, 0.35f}));
  s.objects.push_back(
      object("box", makeBox({0.7f, 0.7f, 0.7f}), at({-0.8f, 0.35f, -0.6f}), {0.4f, 0.6f, 0.8f}));
  s.objects.push_back(
      object("sphere", makeSphere(0.45f), at({0.9f, 0.45f, -0.5f}), {0.8f, 0.4f, 0.4f}));
  s.camera.position = {0.0f, 3.0f, -5.0f};
  s.camera.target = {0, 0.3f, 0.2f};
  s.camera.fovyDegrees = 45;
  s.camera.nearPlane = 0.5f;
  s.camera.farPlane = 30;
  s.light.position = {0.5f, 3.2f, 4.5f};
  s.light.target = {0, 0, -0.5f};
  s.light.up = {0, 1, 0};
  s.light.coneDegrees = 60;
  return s;
}

// Trees on a ground plane (CSM Figs. 1, 7 and 10 use trees; ours are procedural): bare trees
// with thin branches, whose shadows are what PCF loses under minification (Fig. 7 a).
Scene treesScene() {
  Scene s;
  s.name = "trees";
  s.description =
      "procedural trees on a large ground plane (stand-in for the trees of Annen et al.)";
  s.objects.push_back(
      object("ground", makePlane(30, 30, kGroundDivisions), glm::mat4(1), kGround, false, true));
  const glm::vec3 spots[] = {{0, 0, 0},       {2.5f, 0, -1.5f}, {-2.2f, 0, -2.5f}, {-3, 0, 1.8f},
                             {3.2f, 0, 2.0f}, {0.5f, 0, -5},    {-5, 0, -5},       {5, 0, -6}};
  constexpr float kTreeHeight = 2.5f;  // world units
  constexpr float kHeightVariation = 0.3f;
  constexpr int kBranchLevels = 3;  // trunk, then three generations of branches
  for (size_t i = 0; i < std::size(spots); ++i)
    s.objects.push_back(object(
        "tree " + std::to_string(i),
        makeBranchedTree(kTreeHeight + kHeightVariation * float(i % 3), kBranchLevels, unsigned(i)),
        at(spots[i]), {0.45f, 0.38f, 0.28f}));
  s.camera.position = {0, 5, 10};
  s.camera.target = {0, 0.5f, -1};
  s.camera.fovyDegrees = 50;
  s.camera.nearPlane = 0.5f;
  s.camera.farPlane = 60;
  s.light.position = {-6, 10, 4};
  s.light.target = {0, 0, -1};
  s.light.up = {0, 1, 0};
  s.light.coneDegrees = 70;
  return s;
}

// Dueling frusta (Everitt Fig. 6): the light looks back towards the camera.
Scene duelingScene() {
  Scene s = brabecScene();
  s.name = "dueling";
  s.description =
      "the brabec scene with the light facing the camera (dueling frusta, Everitt Fig. 6)";
  s.light.position = {0.0f, 3.5f, -6.0f};
  s.light.target = {0, 0, 0.5f};
  s.light.coneDegrees = 60;
  return s;
}

// A long strip of ground seen from one end, posts and boxes near the camera and far away, the
// spot light high and far with a cone over the whole strip (parallel-split shadow maps, ours,
// after Zhang et al. 2006): one map over the strip gives the near posts blocky shadows.
Scene longScene() {
  Scene s;
  s.name = "long";
  s.description =
      "a 6 x 60 ground strip with posts near and far, light high and far (one map is blocky near)";
  constexpr float kWidth = 6.0f, kLength = 60.0f;  // world units
  constexpr float kNearEnd = 2.5f;                 // z of the strip's end behind the camera
  constexpr int kLongDivisions = 60;               // about a unit per cell along the strip
  s.objects.push_back(object("ground", makePlane(kWidth, kLength, kLongDivisions),
                             at({0, 0, kNearEnd - 0.5f * kLength}), kGround, false, true));
  const glm::vec3 post{0.12f, 1.2f, 0.12f};  // thin: a one-texel-wide shadow in one map
  const float postZ[] = {0.5f, -1.0f, -2.5f, -15.0f, -25.0f, -35.0f, -45.0f};
  for (size_t i = 0; i < std::size(postZ); ++i)
    for (float x : {-1.2f, 1.2f})
      s.objects.push_back(object("post " + std::to_string(2 * i + (x > 0 ? 1 : 0)), makeBox(post),
                                 at({x, 0.5f * post.y, postZ[i]}), {0.55f, 0.45f, 0.35f}));
  const glm::vec3 box{0.5f, 0.5f, 0.5f};
  for (float z : {-1.6f, -20.0f, -40.0f})
    s.objects.push_back(object("box " + std::to_string(int(-z)), makeBox(box),
                               at({0.3f, 0.5f * box.y, z}), {0.4f, 0.55f, 0.8f}));
  s.camera.position = {0.4f, 1.3f, 3.5f};
  s.camera.target = {0, 0.4f, -12};
  s.camera.fovyDegrees = 50;
  s.camera.nearPlane = 0.3f;
  // Nearer than the strip's far corners (61 units), so that the far plane, not the scene, ends
  // the view frustum and the splits do not change as the camera moves.
  s.camera.farPlane = 58;
  s.light.position = {10, 30, 25};
  s.light.target = {0, 0, -26};
  s.light.up = {0, 1, 0};
  s.light.coneDegrees = 48;  // the strip's corners lie within 44 degrees
  return s;
}

glm::vec3 vec3(const json& j, const std::string& what) {
  if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number())
    throw InputError(what + " must be an array of three numbers");
  // Read as double first: a value beyond float's range must not silently become Inf.
  const glm::dvec3 d(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
  if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.z) ||
      glm::max(glm::max(std::fabs(d.x), std::fabs(d.y)), std::fabs(d.z)) > kMaxSceneCoordinate)
    throw InputError(what + " must be finite and at most " + formatNumber(kMaxSceneCoordinate) +
                     " in magnitude");
  return glm::vec3(d);
}

float number(const json& j, const std::string& what) {
  if (!j.is_number()) throw InputError(what + " must be a number");
  const double v = j.get<double>();
  if (!std::isfinite(v) || std::fabs(v) > kMaxSceneCoordinate)
    throw InputError(what + " must be finite and at most " + formatNumber(kMaxSceneCoordinate) +
                     " in magnitude");
  return float(v);
}

// A count (slices, divisions, ...): an integer, read before any conversion so that 3e9 or 2.5
// is refused instead of wrapping around or truncating; the generators check their own caps.
int integer(const json& j, const std::string& what) {
  if (!j.is_number()) throw InputError(what + " must be an integer");
  const double v = j.get<double>();
  if (!(std::floor(v) == v && v >= double(std::numeric_limits<int>::min()) &&
        v <= double(std::numeric_limits<int>::max())))
    throw InputError(what + " must be an integer, got " + formatNumber(v));
  return int(v);
}

bool boolean(const json& j, const std::string& what) {
  if (!j.is_boolean()) throw InputError(what + " must be true or false");
  return j.get<bool>();
}

// Strings go into captions, HTML and JSON lines: bytes that are not UTF-8 become U+FFFD here,
// once, instead of failing later in an output writer.
std::string utf8(const std::string& raw) {
  return json::parse(json(raw).dump(-1, ' ', false, json::error_handler_t::replace))
      .get<std::string>();
}

std::string stringValue(const json& j, const std::string& what) {
  if (!j.is_string()) throw InputError(what + " must be a string");
  return utf8(j.get<std::string>());
}

// A scene file's objects are read strictly: a key this reader does not know is a typo that
// would otherwise be ignored silently ("positon", "stack"), so it is an error that lists the
// keys that are known there.
const json& strictObject(const json& j, const std::string& what,
                         std::initializer_list<const char*> known) {
  if (!j.is_object()) throw InputError(what + " must be a JSON object");
  for (const auto& item : j.items()) {
    // item.key(), not a structured binding: clang before 16 cannot capture one in a lambda.
    const std::string& key = item.key();
    if (std::none_of(known.begin(), known.end(), [&](const char* k) { return key == k; })) {
      std::string list;
      for (const char* k : known) list += std::string(list.empty() ? "" : ", ") + k;
      throw InputError(what + " has an unknown key \"" + utf8(key) + "\" (known: " + list + ")");
    }
  }
  return j;
}

Mesh meshFromJson(const json& j, const std::string& where, const std::string& baseDir) {
  const std::string what = where + ".mesh";
  if (!j.is_object()) throw InputError(what + " must be a JSON object");
  if (j.contains("file")) {
    strictObject(j, what, {"file", "size"});
    const std::string given = stringValue(j["file"], what + ".file");
    // A relative path is read beside the scene file (baseDir is its folder), and only there.
    fs::path p = given;
    if (p.is_relative()) p = fs::path(baseDir) / p;
    std::error_code ec;
    if (!fs::exists(p, ec))
      throw InputError(what + ".file " + given + ": no such file (looked in " +
                       fs::absolute(p, ec).lexically_normal().string() + ")");
    Mesh m = loadMesh(p.string());
    if (j.contains("size")) normalizeMesh(m, number(j["size"], what + ".size"), p.string());
    return m;
  }
  if (!j.contains("primitive"))
    throw InputError(what +
                     " needs \"file\" or a \"primitive\" (plane, box, sphere, "
                     "cylinder, torus, quad, fence, tree)");
  const std::string kind = stringValue(j["primitive"], what + ".primitive");
  auto num = [&](const char* key, float fallback) {
    return j.contains(key) ? number(j[key], what + "." + key) : fallback;
  };
  auto count = [&](const char* key, int fallback) {
    return j.contains(key) ? integer(j[key], what + "." + key) : fallback;
  };
  // Parameters are checked by the generators (core/scene/primitives.h caps); their messages name
  // the primitive and the parameter, prefixed here with where it is in the file.
  try {
    if (kind == "plane") {
      strictObject(j, what, {"primitive", "width", "depth", "divisions"});
      return makePlane(num("width", 10), num("depth", 10), count("divisions", 1));
    }
    if (kind == "box") {
      strictObject(j, what, {"primitive", "extent"});
      return makeBox(j.contains("extent") ? vec3(j["extent"], what + ".extent") : glm::vec3(1));
    }
    if (kind == "sphere") {
      strictObject(j, what, {"primitive", "radius", "slices", "stacks"});
      return makeSphere(num("radius", 1), count("slices", 32), count("stacks", 16));
    }
    if (kind == "cylinder") {
      strictObject(j, what, {"primitive", "radius", "height", "slices"});
      return makeCylinder(num("radius", 0.5f), num("height", 1), count("slices", 32));
    }
    if (kind == "torus") {
      strictObject(j, what, {"primitive", "major", "minor", "rings", "sides"});
      return makeTorus(num("major", 1), num("minor", 0.25f), count("rings", 32),
                       count("sides", 16));
    }
    if (kind == "quad") {
      strictObject(j, what, {"primitive", "width", "height"});
      return makeQuad(num("width", 1), num("height", 1));
    }
    if (kind == "fence") {
      strictObject(j, what, {"primitive", "length", "height", "pickets"});
      return makeFence(num("length", 4), num("height", 1), count("pickets", 10));
    }
    if (kind == "tree") {
      strictObject(j, what, {"primitive", "height"});
      return makeTree(num("height", 2));
    }
  } catch (const InputError& e) {
    const std::string message = e.what();
    if (message.rfind(what, 0) == 0) throw;
    throw InputError(what + ": " + message);
  }
  throw InputError(what +
                   ".primitive must be one of plane, box, sphere, cylinder, torus, quad, "
                   "fence, tree; got '" +
                   kind + "'");
}

}  // namespace

std::vector<std::string> builtinSceneNames() {
  return {"analytic", "brabec", "fence", "trees", "dueling", "long"};
}

Scene builtinScene(const std::string& name) {
  Scene s;
  if (name == "analytic")
    s = analyticScene();
  else if (name == "brabec")
    s = brabecScene();
  else if (name == "fence")
    s = fenceScene();
  else if (name == "trees")
    s = treesScene();
  else if (name == "dueling")
    s = duelingScene();
  else if (name == "long")
    s = longScene();
  else
    throw InputError("unknown scene '" + name + "'");
  validateScene(s);
  return s;
}

std::string assetDirectory() {
  if (const char* env = std::getenv("SHADOWLAB_ASSETS"); env != nullptr && *env != 0) return env;
  return SHADOWLAB_ASSET_DIR;
}

std::vector<std::string> sceneFileNames() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(fs::path(assetDirectory()) / "scenes", ec))
    if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

Scene parseSceneJson(const std::string& text, const std::string& sourceName,
                     const std::string& baseDir) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for a number like 1E9999
    throw InputError("malformed scene file " + sourceName + ": " + e.what());
  }
  try {
    strictObject(doc, "the document", {"name", "description", "camera", "light", "objects"});
    Scene s;
    s.name = doc.contains("name") ? stringValue(doc["name"], "name")
                                  : utf8(fs::path(sourceName).stem().string());
    if (doc.contains("description")) s.description = stringValue(doc["description"], "description");
    if (doc.contains("camera")) {
      const json& c = strictObject(doc["camera"], "camera",
                                   {"position", "target", "up", "fovy", "near", "far"});
      if (c.contains("position")) s.camera.position = vec3(c["position"], "camera.position");
      if (c.contains("target")) s.camera.target = vec3(c["target"], "camera.target");
      if (c.contains("up")) s.camera.up = vec3(c["up"], "camera.up");
      if (c.contains("fovy")) s.camera.fovyDegrees = number(c["fovy"], "camera.fovy");
      if (c.contains("near")) s.camera.nearPlane = number(c["near"], "camera.near");
      if (c.contains("far")) s.camera.farPlane = number(c["far"], "camera.far");
    }
    if (doc.contains("light")) {
      const json& l = strictObject(
          doc["light"], "light",
          {"position", "target", "up", "cone", "near", "far", "radius", "ambient", "color"});
      if (l.contains("position")) s.light.position = vec3(l["position"], "light.position");
      if (l.contains("target")) s.light.target = vec3(l["target"], "light.target");
      if (l.contains("up")) s.light.up = vec3(l["up"], "light.up");
      if (l.contains("cone")) s.light.coneDegrees = number(l["cone"], "light.cone");
      if (l.contains("near")) s.light.nearPlane = number(l["near"], "light.near");
      if (l.contains("far")) s.light.farPlane = number(l["far"], "light.far");
      if (l.contains("radius")) s.light.radius = number(l["radius"], "light.radius");
      if (l.contains("ambient")) s.light.ambient = number(l["ambient"], "light.ambient");
      if (l.contains("color")) s.light.color = vec3(l["color"], "light.color");
    }
    if (!doc.contains("objects") || !doc["objects"].is_array())
      throw InputError("\"objects\" must be an array");
    if (doc["objects"].size() > size_t(kMaxSceneObjects))
      throw InputError("\"objects\" has " + std::to_string(doc["objects"].size()) +
                       " entries; at most " + std::to_string(kMaxSceneObjects));
    int index = 0;
    for (const json& o : doc["objects"]) {
      const std::string where = "objects[" + std::to_string(index++) + "]";
      strictObject(o, where,
                   {"name", "mesh", "translate", "rotate", "scale", "diffuse", "specular", "casts",
                    "receives"});
      if (!o.contains("mesh")) throw InputError(where + " has no mesh");
      Object obj;
      obj.name = o.contains("name") ? stringValue(o["name"], where + ".name") : where;
      obj.mesh = share(meshFromJson(o["mesh"], where, baseDir));
      glm::mat4 m(1.0f);
      if (o.contains("translate"))
        m = glm::translate(m, vec3(o["translate"], where + ".translate"));
      if (o.contains("rotate")) {  // [x, y, z] Euler angles in degrees, applied z, y, x
        const glm::vec3 r = vec3(o["rotate"], where + ".rotate");
        m = glm::rotate(m, glm::radians(r.x), {1, 0, 0});
        m = glm::rotate(m, glm::radians(r.y), {0, 1, 0});
        m = glm::rotate(m, glm::radians(r.z), {0, 0, 1});
      }
      if (o.contains("scale")) {
        const glm::vec3 sc = o["scale"].is_number()
                                 ? glm::vec3(number(o["scale"], where + ".scale"))
                                 : vec3(o["scale"], where + ".scale");
        if (sc.x == 0 || sc.y == 0 || sc.z == 0) throw InputError(where + ".scale must not be 0");
        m = glm::scale(m, sc);
      }
      obj.model = m;
      if (o.contains("diffuse")) obj.diffuse = vec3(o["diffuse"], where + ".diffuse");
      if (o.contains("specular")) obj.specular = number(o["specular"], where + ".specular");
      if (o.contains("casts")) obj.castsShadow = boolean(o["casts"], where + ".casts");
      if (o.contains("receives")) obj.receivesShadow = boolean(o["receives"], where + ".receives");
      s.objects.push_back(std::move(obj));
    }
    validateScene(s);
    return s;
  } catch (const json::exception& e) {
    throw InputError("malformed scene file " + sourceName + ": " + e.what());
  } catch (const InputError& e) {
    const std::string what = e.what();
    if (what.rfind("scene '", 0) == 0 || what.find(sourceName) != std::string::npos) throw;
    throw InputError("scene file " + sourceName + ": " + what);
  }
}

std::string sceneFilePath(const std::string& nameOrPath) {
  const auto builtins = builtinSceneNames();
  if (std::find(builtins.begin(), builtins.end(), nameOrPath) != builtins.end()) return "";
  const bool namesAFile =
      fs::path(nameOrPath).extension() == ".json" || nameOrPath.find('/') != std::string::npos;
  return namesAFile ? nameOrPath
                    : (fs::path(assetDirectory()) / "scenes" / (nameOrPath + ".json")).string();
}

Scene loadScene(const std::string& nameOrPath) {
  const auto builtins = builtinSceneNames();
  if (std::find(builtins.begin(), builtins.end(), nameOrPath) != builtins.end())
    return builtinScene(nameOrPath);
  // A name that ends in .json or holds a folder is a file the user named: when it is not
  // there, the message names that file (not the list of scene names).
  const bool namesAFile =
      fs::path(nameOrPath).extension() == ".json" || nameOrPath.find('/') != std::string::npos;
  const fs::path path = sceneFilePath(nameOrPath);
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    if (namesAFile) throw InputError("scene file " + nameOrPath + ": no such file");
    std::string known;
    for (const auto& n : builtins) known += (known.empty() ? "" : ", ") + n;
    for (const auto& n : sceneFileNames()) known += ", " + n;
    throw InputError("unknown scene '" + nameOrPath + "' (known: " + known + ")");
  }
  if (!fs::is_regular_file(path, ec))
    throw InputError("scene file " + path.string() + ": not a regular file");
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) throw InputError("scene file " + path.string() + ": cannot read it");
  // Relative mesh paths in a scene file are read beside the scene file, the files of
  // assets/scenes/ included (their meshes are ../models/...); docs/scene-files.md.
  return parseSceneJson(text.str(), path.string(), path.parent_path().string());
}

}  // namespace sl
