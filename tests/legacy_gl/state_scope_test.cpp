// Every legacy technique leaves the GL context as it found it (legacy_gl/fixed_function.h
// ScopedLegacyState), and its images do not depend on what rendered before it in the context:
// the lab and the benchmarks render technique after technique in one context, so one missed
// reset would leak into the next technique.
//
// Which orders. All n! orders of the n techniques are not needed:
//   - The state check (readState, below, read after every render and compared with the fresh
//     context's) catches every leak of the state it reads, whatever comes next: for that state
//     one render after each technique suffices, and each technique renders many times.
//   - A leak of state the check does not read (the contents of a table or a texture, the
//     accumulation buffer, an emulation cache) shows only in the image of a technique that
//     reads it. Every ordered pair (a, b), a == b included, follows once in one context (an
//     Eulerian circuit of the complete directed graph with loops: n * n + 1 renders), so every
//     technique renders right after every technique, itself included (the benchmark's case).
//   - A leak that only a technique two or more renders later would see (a pass that leaves
//     something, the next technique does not touch it, a third reads it) is sampled by three
//     full permutations from a fixed seed, rendered on in the same context.
// Each image (colour, visibility mask and every --dump-passes buffer) must equal, bit for bit,
// the image the technique renders alone in a fresh context of its own.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/gl/context.h"
#include "core/gl/gl.h"
#include "core/scene/scene_library.h"
#include "legacy_test_support.h"
#include "registry/registry.h"

namespace sl {
namespace {
using namespace sl::gl;

// Small on purpose (two CI cores): the light pass (64^2) does not fit in the 64x48 window, so
// the off-screen light target (a framebuffer binding) is in every Brabec–Seidel frame too.
constexpr int kWidth = 64;
constexpr int kHeight = 48;
constexpr int kMapTexels = 64;
constexpr unsigned kPermutationSeed = 40;  // issue 40
constexpr int kPermutations = 3;

// One technique with the settings that run most of its passes.
struct Job {
  std::string technique;
  int filter;  // legacy.pcf 3x3: groups, accumulation, the saved camera pass; fast PCF 4x4: phases
};
const std::vector<Job>& jobs() {
  static const std::vector<Job> list = {{"legacy.hw", 1},           {"legacy.woo", 1},
                                        {"legacy.second-depth", 1}, {"legacy.ramp", 1},
                                        {"legacy.pcf", 3},          {"legacy.fast-pcf", 4}};
  return list;
}

RenderParams paramsFor(const Job& job, Backend backend) {
  RenderParams p;
  p.width = kWidth;
  p.height = kHeight;
  p.shadowMapTexels = kMapTexels;
  p.filter = job.filter;
  p.backend = backend;
  p.capturePasses = true;  // the dump's readbacks (colour table reads, texture reads) as well
  return p;
}

// ------------------------------------------------------------------ the state read back

// One named state value: the numbers GL returns for it.
using StateValues = std::vector<std::pair<std::string, std::vector<double>>>;

void addFloats(StateValues& out, const std::string& name, GLenum query, int count) {
  std::vector<float> v(16, 0.0f);
  glGetFloatv(query, v.data());
  out.emplace_back(name, std::vector<double>(v.begin(), v.begin() + count));
}

void addEnable(StateValues& out, const std::string& name, GLenum cap) {
  out.emplace_back(name, std::vector<double>{glIsEnabled(cap) ? 1.0 : 0.0});
}

#define SL_FLOATS(list, query, count) addFloats(list, #query, query, count)
#define SL_ENABLE(list, cap) addEnable(list, #cap, cap)
#define SL_NAMED(e) std::pair<std::string, GLenum>(#e, e)

// The state of glspec121's tables 6.5-6.21 that a fixed-function pass can set, per texture
// unit where it is per unit, plus the framebuffer binding and the matrix stacks' depths (an
// unbalanced push shows there). Left out: the lights' and materials' own parameters (no
// glGetLight/glGetMaterial in core/gl's dispatch; every lighting pass sets all of them before
// it draws, and the image check would show one that did not), and the contents of objects and
// tables (textures, colour tables, convolution filters: ScopedLegacyState does not restore
// them, every pass loads them before use; the image check covers them).
StateValues readState(bool imaging) {
  StateValues s;
  for (const auto& [name, cap] : {SL_NAMED(GL_ALPHA_TEST),
                                  SL_NAMED(GL_AUTO_NORMAL),
                                  SL_NAMED(GL_BLEND),
                                  SL_NAMED(GL_COLOR_LOGIC_OP),
                                  SL_NAMED(GL_COLOR_MATERIAL),
                                  SL_NAMED(GL_CULL_FACE),
                                  SL_NAMED(GL_DEPTH_TEST),
                                  SL_NAMED(GL_DITHER),
                                  SL_NAMED(GL_FOG),
                                  SL_NAMED(GL_LIGHTING),
                                  SL_NAMED(GL_LINE_SMOOTH),
                                  SL_NAMED(GL_LINE_STIPPLE),
                                  SL_NAMED(GL_NORMALIZE),
                                  SL_NAMED(GL_POINT_SMOOTH),
                                  SL_NAMED(GL_POLYGON_OFFSET_FILL),
                                  SL_NAMED(GL_POLYGON_OFFSET_LINE),
                                  SL_NAMED(GL_POLYGON_OFFSET_POINT),
                                  SL_NAMED(GL_POLYGON_SMOOTH),
                                  SL_NAMED(GL_POLYGON_STIPPLE),
                                  SL_NAMED(GL_RESCALE_NORMAL),
                                  SL_NAMED(GL_SCISSOR_TEST),
                                  SL_NAMED(GL_STENCIL_TEST),
                                  SL_NAMED(GL_VERTEX_ARRAY),
                                  SL_NAMED(GL_NORMAL_ARRAY),
                                  SL_NAMED(GL_COLOR_ARRAY),
                                  SL_NAMED(GL_INDEX_ARRAY),
                                  SL_NAMED(GL_EDGE_FLAG_ARRAY)})
    addEnable(s, name, cap);
  for (int i = 0; i < 8; ++i) addEnable(s, "GL_LIGHT" + std::to_string(i), GLenum(GL_LIGHT0 + i));
  for (int i = 0; i < 6; ++i)
    addEnable(s, "GL_CLIP_PLANE" + std::to_string(i), GLenum(GL_CLIP_PLANE0 + i));
  if (imaging) {
    SL_ENABLE(s, GL_COLOR_TABLE);
    SL_ENABLE(s, GL_POST_CONVOLUTION_COLOR_TABLE);
    SL_ENABLE(s, GL_POST_COLOR_MATRIX_COLOR_TABLE);
    SL_ENABLE(s, GL_CONVOLUTION_1D);
    SL_ENABLE(s, GL_CONVOLUTION_2D);
    SL_ENABLE(s, GL_SEPARABLE_2D);
    SL_ENABLE(s, GL_HISTOGRAM);
    SL_ENABLE(s, GL_MINMAX);
    SL_FLOATS(s, GL_COLOR_MATRIX, 16);
    SL_FLOATS(s, GL_COLOR_MATRIX_STACK_DEPTH, 1);
    for (const auto& [name, q] :
         {SL_NAMED(GL_POST_CONVOLUTION_RED_SCALE), SL_NAMED(GL_POST_CONVOLUTION_GREEN_SCALE),
          SL_NAMED(GL_POST_CONVOLUTION_BLUE_SCALE), SL_NAMED(GL_POST_CONVOLUTION_ALPHA_SCALE),
          SL_NAMED(GL_POST_CONVOLUTION_RED_BIAS), SL_NAMED(GL_POST_CONVOLUTION_GREEN_BIAS),
          SL_NAMED(GL_POST_CONVOLUTION_BLUE_BIAS), SL_NAMED(GL_POST_CONVOLUTION_ALPHA_BIAS),
          SL_NAMED(GL_POST_COLOR_MATRIX_RED_SCALE), SL_NAMED(GL_POST_COLOR_MATRIX_GREEN_SCALE),
          SL_NAMED(GL_POST_COLOR_MATRIX_BLUE_SCALE), SL_NAMED(GL_POST_COLOR_MATRIX_ALPHA_SCALE),
          SL_NAMED(GL_POST_COLOR_MATRIX_RED_BIAS), SL_NAMED(GL_POST_COLOR_MATRIX_GREEN_BIAS),
          SL_NAMED(GL_POST_COLOR_MATRIX_BLUE_BIAS), SL_NAMED(GL_POST_COLOR_MATRIX_ALPHA_BIAS)})
      addFloats(s, name, q, 1);
    for (const auto& [target, t] :
         {SL_NAMED(GL_CONVOLUTION_1D), SL_NAMED(GL_CONVOLUTION_2D), SL_NAMED(GL_SEPARABLE_2D)}) {
      GLint mode = 0;
      glGetConvolutionParameteriv(t, GL_CONVOLUTION_BORDER_MODE, &mode);
      s.emplace_back(target + " GL_CONVOLUTION_BORDER_MODE", std::vector<double>{double(mode)});
      for (const auto& [name, p] :
           {SL_NAMED(GL_CONVOLUTION_BORDER_COLOR), SL_NAMED(GL_CONVOLUTION_FILTER_SCALE),
            SL_NAMED(GL_CONVOLUTION_FILTER_BIAS)}) {
        float v[4] = {0, 0, 0, 0};
        glGetConvolutionParameterfv(t, p, v);
        s.emplace_back(target + " " + name, std::vector<double>(v, v + 4));
      }
    }
    for (const auto& [target, t] :
         {SL_NAMED(GL_COLOR_TABLE), SL_NAMED(GL_POST_CONVOLUTION_COLOR_TABLE),
          SL_NAMED(GL_POST_COLOR_MATRIX_COLOR_TABLE)})
      for (const auto& [name, p] :
           {SL_NAMED(GL_COLOR_TABLE_SCALE), SL_NAMED(GL_COLOR_TABLE_BIAS)}) {
        float v[4] = {0, 0, 0, 0};
        glGetColorTableParameterfv(t, p, v);
        s.emplace_back(target + " " + name, std::vector<double>(v, v + 4));
      }
  }
  SL_FLOATS(s, GL_MATRIX_MODE, 1);
  SL_FLOATS(s, GL_ACTIVE_TEXTURE, 1);
  SL_FLOATS(s, GL_CLIENT_ACTIVE_TEXTURE, 1);
  SL_FLOATS(s, GL_PROJECTION_MATRIX, 16);
  SL_FLOATS(s, GL_MODELVIEW_MATRIX, 16);
  SL_FLOATS(s, GL_PROJECTION_STACK_DEPTH, 1);
  SL_FLOATS(s, GL_MODELVIEW_STACK_DEPTH, 1);
  SL_FLOATS(s, GL_ATTRIB_STACK_DEPTH, 1);
  SL_FLOATS(s, GL_CLIENT_ATTRIB_STACK_DEPTH, 1);
  SL_FLOATS(s, GL_VIEWPORT, 4);
  SL_FLOATS(s, GL_DEPTH_RANGE, 2);
  SL_FLOATS(s, GL_SCISSOR_BOX, 4);
  SL_FLOATS(s, GL_COLOR_WRITEMASK, 4);
  SL_FLOATS(s, GL_DEPTH_WRITEMASK, 1);
  SL_FLOATS(s, GL_DEPTH_FUNC, 1);
  SL_FLOATS(s, GL_BLEND_SRC, 1);
  SL_FLOATS(s, GL_BLEND_DST, 1);
  SL_FLOATS(s, GL_BLEND_EQUATION, 1);
  SL_FLOATS(s, GL_BLEND_COLOR, 4);
  SL_FLOATS(s, GL_LOGIC_OP_MODE, 1);
  SL_FLOATS(s, GL_ALPHA_TEST_FUNC, 1);
  SL_FLOATS(s, GL_ALPHA_TEST_REF, 1);
  SL_FLOATS(s, GL_STENCIL_FUNC, 1);
  SL_FLOATS(s, GL_STENCIL_REF, 1);
  SL_FLOATS(s, GL_STENCIL_VALUE_MASK, 1);
  SL_FLOATS(s, GL_STENCIL_WRITEMASK, 1);
  SL_FLOATS(s, GL_STENCIL_FAIL, 1);
  SL_FLOATS(s, GL_STENCIL_PASS_DEPTH_FAIL, 1);
  SL_FLOATS(s, GL_STENCIL_PASS_DEPTH_PASS, 1);
  SL_FLOATS(s, GL_COLOR_CLEAR_VALUE, 4);
  SL_FLOATS(s, GL_DEPTH_CLEAR_VALUE, 1);
  SL_FLOATS(s, GL_STENCIL_CLEAR_VALUE, 1);
  SL_FLOATS(s, GL_ACCUM_CLEAR_VALUE, 4);
  SL_FLOATS(s, GL_CULL_FACE_MODE, 1);
  SL_FLOATS(s, GL_FRONT_FACE, 1);
  SL_FLOATS(s, GL_POLYGON_MODE, 2);
  SL_FLOATS(s, GL_POLYGON_OFFSET_FACTOR, 1);
  SL_FLOATS(s, GL_POLYGON_OFFSET_UNITS, 1);
  SL_FLOATS(s, GL_SHADE_MODEL, 1);
  SL_FLOATS(s, GL_LINE_WIDTH, 1);
  SL_FLOATS(s, GL_POINT_SIZE, 1);
  SL_FLOATS(s, GL_LIGHT_MODEL_AMBIENT, 4);
  SL_FLOATS(s, GL_LIGHT_MODEL_LOCAL_VIEWER, 1);
  SL_FLOATS(s, GL_LIGHT_MODEL_TWO_SIDE, 1);
  SL_FLOATS(s, GL_LIGHT_MODEL_COLOR_CONTROL, 1);
  SL_FLOATS(s, GL_COLOR_MATERIAL_FACE, 1);
  SL_FLOATS(s, GL_COLOR_MATERIAL_PARAMETER, 1);
  SL_FLOATS(s, GL_FOG_MODE, 1);
  SL_FLOATS(s, GL_FOG_COLOR, 4);
  SL_FLOATS(s, GL_CURRENT_COLOR, 4);
  SL_FLOATS(s, GL_CURRENT_NORMAL, 3);
  SL_FLOATS(s, GL_CURRENT_TEXTURE_COORDS, 4);
  SL_FLOATS(s, GL_CURRENT_RASTER_POSITION, 4);
  SL_FLOATS(s, GL_CURRENT_RASTER_POSITION_VALID, 1);
  SL_FLOATS(s, GL_DRAW_BUFFER, 1);
  SL_FLOATS(s, GL_READ_BUFFER, 1);
  SL_FLOATS(s, GL_FRAMEBUFFER_BINDING, 1);
  SL_FLOATS(s, GL_RED_SCALE, 1);
  SL_FLOATS(s, GL_GREEN_SCALE, 1);
  SL_FLOATS(s, GL_BLUE_SCALE, 1);
  SL_FLOATS(s, GL_ALPHA_SCALE, 1);
  SL_FLOATS(s, GL_RED_BIAS, 1);
  SL_FLOATS(s, GL_GREEN_BIAS, 1);
  SL_FLOATS(s, GL_BLUE_BIAS, 1);
  SL_FLOATS(s, GL_ALPHA_BIAS, 1);
  SL_FLOATS(s, GL_DEPTH_SCALE, 1);
  SL_FLOATS(s, GL_DEPTH_BIAS, 1);
  SL_FLOATS(s, GL_MAP_COLOR, 1);
  SL_FLOATS(s, GL_ZOOM_X, 1);
  SL_FLOATS(s, GL_ZOOM_Y, 1);
  SL_FLOATS(s, GL_PACK_ALIGNMENT, 1);
  SL_FLOATS(s, GL_PACK_ROW_LENGTH, 1);
  SL_FLOATS(s, GL_PACK_SKIP_ROWS, 1);
  SL_FLOATS(s, GL_PACK_SKIP_PIXELS, 1);
  SL_FLOATS(s, GL_UNPACK_ALIGNMENT, 1);
  SL_FLOATS(s, GL_UNPACK_ROW_LENGTH, 1);
  SL_FLOATS(s, GL_UNPACK_SKIP_ROWS, 1);
  SL_FLOATS(s, GL_UNPACK_SKIP_PIXELS, 1);
  SL_FLOATS(s, GL_ARRAY_BUFFER_BINDING, 1);
  SL_FLOATS(s, GL_ELEMENT_ARRAY_BUFFER_BINDING, 1);
  // Per texture unit: enables, bindings, environment, texgen and the texture matrix.
  GLint units = 1, active = GL_TEXTURE0, clientActive = GL_TEXTURE0;
  glGetIntegerv(GL_MAX_TEXTURE_UNITS, &units);
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
  glGetIntegerv(GL_CLIENT_ACTIVE_TEXTURE, &clientActive);
  for (GLint u = 0; u < units; ++u) {
    const std::string unit = "unit " + std::to_string(u) + " ";
    glActiveTexture(GLenum(GL_TEXTURE0 + u));
    glClientActiveTexture(GLenum(GL_TEXTURE0 + u));
    for (const auto& [name, cap] :
         {SL_NAMED(GL_TEXTURE_1D), SL_NAMED(GL_TEXTURE_2D), SL_NAMED(GL_TEXTURE_3D),
          SL_NAMED(GL_TEXTURE_CUBE_MAP), SL_NAMED(GL_TEXTURE_GEN_S), SL_NAMED(GL_TEXTURE_GEN_T),
          SL_NAMED(GL_TEXTURE_GEN_R), SL_NAMED(GL_TEXTURE_GEN_Q), SL_NAMED(GL_TEXTURE_COORD_ARRAY)})
      addEnable(s, unit + name, cap);
    for (const auto& [name, binding] :
         {SL_NAMED(GL_TEXTURE_BINDING_1D), SL_NAMED(GL_TEXTURE_BINDING_2D),
          SL_NAMED(GL_TEXTURE_BINDING_3D)})
      addFloats(s, unit + name, binding, 1);
    addFloats(s, unit + "GL_TEXTURE_MATRIX", GL_TEXTURE_MATRIX, 16);
    addFloats(s, unit + "GL_TEXTURE_STACK_DEPTH", GL_TEXTURE_STACK_DEPTH, 1);
    GLint envMode = 0;
    glGetTexEnviv(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, &envMode);
    s.emplace_back(unit + "GL_TEXTURE_ENV_MODE", std::vector<double>{double(envMode)});
    const GLenum coords[4] = {GL_S, GL_T, GL_R, GL_Q};
    for (int c = 0; c < 4; ++c) {
      const std::string coord = unit + "texgen " + "STRQ"[c] + " ";
      float mode = 0.0f, eye[4] = {0, 0, 0, 0}, object[4] = {0, 0, 0, 0};
      glGetTexGenfv(coords[c], GL_TEXTURE_GEN_MODE, &mode);
      glGetTexGenfv(coords[c], GL_EYE_PLANE, eye);
      glGetTexGenfv(coords[c], GL_OBJECT_PLANE, object);
      s.emplace_back(coord + "mode", std::vector<double>{mode});
      s.emplace_back(coord + "eye plane", std::vector<double>(eye, eye + 4));
      s.emplace_back(coord + "object plane", std::vector<double>(object, object + 4));
    }
  }
  glActiveTexture(GLenum(active));
  glClientActiveTexture(GLenum(clientActive));
  return s;
}

#undef SL_FLOATS
#undef SL_ENABLE
#undef SL_NAMED

// The values that differ, "name: before -> after", one a line.
std::string differences(const StateValues& before, const StateValues& after) {
  std::ostringstream out;
  if (before.size() != after.size()) return "the state lists differ in length";
  auto text = [](const std::vector<double>& v) {
    std::ostringstream t;
    for (size_t i = 0; i < v.size(); ++i) t << (i ? " " : "") << v[i];
    return t.str();
  };
  for (size_t i = 0; i < before.size(); ++i)
    if (before[i].second != after[i].second)
      out << "  " << before[i].first << ": " << text(before[i].second) << " -> "
          << text(after[i].second) << "\n";
  return out.str();
}

// ------------------------------------------------------------------ the images

// Bit-identical frames: colour, visibility and every dump buffer, in order. Empty when equal.
std::string imageDifference(const Frame& expected, const Frame& got) {
  auto differ = [](const Image& a, const Image& b) {
    return a.width != b.width || a.height != b.height || a.channels != b.channels ||
           a.data != b.data;
  };
  if (differ(expected.color, got.color)) return "the shaded image";
  if (differ(expected.visibility, got.visibility)) return "the visibility mask";
  if (expected.intermediates.size() != got.intermediates.size()) return "the number of dumps";
  for (size_t i = 0; i < expected.intermediates.size(); ++i)
    if (expected.intermediates[i].name != got.intermediates[i].name ||
        differ(expected.intermediates[i].image, got.intermediates[i].image))
      return "the dump " + expected.intermediates[i].name;
  return "";
}

// ------------------------------------------------------------------ the orders

// An Eulerian circuit of the complete directed graph on n nodes with a loop at each (every
// node has n out- and n in-edges): n * n + 1 nodes in which each ordered pair (a, b),
// a == b included, follows exactly once (Hierholzer's algorithm).
std::vector<int> everyOrderedPairOnce(int n) {
  std::vector<int> next(size_t(n), 0);  // node a's next unused edge: a -> next[a]
  std::vector<int> stack = {0}, circuit;
  while (!stack.empty()) {
    const int a = stack.back();
    if (next[size_t(a)] < n) {
      stack.push_back(next[size_t(a)]++);
    } else {
      circuit.push_back(a);
      stack.pop_back();
    }
  }
  std::reverse(circuit.begin(), circuit.end());
  return circuit;
}

TEST(LegacyStateOrder, EveryOrderedPairFollowsOnce) {
  const int n = int(jobs().size());
  const std::vector<int> order = everyOrderedPairOnce(n);
  ASSERT_EQ(order.size(), size_t(n * n + 1));
  std::set<std::pair<int, int>> pairs;
  for (size_t i = 1; i < order.size(); ++i) pairs.insert({order[i - 1], order[i]});
  EXPECT_EQ(pairs.size(), size_t(n * n));
}

class LegacyStateScope : public ::testing::TestWithParam<Backend> {};

TEST_P(LegacyStateScope, EveryTechniqueLeavesTheStateItFoundAndRendersAsAloneInAnyOrder) {
  const Backend backend = GetParam();
  const Scene scene = builtinScene("brabec");
  std::vector<const Technique*> techniques;
  for (const Job& job : jobs()) techniques.push_back(&findTechnique(job.technique));

  // Each technique alone in a fresh context of its own, as `shadowlab render` renders it.
  std::vector<Frame> alone;
  for (size_t j = 0; j < jobs().size(); ++j) {
    const RenderParams p = paramsFor(jobs()[j], backend);
    auto context = makeRenderContext(*techniques[j], p);
    alone.push_back(techniques[j]->render(*context, scene, p));
  }

  // One context for all: the PCF techniques' (accumulation buffer, imaging installed), which
  // every legacy technique can render into at 8 bits.
  auto context = makeRenderContext(findTechnique("legacy.pcf"), paramsFor(jobs()[4], backend));
  context->makeCurrent();
  const bool imaging = context->caps().nativeImaging() || context->layerState("imaging");
  const StateValues fresh = readState(imaging);
  ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR)) << "a state query is not known to this GL";

  std::vector<int> order = everyOrderedPairOnce(int(jobs().size()));
  std::mt19937 random(kPermutationSeed);
  std::vector<int> permutation(jobs().size());
  for (int k = 0; k < kPermutations; ++k) {
    for (size_t j = 0; j < permutation.size(); ++j) permutation[j] = int(j);
    std::shuffle(permutation.begin(), permutation.end(), random);
    order.insert(order.end(), permutation.begin(), permutation.end());
  }

  std::string previous = "(a fresh context)";
  int leaks = 0, images = 0;
  constexpr int kReported = 3;  // the first few of each kind say enough
  for (const int j : order) {
    const Job& job = jobs()[size_t(j)];
    const std::string which = job.technique + " after " + previous;
    const RenderParams p = paramsFor(job, backend);
    const Frame frame = techniques[size_t(j)]->render(*context, scene, p);
    const std::string leaked = differences(fresh, readState(imaging));
    if (!leaked.empty() && leaks++ < kReported)
      ADD_FAILURE() << which << " left state behind:\n" << leaked;
    const std::string image = imageDifference(alone[size_t(j)], frame);
    if (!image.empty() && images++ < kReported)
      ADD_FAILURE() << which << ": " << image << " differs from its render alone";
    previous = job.technique;
  }
  EXPECT_EQ(leaks, 0) << "renders that left state behind, of " << order.size();
  EXPECT_EQ(images, 0) << "renders whose images differ from the technique's alone, of "
                       << order.size();
}

INSTANTIATE_TEST_SUITE_P(Backends, LegacyStateScope,
                         ::testing::ValuesIn(testing::imagingBackends()),
                         [](const auto& info) { return std::string(backendName(info.param)); });

}  // namespace
}  // namespace sl
