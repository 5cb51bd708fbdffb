// interpose/glut_shapes.cpp — the GLUT shapes of libshadowlab-glut.so (glutSolid*/glutWire*:
// sphere, cube, cone, torus, teapot and the dodecahedron, octahedron, tetrahedron and
// icosahedron), tessellated as Debian 12's freeglut (3.4.0, libglut3.12) tessellates them, so
// that a program draws the same primitives on `run-legacy --backend osmesa|reference` as on
// `--backend glx`.
//
// What has to match for the same pixels: the GL sees the same primitives (mode, count), with
// the same vertices and normals, in the same order, in single precision. freeglut (in its
// fixed-function path, the one GLUT 3 programs take) builds float arrays and draws them with
// vertex arrays: GL_VERTEX_ARRAY and GL_NORMAL_ARRAY enabled for the draw and disabled after
// it, glDrawArrays or glDrawElements (GL_UNSIGNED_SHORT indices), one call per strip, loop or
// face. This file makes the same calls with arrays computed by the same single-precision
// arithmetic (the same operations in the same order; sin, cos and sqrt in double, rounded to
// float, as C's <math.h> does for freeglut). Our reading of freeglut 3.4.0's src/fg_geometry.c
// and src/fg_teapot.c, written here anew. GlutShapes.SameCallsAsFreeglut
// (tests/interpose/legacy_clients_test.cpp) compares the two call streams, captured by
// tests/interpose/glut_capture_preload.c from tests/interpose/clients/glut_shapes.c.
//
// The teapot's control points are the Newell teapot (Martin Newell, Utah, 1975) as freeglut
// 3.4.0 ships them in src/fg_teapot_data.h (MIT-style licence, Pawel W. Olszta): taken from
// the "teasetorig" archive of Philip Schneider's data (Juhana Kouhia, 1990), each control
// point once, with a bottom added. They are data; freeglut's exact numbers are needed for its
// exact vertices.
#include <GL/freeglut_std.h>
#include <GL/gl.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "interpose/glut_headless.h"

#define SL_EXPORT extern "C" __attribute__((visibility("default")))

namespace sl::interpose {
namespace {

using Index = GLushort;  // freeglut's index type (GL ES 1 has no 32-bit indices)
constexpr float kPiF = float(M_PI);

// ---- drawing: vertex arrays, as freeglut's fixed-function path ----
struct ArrayGl {
  decltype(&::glEnableClientState) enable =
      gl<decltype(&::glEnableClientState)>("glEnableClientState");
  decltype(&::glDisableClientState) disable =
      gl<decltype(&::glDisableClientState)>("glDisableClientState");
  decltype(&::glVertexPointer) vertexPointer = gl<decltype(&::glVertexPointer)>("glVertexPointer");
  decltype(&::glNormalPointer) normalPointer = gl<decltype(&::glNormalPointer)>("glNormalPointer");
  decltype(&::glTexCoordPointer) texCoordPointer =
      gl<decltype(&::glTexCoordPointer)>("glTexCoordPointer");
  decltype(&::glDrawArrays) drawArrays = gl<decltype(&::glDrawArrays)>("glDrawArrays");
  decltype(&::glDrawElements) drawElements = gl<decltype(&::glDrawElements)>("glDrawElements");
};
const ArrayGl& arrays() {
  static const ArrayGl g;
  return g;
}

struct Arrays {
  std::vector<float> vertices, normals;  // 3 floats a vertex
};

void bind(const ArrayGl& g, const Arrays& a) {
  g.enable(GL_VERTEX_ARRAY);
  g.enable(GL_NORMAL_ARRAY);
  g.vertexPointer(3, GL_FLOAT, 0, a.vertices.data());
  g.normalPointer(GL_FLOAT, 0, a.normals.data());
}
void unbind(const ArrayGl& g) {
  g.disable(GL_VERTEX_ARRAY);
  g.disable(GL_NORMAL_ARRAY);
}

// Solid: without indices one GL_TRIANGLES draw of every vertex; with indices, `parts` > 1
// triangle strips of `perPart` indices each, or one GL_TRIANGLES draw of `perPart` indices.
// `texcoords` (2 floats a vertex), when given, is the texture coordinate array.
void drawSolid(const Arrays& a, const std::vector<float>* texcoords, const Index* indices,
               int parts, int perPart) {
  const ArrayGl& g = arrays();
  bind(g, a);
  if (texcoords != nullptr) {
    g.enable(GL_TEXTURE_COORD_ARRAY);
    g.texCoordPointer(2, GL_FLOAT, 0, texcoords->data());
  }
  if (indices == nullptr) {
    g.drawArrays(GL_TRIANGLES, 0, GLsizei(a.vertices.size() / 3));
  } else if (parts > 1) {
    for (int i = 0; i < parts; ++i)
      g.drawElements(GL_TRIANGLE_STRIP, perPart, GL_UNSIGNED_SHORT, indices + i * perPart);
  } else {
    g.drawElements(GL_TRIANGLES, perPart, GL_UNSIGNED_SHORT, indices);
  }
  unbind(g);
  if (texcoords != nullptr) g.disable(GL_TEXTURE_COORD_ARRAY);
}

// Wire: `parts` primitives of `mode`, `perPart` vertices each (consecutive vertices without
// indices, else consecutive indices), then `parts2` line loops of `perPart2` indices.
void drawWire(const Arrays& a, const Index* indices, int parts, int perPart, GLenum mode,
              const Index* indices2 = nullptr, int parts2 = 0, int perPart2 = 0) {
  const ArrayGl& g = arrays();
  bind(g, a);
  for (int i = 0; i < parts; ++i) {
    if (indices == nullptr)
      g.drawArrays(mode, i * perPart, perPart);
    else
      g.drawElements(mode, perPart, GL_UNSIGNED_SHORT, indices + i * perPart);
  }
  for (int i = 0; indices2 != nullptr && i < parts2; ++i)
    g.drawElements(GL_LINE_LOOP, perPart2, GL_UNSIGNED_SHORT, indices2 + i * perPart2);
  unbind(g);
}

void push(std::vector<float>& out, float x, float y, float z) {
  out.push_back(x);
  out.push_back(y);
  out.push_back(z);
}

// ---- polyhedra: each face its own vertices (one normal a face) ----
struct Polyhedron {
  int faceCount, cornersPerFace;
  const float (*corners)[3];
  const float (*faceNormals)[3];
  const int* faceCorners;  // cornersPerFace a face, counter-clockwise seen from outside
};

Arrays expand(const Polyhedron& p, float scale) {
  Arrays a;
  for (int f = 0; f < p.faceCount; ++f)
    for (int k = 0; k < p.cornersPerFace; ++k) {
      const float* c = p.corners[p.faceCorners[f * p.cornersPerFace + k]];
      push(a.vertices, scale * c[0], scale * c[1], scale * c[2]);
      push(a.normals, p.faceNormals[f][0], p.faceNormals[f][1], p.faceNormals[f][2]);
    }
  return a;
}

// Quads and pentagons as triangles, fanned from the face's first corner as freeglut does
// (a pentagon 0 1 2 | 0 2 4 | 4 2 3), counter-clockwise kept.
std::vector<Index> triangulate(const Polyhedron& p) {
  static const int kQuad[] = {0, 1, 2, 0, 2, 3};
  static const int kPentagon[] = {0, 1, 2, 0, 2, 4, 4, 2, 3};
  const int* pattern = p.cornersPerFace == 4 ? kQuad : kPentagon;
  const int perFace = p.cornersPerFace == 4 ? 6 : 9;
  std::vector<Index> out;
  for (int f = 0; f < p.faceCount; ++f)
    for (int k = 0; k < perFace; ++k) out.push_back(Index(f * p.cornersPerFace + pattern[k]));
  return out;
}

void drawPolyhedron(const Polyhedron& p, float scale, bool wire) {
  const Arrays a = expand(p, scale);
  if (wire) {
    drawWire(a, nullptr, p.faceCount, p.cornersPerFace, GL_LINE_LOOP);
  } else if (p.cornersPerFace == 3) {
    drawSolid(a, nullptr, nullptr, 1, 0);
  } else {
    const std::vector<Index> triangles = triangulate(p);
    drawSolid(a, nullptr, triangles.data(), 1, int(triangles.size()));
  }
}

// The solids' numbers: unit circumradius but for the cube (side 1) and the dodecahedron
// (circumradius sqrt(3)); the corners' order and each face's corner order are freeglut's.
constexpr float kInvSqrt3 = 0.577350269189f;  // 1 / sqrt(3)
constexpr float kPhi = 1.61803398875f;        // (1 + sqrt(5)) / 2
constexpr float kPhiInv = 0.61803398875f;     // (sqrt(5) - 1) / 2
constexpr float kDodecaA = 0.525731112119f;   // 1 / sqrt(1 + phi^2)
constexpr float kDodecaB = 0.850650808354f;   // phi / sqrt(1 + phi^2)

constexpr float kCubeCorners[8][3] = {{.5f, .5f, .5f},   {-.5f, .5f, .5f},  {-.5f, -.5f, .5f},
                                      {.5f, -.5f, .5f},  {.5f, -.5f, -.5f}, {.5f, .5f, -.5f},
                                      {-.5f, .5f, -.5f}, {-.5f, -.5f, -.5f}};
constexpr float kCubeNormals[6][3] = {{0, 0, 1},  {1, 0, 0},  {0, 1, 0},
                                      {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
constexpr int kCubeFaces[6 * 4] = {0, 1, 2, 3, 0, 3, 4, 5, 0, 5, 6, 1,
                                   1, 6, 7, 2, 7, 4, 3, 2, 4, 7, 6, 5};
constexpr Polyhedron kCube{6, 4, kCubeCorners, kCubeNormals, kCubeFaces};

constexpr float kOctahedronCorners[6][3] = {{1, 0, 0},  {0, 1, 0},  {0, 0, 1},
                                            {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
constexpr float kOctahedronNormals[8][3] = {
    {kInvSqrt3, kInvSqrt3, kInvSqrt3},   {kInvSqrt3, kInvSqrt3, -kInvSqrt3},
    {kInvSqrt3, -kInvSqrt3, kInvSqrt3},  {kInvSqrt3, -kInvSqrt3, -kInvSqrt3},
    {-kInvSqrt3, kInvSqrt3, kInvSqrt3},  {-kInvSqrt3, kInvSqrt3, -kInvSqrt3},
    {-kInvSqrt3, -kInvSqrt3, kInvSqrt3}, {-kInvSqrt3, -kInvSqrt3, -kInvSqrt3}};
constexpr int kOctahedronFaces[8 * 3] = {0, 1, 2, 0, 5, 1, 0, 2, 4, 0, 4, 5,
                                         3, 2, 1, 3, 1, 5, 3, 4, 2, 3, 5, 4};
constexpr Polyhedron kOctahedron{8, 3, kOctahedronCorners, kOctahedronNormals, kOctahedronFaces};

// Tetrahedron: r0 = (1, 0, 0), the others at x = -1/3; each face's normal is minus the corner
// off it.
constexpr float kThird = 0.333333333333f;
constexpr float kTetraY1 = 0.942809041582f;  // 2 sqrt(2) / 3
constexpr float kTetraY2 = 0.471404520791f;  // sqrt(2) / 3
constexpr float kTetraZ = 0.816496580928f;   // sqrt(6) / 3
constexpr float kTetrahedronCorners[4][3] = {{1, 0, 0},
                                             {-kThird, kTetraY1, 0},
                                             {-kThird, -kTetraY2, kTetraZ},
                                             {-kThird, -kTetraY2, -kTetraZ}};
constexpr float kTetrahedronNormals[4][3] = {
    {-1, 0, 0}, {kThird, -kTetraY1, 0}, {kThird, kTetraY2, -kTetraZ}, {kThird, kTetraY2, kTetraZ}};
constexpr int kTetrahedronFaces[4 * 3] = {1, 3, 2, 0, 2, 3, 0, 3, 1, 0, 1, 2};
constexpr Polyhedron kTetrahedron{4, 3, kTetrahedronCorners, kTetrahedronNormals,
                                  kTetrahedronFaces};

constexpr float kDodecahedronCorners[20][3] = {{0, kPhi, kPhiInv},
                                               {-1, 1, 1},
                                               {-kPhiInv, 0, kPhi},
                                               {kPhiInv, 0, kPhi},
                                               {1, 1, 1},
                                               {0, kPhi, -kPhiInv},
                                               {1, 1, -1},
                                               {kPhiInv, 0, -kPhi},
                                               {-kPhiInv, 0, -kPhi},
                                               {-1, 1, -1},
                                               {0, -kPhi, kPhiInv},
                                               {1, -1, 1},
                                               {-1, -1, 1},
                                               {0, -kPhi, -kPhiInv},
                                               {-1, -1, -1},
                                               {1, -1, -1},
                                               {kPhi, -kPhiInv, 0},
                                               {kPhi, kPhiInv, 0},
                                               {-kPhi, kPhiInv, 0},
                                               {-kPhi, -kPhiInv, 0}};
constexpr float kDodecahedronNormals[12][3] = {
    {0, kDodecaA, kDodecaB},   {0, kDodecaA, -kDodecaB},  {0, -kDodecaA, kDodecaB},
    {0, -kDodecaA, -kDodecaB}, {kDodecaB, 0, kDodecaA},   {-kDodecaB, 0, kDodecaA},
    {kDodecaB, 0, -kDodecaA},  {-kDodecaB, 0, -kDodecaA}, {kDodecaA, kDodecaB, 0},
    {kDodecaA, -kDodecaB, 0},  {-kDodecaA, kDodecaB, 0},  {-kDodecaA, -kDodecaB, 0}};
constexpr int kDodecahedronFaces[12 * 5] = {
    0,  1,  2,  3,  4, 5,  6,  7,  8,  9,  10, 11, 3,  2,  12, 13, 14, 8,  7,  15,
    3,  11, 16, 17, 4, 2,  1,  18, 19, 12, 7,  6,  17, 16, 15, 8,  14, 19, 18, 9,
    17, 6,  5,  0,  4, 16, 11, 10, 13, 15, 18, 1,  0,  5,  9,  19, 14, 13, 10, 12};
constexpr Polyhedron kDodecahedron{12, 5, kDodecahedronCorners, kDodecahedronNormals,
                                   kDodecahedronFaces};

// Icosahedron: two poles on x, two pentagons at x = +-1/sqrt(5). Face normals as freeglut
// tabulates them (the cross products of two edges, normalised).
constexpr float kIcoX = 0.447213595500f;  // 1 / sqrt(5)
constexpr float kIcoA = 0.894427191000f;  // 2 / sqrt(5)
constexpr float kIcoB = 0.276393202252f;
constexpr float kIcoC = 0.850650808354f;
constexpr float kIcoD = 0.723606797748f;
constexpr float kIcoE = 0.525731112119f;
constexpr float kIcosahedronCorners[12][3] = {{1, 0, 0},
                                              {kIcoX, kIcoA, 0},
                                              {kIcoX, kIcoB, kIcoC},
                                              {kIcoX, -kIcoD, kIcoE},
                                              {kIcoX, -kIcoD, -kIcoE},
                                              {kIcoX, kIcoB, -kIcoC},
                                              {-kIcoX, -kIcoA, 0},
                                              {-kIcoX, -kIcoB, kIcoC},
                                              {-kIcoX, kIcoD, kIcoE},
                                              {-kIcoX, kIcoD, -kIcoE},
                                              {-kIcoX, -kIcoB, -kIcoC},
                                              {-1, 0, 0}};
constexpr float kIcosahedronNormals[20][3] = {
    {0.760845213037948f, 0.470228201835026f, 0.341640786498800f},
    {0.760845213036861f, -0.179611190632978f, 0.552786404500000f},
    {0.760845213033849f, -0.581234022404097f, 0},
    {0.760845213036861f, -0.179611190632978f, -0.552786404500000f},
    {0.760845213037948f, 0.470228201835026f, -0.341640786498800f},
    {0.179611190628666f, 0.760845213037948f, 0.552786404498399f},
    {0.179611190634277f, -0.290617011204044f, 0.894427191000000f},
    {0.179611190633958f, -0.940456403667806f, 0},
    {0.179611190634278f, -0.290617011204044f, -0.894427191000000f},
    {0.179611190628666f, 0.760845213037948f, -0.552786404498399f},
    {-0.179611190633958f, 0.940456403667806f, 0},
    {-0.179611190634277f, 0.290617011204044f, 0.894427191000000f},
    {-0.179611190628666f, -0.760845213037948f, 0.552786404498399f},
    {-0.179611190628666f, -0.760845213037948f, -0.552786404498399f},
    {-0.179611190634277f, 0.290617011204044f, -0.894427191000000f},
    {-0.760845213036861f, 0.179611190632978f, -0.552786404500000f},
    {-0.760845213033849f, 0.581234022404097f, 0},
    {-0.760845213036861f, 0.179611190632978f, 0.552786404500000f},
    {-0.760845213037948f, -0.470228201835026f, 0.341640786498800f},
    {-0.760845213037948f, -0.470228201835026f, -0.341640786498800f}};
constexpr int kIcosahedronFaces[20 * 3] = {0,  1, 2,  0,  2, 3, 0,  3, 4, 0,  4,  5,  0,  5,  1,
                                           1,  8, 2,  2,  7, 3, 3,  6, 4, 4,  10, 5,  5,  9,  1,
                                           1,  9, 8,  2,  8, 7, 3,  7, 6, 4,  6,  10, 5,  10, 9,
                                           11, 9, 10, 11, 8, 9, 11, 7, 8, 11, 6,  7,  11, 10, 6};
constexpr Polyhedron kIcosahedron{20, 3, kIcosahedronCorners, kIcosahedronNormals,
                                  kIcosahedronFaces};

// ---- round shapes ----
// sin and cos of n + 1 angles stepping by 2 pi / n (pi / n for a half circle) from 0; a
// negative n turns the other way. The last entry closes the circle exactly: (0, 1) again, or
// (0, -1) for the half circle. The angle is single precision, its sine and cosine double,
// rounded.
struct Circle {
  std::vector<float> sin, cos;
};
Circle circle(int n, bool half) {
  const int size = std::abs(n);
  const float step = float(half ? 1 : 2) * kPiF / float(n == 0 ? 1 : n);
  Circle c;
  c.sin.assign(size_t(size) + 1, 0.0f);
  c.cos.assign(size_t(size) + 1, 0.0f);
  c.cos[0] = 1.0f;
  for (int i = 1; i < size; ++i) {
    const float angle = step * float(i);
    c.sin[size_t(i)] = float(std::sin(double(angle)));
    c.cos[size_t(i)] = float(std::cos(double(angle)));
  }
  c.sin[size_t(size)] = half ? 0.0f : c.sin[0];
  c.cos[size_t(size)] = half ? -1.0f : c.cos[0];
  return c;
}

// Sphere around z: the top pole, `stacks` - 1 rings of `slices` vertices (clockwise seen from
// +z) from the top down, the bottom pole. Solid: one triangle strip a stack; wire: a line
// strip a slice pole to pole, then a line loop a ring.
void sphere(float radius, int slices, int stacks, bool wire) {
  if (slices <= 0 || stacks < 2) return;  // freeglut draws nothing (slices 0, stacks < 2)
  const int vertexCount = slices * (stacks - 1) + 2;
  const Circle around = circle(-slices, false), down = circle(stacks, true);
  Arrays a;
  push(a.vertices, 0.0f, 0.0f, radius);
  push(a.normals, 0.0f, 0.0f, 1.0f);
  for (int i = 1; i < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      const float x = around.cos[size_t(j)] * down.sin[size_t(i)];
      const float y = around.sin[size_t(j)] * down.sin[size_t(i)];
      const float z = down.cos[size_t(i)];
      push(a.vertices, x * radius, y * radius, z * radius);
      push(a.normals, x, y, z);
    }
  push(a.vertices, 0.0f, 0.0f, -radius);
  push(a.normals, 0.0f, 0.0f, -1.0f);
  const Index bottom = Index(vertexCount - 1);
  if (wire) {
    std::vector<Index> slicesIdx, rings;
    for (int i = 0; i < stacks - 1; ++i)
      for (int j = 0; j < slices; ++j) rings.push_back(Index(1 + i * slices + j));
    for (int i = 0; i < slices; ++i) {
      slicesIdx.push_back(0);
      for (int j = 0; j < stacks - 1; ++j) slicesIdx.push_back(Index(1 + i + j * slices));
      slicesIdx.push_back(bottom);
    }
    drawWire(a, slicesIdx.data(), slices, stacks + 1, GL_LINE_STRIP, rings.data(), stacks - 1,
             slices);
    return;
  }
  std::vector<Index> strips;
  auto pair = [&](int first, int second) {
    strips.push_back(Index(first));
    strips.push_back(Index(second));
  };
  for (int j = 0; j < slices; ++j) pair(j + 1, 0);  // the top cap
  pair(1, 0);
  for (int i = 0; i < stacks - 2; ++i) {
    const int ring = 1 + i * slices;
    for (int j = 0; j < slices; ++j) pair(ring + j + slices, ring + j);
    pair(ring + slices, ring);
  }
  const int last = 1 + (stacks - 2) * slices;  // the bottom cap
  for (int j = 0; j < slices; ++j) pair(bottom, last + j);
  pair(bottom, last);
  drawSolid(a, nullptr, strips.data(), stacks, (slices + 1) * 2);
}

// Cone along +z, base at z = 0: the base's centre, the base ring again with the base's
// normal, then `stacks` + 1 rings from the base up (the last of radius ~0 at the apex).
// Solid: the base and each stack a triangle strip; wire: one GL_LINES draw of the slices,
// then a line loop a ring (the apex's excluded).
void cone(float base, float height, int slices, int stacks, bool wire) {
  if (slices <= 0 || stacks < 1) return;  // freeglut draws nothing (slices 0, stacks < 1)
  const float zStep = height / float(stacks), rStep = base / float(stacks);
  const double side = std::sqrt(double(height * height + base * base));
  const float cosn = float(double(height) / side), sinn = float(double(base) / side);
  const Circle around = circle(-slices, false);
  Arrays a;
  float z = 0.0f, r = base;
  push(a.vertices, 0.0f, 0.0f, z);
  push(a.normals, 0.0f, 0.0f, -1.0f);
  for (int j = 0; j < slices; ++j) {
    push(a.vertices, around.cos[size_t(j)] * r, around.sin[size_t(j)] * r, z);
    push(a.normals, 0.0f, 0.0f, -1.0f);
  }
  for (int i = 0; i < stacks + 1; ++i) {
    for (int j = 0; j < slices; ++j) {
      push(a.vertices, around.cos[size_t(j)] * r, around.sin[size_t(j)] * r, z);
      push(a.normals, around.cos[size_t(j)] * cosn, around.sin[size_t(j)] * cosn, sinn);
    }
    z += zStep;
    r -= rStep;
  }
  if (wire) {
    std::vector<Index> lines, rings;
    for (int i = 0; i < stacks; ++i)
      for (int j = 0; j < slices; ++j) rings.push_back(Index(1 + (i + 1) * slices + j));
    for (int i = 0; i < slices; ++i) {
      lines.push_back(Index(1 + i + slices));
      lines.push_back(Index(1 + i + (stacks + 1) * slices));
    }
    drawWire(a, lines.data(), 1, slices * 2, GL_LINES, rings.data(), stacks, slices);
    return;
  }
  std::vector<Index> strips;
  auto pair = [&](int first, int second) {
    strips.push_back(Index(first));
    strips.push_back(Index(second));
  };
  for (int j = 0; j < slices; ++j) pair(0, j + 1);  // the base
  pair(0, 1);
  for (int i = 0; i < stacks; ++i) {
    const int ring = 1 + (i + 1) * slices;
    for (int j = 0; j < slices; ++j) pair(ring + j, ring + j + slices);
    pair(ring, ring + slices);
  }
  drawSolid(a, nullptr, strips.data(), stacks + 1, (slices + 1) * 2);
}

// Torus around z: `rings` rings (counter-clockwise around z) of `sides` vertices each (the
// tube's cross-section). Solid: one triangle strip a side, around the whole torus; wire: a
// line loop a ring, then a line loop a side.
void torus(float inner, float outer, int sides, int rings, bool wire) {
  if (sides < 2 || rings < 2) return;  // freeglut draws nothing
  const Circle ring = circle(rings, false), tube = circle(-sides, false);
  Arrays a;
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < sides; ++i) {
      const float cj = ring.cos[size_t(j)], sj = ring.sin[size_t(j)];
      const float ci = tube.cos[size_t(i)], si = tube.sin[size_t(i)];
      push(a.vertices, cj * (outer + ci * inner), sj * (outer + ci * inner), si * inner);
      push(a.normals, cj * ci, sj * ci, si);
    }
  if (wire) {
    std::vector<Index> ringLoops, sideLoops;
    for (int j = 0; j < rings; ++j)
      for (int i = 0; i < sides; ++i) ringLoops.push_back(Index(j * sides + i));
    for (int i = 0; i < sides; ++i)
      for (int j = 0; j < rings; ++j) sideLoops.push_back(Index(j * sides + i));
    drawWire(a, ringLoops.data(), rings, sides, GL_LINE_LOOP, sideLoops.data(), sides, rings);
    return;
  }
  std::vector<Index> strips;
  for (int i = 0; i < sides; ++i) {
    const int next = i == sides - 1 ? -i : 1;  // the last side pairs with the first
    for (int j = 0; j < rings; ++j) {
      strips.push_back(Index(j * sides + i));
      strips.push_back(Index(j * sides + i + next));
    }
    strips.push_back(Index(i));
    strips.push_back(Index(i + next));
  }
  drawSolid(a, nullptr, strips.data(), sides, (rings + 1) * 2);
}

// ---- the teapot: 32 bicubic Bezier patches from 10 ----
constexpr int kTeapotInputPatches = 10;
constexpr int kTeapotRotatedPatches = 6;  // rim, body, lid, bottom: turned into 4 quadrants
constexpr int kTeapotPatches = kTeapotRotatedPatches * 4 + (kTeapotInputPatches - 6) * 2;
constexpr int kTeapotLidTopPatch = 3;     // its first row of normals degenerates: +y
constexpr int kTeapotBottomPatch = 5;     // likewise: -y
constexpr float kTeapotZOffset = 1.575f;  // centres the teapot on the z axis (freeglut)
constexpr int kSolidSubdivisions = 8;     // vertices along each side of a patch, solid
constexpr int kWireSubdivisions = 10;     // wire

// Patches as 4 x 4 indices into kTeapotControlPoints. The first six are mirrored into the
// other three quadrants (rotated about the teapot's up axis), the handle's and the spout's
// (the last four) across the teapot's symmetry plane.
constexpr int kTeapotPatchCorners[kTeapotInputPatches][16] = {
    {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15},                            // rim
    {12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27},                  // body
    {24, 25, 26, 27, 28, 29, 30, 31, 32, 33, 34, 35, 36, 37, 38, 39},                  // body
    {40, 41, 42, 40, 43, 44, 45, 46, 47, 47, 47, 47, 48, 49, 50, 51},                  // lid
    {48, 49, 50, 51, 52, 53, 54, 55, 56, 57, 58, 59, 60, 61, 62, 63},                  // lid
    {64, 64, 64, 64, 65, 66, 67, 68, 69, 70, 71, 72, 39, 38, 37, 36},                  // bottom
    {73, 74, 75, 76, 77, 78, 79, 80, 81, 82, 83, 84, 85, 86, 87, 88},                  // handle
    {85, 86, 87, 88, 89, 90, 91, 92, 93, 94, 95, 96, 97, 98, 99, 100},                 // handle
    {101, 102, 103, 104, 105, 106, 107, 108, 109, 110, 111, 112, 113, 114, 115, 116},  // spout
    {113, 114, 115, 116, 117, 118, 119, 120, 121, 122, 123, 124, 125, 126, 127, 128},  // spout
};
// x, y, z with z up, in the data set's units. From freeglut 3.4.0's src/fg_teapot_data.h,
// which carries this notice:
//   Permission is hereby granted, free of charge, to any person obtaining a copy of this
//   software and associated documentation files (the "Software"), to deal in the Software
//   without restriction, including without limitation the rights to use, copy, modify, merge,
//   publish, distribute, sublicense, and/or sell copies of the Software, and to permit persons
//   to whom the Software is furnished to do so, subject to the following conditions: The above
//   copyright notice and this permission notice shall be included in all copies or substantial
//   portions of the Software. THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND,
//   EXPRESS OR IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY, FITNESS
//   FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL PAWEL W. OLSZTA BE LIABLE
//   FOR ANY CLAIM, DAMAGES OR OTHER LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR
//   OTHERWISE, ARISING FROM, OUT OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER
//   DEALINGS IN THE SOFTWARE.
constexpr float kTeapotControlPoints[][3] = {
    {1.4f, 0.0f, 2.4f},           {1.4f, -0.784f, 2.4f},        {0.784f, -1.4f, 2.4f},
    {0.0f, -1.4f, 2.4f},          {1.3375f, 0.0f, 2.53125f},    {1.3375f, -0.749f, 2.53125f},
    {0.749f, -1.3375f, 2.53125f}, {0.0f, -1.3375f, 2.53125f},   {1.4375f, 0.0f, 2.53125f},
    {1.4375f, -0.805f, 2.53125f}, {0.805f, -1.4375f, 2.53125f}, {0.0f, -1.4375f, 2.53125f},
    {1.5f, 0.0f, 2.4f},           {1.5f, -0.84f, 2.4f},         {0.84f, -1.5f, 2.4f},
    {0.0f, -1.5f, 2.4f},          {1.75f, 0.0f, 1.875f},        {1.75f, -0.98f, 1.875f},
    {0.98f, -1.75f, 1.875f},      {0.0f, -1.75f, 1.875f},       {2.0f, 0.0f, 1.35f},
    {2.0f, -1.12f, 1.35f},        {1.12f, -2.0f, 1.35f},        {0.0f, -2.0f, 1.35f},
    {2.0f, 0.0f, 0.9f},           {2.0f, -1.12f, 0.9f},         {1.12f, -2.0f, 0.9f},
    {0.0f, -2.0f, 0.9f},          {2.0f, 0.0f, 0.45f},          {2.0f, -1.12f, 0.45f},
    {1.12f, -2.0f, 0.45f},        {0.0f, -2.0f, 0.45f},         {1.5f, 0.0f, 0.225f},
    {1.5f, -0.84f, 0.225f},       {0.84f, -1.5f, 0.225f},       {0.0f, -1.5f, 0.225f},
    {1.5f, 0.0f, 0.15f},          {1.5f, -0.84f, 0.15f},        {0.84f, -1.5f, 0.15f},
    {0.0f, -1.5f, 0.15f},         {0.0f, 0.0f, 3.15f},          {0.0f, -0.002f, 3.15f},
    {0.002f, 0.0f, 3.15f},        {0.8f, 0.0f, 3.15f},          {0.8f, -0.45f, 3.15f},
    {0.45f, -0.8f, 3.15f},        {0.0f, -0.8f, 3.15f},         {0.0f, 0.0f, 2.85f},
    {0.2f, 0.0f, 2.7f},           {0.2f, -0.112f, 2.7f},        {0.112f, -0.2f, 2.7f},
    {0.0f, -0.2f, 2.7f},          {0.4f, 0.0f, 2.55f},          {0.4f, -0.224f, 2.55f},
    {0.224f, -0.4f, 2.55f},       {0.0f, -0.4f, 2.55f},         {1.3f, 0.0f, 2.55f},
    {1.3f, -0.728f, 2.55f},       {0.728f, -1.3f, 2.55f},       {0.0f, -1.3f, 2.55f},
    {1.3f, 0.0f, 2.4f},           {1.3f, -0.728f, 2.4f},        {0.728f, -1.3f, 2.4f},
    {0.0f, -1.3f, 2.4f},          {0.0f, 0.0f, 0.0f},           {0.0f, -1.425f, 0.0f},
    {0.798f, -1.425f, 0.0f},      {1.425f, -0.798f, 0.0f},      {1.425f, 0.0f, 0.0f},
    {0.0f, -1.5f, 0.075f},        {0.84f, -1.5f, 0.075f},       {1.5f, -0.84f, 0.075f},
    {1.5f, 0.0f, 0.075f},         {-1.6f, 0.0f, 2.025f},        {-1.6f, -0.3f, 2.025f},
    {-1.5f, -0.3f, 2.25f},        {-1.5f, 0.0f, 2.25f},         {-2.3f, 0.0f, 2.025f},
    {-2.3f, -0.3f, 2.025f},       {-2.5f, -0.3f, 2.25f},        {-2.5f, 0.0f, 2.25f},
    {-2.7f, 0.0f, 2.025f},        {-2.7f, -0.3f, 2.025f},       {-3.0f, -0.3f, 2.25f},
    {-3.0f, 0.0f, 2.25f},         {-2.7f, 0.0f, 1.8f},          {-2.7f, -0.3f, 1.8f},
    {-3.0f, -0.3f, 1.8f},         {-3.0f, 0.0f, 1.8f},          {-2.7f, 0.0f, 1.575f},
    {-2.7f, -0.3f, 1.575f},       {-3.0f, -0.3f, 1.35f},        {-3.0f, 0.0f, 1.35f},
    {-2.5f, 0.0f, 1.125f},        {-2.5f, -0.3f, 1.125f},       {-2.65f, -0.3f, 0.9375f},
    {-2.65f, 0.0f, 0.9375f},      {-2.0f, 0.0f, 0.9f},          {-2.0f, -0.3f, 0.9f},
    {-1.9f, -0.3f, 0.6f},         {-1.9f, 0.0f, 0.6f},          {1.7f, 0.0f, 1.425f},
    {1.7f, -0.66f, 1.425f},       {1.7f, -0.66f, 0.6f},         {1.7f, 0.0f, 0.6f},
    {2.6f, 0.0f, 1.425f},         {2.6f, -0.66f, 1.425f},       {3.1f, -0.66f, 0.825f},
    {3.1f, 0.0f, 0.825f},         {2.3f, 0.0f, 2.1f},           {2.3f, -0.25f, 2.1f},
    {2.4f, -0.25f, 2.025f},       {2.4f, 0.0f, 2.025f},         {2.7f, 0.0f, 2.4f},
    {2.7f, -0.25f, 2.4f},         {3.3f, -0.25f, 2.4f},         {3.3f, 0.0f, 2.4f},
    {2.8f, 0.0f, 2.475f},         {2.8f, -0.25f, 2.475f},       {3.525f, -0.25f, 2.49375f},
    {3.525f, 0.0f, 2.49375f},     {2.9f, 0.0f, 2.475f},         {2.9f, -0.15f, 2.475f},
    {3.45f, -0.15f, 2.5125f},     {3.45f, 0.0f, 2.5125f},       {2.8f, 0.0f, 2.4f},
    {2.8f, -0.15f, 2.4f},         {3.2f, -0.15f, 2.4f},         {3.2f, 0.0f, 2.4f},
};

// The cubic Bernstein polynomials and their derivatives at `n` evenly spaced parameters.
struct Bernstein {
  std::vector<float> value, slope;  // 4 a parameter
};
Bernstein bernstein(int n) {
  Bernstein b;
  for (int s = 0; s < n; ++s) {
    const float x = float(s) / (float(n) - 1.0f), inv = 1.0f - x;
    const float inv2 = inv * inv, x2 = x * x;
    const float value[4] = {inv * inv2, 3.0f * x * inv2, 3.0f * x2 * inv, x * x2};
    const float slope[4] = {-3.0f * inv2, 3.0f * inv2 - 6.0f * x * inv, 6.0f * x * inv - 3.0f * x2,
                            3.0f * x2};
    b.value.insert(b.value.end(), value, value + 4);
    b.slope.insert(b.slope.end(), slope, slope + 4);
  }
  return b;
}

// Copies of the patch just evaluated (`count` floats at out[0]): `copies` 4, the three other
// quadrants (x, y, z) -> (z, y, -x), (-x, y, -z), (-z, y, x); `copies` 2, the mirror image
// (z negated) with its rows in reverse order, so that it keeps its winding.
void replicate(int copies, int count, int n, float* out) {
  if (copies == 4) {
    for (int o = 0; o < count; o += 3) {
      const float x = out[o], y = out[o + 1], z = out[o + 2];
      float* q = out + count + o;
      q[0] = z, q[1] = y, q[2] = -x;
      q += count;
      q[0] = -x, q[1] = y, q[2] = -z;
      q += count;
      q[0] = -z, q[1] = y, q[2] = x;
    }
  } else if (copies == 2) {
    for (int u = 0; u < n; ++u) {
      const float* from = out + (n - u - 1) * n * 3;
      float* to = out + count + u * n * 3;
      for (int i = 0; i < n * 3; i += 3) {
        to[i] = from[i];
        to[i + 1] = from[i + 1];
        to[i + 2] = -from[i + 2];
      }
    }
  }
}

struct TeapotCache {
  bool made = false;
  float scale = 0.0f;
  std::vector<float> texcoords;  // solid only
  std::vector<Index> indices;
  Arrays arrays;
};

// Evaluates one patch (control points `cp`, already scaled and turned upright) on an n x n
// grid into vertices at v (and, `withNormals`, unit normals at nrm), then its copies.
// Returns the floats written. The normal is the cross product of the two tangents.
int evaluatePatch(const float (&cp)[4][4][3], const Bernstein& b, int n, int copies, int normalFix,
                  bool withNormals, float* v, float* nrm) {
  const int count = n * n * 3;
  for (int u = 0, o = 0; u < n; ++u)
    for (int w = 0; w < n; ++w, o += 3) {
      float tu[3] = {0, 0, 0}, tw[3] = {0, 0, 0};
      for (int i = 0; i <= 3; ++i) {
        float along[3] = {0, 0, 0}, alongSlope[3] = {0, 0, 0};
        for (int j = 0; j <= 3; ++j)
          for (int k = 0; k < 3; ++k) {
            along[k] += b.value[size_t(w * 4 + j)] * cp[i][j][k];
            alongSlope[k] += b.slope[size_t(w * 4 + j)] * cp[i][j][k];
          }
        const float bu = b.value[size_t(u * 4 + i)], su = b.slope[size_t(u * 4 + i)];
        for (int k = 0; k < 3; ++k) {
          v[o + k] += bu * along[k];
          tu[k] += bu * alongSlope[k];
          tw[k] += su * along[k];
        }
      }
      if (!withNormals) continue;
      float* m = nrm + o;
      m[0] = tu[1] * tw[2] - tu[2] * tw[1];
      m[1] = tu[2] * tw[0] - tu[0] * tw[2];
      m[2] = tu[0] * tw[1] - tu[1] * tw[0];
      const float length = float(std::sqrt(double(m[0] * m[0] + m[1] * m[1] + m[2] * m[2])));
      m[0] /= length;
      m[1] /= length;
      m[2] /= length;
    }
  if (withNormals && normalFix != 0)
    for (int o = 0; o < n * 3; o += 3) {
      nrm[o] = 0.0f;
      nrm[o + 1] = normalFix == 1 ? 1.0f : -1.0f;
      nrm[o + 2] = 0.0f;
    }
  replicate(copies, count, n, v);
  if (withNormals) replicate(copies, count, n, nrm);
  return count * copies;
}

// As freeglut: the normals, indices and texture coordinates are made on the first call, the
// vertices again whenever the size changes (the normals of the first size are kept).
void teapot(float scale, bool wire) {
  static TeapotCache caches[2];
  TeapotCache& c = caches[wire ? 1 : 0];
  const int n = wire ? kWireSubdivisions : kSolidSubdivisions;
  const int vertexCount = n * n * kTeapotPatches;
  static const Bernstein solidBasis = bernstein(kSolidSubdivisions);
  static const Bernstein wireBasis = bernstein(kWireSubdivisions);
  const Bernstein& b = wire ? wireBasis : solidBasis;
  if (!c.made || scale != c.scale) {
    const bool withNormals = !c.made;
    c.arrays.vertices.assign(size_t(vertexCount) * 3, 0.0f);
    if (withNormals) c.arrays.normals.assign(size_t(vertexCount) * 3, 0.0f);
    for (int p = 0, o = 0; p < kTeapotInputPatches; ++p) {
      float cp[4][4][3];
      for (int i = 0; i < 16; ++i) {
        const float* q = kTeapotControlPoints[kTeapotPatchCorners[p][i]];
        // Stood upright (z up becomes y up), centred on the origin, half size times `scale`.
        cp[i / 4][i % 4][0] = q[0] * scale / 2.0f;
        cp[i / 4][i % 4][1] = (q[2] - kTeapotZOffset) * scale / 2.0f;
        cp[i / 4][i % 4][2] = -q[1] * scale / 2.0f;
      }
      const int copies = p < kTeapotRotatedPatches ? 4 : 2;
      const int fix = p == kTeapotLidTopPatch ? 1 : p == kTeapotBottomPatch ? 2 : 0;
      o += evaluatePatch(cp, b, n, copies, fix, withNormals, c.arrays.vertices.data() + o,
                         c.arrays.normals.data() + o);
    }
    c.scale = scale;
  }
  if (!c.made) {
    if (!wire) {
      for (int p = 0; p < kTeapotPatches; ++p)
        for (int r = 0; r < n; ++r)
          for (int col = 0; col < n; ++col) {
            c.texcoords.push_back(float(r) / (float(n) - 1.0f));
            c.texcoords.push_back(float(col) / (float(n) - 1.0f));
          }
      for (int p = 0; p < kTeapotPatches; ++p)
        for (int r = 0; r < n - 1; ++r)
          for (int col = 0; col < n - 1; ++col) {
            const int row1 = n * n * p + r * n + col, row2 = row1 + n;
            for (int k : {row1, row2, row2 + 1, row1, row2 + 1, row1 + 1})
              c.indices.push_back(Index(k));
          }
    } else {
      for (int p = 0; p < kTeapotPatches; ++p)  // line strips along u, then along v
        for (int col = 0; col < n; ++col)
          for (int r = 0; r < n; ++r) c.indices.push_back(Index(n * n * p + r * n + col));
      for (int p = 0; p < kTeapotPatches; ++p)
        for (int r = 0; r < n; ++r)
          for (int col = 0; col < n; ++col) c.indices.push_back(Index(n * n * p + r * n + col));
    }
    c.made = true;
  }
  if (wire)
    drawWire(c.arrays, c.indices.data(), kTeapotPatches * n * 2, n, GL_LINE_STRIP);
  else
    drawSolid(c.arrays, &c.texcoords, c.indices.data(), 1, int(c.indices.size()));
}

}  // namespace
}  // namespace sl::interpose

// ---- the exports: sizes reach the tessellation in single precision, as freeglut's do ----
namespace sh = sl::interpose;
SL_EXPORT void glutSolidSphere(double r, GLint slices, GLint stacks) {
  sh::sphere(float(r), slices, stacks, false);
}
SL_EXPORT void glutWireSphere(double r, GLint slices, GLint stacks) {
  sh::sphere(float(r), slices, stacks, true);
}
SL_EXPORT void glutSolidCone(double base, double height, GLint slices, GLint stacks) {
  sh::cone(float(base), float(height), slices, stacks, false);
}
SL_EXPORT void glutWireCone(double base, double height, GLint slices, GLint stacks) {
  sh::cone(float(base), float(height), slices, stacks, true);
}
SL_EXPORT void glutSolidTorus(double inner, double outer, GLint sides, GLint rings) {
  sh::torus(float(inner), float(outer), sides, rings, false);
}
SL_EXPORT void glutWireTorus(double inner, double outer, GLint sides, GLint rings) {
  sh::torus(float(inner), float(outer), sides, rings, true);
}
SL_EXPORT void glutSolidCube(double side) { sh::drawPolyhedron(sh::kCube, float(side), false); }
SL_EXPORT void glutWireCube(double side) { sh::drawPolyhedron(sh::kCube, float(side), true); }
SL_EXPORT void glutSolidTeapot(double size) { sh::teapot(float(size), false); }
SL_EXPORT void glutWireTeapot(double size) { sh::teapot(float(size), true); }
SL_EXPORT void glutSolidDodecahedron() { sh::drawPolyhedron(sh::kDodecahedron, 1.0f, false); }
SL_EXPORT void glutWireDodecahedron() { sh::drawPolyhedron(sh::kDodecahedron, 1.0f, true); }
SL_EXPORT void glutSolidOctahedron() { sh::drawPolyhedron(sh::kOctahedron, 1.0f, false); }
SL_EXPORT void glutWireOctahedron() { sh::drawPolyhedron(sh::kOctahedron, 1.0f, true); }
SL_EXPORT void glutSolidTetrahedron() { sh::drawPolyhedron(sh::kTetrahedron, 1.0f, false); }
SL_EXPORT void glutWireTetrahedron() { sh::drawPolyhedron(sh::kTetrahedron, 1.0f, true); }
SL_EXPORT void glutSolidIcosahedron() { sh::drawPolyhedron(sh::kIcosahedron, 1.0f, false); }
SL_EXPORT void glutWireIcosahedron() { sh::drawPolyhedron(sh::kIcosahedron, 1.0f, true); }
