#include "core/scene/primitives.h"

#include <cmath>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <sstream>
#include <string>
#include <tuple>

#include "core/base/errors.h"

namespace sl {
namespace {

// The generators' argument checks: one line naming the primitive, the parameter and the bound.
void checkCount(const char* primitive, const char* parameter, int value, int lo, int hi) {
  if (value < lo || value > hi)
    throw InputError(std::string(primitive) + " " + parameter + " must be in [" +
                     std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                     std::to_string(value));
}

void checkLength(const char* primitive, const char* parameter, float value) {
  if (!(value > 0.0f && value <= kMaxPrimitiveLength)) {
    std::ostringstream s;
    s << primitive << " " << parameter << " must be in (0, " << kMaxPrimitiveLength << "], got "
      << value;
    throw InputError(s.str());
  }
}

void addQuad(Mesh& m, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 n) {
  const unsigned base = unsigned(m.positions.size());
  for (const glm::vec3& p : {a, b, c, d}) {
    m.positions.push_back(p);
    m.normals.push_back(n);
  }
  for (unsigned i : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + i);
}

}  // namespace

Mesh makePlane(float sizeX, float sizeZ, int divisions) {
  checkLength("plane", "width", sizeX);
  checkLength("plane", "depth", sizeZ);
  checkCount("plane", "divisions", divisions, 1, kMaxPlaneDivisions);
  Mesh m;
  for (int j = 0; j <= divisions; ++j)
    for (int i = 0; i <= divisions; ++i) {
      m.positions.push_back(
          {sizeX * (float(i) / divisions - 0.5f), 0.0f, sizeZ * (float(j) / divisions - 0.5f)});
      m.normals.push_back({0, 1, 0});
    }
  const unsigned row = unsigned(divisions + 1);
  for (int j = 0; j < divisions; ++j)
    for (int i = 0; i < divisions; ++i) {
      const unsigned a = j * row + i, b = a + 1, c = a + row, d = c + 1;
      // counter-clockwise seen from +y
      for (unsigned k : {a, c, b, b, c, d}) m.indices.push_back(k);
    }
  return m;
}

Mesh makeQuad(float sizeX, float sizeY) {
  checkLength("quad", "width", sizeX);
  checkLength("quad", "height", sizeY);
  Mesh m;
  const float x = 0.5f * sizeX, y = 0.5f * sizeY;
  addQuad(m, {-x, -y, 0}, {x, -y, 0}, {x, y, 0}, {-x, y, 0}, {0, 0, 1});
  return m;
}

Mesh makeBox(const glm::vec3& size) {
  checkLength("box", "extent x", size.x);
  checkLength("box", "extent y", size.y);
  checkLength("box", "extent z", size.z);
  Mesh m;
  const glm::vec3 h = 0.5f * size;
  const glm::vec3 p[8] = {{-h.x, -h.y, -h.z}, {h.x, -h.y, -h.z}, {h.x, h.y, -h.z},
                          {-h.x, h.y, -h.z},  {-h.x, -h.y, h.z}, {h.x, -h.y, h.z},
                          {h.x, h.y, h.z},    {-h.x, h.y, h.z}};
  addQuad(m, p[4], p[5], p[6], p[7], {0, 0, 1});   // front  (+z)
  addQuad(m, p[1], p[0], p[3], p[2], {0, 0, -1});  // back   (-z)
  addQuad(m, p[5], p[1], p[2], p[6], {1, 0, 0});   // right  (+x)
  addQuad(m, p[0], p[4], p[7], p[3], {-1, 0, 0});  // left   (-x)
  addQuad(m, p[7], p[6], p[2], p[3], {0, 1, 0});   // top    (+y)
  addQuad(m, p[0], p[1], p[5], p[4], {0, -1, 0});  // bottom (-y)
  m.closed = true;
  return m;
}

Mesh makeSphere(float radius, int slices, int stacks) {
  checkLength("sphere", "radius", radius);
  checkCount("sphere", "slices", slices, kMinSphereSlices, kMaxSphereSlices);
  checkCount("sphere", "stacks", stacks, kMinSphereStacks, kMaxSphereStacks);
  Mesh m;
  // Poles are single vertices so that the mesh is closed (no degenerate seams).
  m.positions.push_back({0, radius, 0});
  m.normals.push_back({0, 1, 0});
  for (int j = 1; j < stacks; ++j) {
    const float phi = glm::pi<float>() * float(j) / stacks;
    for (int i = 0; i < slices; ++i) {
      const float theta = 2.0f * glm::pi<float>() * float(i) / slices;
      const glm::vec3 n(std::sin(phi) * std::cos(theta), std::cos(phi),
                        -std::sin(phi) * std::sin(theta));
      m.positions.push_back(radius * n);
      m.normals.push_back(n);
    }
  }
  m.positions.push_back({0, -radius, 0});
  m.normals.push_back({0, -1, 0});
  const unsigned bottom = unsigned(m.positions.size() - 1);
  auto ring = [&](int j, int i) { return unsigned(1 + (j - 1) * slices + (i % slices)); };
  for (int i = 0; i < slices; ++i) {
    m.indices.insert(m.indices.end(), {0u, ring(1, i), ring(1, i + 1)});
    m.indices.insert(m.indices.end(), {bottom, ring(stacks - 1, i + 1), ring(stacks - 1, i)});
  }
  for (int j = 1; j < stacks - 1; ++j)
    for (int i = 0; i < slices; ++i) {
      const unsigned a = ring(j, i), b = ring(j, i + 1), c = ring(j + 1, i), d = ring(j + 1, i + 1);
      m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
    }
  m.closed = true;
  return m;
}

Mesh makeCylinder(float radius, float height, int slices) {
  checkLength("cylinder", "radius", radius);
  checkLength("cylinder", "height", height);
  checkCount("cylinder", "slices", slices, kMinCylinderSlices, kMaxCylinderSlices);
  Mesh m;
  const float h = 0.5f * height;
  // side: separate vertices so the caps keep flat normals; closedness is judged on positions
  for (int i = 0; i < slices; ++i) {
    const float t0 = 2.0f * glm::pi<float>() * float(i) / slices;
    // (i + 1) % slices: the last slice reuses angle 0 exactly, so the seam welds (closed mesh).
    const float t1 = 2.0f * glm::pi<float>() * float((i + 1) % slices) / slices;
    const glm::vec3 n0(std::cos(t0), 0, -std::sin(t0)), n1(std::cos(t1), 0, -std::sin(t1));
    const unsigned base = unsigned(m.positions.size());
    m.positions.insert(m.positions.end(),
                       {radius * n0 + glm::vec3(0, -h, 0), radius * n1 + glm::vec3(0, -h, 0),
                        radius * n1 + glm::vec3(0, h, 0), radius * n0 + glm::vec3(0, h, 0)});
    m.normals.insert(m.normals.end(), {n0, n1, n1, n0});
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    // caps as fans around centre vertices
    const unsigned c = unsigned(m.positions.size());
    m.positions.insert(m.positions.end(), {{0, h, 0},
                                           radius * n0 + glm::vec3(0, h, 0),
                                           radius * n1 + glm::vec3(0, h, 0),
                                           {0, -h, 0},
                                           radius * n0 + glm::vec3(0, -h, 0),
                                           radius * n1 + glm::vec3(0, -h, 0)});
    m.normals.insert(m.normals.end(),
                     {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, -1, 0}, {0, -1, 0}, {0, -1, 0}});
    m.indices.insert(m.indices.end(), {c, c + 1, c + 2, c + 3, c + 5, c + 4});
  }
  m.closed = true;
  return m;
}

Mesh makeTorus(float major, float minor, int rings, int sides) {
  checkLength("torus", "major", major);
  checkLength("torus", "minor", minor);
  checkCount("torus", "rings", rings, kMinTorusSegments, kMaxTorusSegments);
  checkCount("torus", "sides", sides, kMinTorusSegments, kMaxTorusSegments);
  Mesh m;
  for (int j = 0; j < rings; ++j) {
    const float u = 2.0f * glm::pi<float>() * float(j) / rings;
    for (int i = 0; i < sides; ++i) {
      const float v = 2.0f * glm::pi<float>() * float(i) / sides;
      const glm::vec3 centre(major * std::cos(u), 0, -major * std::sin(u));
      const glm::vec3 n(std::cos(v) * std::cos(u), std::sin(v), -std::cos(v) * std::sin(u));
      m.positions.push_back(centre + minor * n);
      m.normals.push_back(n);
    }
  }
  auto at = [&](int j, int i) { return unsigned((j % rings) * sides + (i % sides)); };
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < sides; ++i) {
      const unsigned a = at(j, i), b = at(j + 1, i), c = at(j, i + 1), d = at(j + 1, i + 1);
      m.indices.insert(m.indices.end(), {a, b, c, c, b, d});
    }
  m.closed = true;
  return m;
}

void appendMesh(Mesh& a, const Mesh& b, const glm::mat4& transform) {
  const bool wasEmpty = a.indices.empty();
  const unsigned base = unsigned(a.positions.size());
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(transform)));
  for (size_t i = 0; i < b.positions.size(); ++i) {
    a.positions.push_back(glm::vec3(transform * glm::vec4(b.positions[i], 1.0f)));
    a.normals.push_back(glm::normalize(normalMatrix * b.normals[i]));
  }
  for (unsigned i : b.indices) a.indices.push_back(base + i);
  a.closed = (wasEmpty || a.closed) && b.closed;
}

Mesh makeFence(float length, float height, int pickets) {
  checkLength("fence", "length", length);
  checkLength("fence", "height", height);
  checkCount("fence", "pickets", pickets, 1, kMaxFencePickets);
  Mesh m;
  m.closed = true;
  const float spacing = length / pickets;
  const float picketWidth = 0.45f * spacing;
  const float depth = 0.05f * height;
  for (int i = 0; i < pickets; ++i) {
    const float x = -0.5f * length + (i + 0.5f) * spacing;
    appendMesh(m, makeBox({picketWidth, height, depth}),
               glm::translate(glm::mat4(1), {x, 0.5f * height, 0}));
  }
  for (float y : {0.25f * height, 0.75f * height})
    appendMesh(m, makeBox({length, 0.06f * height, depth}),
               glm::translate(glm::mat4(1), {0, y, -depth}));
  return m;
}

Mesh makeTree(float height) {
  checkLength("tree", "height", height);
  Mesh m;
  m.closed = true;
  const float trunk = 0.45f * height;
  appendMesh(m, makeCylinder(0.05f * height, trunk, 12),
             glm::translate(glm::mat4(1), {0, 0.5f * trunk, 0}));
  const struct {
    glm::vec3 c;
    float r;
  } blobs[] = {{{0, 0.62f, 0}, 0.22f},
               {{0.14f, 0.78f, 0.05f}, 0.16f},
               {{-0.13f, 0.76f, -0.06f}, 0.17f},
               {{0.02f, 0.9f, 0.08f}, 0.12f}};
  for (const auto& b : blobs)
    appendMesh(m, makeSphere(b.r * height, 16, 8), glm::translate(glm::mat4(1), b.c * height));
  return m;
}

namespace {
constexpr float kTrunkShare = 0.45f;          // trunk length / tree height
constexpr float kTrunkRadiusShare = 0.035f;   // trunk radius / tree height
constexpr float kLengthRatio = 0.62f;         // child branch length / parent length
constexpr float kRadiusRatio = 0.45f;         // child branch radius / parent radius
constexpr float kBranchElevationDeg = 42.0f;  // child branches from the parent's axis
constexpr float kLeafShare = 0.035f;          // leaf cluster radius / tree height
constexpr int kBranchSlices = 8;              // cylinder sides of a branch
constexpr int kTrunkChildren = 4, kBranchChildren = 3;

// A small deterministic generator (the tree's variations must not depend on the library).
float unitRandom(unsigned& state) {
  state = state * 1664525u + 1013904223u;  // Numerical Recipes' LCG
  return float(state >> 8) / float(1u << 24);
}

// Rotation taking +y to `direction` (unit).
glm::mat4 yTo(const glm::vec3& direction) {
  const glm::vec3 y(0, 1, 0);
  const glm::vec3 axis = glm::cross(y, direction);
  const float s = glm::length(axis), c = glm::dot(y, direction);
  if (s < 1e-6f)
    return c > 0.0f ? glm::mat4(1) : glm::rotate(glm::mat4(1), glm::pi<float>(), {1, 0, 0});
  return glm::rotate(glm::mat4(1), std::atan2(s, c), axis / s);
}

void addBranch(Mesh& m, const glm::vec3& base, const glm::vec3& direction, float length,
               float radius, int level, int levels, float leafRadius, unsigned& state) {
  appendMesh(m, makeCylinder(radius, length, kBranchSlices),
             glm::translate(glm::mat4(1), base) * yTo(direction) *
                 glm::translate(glm::mat4(1), {0, 0.5f * length, 0}));
  const glm::vec3 tip = base + length * direction;
  if (level == levels) {
    appendMesh(m, makeSphere(leafRadius, 8, 5), glm::translate(glm::mat4(1), tip));
    return;
  }
  // Children around the parent's axis, evenly spaced with a random phase and jitter.
  const int children = level == 0 ? kTrunkChildren : kBranchChildren;
  const glm::vec3 any = std::fabs(direction.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 u = glm::normalize(glm::cross(direction, any));
  const glm::vec3 v = glm::cross(direction, u);
  const float phase = 2.0f * glm::pi<float>() * unitRandom(state);
  for (int i = 0; i < children; ++i) {
    const float azimuth =
        phase + 2.0f * glm::pi<float>() * (float(i) + 0.3f * unitRandom(state)) / float(children);
    const float elevation = glm::radians(kBranchElevationDeg * (0.8f + 0.4f * unitRandom(state)));
    const glm::vec3 d =
        glm::normalize(std::cos(elevation) * direction +
                       std::sin(elevation) * (std::cos(azimuth) * u + std::sin(azimuth) * v));
    // Children start a little below the tip, so that the joints overlap.
    addBranch(m, tip - 0.5f * radius * direction, d,
              length * kLengthRatio * (0.85f + 0.3f * unitRandom(state)), radius * kRadiusRatio,
              level + 1, levels, leafRadius, state);
  }
}
}  // namespace

Mesh makeBranchedTree(float height, int levels, unsigned seed) {
  checkLength("branched tree", "height", height);
  checkCount("branched tree", "levels", levels, 0, kMaxTreeLevels);
  Mesh m;
  m.closed = true;
  unsigned state = seed * 2654435761u + 1u;
  addBranch(m, {0, 0, 0}, {0, 1, 0}, kTrunkShare * height, kTrunkRadiusShare * height, 0, levels,
            kLeafShare * height, state);
  return m;
}

bool isClosedManifold(const Mesh& mesh) {
  // Weld equal positions, then every undirected edge must be used exactly twice, once in each
  // direction (consistent orientation).
  std::map<std::tuple<float, float, float>, unsigned> weld;
  std::vector<unsigned> id(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3& p = mesh.positions[i];
    id[i] = weld.emplace(std::make_tuple(p.x, p.y, p.z), unsigned(weld.size())).first->second;
  }
  std::map<std::pair<unsigned, unsigned>, int> directed;
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
    for (int e = 0; e < 3; ++e) {
      const unsigned a = id[mesh.indices[t + e]], b = id[mesh.indices[t + (e + 1) % 3]];
      if (a == b) return false;  // degenerate triangle
      ++directed[{a, b}];
    }
  for (const auto& [edge, count] : directed) {
    if (count != 1) return false;
    auto twin = directed.find({edge.second, edge.first});
    if (twin == directed.end() || twin->second != 1) return false;
  }
  return !directed.empty();
}

}  // namespace sl
