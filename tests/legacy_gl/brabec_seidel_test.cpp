// Brabec & Seidel 2001 §2-§4 (legacy.ramp, legacy.pcf, legacy.fast-pcf): expectations computed
// from the paper's formulas and from the geometry, never copied from an output.
#include "legacy_gl/brabec_seidel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <optional>
#include <set>
#include <string>

#include "core/base/errors.h"
#include "core/scene/scene_library.h"
#include "imaging/imaging.h"
#include "legacy_gl/brabec_seidel_passes.h"
#include "legacy_test_support.h"
#include "registry/registry.h"

namespace sl {
namespace {
using namespace sl::gl;

constexpr int kWidth = 400;  // small window (team rule); the 256 map fits in it (window path)
constexpr int kHeight = 300;
constexpr int kMapTexels = 256;

RenderParams params(Backend backend, int filter, Precision precision = Precision::k8) {
  RenderParams p;
  p.width = kWidth;
  p.height = kHeight;
  p.shadowMapTexels = kMapTexels;
  p.filter = filter;
  p.precision = precision;
  p.backend = backend;
  return p;
}

Frame render(const std::string& technique, const std::string& scene, const RenderParams& p) {
  return renderTechnique(findTechnique(technique), builtinScene(scene), p);
}

// 8-bit alpha shadow term back from the visibility (visibility = 1 - A / 255, exact in float).
int alphaOf(float visibility) { return int(std::lround((1.0f - visibility) * 255.0f)); }

// ------------------------------------------------------------------ matrices

// Everitt's notation: S · P · L^-1 · V with L^-1 the light's view matrix and V the inverse of
// the camera's view matrix (camera eye -> world), computed here with GLM from the scene.
TEST(BrabecSeidel, ProjectiveTexgenEqualsSPLinvV) {
  const Scene scene = builtinScene("brabec");
  const DepthRange range = lightDepthRange(scene);
  const glm::mat4 S = glm::mat4(0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 0.5f, 0, 0.5f, 0.5f, 0.5f, 1);
  const glm::mat4 P = glm::perspective(glm::radians(scene.light.coneDegrees), 1.0f, range.nearPlane,
                                       range.farPlane);
  const glm::mat4 Linv = glm::lookAt(scene.light.position, scene.light.target, scene.light.up);
  const glm::mat4 V =
      glm::inverse(glm::lookAt(scene.camera.position, scene.camera.target, scene.camera.up));
  for (const glm::vec2 offset : {glm::vec2(0.0f), glm::vec2(0.5f, 0.5f), glm::vec2(-0.5f, 0.5f)}) {
    const glm::mat4 T = glm::translate(glm::mat4(1.0f), glm::vec3(offset / float(kMapTexels), 0));
    const glm::mat4 expected = T * S * P * Linv * V;

    // What GL holds after the technique's set-up: the eye planes (rows) and the texture matrix.
    ContextSpec spec;
    spec.width = 16;
    spec.height = 16;
    auto ctx = GlContext::create(spec);
    RenderParams p = params(Backend::kOsmesa, 2);
    legacy::setCameraMatrices(scene, p.width, p.height);
    ScopedTexgen texgen(GL_TEXTURE0);
    legacy::bs::loadProjectiveTexgen(scene, p, offset, texgen);
    glm::mat4 planes(0.0f);
    const GLenum coords[4] = {GL_S, GL_T, GL_R, GL_Q};
    for (int i = 0; i < 4; ++i) {
      float plane[4];
      glGetTexGenfv(coords[i], GL_EYE_PLANE, plane);
      for (int j = 0; j < 4; ++j) planes[j][i] = plane[j];  // row i
    }
    glm::mat4 texture;
    glGetFloatv(GL_TEXTURE_MATRIX, glm::value_ptr(texture));
    const glm::mat4 loaded = texture * planes;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        // float products of matrices with entries up to ~10: 1e-5 relative is float rounding
        EXPECT_NEAR(loaded[c][r], expected[c][r], 1e-5f * (1.0f + std::fabs(expected[c][r])))
            << "column " << c << " row " << r << " offset " << offset.x << "," << offset.y;
  }
}

// §2: the camera pass's ramp coordinate is the linear light depth d = (dist along the light's
// axis - near) / (far - near), minus the bias, placed on the centres of the N ramp texels.
TEST(BrabecSeidel, CameraRampCoordinateIsBiasedLinearLightDepth) {
  const Scene scene = builtinScene("brabec");
  const DepthRange range = lightDepthRange(scene);
  const glm::vec3 axis = glm::normalize(scene.light.target - scene.light.position);
  constexpr int kRamp = 256;
  constexpr double kBias = 0.01;
  ContextSpec spec;
  spec.width = 16;
  spec.height = 16;
  auto ctx = GlContext::create(spec);
  legacy::setCameraMatrices(scene, 16, 16);
  legacy::bs::DepthEncoding enc = legacy::bs::depthEncoding(Precision::k8);
  ScopedTexgen texgen(GL_TEXTURE0);
  legacy::bs::loadCameraToRampTexgen(scene, enc, kBias, texgen);
  glm::mat4 texture;
  glGetFloatv(GL_TEXTURE_MATRIX, glm::value_ptr(texture));
  const glm::mat4 view = glm::lookAt(scene.camera.position, scene.camera.target, scene.camera.up);
  for (const glm::vec3 world : {glm::vec3(0, 0, 0), glm::vec3(1.3f, 0.9f, -0.6f),
                                glm::vec3(-4, 0, 5), glm::vec3(2, 1.5f, 2)}) {
    const double d = (glm::dot(world - scene.light.position, axis) - range.nearPlane) /
                     (range.farPlane - range.nearPlane);
    const double expected = (0.5 + (kRamp - 1) * (d - kBias)) / kRamp;
    const glm::vec4 s = texture * (view * glm::vec4(world, 1.0f));
    EXPECT_NEAR(s.x, expected, 1e-5) << "float rounding of a 4x4 product";
    EXPECT_NEAR(s.w, 1.0, 1e-6);
  }
}

// Eq. (1) as printed (top row first) is the kernel read bottom-up by glConvolutionFilter2D.
TEST(BrabecSeidel, PackingKernelIsEquationOne) {
  const float C[3][3][4] = {{{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}},
                            {{0, 0, 1, 0}, {0, 0, 0, 1}, {0, 0, 0, 0}},
                            {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 0, 0}}};
  const auto k = legacy::bs::packingKernel({0, 0});
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col)
      for (int c = 0; c < 4; ++c)
        EXPECT_EQ(k[size_t(((2 - row) * 3 + col) * 4 + c)], C[row][col][c])
            << "row " << row << " col " << col << " channel " << c;
  // The 4x4 phases move the same pattern by one texel right and/or up.
  const auto upperRight = legacy::bs::packingKernel({1, 1});
  EXPECT_EQ(upperRight[size_t((1 * 3 + 1) * 4 + 0)], 1.0f);  // red from (x, y)
  EXPECT_EQ(upperRight[size_t((2 * 3 + 2) * 4 + 3)], 1.0f);  // alpha from (x+1, y+1)
}

// Footnote 2: 64, 64, 64, 63 sum to 255.
TEST(BrabecSeidel, SharesSumToFullShadow) {
  const auto enc = legacy::bs::depthEncoding(Precision::k8);
  const auto s4 = legacy::bs::shadowShares(enc, 4);
  EXPECT_EQ(s4[0], 64);
  EXPECT_EQ(s4[3], 63);
  EXPECT_EQ(s4[0] + s4[1] + s4[2] + s4[3], 255);
  const auto s1 = legacy::bs::shadowShares(enc, 1);
  EXPECT_EQ(s1[0], 255);
  const auto enc12 = legacy::bs::depthEncoding(Precision::k12);
  const auto t4 = legacy::bs::shadowShares(enc12, 4);
  EXPECT_EQ(t4[0] + t4[1] + t4[2] + t4[3], 4095);
}

// ------------------------------------------------------------------ shadow levels

// §3: "five different levels of shadowing": A = 64 per shadowed R/G/B sample, 63 for alpha.
void expectFiveLevels(const Frame& f, const std::string& what) {
  const std::set<int> allowed = {0, 63, 64, 127, 128, 191, 192, 255};
  std::set<int> levels;
  for (float v : f.visibility.data) {
    const int a = alphaOf(v);
    ASSERT_TRUE(allowed.count(a)) << what << ": alpha " << a << " is no sum of 64/64/64/63";
    levels.insert(int(std::lround(a / 63.75)));  // samples shadowed, 0..4
  }
  EXPECT_EQ(levels.size(), 5u) << what;
}

TEST(BrabecSeidel, TwoByTwoFootprintsGiveFiveLevels) {
  const auto backends = testing::imagingBackends();
  for (Backend b : backends) {
    expectFiveLevels(render("legacy.pcf", "brabec", params(b, 2)),
                     std::string("legacy.pcf 2x2 on ") + backendName(b));
    expectFiveLevels(render("legacy.fast-pcf", "brabec", params(b, 2)),
                     std::string("legacy.fast-pcf 2x2 on ") + backendName(b));
  }
}

TEST(BrabecSeidel, FastPcfFourByFourGivesAtLeastSeventeenLevels) {
  const auto backends = testing::imagingBackends();
  for (Backend b : backends) {
    const Frame f = render("legacy.fast-pcf", "brabec", params(b, 4));
    std::set<int> levels;
    for (float v : f.visibility.data) levels.insert(alphaOf(v));
    // 16 samples: 0..16 shadowed = 17 levels at least (§4 counts 4 x 5 = 20)
    EXPECT_GE(levels.size(), 17u) << backendName(b);
  }
}

// §3/§4 accumulation: the returned alpha is the weighted sum of the groups' (phases') alphas,
// weights = samples in the group / samples in the footprint. The sum is modelled exactly; one
// 8-bit step is allowed because the accumulation buffer's fixed-point format and the rounding
// of GL_ACCUM/GL_RETURN are implementation-dependent (glspec121 §4.2.4).
TEST(BrabecSeidel, AccumulationSumsTheGroupsWithTheirWeights) {
  const auto backends = testing::imagingBackends();
  struct Variant {
    const char* technique;
    int filter;
    std::vector<std::string> groups;
    std::vector<double> weights;
    const char* result;
  };
  const Variant variants[] = {
      {"legacy.pcf",
       3,
       {"4-alpha-after-colour-matrix-group1", "4-alpha-after-colour-matrix-group2",
        "4-alpha-after-colour-matrix-group3"},
       {4.0 / 9, 4.0 / 9, 1.0 / 9},
       "5b-accumulation-result-alpha"},
      {"legacy.fast-pcf",
       4,
       {"5-alpha-after-colour-matrix-upper-left", "5-alpha-after-colour-matrix-upper-right",
        "5-alpha-after-colour-matrix-lower-left", "5-alpha-after-colour-matrix-lower-right"},
       {0.25, 0.25, 0.25, 0.25},
       "6b-accumulation-result-alpha"}};
  for (Backend b : backends)
    for (const Variant& v : variants) {
      RenderParams p = params(b, v.filter);
      p.capturePasses = true;
      const Frame f = render(v.technique, "brabec", p);
      auto find = [&](const std::string& name) -> const Image& {
        for (const PassImage& i : f.intermediates)
          if (i.name == name) return i.image;
        throw std::runtime_error("no intermediate " + name);
      };
      const Image& result = find(v.result);
      long checked = 0, partial = 0;
      for (size_t i = 0; i < result.data.size(); ++i) {
        double sum = 0;
        for (size_t g = 0; g < v.groups.size(); ++g)
          sum += v.weights[g] * std::lround(find(v.groups[g]).data[i] * 255.0f);
        const long got = std::lround(result.data[i] * 255.0f);
        ASSERT_LE(std::fabs(double(got) - sum), 1.0)
            << v.technique << " " << v.filter << " on " << backendName(b) << " pixel " << i;
        ++checked;
        partial += got > 0 && got < 255;
      }
      EXPECT_GT(partial, 500) << "penumbra pixels present";
      EXPECT_EQ(checked, long(kWidth) * kHeight);
    }
}

// PCF 3x3/4x4 (§3) and fast PCF 4x4 (§4) draw the camera pass once and restore it from a copy
// before each later subtraction (kCameraPassCopyDeviation): the restored window holds the drawn
// camera pass's values exactly, at every precision (the copy has the map's format).
TEST(BrabecSeidel, RestoredCameraPassEqualsTheDrawnOne) {
  const Scene scene = builtinScene("brabec");
  for (Precision precision : {Precision::k8, Precision::k12, Precision::kFloat}) {
    const RenderParams p = params(Backend::kOsmesa, 4, precision);
    auto context = makeRenderContext(findTechnique("legacy.pcf"), p);
    const legacy::bs::DepthEncoding enc = legacy::bs::depthEncoding(precision);
    legacy::bs::RampTexture ramp;
    legacy::bs::createRampTexture(ramp, enc);
    legacy::bs::renderCameraDepth(scene, p, enc, ramp, legacy::bs::depthBias(p, enc),
                                  legacy::bs::kAllChannels);
    const Image drawn = readColorBuffer(0, 0, p.width, p.height);
    legacy::bs::SavedCameraPass saved;
    legacy::bs::allocateSavedCameraPass(saved, p, enc);
    legacy::bs::saveCameraPass(saved, p);
    glClearColor(0.5f, 0.25f, 1.0f, 0.75f);  // what a subtraction would leave: anything else
    glClear(GL_COLOR_BUFFER_BIT);
    legacy::bs::restoreCameraPass(saved, p);
    const Image restored = readColorBuffer(0, 0, p.width, p.height);
    long nonZero = 0;
    for (float v : drawn.data) nonZero += v > 0.0f;
    EXPECT_GT(nonZero, 1000) << "the camera pass drew receivers";
    EXPECT_EQ(restored.data, drawn.data) << "precision " << int(precision);
    checkGl("restored camera pass test");
  }
}

// ------------------------------------------------------------------ analytic scene

struct Geometry {
  enum Kind { kNothing, kOccluder, kGroundLit, kGroundShadow, kNearBoundary };
};

// The analytic scene's exact shadow: a point light at height H straight above the centre, the
// occluder's top face (half width a, height yTop) casts the square |x|, |z| < a H / (H - yTop)
// on the ground (similar triangles; the top face's outline contains the bottom face's).
class AnalyticShadow {
 public:
  AnalyticShadow(const Scene& scene, int width, int height, double bandTexels, int mapTexels)
      : width_(width), height_(height) {
    const Object& occ = scene.objects.at(1);
    box_ = worldBounds(occ);
    const double H = scene.light.position.y;
    const double a = 0.5 * (box_.hi.x - box_.lo.x);
    half_ = a * H / (H - box_.hi.y);
    // The shadow-map texel on the ground: the light frustum's width at distance H over N.
    const double texel =
        2.0 * H * std::tan(glm::radians(scene.light.coneDegrees) / 2.0) / mapTexels;
    band_ = bandTexels * texel;
    texel_ = texel;
    const Bounds ground = worldBounds(scene.objects.at(0));
    groundHalf_ = ground.hi.x;
    inverse_ = glm::inverse(cameraProjection(scene.camera, float(width) / float(height)) *
                            cameraView(scene.camera));
  }

  Geometry::Kind classify(double px, double py) const {
    const glm::vec4 a =
        inverse_ * glm::vec4(float(2 * px / width_ - 1), float(2 * py / height_ - 1), -1, 1);
    const glm::vec4 b =
        inverse_ * glm::vec4(float(2 * px / width_ - 1), float(2 * py / height_ - 1), 1, 1);
    const glm::dvec3 o = glm::dvec3(a) / double(a.w);
    const glm::dvec3 d = glm::normalize(glm::dvec3(b) / double(b.w) - o);
    // Slab test against the occluder box.
    double t0 = 0, t1 = 1e30;
    for (int i = 0; i < 3; ++i) {
      const double inv = 1.0 / d[i];
      double ta = (box_.lo[i] - o[i]) * inv, tb = (box_.hi[i] - o[i]) * inv;
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    if (t0 <= t1) return Geometry::kOccluder;
    if (d.y >= 0) return Geometry::kNothing;
    const glm::dvec3 p = o + d * (-o.y / d.y);
    if (std::fabs(p.x) > groundHalf_ || std::fabs(p.z) > groundHalf_) return Geometry::kNothing;
    const double m = std::max(std::fabs(p.x), std::fabs(p.z));
    if (std::fabs(m - half_) < band_) return Geometry::kNearBoundary;
    return m < half_ ? Geometry::kGroundShadow : Geometry::kGroundLit;
  }

  // Where the ground point seen at pixel centre (px, py) lies from the shadow square's outline,
  // in shadow-map texels projected to the ground (negative inside the shadow); nothing when the
  // ray meets the occluder or misses the ground.
  std::optional<double> texelsFromOutline(double px, double py) const {
    if (classify(px, py) == Geometry::kOccluder) return std::nullopt;
    const glm::vec4 a =
        inverse_ * glm::vec4(float(2 * px / width_ - 1), float(2 * py / height_ - 1), -1, 1);
    const glm::vec4 b =
        inverse_ * glm::vec4(float(2 * px / width_ - 1), float(2 * py / height_ - 1), 1, 1);
    const glm::dvec3 o = glm::dvec3(a) / double(a.w);
    const glm::dvec3 d = glm::normalize(glm::dvec3(b) / double(b.w) - o);
    if (d.y >= 0) return std::nullopt;
    const glm::dvec3 p = o + d * (-o.y / d.y);
    if (std::fabs(p.x) > groundHalf_ || std::fabs(p.z) > groundHalf_) return std::nullopt;
    return (std::max(std::fabs(p.x), std::fabs(p.z)) - half_) / texel_;
  }

  // The pixel's class when its centre and four corners agree, else kNearBoundary.
  Geometry::Kind pixel(int x, int y) const {
    const Geometry::Kind c = classify(x + 0.5, y + 0.5);
    for (const auto& [dx, dy] : {std::pair{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}})
      if (classify(x + dx, y + dy) != c) return Geometry::kNearBoundary;
    return c;
  }

 private:
  int width_, height_;
  Bounds box_;
  double half_ = 0, band_ = 0, groundHalf_ = 0, texel_ = 1;
  glm::mat4 inverse_;
};

void expectGeometricShadow(const Frame& f, double bandTexels, const std::string& what,
                           int mapTexels = kMapTexels) {
  const Scene scene = builtinScene("analytic");
  const AnalyticShadow exact(scene, kWidth, kHeight, bandTexels, mapTexels);
  long compared = 0, shadowed = 0, wrong = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const Geometry::Kind k = exact.pixel(x, y);
      if (k == Geometry::kNearBoundary) continue;
      const float expected = k == Geometry::kGroundShadow ? 0.0f : 1.0f;
      ++compared;
      shadowed += k == Geometry::kGroundShadow;
      // 1 - A/255 with A in {0, 255} is exact in float: no tolerance beyond float equality.
      if (f.visibility.at(x, y) != expected) {
        if (wrong < 5)
          ADD_FAILURE() << what << ": pixel (" << x << ", " << y << ") visibility "
                        << f.visibility.at(x, y) << ", exact shadow says " << expected;
        ++wrong;
      }
    }
  EXPECT_EQ(wrong, 0) << what;
  // Not vacuous: most of the window is compared and the shadow square is in view.
  EXPECT_GT(compared, long(kWidth) * kHeight / 2) << what;
  EXPECT_GT(shadowed, 2000) << what;
}

// Away from the boundary band, every variant's mask is exactly the geometric shadow. The band
// is two shadow-map texels (projected to the ground) wide on each side: nearest sampling puts
// a map sample up to half a texel from the point (ramp), PCF's samples lie inside the texel
// that holds the point (under one texel away), fast PCF 2x2's 2x2 block is centred within half
// a texel of the point (samples under 1.5 texels away).
TEST(BrabecSeidel, RampMaskEqualsGeometricShadowOnAnalyticScene) {
  std::vector<Backend> backends = {Backend::kOsmesa};
  if (testing::referenceAvailable()) backends.push_back(Backend::kReference);
  for (Backend b : backends)
    expectGeometricShadow(render("legacy.ramp", "analytic", params(b, 1)), 2.0,
                          std::string("legacy.ramp on ") + backendName(b));
  for (Precision p : {Precision::k12, Precision::kFloat})
    expectGeometricShadow(render("legacy.ramp", "analytic", params(Backend::kOsmesa, 1, p)), 2.0,
                          std::string("legacy.ramp at precision ") + precisionName(p));
}

TEST(BrabecSeidel, FilteredMasksEqualGeometricShadowOnAnalyticScene) {
  const auto backends = testing::imagingBackends();
  for (Backend b : backends) {
    const std::string on = std::string(" on ") + backendName(b);
    for (int filter : {2, 3, 4})
      expectGeometricShadow(render("legacy.pcf", "analytic", params(b, filter)), 2.0,
                            "legacy.pcf " + std::to_string(filter) + on);
    expectGeometricShadow(render("legacy.fast-pcf", "analytic", params(b, 2)), 2.0,
                          "legacy.fast-pcf 2x2" + on);
    // 4x4: the footprint's texel centres reach 2 texels from the point (x0 - 1.5 .. x0 + 1.5
    // around the texel corner x0 nearest the point), so the band needs more than 2 texels.
    expectGeometricShadow(render("legacy.fast-pcf", "analytic", params(b, 4)), 2.5,
                          "legacy.fast-pcf 4x4" + on);
  }
}

// The penumbra of a mask on the analytic scene: how wide it is across the shadow's outline, in
// shadow-map texels.
struct Penumbra {
  double widthTexels = 0;  // the 2nd to 98th percentile of the partial pixels' distances
  size_t pixels = 0;       // partial pixels on the ground
};

Penumbra penumbraOf(const Frame& f, int mapTexels) {
  const AnalyticShadow exact(builtinScene("analytic"), kWidth, kHeight, 0.0, mapTexels);
  std::vector<double> at;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const float v = f.visibility.at(x, y);
      if (v <= 0.0f || v >= 1.0f) continue;
      if (const auto d = exact.texelsFromOutline(x + 0.5, y + 0.5)) {
        at.push_back(*d);
      }
    }
  Penumbra p;
  p.pixels = at.size();
  if (at.empty()) return p;
  std::sort(at.begin(), at.end());
  // Percentiles, not the extremes: a pixel whose centre is a rasterisation tie away from the
  // outline would stretch the extremes without widening the edge anyone sees.
  constexpr double kTail = 0.02;
  const auto q = [&](double share) { return at[size_t(share * double(at.size() - 1))]; };
  p.widthTexels = q(1.0 - kTail) - q(kTail);
  return p;
}

// Brabec & Seidel §3 jitter the n x n samples inside one texel (Fig. 3): a 4x4 footprint adds
// levels (17 instead of 5; TwoByTwoFootprintsGiveFiveLevels and the 4x4 level tests), not width,
// so legacy.pcf's 2x2 and 4x4 edges are within a texel of
// each other. §4's fast PCF takes its samples from neighbouring texels, so its 4x4 edge is
// wider than its 2x2 one (two texels more in theory). The course's answers say both.
TEST(BrabecSeidel, PcfFootprintAddsLevelsNotWidthWhileFastPcfWidens) {
  // 64 texels: one texel spans several pixels on the ground, so widths are measurable.
  constexpr int kCoarseMap = 64;
  RenderParams p = params(Backend::kOsmesa, 2);
  p.shadowMapTexels = kCoarseMap;
  const auto penumbra = [&](const std::string& technique, int filter) {
    RenderParams q = p;
    q.filter = filter;
    return penumbraOf(render(technique, "analytic", q), kCoarseMap);
  };
  const Penumbra pcf2 = penumbra("legacy.pcf", 2), pcf4 = penumbra("legacy.pcf", 4);
  const Penumbra fast2 = penumbra("legacy.fast-pcf", 2), fast4 = penumbra("legacy.fast-pcf", 4);
  for (const Penumbra* q : {&pcf2, &pcf4, &fast2, &fast4}) EXPECT_GT(q->pixels, 200u);
  // "Within a texel": the sample spread grows from 1/2 to 3/4 of a texel (Fig. 3's grid).
  EXPECT_LT(std::fabs(pcf4.widthTexels - pcf2.widthTexels), 1.0)
      << "legacy.pcf 2x2 " << pcf2.widthTexels << " texels, 4x4 " << pcf4.widthTexels;
  // Fast PCF's 4x4 block spans two texels more than its 2x2 block; more than one is required.
  EXPECT_GT(fast4.widthTexels - fast2.widthTexels, 1.0)
      << "fast PCF 2x2 " << fast2.widthTexels << " texels, 4x4 " << fast4.widthTexels;
}

// A map larger than the window goes through legacy_gl's LightTarget framebuffer object
// (DEVIATION in fixed_function.h); the mask is still the exact shadow outside the band.
TEST(BrabecSeidel, MapLargerThanTheWindowRendersOffscreen) {
  constexpr int kLargeMap = 512;  // > kHeight
  std::vector<Backend> backends = {Backend::kOsmesa};
  if (testing::referenceAvailable()) backends.push_back(Backend::kReference);
  for (Backend b : backends) {
    RenderParams p = params(b, 1);
    p.shadowMapTexels = kLargeMap;
    expectGeometricShadow(render("legacy.ramp", "analytic", p), 2.0,
                          std::string("legacy.ramp 512 map on ") + backendName(b), kLargeMap);
  }
  for (Backend b : testing::imagingBackends()) {
    RenderParams p = params(b, 2);
    p.shadowMapTexels = kLargeMap;
    expectGeometricShadow(render("legacy.fast-pcf", "analytic", p), 2.0,
                          std::string("legacy.fast-pcf 512 map on ") + backendName(b), kLargeMap);
  }
}

// ------------------------------------------------------------------ 8-bit arithmetic model

// §3 step by step for PCF 2x2, modelled in integers as the paper's 8-bit hardware computes it:
// camera value = round(255 (d - bias)) from the ramp, difference = max(0, camera - map texel)
// per channel (blending unit), alpha = sum of 64/64/64/63 over channels with difference > 0
// (colour table then colour matrix). Checked bit for bit on every pixel where the model's
// inputs are unambiguous (texel and rounding decisions not within 5 % of a boundary).
TEST(BrabecSeidel, EightBitModelMatchesPipelineBitForBit) {
  const auto backends = testing::imagingBackends();
  namespace bs = legacy::bs;
  for (Backend backend : backends) {
    SCOPED_TRACE(backendName(backend));
    const Scene scene = builtinScene("brabec");
    RenderParams p = params(backend, 2);
    ContextSpec spec;
    spec.backend = backend;
    spec.width = p.width;
    spec.height = p.height;
    auto ctx = GlContext::create(spec);
    imaging::install(*ctx);
    const bs::DepthEncoding enc = bs::depthEncoding(Precision::k8);
    const double bias = bs::depthBias(p, enc);
    bs::RampTexture ramp;
    bs::createRampTexture(ramp, enc);
    bs::ShadowMapTexture map;
    bs::allocateShadowMap(map, enc, kMapTexels);
    // Fig. 3: the 2x2 sub-texel samples, R lower left, G lower right, B upper left, A upper right.
    const glm::vec2 sub[4] = {{-0.25f, -0.25f}, {0.25f, -0.25f}, {-0.25f, 0.25f}, {0.25f, 0.25f}};
    for (int c = 0; c < 4; ++c)
      bs::renderLightDepth(scene, enc, ramp, kMapTexels, -sub[c], bs::onlyChannel(c), c == 0);
    bs::copyLightPassToMap(map, kMapTexels);
    std::vector<uint8_t> mapTexels(size_t(kMapTexels) * kMapTexels * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, mapTexels.data());

    auto readRgba = [&] {
      std::vector<uint8_t> v(size_t(kWidth) * kHeight * 4);
      glReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_UNSIGNED_BYTE, v.data());
      return v;
    };
    bs::renderCameraDepth(scene, p, enc, ramp, bias, bs::kAllChannels);
    const auto camera = readRgba();
    std::vector<float> depth(size_t(kWidth) * kHeight);
    glReadPixels(0, 0, kWidth, kHeight, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
    bs::subtractProjectedMap(scene, p, map, glm::vec2(0.0f), bs::kAllChannels);
    const auto difference = readRgba();
    bs::countShadowSamplesByCopy(p, enc, 4);
    const auto counted = readRgba();
    ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));

    const glm::mat4 projInv = glm::inverse(cameraProjection(scene.camera, float(kWidth) / kHeight));
    const glm::mat4 toMap = legacy::cameraEyeToShadowMap(scene, kMapTexels);
    const glm::mat4 eyeToWorld = glm::inverse(cameraView(scene.camera));
    const glm::vec3 axis = glm::normalize(scene.light.target - scene.light.position);
    const DepthRange range = lightDepthRange(scene);
    // A texel or rounding decision this close to its boundary may go either way: rasterisers
    // interpolate texture coordinates in float per fragment (Mesa 7.8 was seen 0.024 texel off
    // the exact perspective value), not in the double precision of this model.
    constexpr double kDecisionMargin = 0.05;
    auto ambiguous = [](double v) {
      const double f = v - std::floor(v);
      return f < kDecisionMargin || f > 1.0 - kDecisionMargin;
    };
    long modelled = 0, covered = 0, shadowedSamples = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const size_t i = size_t(y) * kWidth + x;
        // Colour table + colour matrix: on every pixel, from the GL's own differences.
        int alpha = 0;
        for (int c = 0; c < 4; ++c) alpha += difference[i * 4 + c] > 0 ? (c == 3 ? 63 : 64) : 0;
        ASSERT_EQ(int(counted[i * 4 + 3]), alpha) << "colour table/matrix at " << x << "," << y;
        if (depth[i] >= 1.0f) continue;  // background
        ++covered;
        const glm::vec4 ndc(2.0f * (x + 0.5f) / kWidth - 1, 2.0f * (y + 0.5f) / kHeight - 1,
                            2.0f * depth[i] - 1, 1);
        glm::vec4 eye = projInv * ndc;
        eye /= eye.w;
        const glm::vec4 tc = toMap * eye;
        const double u = tc.x / tc.w * kMapTexels, v = tc.y / tc.w * kMapTexels;
        const glm::vec3 world(eyeToWorld * eye);
        const double d = (glm::dot(world - scene.light.position, axis) - range.nearPlane) /
                         (range.farPlane - range.nearPlane);
        const double ramp255 = 255.0 * (d - bias) + 0.5;  // floor() of this = the ramp texel
        if (ambiguous(u) || ambiguous(v) || ambiguous(ramp255)) continue;
        const int cam = std::clamp(int(std::floor(ramp255)), 0, 255);
        const int tu = int(std::floor(u)), tv = int(std::floor(v));
        const bool inside = tu >= 0 && tv >= 0 && tu < kMapTexels && tv < kMapTexels;
        for (int c = 0; c < 4; ++c) {
          ASSERT_EQ(int(camera[i * 4 + c]), cam) << "ramp value at " << x << "," << y;
          const int stored = inside ? mapTexels[(size_t(tv) * kMapTexels + tu) * 4 + c] : 255;
          const int diff = std::max(0, cam - stored);
          ASSERT_EQ(int(difference[i * 4 + c]), diff)
              << "subtraction at " << x << "," << y << " channel " << c << " u " << u << " v " << v
              << " camera " << cam << " texel " << stored << " right "
              << int(mapTexels[(size_t(tv) * kMapTexels + tu + 1) * 4 + c]) << " up "
              << int(mapTexels[(size_t(tv + 1) * kMapTexels + tu) * 4 + c]) << " left "
              << int(mapTexels[(size_t(tv) * kMapTexels + tu - 1) * 4 + c]) << " down "
              << int(mapTexels[(size_t(tv - 1) * kMapTexels + tu) * 4 + c]);
          shadowedSamples += diff > 0;
        }
        ++modelled;
      }
    // Most covered pixels are modelled: three decisions (u, v, ramp rounding) each excluded in
    // 10 % of cases leave about 0.9^3 = 73 %. And the model saw shadow, not only lit pixels.
    EXPECT_GT(modelled, covered * 6 / 10);
    EXPECT_GT(shadowedSamples, 1000);
  }
}

// §4 Fig. 5: the copy through the packing convolution gives texel (x, y) the channels
// R = light(x-1+ox, y-1+oy).r, G = light(x+ox, y-1+oy).g, B = light(x-1+ox, y+oy).b,
// A = light(x+ox, y+oy).a of the unpacked light image (outside it: the far plane, 255),
// bit for bit, for Eq. (1) (ox = oy = 0) and the three moved kernels of the 4x4 phases.
TEST(BrabecSeidel, PackingConvolutionGathersTheTwoByTwoBlock) {
  const auto backends = testing::imagingBackends();
  namespace bs = legacy::bs;
  for (Backend backend : backends) {
    SCOPED_TRACE(backendName(backend));
    const Scene scene = builtinScene("brabec");
    ContextSpec spec;
    spec.backend = backend;
    spec.width = kWidth;
    spec.height = kHeight;
    auto ctx = GlContext::create(spec);
    imaging::install(*ctx);
    const bs::DepthEncoding enc = bs::depthEncoding(Precision::k8);
    bs::RampTexture ramp;
    bs::createRampTexture(ramp, enc);
    // A light image whose four channels differ (four jittered passes), so that a channel taken
    // from the wrong neighbour or the wrong channel shows.
    const glm::vec2 sub[4] = {{-0.25f, -0.25f}, {0.25f, -0.25f}, {-0.25f, 0.25f}, {0.25f, 0.25f}};
    for (int c = 0; c < 4; ++c)
      bs::renderLightDepth(scene, enc, ramp, kMapTexels, -sub[c], bs::onlyChannel(c), c == 0);
    const size_t n = kMapTexels;
    std::vector<uint8_t> light(n * n * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, kMapTexels, kMapTexels, GL_RGBA, GL_UNSIGNED_BYTE, light.data());
    auto at = [&](int x, int y, int c) -> int {
      if (x < 0 || y < 0 || x >= kMapTexels || y >= kMapTexels) return 255;  // far border
      return light[(size_t(y) * n + size_t(x)) * 4 + size_t(c)];
    };
    for (const glm::ivec2 o :
         {glm::ivec2(0, 0), glm::ivec2(1, 0), glm::ivec2(0, 1), glm::ivec2(1, 1)}) {
      bs::ShadowMapTexture map;
      bs::allocateShadowMap(map, enc, kMapTexels);
      bs::copyLightPassToMapPacked(map, kMapTexels, o);
      std::vector<uint8_t> packed(n * n * 4);
      glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, packed.data());
      ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));
      long wrong = 0, differingNeighbours = 0;
      for (int y = 0; y < kMapTexels; ++y)
        for (int x = 0; x < kMapTexels; ++x) {
          const int expected[4] = {at(x - 1 + o.x, y - 1 + o.y, 0), at(x + o.x, y - 1 + o.y, 1),
                                   at(x - 1 + o.x, y + o.y, 2), at(x + o.x, y + o.y, 3)};
          for (int c = 0; c < 4; ++c) {
            wrong += packed[(size_t(y) * n + size_t(x)) * 4 + size_t(c)] != expected[c];
            differingNeighbours += expected[c] != at(x, y, c);
          }
        }
      EXPECT_EQ(wrong, 0) << "kernel offset " << o.x << "," << o.y;
      EXPECT_GT(differingNeighbours, 1000) << "the test image must tell neighbours apart";
    }
  }
}

// ------------------------------------------------------------------ precision

// §6: 12-bit channels (Octane VPro) as a 16-bit buffer holding 12-bit steps: every encoded
// depth of the camera pass is k / 4095, and finer than 8 bits.
TEST(BrabecSeidel, TwelveBitPrecisionQuantisesDepthTo4096Steps) {
  RenderParams p = params(Backend::kOsmesa, 1, Precision::k12);
  p.capturePasses = true;
  const Frame f = render("legacy.ramp", "brabec", p);
  const Image* cameraPass = nullptr;
  for (const PassImage& i : f.intermediates)
    if (i.name == "2-camera-pass-ramp-depth-alpha") cameraPass = &i.image;
  ASSERT_NE(cameraPass, nullptr);
  std::set<long> steps;
  long wrong = 0;
  for (float v : cameraPass->data) {
    // The 16-bit value is k / 4095 rounded to 16 bits: one of the two 16-bit neighbours of the
    // exact k * 65535 / 4095 (a near-tie may round either way in the float upload).
    const long k = std::lround(double(v) * 4095.0);
    const long stored = std::lround(double(v) * 65535.0);
    const double exact = double(k) * 65535.0 / 4095.0;
    if (stored != long(std::floor(exact)) && stored != long(std::ceil(exact))) ++wrong;
    steps.insert(k);
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(steps.size(), 256u) << "no finer than 8 bits";
}

// ------------------------------------------------------------------ input errors

TEST(BrabecSeidel, ImpossibleFootprintsAreInputErrors) {
  EXPECT_THROW(render("legacy.fast-pcf", "analytic", params(Backend::kOsmesa, 3)), InputError);
  EXPECT_THROW(render("legacy.pcf", "analytic", params(Backend::kOsmesa, 5)), InputError);
  RenderParams p = params(Backend::kOsmesa, 1);
  p.extra["depth-bias"] = "-1";
  EXPECT_THROW(render("legacy.ramp", "analytic", p), InputError);
}

// --dump-passes: the pictures a student follows, named by pass.
TEST(BrabecSeidel, DumpPassesNamesEveryIntermediate) {
  RenderParams p = params(Backend::kOsmesa, 1);
  p.capturePasses = true;
  const Frame f = render("legacy.ramp", "analytic", p);
  std::set<std::string> names;
  for (const PassImage& i : f.intermediates) {
    names.insert(i.name);
    EXPECT_TRUE(allFinite(i.image)) << i.name;
    EXPECT_FALSE(i.caption.empty()) << i.name;
  }
  for (const char* n : {"1-light-pass-ramp-depth-alpha", "2-camera-pass-ramp-depth-alpha",
                        "3-difference-alpha", "4-shadow-mask-alpha", "5-shaded"})
    EXPECT_TRUE(names.count(n)) << n;
}

}  // namespace
}  // namespace sl

namespace sl {
namespace {

// The packing figure (brabec-fig5-packing) shows Fig. 5's one-texel shift as the
// packed map's G, B and A channels minus its R channel, the lower left of each texel's 2x2 block
// (the texel's own depth is A). With one light pass in all four channels, the lower-right
// channel of texel (x, y) is the lower-left depth of texel (x + 1, y), the upper-left that of
// (x, y + 1), the upper-right that of (x + 1, y + 1); the view must be
// 0.5 + 32 (that depth - R), clamped, computed here from the R panel of the captured map.
TEST(BrabecSeidel, ShiftViewIsTheOneTexelShiftOfFigureFive) {
  RenderParams p = params(Backend::kOsmesa, 2);
  p.capturePasses = true;
  const Frame f = render("legacy.fast-pcf", "brabec", p);
  const Image* packed = nullptr;
  const Image* view = nullptr;
  for (const PassImage& pass : f.intermediates) {
    if (pass.name.rfind("2-packed-shadow-map", 0) == 0) packed = &pass.image;
    if (pass.name.rfind("2-packed-neighbours-minus-lower-left", 0) == 0) view = &pass.image;
  }
  ASSERT_NE(packed, nullptr);
  ASSERT_NE(view, nullptr);
  constexpr int kPanelGap = 4;         // sideBySide's default gap (core/base/image.h)
  constexpr float kGain = 32.0f;       // the view's amplification (legacy_gl/fast_pcf.cpp)
  constexpr float kTolerance = 1e-5f;  // float arithmetic on the same stored values
  const int n = kMapTexels;
  ASSERT_EQ(view->width, 3 * n + 2 * kPanelGap);
  const auto own = [&](int x, int y) { return packed->at(x, y, 0); };  // R panel of the strip
  const glm::ivec2 neighbour[3] = {{1, 0}, {0, 1}, {1, 1}};            // G, B, A
  long wrong = 0, notGrey = 0;
  for (int k = 0; k < 3; ++k)
    for (int y = 0; y + 1 < n; ++y)
      for (int x = 0; x + 1 < n; ++x) {
        const float expected = std::clamp(
            0.5f + kGain * (own(x + neighbour[k].x, y + neighbour[k].y) - own(x, y)), 0.0f, 1.0f);
        const float shown = view->at(k * (n + kPanelGap) + x, y, 0);
        wrong += std::fabs(shown - expected) > kTolerance;
        notGrey += std::fabs(shown - 0.5f) > kTolerance;
      }
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(notGrey, 1000) << "the depth edges of the brabec scene must show";
}

}  // namespace
}  // namespace sl

namespace sl {
namespace {

// The figure brabec-fig8 (a) shows light under the teapot's base. The cause is the depth bias of
// the 8-bit method, not a bug: receivers within two 8-bit steps (1/255 of the light's fitted
// depth range each) below a caster count as lit, and next to the base the teapot's lowest body
// is that close to the ground. The same 12-bit frame with the bias in 12-bit steps (2 steps =
// 0.125 8-bit steps) has almost no such pixels. Counted: pixels lit in legacy.ramp that both
// the ray tracer and legacy.hw (24-bit depth, polygon offset) put in shadow.
TEST(BrabecSeidel, TeapotContactLeakIsTheEightBitDepthBias) {
  const Scene scene = loadScene("teapot");
  RenderParams p;
  p.width = 800;  // brabec-fig8's size and map
  p.height = 600;
  p.shadowMapTexels = 1024;
  const Frame reference = renderTechnique(findTechnique("reference.hard"), scene, p);
  const Frame hw = renderTechnique(findTechnique("legacy.hw"), scene, p);
  const auto leaks = [&](const Frame& f) {
    long n = 0;
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x)
        n += f.visibility.at(x, y) > 0.5f && reference.visibility.at(x, y) < 0.5f &&
             hw.visibility.at(x, y) < 0.5f;
    return n;
  };
  const long eightBit = leaks(renderTechnique(findTechnique("legacy.ramp"), scene, p));
  RenderParams twelve = p;
  twelve.precision = Precision::k12;
  twelve.extra = {{"depth-bias", "0.125"}};  // two 12-bit steps, in the parameter's 8-bit unit
  const long twelveBit = leaks(renderTechnique(findTechnique("legacy.ramp"), scene, twelve));
  // Measured 1013 against 54 (2026-12-02): the leak must be there at 8 bits (else the page's
  // explanation is stale) and at least 5 times smaller with the 12-bit bias.
  EXPECT_GT(eightBit, 200);
  EXPECT_GT(eightBit, 5 * twelveBit) << "8-bit " << eightBit << ", 12-bit " << twelveBit;
}

}  // namespace
}  // namespace sl
