// The colour matrix's vector path (imaging/color_matrix_groups.cpp) against the general path of
// glspec121: unpackImage (3.6.4), runPipeline with applyColorMatrix (3.6.5 "Color Matrix
// Transformation" and its post-color-matrix scale and bias) and the final conversion of 4.3.2
// (clamp to [0, 1], times 255, round). The bytes must be identical — no tolerance: the vector
// path does the same float operations in the same order — for dense matrices with negative
// entries and entries above 1, every client layout it takes (GL_RGBA / GL_RGB of
// GL_UNSIGNED_BYTE / GL_FLOAT), every instruction set this processor has, odd row ends, padded
// and skipped rows, float input with NaN, infinities, -0 and denormals, and all 2^24 RGB byte
// groups.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "imaging/imaging_test_util.h"
#include "imaging/internal.h"

namespace sl::imaging::detail {
namespace {
using namespace sl::gl;

constexpr uint32_t kSeed = 4242;  // fixed: the cases are reproducible
constexpr int kRandomStates = 16;

struct Layout {
  GLenum format, type;
  const char* name;
};
constexpr Layout kLayouts[] = {{GL_RGBA, GL_UNSIGNED_BYTE, "RGBA bytes"},
                               {GL_RGB, GL_UNSIGNED_BYTE, "RGB bytes"},
                               {GL_RGBA, GL_FLOAT, "RGBA floats"},
                               {GL_RGB, GL_FLOAT, "RGB floats"}};

std::vector<MatrixIsa> availableIsas() {
  std::vector<MatrixIsa> isas;
  for (MatrixIsa isa : {MatrixIsa::kBest, MatrixIsa::kAvx512Vbmi, MatrixIsa::kAvx512,
                        MatrixIsa::kAvx2, MatrixIsa::kSse2})
    if (matrixIsaAvailable(isa)) isas.push_back(isa);
  return isas;
}
const char* isaName(MatrixIsa isa) {
  switch (isa) {
    case MatrixIsa::kBest: return "best";
    case MatrixIsa::kAvx512Vbmi: return "AVX-512 VBMI (planar)";
    case MatrixIsa::kAvx512: return "AVX-512";
    case MatrixIsa::kAvx2: return "AVX2";
    case MatrixIsa::kSse2: return "SSE2";
  }
  return "?";
}

// A dense colour matrix: entries in [-2.5, 2.5] (negative, above 1), some exactly 0 (the
// products with zero are still summed), some halves and whole numbers (exact rounding ties
// of byte inputs: both paths must break them the same way); post-color-matrix scale 1 or in
// [-2, 2], bias 0 or in [-0.5, 0.5].
TransferState randomState(std::mt19937& rng) {
  std::uniform_real_distribution<float> entry(-2.5f, 2.5f), scale(-2.0f, 2.0f), bias(-0.5f, 0.5f),
      unit(0.0f, 1.0f);
  const float exact[] = {0.0f, 0.5f, -0.5f, 1.0f, -1.0f, 2.0f, 0.25f};
  TransferState t;
  Matrix4& m = t.colorMatrixStack.back();
  for (float& v : m.m) {
    const float u = unit(rng);
    v = u < 0.25f ? exact[size_t(unit(rng) * 6.999f)] : entry(rng);
  }
  m.m[0] = 1.25f;  // never the identity
  if (unit(rng) < 0.5f)
    for (float& s : t.postColorMatrixScale) s = scale(rng);
  if (unit(rng) < 0.67f)
    for (float& b : t.postColorMatrixBias) b = bias(rng);
  return t;
}

// Client groups: random bytes, or floats in [-1.5, 2.5] with every special value among them.
std::vector<uint8_t> randomClient(const Layout& l, size_t bytes, std::mt19937& rng) {
  std::vector<uint8_t> data(bytes);
  if (l.type == GL_UNSIGNED_BYTE) {
    std::uniform_int_distribution<int> byte(0, 255);
    for (uint8_t& b : data) b = uint8_t(byte(rng));
    return data;
  }
  constexpr float kInf = std::numeric_limits<float>::infinity();
  const float special[] = {std::numeric_limits<float>::quiet_NaN(),
                           kInf,
                           -kInf,
                           -0.0f,
                           0.0f,
                           1.0f,
                           std::numeric_limits<float>::denorm_min(),
                           1e-40f,
                           1e30f,
                           -1e30f,
                           std::numeric_limits<float>::max(),
                           254.5f / 255.0f};
  std::uniform_real_distribution<float> value(-1.5f, 2.5f);
  std::uniform_int_distribution<int> pick(0, 15);
  for (size_t i = 0; i + sizeof(float) <= bytes; i += sizeof(float)) {
    const int k = pick(rng);
    const float v = k < int(std::size(special)) && pick(rng) < 3 ? special[k] : value(rng);
    std::memcpy(data.data() + i, &v, sizeof v);
  }
  return data;
}

// The general path: 3.6.4 unpacking, the stages of 3.6.5, the final conversion of 4.3.2.
std::vector<uint8_t> generalPath(TransferState t, const void* data, int w, int h, GLenum format,
                                 GLenum type, const PixelStore& store) {
  Image4 image = unpackImage(data, w, h, format, type, store);
  EXPECT_TRUE(runPipeline(t, image, Dimensionality::k2D));
  std::vector<uint8_t> out(image.px.size());
  for (size_t i = 0; i < out.size(); ++i) {
    const float v = image.px[i];
    const float c = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
    out[i] = uint8_t(c * 255.0f + 0.5f);
  }
  return out;
}

// The first differing byte, for the failure message ("" when equal).
std::string firstDifference(const std::vector<uint8_t>& got, const std::vector<uint8_t>& want) {
  if (got.size() != want.size()) return "sizes differ";
  for (size_t i = 0; i < got.size(); ++i)
    if (got[i] != want[i])
      return "group " + std::to_string(i / 4) + " component " + std::to_string(i % 4) + ": " +
             std::to_string(got[i]) + " instead of " + std::to_string(want[i]);
  return "";
}

// Bytes a w x h image of layout `l` takes in client memory under `store` (3.6.4).
size_t clientBytes(const Layout& l, int w, int h, const PixelStore& store) {
  const size_t size = l.type == GL_FLOAT ? 4 : 1, n = l.format == GL_RGBA ? 4 : 3;
  size_t row = size_t(store.rowLength > 0 ? store.rowLength : w) * n * size;
  if (size < size_t(store.alignment))
    row = (row + store.alignment - 1) / store.alignment * store.alignment;
  return row * size_t(h + store.skipRows) + size_t(store.skipPixels) * n * size + 64;
}

TEST(ColorMatrixGroups, RandomDenseMatricesEveryLayoutAndInstructionSet) {
  std::mt19937 rng(kSeed);
  PixelStore tight;
  tight.alignment = 1;
  PixelStore padded;  // RGB rows of 37 groups padded to 8 bytes; skipped pixels and rows
  padded.alignment = 8;
  padded.rowLength = 41;
  padded.skipPixels = 3;
  padded.skipRows = 2;
  struct Case {
    int w, h;
    const PixelStore* store;
  };
  // 37 groups: two 16-group blocks and a tail of 5; 512 x 300: both threads
  // (the four-groups forms; the planar form runs on one).
  const Case cases[] = {{37, 11, &tight}, {37, 9, &padded}, {1, 3, &tight}, {512, 300, &tight}};
  size_t compared = 0;
  for (int k = 0; k < kRandomStates; ++k) {
    const TransferState state = randomState(rng);
    ASSERT_TRUE(matrixOnlyPipeline(state));
    for (const Layout& l : kLayouts) {
      ASSERT_TRUE(matrixGroupsApply(state, l.format, l.type));
      for (const Case& c : cases) {
        const std::vector<uint8_t> data = randomClient(l, clientBytes(l, c.w, c.h, *c.store), rng);
        const std::vector<uint8_t> want =
            generalPath(state, data.data(), c.w, c.h, l.format, l.type, *c.store);
        for (MatrixIsa isa : availableIsas()) {
          std::vector<uint8_t> got(size_t(c.w) * c.h * 4, 0xCD);
          matrixGroupsToBytes(state, data.data(), c.w, c.h, l.format, l.type, *c.store, got.data(),
                              isa);
          ASSERT_EQ(firstDifference(got, want), "") << "state " << k << ", " << l.name << ", "
                                                    << c.w << "x" << c.h << ", " << isaName(isa);
          compared += got.size();
        }
      }
    }
  }
  EXPECT_GT(compared, size_t(0));
}

// The final conversion at the values where the vector forms' clamps could part from toByte's
// (4.3.2: clamp to [0, 1], times 255, + 0.5, truncate): NaN, infinities, -0, values at and
// beside 0 and 1, just below and above a rounding tie, and far outside [0, 1] (past the 32-bit
// range of the conversion). Each value is one component of a group whose other components are
// 0, and reaches the final conversion unchanged in its own row (1 times it plus +0 times the
// zeros; A is doubled, 2 times it); float layouts, then random groups, every instruction set.
TEST(ColorMatrixGroups, FinalConversionAtTheClampEdges) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  const float one = 1.0f, below1 = std::nextafter(one, 0.0f), above1 = std::nextafter(one, 2.0f);
  const float tie = 254.5f / 255.0f;  // o * 255 + 0.5 near 255: the last rounding step
  const float edges[] = {std::numeric_limits<float>::quiet_NaN(),
                         -std::numeric_limits<float>::quiet_NaN(),
                         kInf,
                         -kInf,
                         0.0f,
                         -0.0f,
                         std::numeric_limits<float>::denorm_min(),
                         -std::numeric_limits<float>::denorm_min(),
                         one,
                         below1,
                         above1,
                         std::nextafter(tie, 0.0f),
                         tie,
                         std::nextafter(tie, 2.0f),
                         0.5f / 255.0f,
                         -0.5f / 255.0f,
                         2147483648.0f,   // 2^31: past int32
                         -2147483648.0f,  // -2^31
                         16777216.0f,
                         std::numeric_limits<float>::max(),
                         -std::numeric_limits<float>::max(),
                         -1.0f,
                         2.0f};
  TransferState state;
  state.colorMatrixStack.back().m[15] = 2.0f;  // A doubled: not the identity
  ASSERT_TRUE(matrixOnlyPipeline(state));
  PixelStore tight;
  tight.alignment = 1;
  std::mt19937 rng(kSeed + 3);
  for (const Layout& l : kLayouts) {
    if (l.type != GL_FLOAT) continue;  // bytes cannot reach these values without scale/bias
    const int n = l.format == GL_RGBA ? 4 : 3;
    // Each edge value in each component of a group whose other components are 0; 61 groups:
    // three blocks and a tail.
    constexpr int kW = 61, kH = 3;
    std::vector<float> groups(size_t(kW) * kH * size_t(n), 0.0f);
    size_t g = 0;
    for (float e : edges)
      for (int c = 0; c < n; ++c, ++g) groups[g * size_t(n) + size_t(c)] = e;
    ASSERT_LE(g, size_t(kW) * kH);
    std::uniform_real_distribution<float> value(-1.5f, 2.5f);
    for (size_t i = g * size_t(n); i < groups.size(); ++i) groups[i] = value(rng);
    const std::vector<uint8_t> want =
        generalPath(state, groups.data(), kW, kH, l.format, l.type, tight);
    for (MatrixIsa isa : availableIsas()) {
      std::vector<uint8_t> got(want.size(), 0xCD);
      matrixGroupsToBytes(state, groups.data(), kW, kH, l.format, l.type, tight, got.data(), isa);
      ASSERT_EQ(firstDifference(got, want), "") << l.name << ", " << isaName(isa);
    }
  }
}

// All 2^24 RGB byte groups (a 4096 x 4096 image, every (R, G, B) once), in strips of 256
// rows, through two random dense matrices (one with post scale and bias) at every instruction
// set; and as RGBA bytes through transformBytes in place (the glCopyPixels / glReadPixels
// path), alpha a function of the group.
TEST(ColorMatrixGroups, AllRgbByteGroups) {
  constexpr int kSide = 4096, kStripRows = 256;  // 4096^2 = 2^24 groups
  std::mt19937 rng(kSeed + 1);
  TransferState states[2] = {randomState(rng), randomState(rng)};
  for (float& s : states[1].postColorMatrixScale) s = 1.5f;
  states[1].postColorMatrixBias = {-0.25f, 0.125f, 0.0f, 0.3f};
  PixelStore tight;
  tight.alignment = 1;
  std::vector<uint8_t> rgb(size_t(kSide) * kStripRows * 3), rgba(size_t(kSide) * kStripRows * 4);
  size_t groups = 0;
  for (int y0 = 0; y0 < kSide; y0 += kStripRows) {
    for (size_t i = 0; i < size_t(kSide) * kStripRows; ++i) {
      const uint32_t v = uint32_t(size_t(y0) * kSide + i);  // 24 bits: R, G, B
      const uint8_t px[4] = {uint8_t(v), uint8_t(v >> 8), uint8_t(v >> 16),
                             uint8_t((v * 2654435761u) >> 24)};
      std::memcpy(&rgb[i * 3], px, 3);
      std::memcpy(&rgba[i * 4], px, 4);
    }
    for (int k = 0; k < 2; ++k) {
      const std::vector<uint8_t> want =
          generalPath(states[k], rgb.data(), kSide, kStripRows, GL_RGB, GL_UNSIGNED_BYTE, tight);
      for (MatrixIsa isa : availableIsas()) {
        std::vector<uint8_t> got(want.size());
        matrixGroupsToBytes(states[k], rgb.data(), kSide, kStripRows, GL_RGB, GL_UNSIGNED_BYTE,
                            tight, got.data(), isa);
        ASSERT_EQ(firstDifference(got, want), "")
            << "matrix " << k << ", rows " << y0 << "+, " << isaName(isa);
      }
    }
    const std::vector<uint8_t> want =
        generalPath(states[1], rgba.data(), kSide, kStripRows, GL_RGBA, GL_UNSIGNED_BYTE, tight);
    TransferState t = states[1];
    std::vector<uint8_t> bytes = rgba;
    ASSERT_TRUE(transformBytes(t, bytes, kSide, kStripRows));
    ASSERT_EQ(firstDifference(bytes, want), "") << "transformBytes, rows " << y0 << "+";
    groups += size_t(kSide) * kStripRows;
  }
  EXPECT_EQ(groups, size_t(1) << 24);
}

// The GL calls that take the vector path write the general path's bytes: glDrawPixels of each
// layout into the window, glTexImage2D into an RGBA8 texture (read back with glGetTexImage,
// which has no pixel transfer, 6.1.4).
TEST(ColorMatrixGroups, DrawPixelsAndTexImageWriteTheGeneralPathsBytes) {
  constexpr int kW = 29, kH = 7;  // 203 groups: blocks and a tail
  auto context = imaging::testing::emulatedContext(kW, kH);
  std::mt19937 rng(kSeed + 2);
  const TransferState state = randomState(rng);
  glMatrixMode(GL_COLOR);
  glLoadMatrixf(state.colorMatrixStack.back().m.data());
  glMatrixMode(GL_MODELVIEW);
  const GLenum scales[4] = {GL_POST_COLOR_MATRIX_RED_SCALE, GL_POST_COLOR_MATRIX_GREEN_SCALE,
                            GL_POST_COLOR_MATRIX_BLUE_SCALE, GL_POST_COLOR_MATRIX_ALPHA_SCALE};
  const GLenum biases[4] = {GL_POST_COLOR_MATRIX_RED_BIAS, GL_POST_COLOR_MATRIX_GREEN_BIAS,
                            GL_POST_COLOR_MATRIX_BLUE_BIAS, GL_POST_COLOR_MATRIX_ALPHA_BIAS};
  for (int c = 0; c < 4; ++c) {
    glPixelTransferf(scales[c], state.postColorMatrixScale[size_t(c)]);
    glPixelTransferf(biases[c], state.postColorMatrixBias[size_t(c)]);
  }
  PixelStore tight;
  tight.alignment = 1;
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  for (const Layout& l : kLayouts) {
    const std::vector<uint8_t> data = randomClient(l, clientBytes(l, kW, kH, tight), rng);
    const std::vector<uint8_t> want =
        generalPath(state, data.data(), kW, kH, l.format, l.type, tight);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glWindowPos2i(0, 0);
    glDrawPixels(kW, kH, l.format, l.type, data.data());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, kW, kH, 0, l.format, l.type, data.data());
    // The reads with the colour matrix in place would transform again: identity first.
    glMatrixMode(GL_COLOR);
    glPushMatrix();
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    for (int c = 0; c < 4; ++c) {
      glPixelTransferf(scales[c], 1.0f);
      glPixelTransferf(biases[c], 0.0f);
    }
    EXPECT_EQ(firstDifference(imaging::testing::readRgba8(0, 0, kW, kH), want), "")
        << "glDrawPixels " << l.name;
    std::vector<uint8_t> texels(want.size(), 0xCD);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
    EXPECT_EQ(firstDifference(texels, want), "") << "glTexImage2D " << l.name;
    glMatrixMode(GL_COLOR);
    glPopMatrix();
    glMatrixMode(GL_MODELVIEW);
    for (int c = 0; c < 4; ++c) {
      glPixelTransferf(scales[c], state.postColorMatrixScale[size_t(c)]);
      glPixelTransferf(biases[c], state.postColorMatrixBias[size_t(c)]);
    }
  }
  glDeleteTextures(1, &texture);
  EXPECT_TRUE(imaging::testing::drainErrors().empty());
}

}  // namespace
}  // namespace sl::imaging::detail
