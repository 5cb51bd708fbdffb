// The 8-bit path (imaging/fast_paths.cpp) and its vector maps (imaging/byte_maps.cpp) against
// the general float pipeline: for every state below, the bytes of transformBytes (vector
// maps where they apply, and the scalar loops forced) must equal runPipeline on the float
// image followed by the final conversion of glspec121 4.3.2 (clamp to [0, 1], times 255,
// round to nearest) — exactly, since the fast paths only re-use values the stage code
// computed (no tolerance).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <string>

#include "imaging/internal.h"

namespace sl::imaging::detail {
namespace {

constexpr uint32_t kSeed = 20011;  // fixed: the cases are reproducible

// A width and height whose group count is not a multiple of the eight groups of one vector,
// so the scalar tail runs too; and one large enough for the second thread.
constexpr int kSmallWidth = 37, kSmallHeight = 11;
constexpr int kLargeWidth = 512, kLargeHeight = 300;

std::vector<uint8_t> randomBytes(int w, int h, std::mt19937& rng) {
  std::vector<uint8_t> bytes(size_t(w) * h * 4);
  std::uniform_int_distribution<int> byte(0, 255);
  for (uint8_t& b : bytes) b = uint8_t(byte(rng));
  // Every byte value in every component at least once (the edges of every step).
  for (size_t i = 0; i < std::min<size_t>(bytes.size(), 1024); ++i) bytes[i] = uint8_t(i / 4);
  return bytes;
}

std::vector<uint8_t> generalPath(TransferState t, const std::vector<uint8_t>& bytes, int w, int h) {
  Image4 image(w, h);
  for (size_t i = 0; i < bytes.size(); ++i) image.px[i] = float(bytes[i]) / 255.0f;  // table 2.6
  EXPECT_TRUE(runPipeline(t, image, Dimensionality::k2D));
  std::vector<uint8_t> out(bytes.size());
  for (size_t i = 0; i < out.size(); ++i) {
    const float v = image.px[i];
    const float c = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;  // 4.3.2 "Final Conversion"
    out[i] = uint8_t(c * 255.0f + 0.5f);
  }
  return out;
}

void expectSameBytes(const TransferState& state, const std::string& name) {
  std::mt19937 rng(kSeed);
  for (const auto& size : {std::pair{kSmallWidth, kSmallHeight}, {kLargeWidth, kLargeHeight}}) {
    const int w = size.first, h = size.second;
    const std::vector<uint8_t> source = randomBytes(w, h, rng);
    const std::vector<uint8_t> expected = generalPath(state, source, w, h);
    for (BytePath path : {BytePath::kFastest, BytePath::kScalar}) {
      TransferState t = state;
      std::vector<uint8_t> bytes = source;
      ASSERT_TRUE(transformBytes(t, bytes, w, h, path)) << name;
      size_t differing = 0, first = 0;
      for (size_t i = 0; i < bytes.size(); ++i)
        if (bytes[i] != expected[i] && differing++ == 0) first = i;
      EXPECT_EQ(differing, 0u) << name << " " << w << "x" << h
                               << (path == BytePath::kScalar ? " scalar" : " fastest")
                               << ": first at byte " << first << " (source " << int(source[first])
                               << ", got " << int(bytes[first]) << ", expected "
                               << int(expected[first]) << ")";
    }
  }
}

// A 256-entry RGBA table whose component c is steps[c](i) for entry i.
ColorTable tableOf(const std::function<float(int, int)>& entry) {
  ColorTable table;
  table.width = 256;
  table.entries.resize(256);
  for (int i = 0; i < 256; ++i)
    for (int c = 0; c < 4; ++c) table.entries[size_t(i)][size_t(c)] = entry(i, c);
  return table;
}

// Brabec & Seidel 2001, Section 3: 0 stays 0, every other value becomes 64 (63 in alpha).
ColorTable brabecSeidelTable() {
  return tableOf([](int i, int c) { return i == 0 ? 0.0f : (c == 3 ? 63.0f : 64.0f) / 255.0f; });
}

Matrix4 sumIntoAlpha() {
  Matrix4 m;
  m.m.fill(0.0f);
  for (int c = 0; c < 4; ++c) m.m[size_t(c * 4 + 3)] = 1.0f;  // column c, row 3
  return m;
}

TEST(BytePaths, BrabecSeidelTableIsOneStepPerComponent) {
  TransferState t;
  t.tables[0] = brabecSeidelTable();
  t.colorTableEnabled = true;
  expectSameBytes(t, "Brabec-Seidel table");
  // The vector map really applies: one step at 1 in each component, 64 (63) added there.
  uint8_t lut[256 * 4];
  for (int v = 0; v < 256; ++v)
    for (int c = 0; c < 4; ++c) lut[v * 4 + c] = v == 0 ? 0 : (c == 3 ? 63 : 64);
  StepMap map;
  ASSERT_TRUE(planStepMap(lut, map));
  EXPECT_EQ(map.steps, 1);
  EXPECT_EQ(map.at[0][0], 1);
  EXPECT_EQ(map.delta[0][3], 63);
}

TEST(BytePaths, BrabecSeidelTableWithSumIntoAlphaMatrix) {
  TransferState t;
  t.tables[0] = brabecSeidelTable();
  t.colorTableEnabled = true;
  t.colorMatrixStack = {sumIntoAlpha()};
  expectSameBytes(t, "Brabec-Seidel table + sum into alpha");
  // Sixteen classes: two values in each of the four components.
  ClassMap map;
  auto same = [](int, int v) { return v != 1; };  // the table's only step is at 1
  const bool matters[4] = {true, true, true, true};
  ASSERT_TRUE(planClassMap(
      same, matters, [](uint8_t*, size_t) {}, map));
  EXPECT_EQ(map.steps, 1);
  EXPECT_EQ(map.weight[0][0] + map.weight[0][1] + map.weight[0][2] + map.weight[0][3],
            1 + 2 + 4 + 8);
}

TEST(BytePaths, SeveralStepsPerComponentWithPostMatrixScaleAndBias) {
  TransferState t;
  // Component c steps at 40 + 50 c and at 200 (three runs), different levels per component.
  t.tables[0] = tableOf([](int i, int c) {
    const int run = (i >= 40 + 50 * c) + (i >= 200);
    return float(run * (c + 1)) / 9.0f;
  });
  t.colorTableEnabled = true;
  t.postColorMatrixScale = {0.5f, 2.0f, -1.0f, 1.5f};
  t.postColorMatrixBias = {0.1f, -0.2f, 1.0f, 0.0f};
  expectSameBytes(t, "three-run table, post scale/bias");
}

TEST(BytePaths, SparseMatrixWithNegativeCoefficientsAndPostMatrixTable) {
  TransferState t;
  t.tables[0] = tableOf([](int i, int c) { return i < 128 ? 0.25f * c : 1.0f - 0.2f * c; });
  t.colorTableEnabled = true;
  Matrix4 m;
  m.m = {0.5f, 0, 1, 0,  // column 0 (R) feeds rows 0 and 2
         0,    1, 0, -0.5f, 0, 0, 0.25f, 0, 0.3f, 0, 0, 1};
  t.colorMatrixStack = {m};
  t.tables[2] = tableOf([](int i, int c) { return float((i / 64 + c) % 4) / 3.0f; });
  t.postColorMatrixTableEnabled = true;
  t.postColorMatrixBias = {0.05f, 0.0f, -0.1f, 0.2f};
  expectSameBytes(t, "sparse matrix, post-matrix table");
}

TEST(BytePaths, ScaleAndBiasThresholdWithMatrix) {
  // No table: scale and bias alone leave the prefix a ramp (nothing clamps before the colour
  // table stage), so the class map refuses and the scalar loop runs, with the same bytes.
  TransferState t;
  t.scale = {4.0f, 4.0f, 4.0f, 4.0f};
  t.bias = {-1.5f, -1.0f, -0.5f, 0.0f};
  t.colorMatrixStack = {sumIntoAlpha()};
  expectSameBytes(t, "scale/bias ramp + matrix");
}

TEST(BytePaths, DenseMatrixOnEveryByteValueWithPostMatrixStages) {
  // No table before the matrix: 256 distinct values per component, so every row sums floats
  // per group (the general case), then post-matrix scale/bias and a post-matrix table.
  TransferState t;
  Matrix4 m;
  m.m = {0.299f, 0.5f, -0.2f, 0.1f, 0.587f, -0.3f, 0.7f, 0.2f,
         0.114f, 0.8f, 0.4f,  0.3f, 0.05f,  0.0f,  0.1f, 0.4f};
  t.colorMatrixStack = {m};
  expectSameBytes(t, "dense matrix");
  t.postColorMatrixScale = {1.5f, 0.5f, 2.0f, 1.0f};
  t.postColorMatrixBias = {-0.1f, 0.2f, 0.0f, 0.05f};
  t.tables[2] = tableOf([](int i, int c) { return std::sqrt(i / 255.0f) * (0.5f + 0.125f * c); });
  t.postColorMatrixTableEnabled = true;
  expectSameBytes(t, "dense matrix, post scale/bias and table");
}

// Too many steps for the step map: the byte permutes (AVX-512 VBMI) where the processor has
// them, else the scalar word tables.
TEST(BytePaths, GammaTableThroughPermutesOrWordTables) {
  TransferState t;
  t.tables[0] = tableOf([](int i, int c) { return std::pow(i / 255.0f, 1.0f + 0.3f * c); });
  t.colorTableEnabled = true;
  expectSameBytes(t, "gamma table");
  t.colorMatrixStack = {sumIntoAlpha()};
  expectSameBytes(t, "gamma table + matrix");
}

TEST(BytePaths, TwoComponentsThreeClassesEachThroughMatrix) {
  // The matrix reads G and A only: 3 x 3 = 9 classes; R and B bytes must not matter.
  TransferState t;
  t.tables[0] =
      tableOf([](int i, int c) { return float((i >= 90) + (i >= 170)) * 0.3f + 0.01f * c; });
  t.colorTableEnabled = true;
  Matrix4 m;
  m.m = {0, 0, 0, 0, 1, 0.5f, 0, 0, 0, 0, 0, 0, 0, 0.5f, 1, 1};
  t.colorMatrixStack = {m};
  expectSameBytes(t, "nine classes");
}

TEST(BytePaths, FourStepsPerComponentIdentityMatrix) {
  TransferState t;
  t.tables[0] = tableOf([](int i, int c) {
    // Non-monotone: levels 3, 0, 2, 1, 3 over five runs (four steps), shifted per component.
    const int bounds[4] = {20 + c, 90, 150 + 10 * c, 240};
    const float levels[5] = {1.0f, 0.0f, 0.66f, 0.33f, 1.0f};
    int run = 0;
    while (run < 4 && i >= bounds[run]) ++run;
    return levels[run];
  });
  t.colorTableEnabled = true;
  expectSameBytes(t, "four steps");
  t.scale = {0.5f, 0.5f, 0.5f, 0.5f};  // halves the index: the steps move
  expectSameBytes(t, "four steps, scaled index");
}

}  // namespace
}  // namespace sl::imaging::detail

namespace sl::imaging::detail {
namespace {

// GL_ACCUM / GL_LOAD on 8-bit colour (accumulation.cpp) through accumulateBytes against the
// specification's A <- keep * A + value * C in 16-bit steps with the clamp to [-1, 1]
// (glspec121 4.2.4; the step table is the emulation's, so the comparison is exact), for
// values of both signs, accumulators at both limits and rows that are not whole blocks.
TEST(BytePaths, AccumulateBytesEqualsTheScalarSum) {
  constexpr int kSteps = 32767;  // accumulator: k / 32767
  constexpr size_t kComponents = 64 * 9 + 28;
  std::mt19937 rng(kSeed);
  std::uniform_int_distribution<int> byte(0, 255), step(-kSteps, kSteps);
  for (const float value : {0.25f, 1.0f, -1.0f, -0.37f, 0.0f})
    for (const bool keep : {true, false}) {
      int16_t scaled[256];
      for (int v = 0; v < 256; ++v)
        scaled[v] = int16_t(std::lround(double(value) * (v / 255.0) * kSteps));
      std::vector<uint8_t> color(kComponents);
      std::vector<int16_t> accum(kComponents);
      for (size_t i = 0; i < kComponents; ++i) {
        color[i] = uint8_t(i < 256 ? i : byte(rng));
        accum[i] = int16_t(i % 7 == 0 ? kSteps : i % 7 == 1 ? -kSteps : step(rng));
      }
      std::vector<int16_t> expected = accum;
      for (size_t i = 0; i < kComponents; ++i)
        expected[i] =
            int16_t(std::clamp((keep ? int(accum[i]) : 0) + scaled[color[i]], -kSteps, kSteps));
      const size_t done = accumulateBytes(scaled, keep, color.data(), accum.data(), kComponents);
      EXPECT_EQ(done % 64, 0u);
      if (vectorTablesAvailable()) {
        EXPECT_EQ(done, kComponents / 64 * 64);
      }
      for (size_t i = 0; i < done; ++i)
        ASSERT_EQ(accum[i], expected[i]) << "value " << value << " keep " << keep << " at " << i;
    }
}

}  // namespace
}  // namespace sl::imaging::detail
