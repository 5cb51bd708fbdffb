// reference.hard and reference.soft against answers computed independently of any renderer:
// the analytic scene's shadow follows from similar triangles (hard) and from the area of a
// disk cut by a line (soft).
#include "reference/reference.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <iostream>
#include <optional>

#include "core/base/errors.h"
#include "core/scene/primitives.h"
#include "core/scene/scene_library.h"
#include "core/technique/pass_table.h"
#include "registry/registry.h"

namespace sl {
namespace {

constexpr int kWidth = 400;  // small window: the whole suite stays within seconds
constexpr int kHeight = 300;

// The analytic scene's geometry (core/scene/scene_library.cpp analyticScene): light 4 units above
// the plane y = 0, a 1 x 0.02 x 1 box centred 1 unit above it, ground 6 x 6.
constexpr float kLightHeight = 4.0f;
constexpr float kOccluderHalf = 0.5f;
constexpr float kOccluderTop = 1.01f;
constexpr float kOccluderBottom = 0.99f;
constexpr float kGroundHalf = 3.0f;

RenderParams smallParams() {
  RenderParams p;
  p.width = kWidth;
  p.height = kHeight;
  return p;
}

void save(const Frame& f, const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(SHADOWLAB_TEST_OUTPUT_DIR) / "reference";
  std::filesystem::create_directories(dir);
  writePng((dir / (name + ".png")).string(), f.color);
  writePng((dir / (name + "-mask.png")).string(), f.visibility, 16);
}

// The world-space ray through window position (wx, wy) of the scene's camera.
struct Ray {
  glm::vec3 origin, direction;
};
Ray cameraRay(const Scene& s, float wx, float wy) {
  const glm::mat4 view = cameraView(s.camera);
  const glm::mat4 proj = cameraProjection(s.camera, float(kWidth) / float(kHeight));
  const glm::vec4 viewport(0, 0, kWidth, kHeight);
  const glm::vec3 nearPoint = glm::unProject(glm::vec3(wx, wy, 0.0f), view, proj, viewport);
  const glm::vec3 farPoint = glm::unProject(glm::vec3(wx, wy, 1.0f), view, proj, viewport);
  return {nearPoint, glm::normalize(farPoint - nearPoint)};
}

std::optional<glm::vec3> hitPlaneY(const Ray& r, float y) {
  if (std::fabs(r.direction.y) < 1e-9f) return std::nullopt;
  const float t = (y - r.origin.y) / r.direction.y;
  if (t <= 0) return std::nullopt;
  return r.origin + t * r.direction;
}

// What the camera sees at a window position: 'o' occluder (a non-receiver: lit), 's' ground in
// the exact shadow, 'l' lit ground, 'n' nothing. The occluder's top face is the first thing a
// ray from above meets; its side faces are 0.02 high and covered by the corner test below.
char classify(const Scene& s, float wx, float wy) {
  const Ray r = cameraRay(s, wx, wy);
  for (float y : {kOccluderTop, kOccluderBottom})
    if (auto p = hitPlaneY(r, y))
      if (std::fabs(p->x) <= kOccluderHalf && std::fabs(p->z) <= kOccluderHalf) return 'o';
  auto g = hitPlaneY(r, 0.0f);
  if (!g || std::fabs(g->x) > kGroundHalf || std::fabs(g->z) > kGroundHalf) return 'n';
  // Similar triangles: the box's top face (nearest the light) casts the largest square,
  // half side 0.5 * 4 / (4 - 1.01).
  const float half = kOccluderHalf * kLightHeight / (kLightHeight - kOccluderTop);
  return std::fabs(g->x) < half && std::fabs(g->z) < half ? 's' : 'l';
}

TEST(ReferenceHard, AnalyticShadowSquareMatchesSimilarTriangles) {
  const Scene scene = builtinScene("analytic");
  const Frame f = renderTechnique(findTechnique("reference.hard"), scene, smallParams());
  save(f, "hard-analytic");
  ASSERT_EQ(f.visibility.width, kWidth);
  int checked = 0, shadowed = 0, wrong = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      // A pixel counts only when its centre and its four corners see the same thing: pixels
      // straddling the shadow edge or the occluder's outline are left out.
      const char c = classify(scene, x + 0.5f, y + 0.5f);
      bool uniform = true;
      for (float dx : {0.0f, 1.0f})
        for (float dy : {0.0f, 1.0f}) uniform = uniform && classify(scene, x + dx, y + dy) == c;
      if (!uniform) continue;
      const float expected = c == 's' ? 0.0f : 1.0f;
      ++checked;
      shadowed += c == 's';
      if (f.visibility.at(x, y) != expected) ++wrong;
    }
  EXPECT_GT(shadowed, 1000) << "the shadow square must be in view";
  EXPECT_GT(checked, kWidth * kHeight * 9 / 10);
  // Exact: away from the edge, one ray per pixel decides visibility with no tolerance.
  EXPECT_EQ(wrong, 0) << "of " << checked << " pixels";
}

TEST(ReferenceHard, OnlyValuesZeroOrOneAndEmptyPixelsLit) {
  Scene scene = builtinScene("brabec");
  scene.camera.fovyDegrees = 80;  // the background is in view
  const Frame f = renderTechnique(findTechnique("reference.hard"), scene, smallParams());
  EXPECT_EQ(f.visibility.at(0, kHeight - 1), 1.0f) << "top-left corner sees the sky";
  int zeros = 0;
  for (float v : f.visibility.data) {
    ASSERT_TRUE(v == 0.0f || v == 1.0f);
    zeros += v == 0.0f;
  }
  EXPECT_GT(zeros, 100);
  EXPECT_TRUE(allFinite(f.color));
}

// A light of radius 0 is a point: every soft ray goes to the centre, so soft == hard exactly.
TEST(ReferenceSoft, ZeroRadiusEqualsHard) {
  Scene scene = builtinScene("brabec");
  scene.light.radius = 0.0f;
  RenderParams p = smallParams();
  p.extra["rays"] = "8";
  const Frame soft = renderTechnique(findTechnique("reference.soft"), scene, p);
  const Frame hard = renderTechnique(findTechnique("reference.hard"), scene, smallParams());
  ASSERT_EQ(soft.visibility.data.size(), hard.visibility.data.size());
  EXPECT_EQ(soft.visibility.data, hard.visibility.data);
}

// Visible fraction of a unit disk beyond a chord at signed offset t (t = -1: all, t = 1: none).
double diskFractionBeyond(double t) {
  t = std::clamp(t, -1.0, 1.0);
  return (std::acos(t) - t * std::sqrt(1.0 - t * t)) / M_PI;
}

// The t at which diskFractionBeyond(t) == fraction (bisection; the function decreases).
double chordForFraction(double fraction) {
  double lo = -1, hi = 1;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (diskFractionBeyond(mid) > fraction ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

struct Sample {
  double x;  // ground position across the right shadow edge
  double v;  // reference.soft visibility
};

TEST(ReferenceSoft, AnalyticPenumbraWidthMatchesGeometry) {
  Scene scene = builtinScene("analytic");
  constexpr float kRadius = 0.5f;  // wide penumbra: about 20 pixels at 400x300
  scene.light.radius = kRadius;
  const Frame f = renderTechnique(findTechnique("reference.soft"), scene, smallParams());
  save(f, "soft-analytic");
  // Ground pixels across the right edge (x > 0), away from the square's corners (|z| < 0.3:
  // the corner penumbrae start at |z| = 0.57).
  std::vector<Sample> samples;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      if (classify(scene, x + 0.5f, y + 0.5f) == 'o') continue;
      auto g = hitPlaneY(cameraRay(scene, x + 0.5f, y + 0.5f), 0.0f);
      if (!g || std::fabs(g->z) > 0.3f || g->x < 0.4f || g->x > 1.0f) continue;
      samples.push_back({g->x, f.visibility.at(x, y)});
    }
  ASSERT_GT(samples.size(), 200u);

  // Geometry (similar triangles through the occluder's top edge at height h = 1.01, light
  // disk of radius r at height H = 4): the line from ground point x over the edge reaches the
  // light's height at x_c = x + (0.5 - x) H / h; the light is visible beyond x_c. The
  // penumbra spans x_c in [-r, r], i.e. a width W = 2 r h / (H - h) = 2 r (H - h_o) / h_o
  // measured from the light (h_o = H - h: the classic formula w = r_L (d_r - d_o) / d_o).
  const double H = kLightHeight, h = kOccluderTop, r = kRadius;
  auto chordAt = [&](double x) { return (x + (kOccluderHalf - x) * H / h) / r; };
  const double width = 2.0 * r * h / (H - h);

  // Measured: where the visibility crosses 10% and 90% (averaged over the pixels nearest each
  // crossing) against where the disk-segment profile crosses them.
  auto crossing = [&](double level) {
    double sum = 0;
    int n = 0;
    for (const Sample& s : samples)
      if (std::fabs(s.v - level) < 0.05) sum += s.x, ++n;
    EXPECT_GT(n, 3) << "level " << level;
    return n ? sum / n : 0.0;
  };
  // x where chordAt(x) == t: chordAt is linear, x = (t r - 0.5 H / h) / (1 - H / h).
  auto xForChord = [&](double t) { return (t * r - kOccluderHalf * H / h) / (1.0 - H / h); };
  const double expected1090 = xForChord(chordForFraction(0.9)) - xForChord(chordForFraction(0.1));
  const double measured1090 = crossing(0.9) - crossing(0.1);
  // Bound 8%: the light disk faces each point instead of lying horizontal (its extent along x
  // shrinks by cos 9.5 degrees: 1.4%), the 0.1-wide bands around each level average pixels on
  // a curve (about 3% of the 10-90 width for this slope) and the Monte Carlo noise (standard
  // error 0.012, i.e. 0.004 units at this slope: 3%).
  std::cout << "penumbra 10-90 width: measured " << measured1090 << ", expected " << expected1090
            << " (full width W = " << width << ")\n";
  EXPECT_NEAR(measured1090, expected1090, 0.08 * expected1090)
      << "full penumbra width W = " << width;
  EXPECT_NEAR(expected1090 / width, 0.687, 0.001) << "disk-segment 10-90 share of W";

  // Pointwise: every pixel's visibility against the disk-segment profile. Bound 0.1: 4
  // standard errors of the estimator (4 x 0.012) plus the slope times the tilt shift (a
  // position error of 1.4% of W = 0.005 units times a slope of at most 4 / (pi W / 2)... = 0.03)
  // plus margin for the occluder's 0.02 thickness (which edge bounds the umbra side).
  double worst = 0;
  for (const Sample& s : samples)
    worst = std::max(worst, std::fabs(s.v - diskFractionBeyond(chordAt(s.x))));
  std::cout << "largest |visibility - disk-segment profile|: " << worst << "\n";
  EXPECT_LT(worst, 0.1);
}

TEST(ReferenceSoft, NoiseEstimateBelowStatedBound) {
  Scene scene = builtinScene("brabec");
  scene.light.radius = 0.2f;
  const Frame f = renderTechnique(findTechnique("reference.soft"), scene, smallParams());
  save(f, "soft-brabec");
  ASSERT_TRUE(f.counters.count("noise_rms_standard_error"));
  EXPECT_EQ(f.counters.at("rays_per_pixel"), reference::kDefaultSoftRays);
  EXPECT_GT(f.counters.at("penumbra_pixels"), 500);
  // Bound: each half is a mean over n^2 strata of which a shadow edge crosses at most about
  // 2n, each a Bernoulli variable of variance <= 1/4: Var(half) <= 2n / (4 n^4) = 1 / (2 n^3);
  // the mask averages two halves: standard error <= 1 / (2 n^1.5) = 0.012 for n = 12.
  const double n = reference::kDefaultSoftStrataPerSide;
  const double bound = 1.0 / (2.0 * std::pow(n, 1.5));
  std::cout << "estimated standard error: RMS " << f.counters.at("noise_rms_standard_error")
            << ", max " << f.counters.at("noise_max_standard_error") << ", bound " << bound << "\n";
  EXPECT_LT(f.counters.at("noise_rms_standard_error"), bound);
  for (float v : f.visibility.data) ASSERT_TRUE(v >= 0.0f && v <= 1.0f);
}

// ---- The pixel-integrated forms (--param pixel=area) ----------------------------

namespace area {

RenderParams areaParams(int perSide = 0) {
  RenderParams p = smallParams();
  p.extra[reference::kPixelParam] = reference::kPixelArea;
  if (perSide > 0) p.extra[reference::kPixelSamplesParam] = std::to_string(perSide);
  return p;
}

// The ground point seen at window position (wx, wy), or nothing when the ray meets the
// occluder first or misses the ground (classify's geometry, with the camera matrices inverted
// once: the fine integrals below call it millions of times).
struct GroundView {
  glm::mat4 inverse;
  explicit GroundView(const Scene& s)
      : inverse(glm::inverse(cameraProjection(s.camera, float(kWidth) / float(kHeight)) *
                             cameraView(s.camera))) {}
  std::optional<glm::vec3> ground(float wx, float wy) const {
    const glm::vec2 ndc(2.0f * wx / kWidth - 1.0f, 2.0f * wy / kHeight - 1.0f);
    glm::vec4 n = inverse * glm::vec4(ndc, -1.0f, 1.0f), f = inverse * glm::vec4(ndc, 1.0f, 1.0f);
    const glm::vec3 a = glm::vec3(n) / n.w, b = glm::vec3(f) / f.w;
    const Ray r{a, glm::normalize(b - a)};
    for (float y : {kOccluderTop, kOccluderBottom})
      if (auto p = hitPlaneY(r, y))
        if (std::fabs(p->x) <= kOccluderHalf && std::fabs(p->z) <= kOccluderHalf)
          return std::nullopt;
    auto g = hitPlaneY(r, 0.0f);
    if (!g || std::fabs(g->x) > kGroundHalf || std::fabs(g->z) > kGroundHalf) return std::nullopt;
    return g;
  }
};

}  // namespace area

// pixel=area with one sample per pixel is the pixel centre: the same surface points, the same
// rays, the same mask bit for bit.
TEST(ReferenceArea, OneSampleEqualsPixelCentre) {
  const Scene scene = builtinScene("brabec");
  for (const char* name : {"reference.hard", "reference.soft"}) {
    RenderParams centre = smallParams(), one = area::areaParams(1);
    if (std::string(name) == "reference.soft") centre.extra["rays"] = one.extra["rays"] = "8";
    const Frame a = renderTechnique(findTechnique(name), scene, centre);
    const Frame b = renderTechnique(findTechnique(name), scene, one);
    if (std::string(name) == "reference.hard") {
      EXPECT_EQ(a.visibility.data, b.visibility.data) << name;
    } else {
      // Soft: the same origins, but the area form deals the light's strata with its own
      // random streams, so only the expectation agrees: check the lit and umbra pixels.
      int differ = 0;
      for (size_t i = 0; i < a.visibility.data.size(); ++i)
        differ += (a.visibility.data[i] == 1.0f) != (b.visibility.data[i] == 1.0f) &&
                  (a.visibility.data[i] == 0.0f || b.visibility.data[i] == 0.0f);
      EXPECT_EQ(differ, 0) << name << ": a pixel fully lit in one and in umbra in the other";
    }
  }
}

// At a straight shadow edge the 8 x 8 ordered grid gives the covered fraction of the pixel
// within 1/(2N) + 1/(4N^2) (reference.h: each of the N columns of samples errs by at most
// half a sample, the midpoint rule being exact for a linear edge; 1/(4N^2) for the columns
// where the edge leaves through the pixel's top or bottom). The covered fraction itself is
// integrated here on an M x M grid (M = 64), with the same bound 1/(2M) + 1/(4M^2).
TEST(ReferenceArea, StraightEdgeEqualsCoveredFraction) {
  const Scene scene = builtinScene("analytic");
  const Frame f = renderTechnique(findTechnique("reference.hard"), scene, area::areaParams());
  save(f, "hard-area-analytic");
  const area::GroundView view(scene);
  const float half = kOccluderHalf * kLightHeight / (kLightHeight - kOccluderTop);
  constexpr int kN = reference::kDefaultHardPixelSamplesPerSide;
  constexpr int kM = 64;
  const double bound =
      1.0 / (2 * kN) + 1.0 / (4.0 * kN * kN) + 1.0 / (2 * kM) + 1.0 / (4.0 * kM * kM);
  int edgePixels = 0;
  double worst = 0.0, sumCentreError = 0.0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      // Edge pixels of the two straight sides |x| = half, away from the corners (|z| < 0.8
      // half): corners are not straight edges, and pixels that see the occluder or miss the
      // ground are left out.
      const char corner = classify(scene, x + 0.5f, y + 0.5f);
      bool straddles = false, usable = corner == 's' || corner == 'l';
      for (float dx : {0.0f, 1.0f})
        for (float dy : {0.0f, 1.0f}) {
          const char c = classify(scene, x + dx, y + dy);
          usable = usable && (c == 's' || c == 'l');
          straddles = straddles || c != corner;
        }
      if (!usable || !straddles) continue;
      int lit = 0;
      bool straight = true;
      for (int i = 0; i < kM && straight; ++i)
        for (int j = 0; j < kM; ++j) {
          const auto g = view.ground(x + (i + 0.5f) / kM, y + (j + 0.5f) / kM);
          if (!g || std::fabs(g->z) > 0.8f * half) {
            straight = false;
            break;
          }
          lit += !(std::fabs(g->x) < half && std::fabs(g->z) < half);
        }
      if (!straight) continue;
      const double covered = double(lit) / (kM * kM);
      ++edgePixels;
      worst = std::max(worst, std::fabs(f.visibility.at(x, y) - covered));
      sumCentreError += std::fabs((corner == 's' ? 0.0 : 1.0) - covered);
    }
  std::cout << edgePixels << " edge pixels: largest |area visibility - covered fraction| " << worst
            << " (bound " << bound << "); the pixel centre errs by "
            << sumCentreError / std::max(edgePixels, 1) << " on average there\n";
  ASSERT_GT(edgePixels, 100) << "both straight sides of the shadow square must be in view";
  EXPECT_LE(worst, bound);
  // The bound is tight enough to tell: the pixel centre's 0/1 errs by far more on average.
  EXPECT_GT(sumCentreError / edgePixels, 2 * bound);
}

// The soft reference with sub-pixel origins against the disk-segment profile averaged over
// each pixel's ground footprint (8 x 8 points per pixel), at every pixel of the edge strip.
// Bound 0.1 as in AnalyticPenumbraWidthMatchesGeometry (4 standard errors, the disk's tilt,
// the occluder's thickness); the footprint average is exact to the 8 x 8 quadrature, whose
// error is at most the profile's slope times 1/16 pixel (0.004 here).
TEST(ReferenceArea, SoftJitteredMatchesDiskSegmentProfile) {
  Scene scene = builtinScene("analytic");
  constexpr float kRadius = 0.5f;
  scene.light.radius = kRadius;
  const Frame f = renderTechnique(findTechnique("reference.soft"), scene, area::areaParams());
  save(f, "soft-area-analytic");
  const area::GroundView view(scene);
  const double H = kLightHeight, h = kOccluderTop, r = kRadius;
  auto chordAt = [&](double x) { return (x + (kOccluderHalf - x) * H / h) / r; };
  constexpr int kQuadrature = 8;
  double worst = 0;
  int pixels = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      double expected = 0;
      bool inside = true;
      for (int i = 0; i < kQuadrature && inside; ++i)
        for (int j = 0; j < kQuadrature; ++j) {
          const auto g = view.ground(x + (i + 0.5f) / kQuadrature, y + (j + 0.5f) / kQuadrature);
          if (!g || std::fabs(g->z) > 0.3f || g->x < 0.4f || g->x > 1.0f) {
            inside = false;
            break;
          }
          expected += diskFractionBeyond(chordAt(g->x));
        }
      if (!inside) continue;
      expected /= kQuadrature * kQuadrature;
      ++pixels;
      worst = std::max(worst, std::fabs(f.visibility.at(x, y) - expected));
    }
  std::cout << pixels << " pixels: largest |visibility - pixel-averaged disk-segment profile| "
            << worst << "\n";
  ASSERT_GT(pixels, 200);
  EXPECT_LT(worst, 0.1);
  EXPECT_EQ(f.counters.at("pixel_samples"), 16.0);
  EXPECT_EQ(f.counters.at("rays_per_pixel"), reference::kDefaultSoftRays);
  // Bound of NoiseEstimateBelowStatedBound: the dealing keeps the halves independent.
  EXPECT_LT(f.counters.at("noise_rms_standard_error"),
            1.0 / (2.0 * std::pow(reference::kDefaultSoftStrataPerSide, 1.5)));
}

// A model matrix with a negative determinant reverses every triangle's winding,
// so gl_FrontFacing took a mirrored object's outside for its back, turned its normals inward
// and started the shadow rays inside it (its lit faces came out shadowed). The same geometry
// must give the same answer however it is mirrored.
namespace mirroring {

const Image* directLightRegion(const Frame& f) {
  for (const PassImage& p : f.intermediates)
    if (p.name == reference::kDirectLightRegionPass) return &p.image;
  return nullptr;
}

// An off-centre box (not mirror-symmetric about its own origin) floating over the ground.
Mesh offCentreBox() {
  Mesh m = makeBox({0.6f, 0.3f, 0.4f});
  for (glm::vec3& p : m.positions) p += glm::vec3(0.35f, 0.1f, -0.15f);
  return m;
}

// The mesh mirrored in x by rewriting it: positions and normals negated in x, and the corner
// order of every triangle reversed so that the outside stays counter-clockwise.
Mesh mirroredInX(Mesh m) {
  for (glm::vec3& p : m.positions) p.x = -p.x;
  for (glm::vec3& n : m.normals) n.x = -n.x;
  for (size_t t = 0; t + 2 < m.indices.size(); t += 3)
    std::swap(m.indices[t + 1], m.indices[t + 2]);
  return m;
}

Scene withCaster(const Mesh& mesh, const glm::mat4& model) {
  Scene s = builtinScene("analytic");
  Object o;
  o.name = "caster";
  o.mesh = std::make_shared<const Mesh>(mesh);
  o.model = model;
  s.objects.push_back(o);
  return s;
}

void expectSameReference(const Scene& a, const Scene& b, const std::string& what) {
  for (const char* name : {"reference.hard", "reference.soft"}) {
    RenderParams p = smallParams();
    p.capturePasses = true;  // the direct-light region (geometric normal . light) too
    if (name == std::string("reference.soft")) p.extra["rays"] = "16";  // seconds, not minutes
    const Frame fa = renderTechnique(findTechnique(name), a, p);
    const Frame fb = renderTechnique(findTechnique(name), b, p);
    // Exact: both scenes hold the same triangles with the same world-space corners (a scale by
    // -1 and a negation are exact in float), so every pixel meets the same surface point and
    // casts the same rays.
    EXPECT_EQ(fa.visibility.data, fb.visibility.data) << name << ", " << what;
    const Image* ra = directLightRegion(fa);
    const Image* rb = directLightRegion(fb);
    ASSERT_TRUE(ra && rb);
    EXPECT_EQ(ra->data, rb->data) << name << " direct-light region, " << what;
  }
}

}  // namespace mirroring

TEST(ReferenceMirroring, ModelMirrorEqualsRewrittenVertices) {
  const glm::mat4 place = glm::translate(glm::mat4(1.0f), {-0.2f, 1.8f, 0.3f});
  const Mesh box = mirroring::offCentreBox();
  const Scene byMatrix =
      mirroring::withCaster(box, glm::scale(place, glm::vec3(-1.0f, 1.0f, 1.0f)));
  const Scene byVertices = mirroring::withCaster(mirroring::mirroredInX(box), place);
  mirroring::expectSameReference(byMatrix, byVertices, "box mirrored by matrix vs by vertices");
}

// Mirror-symmetric objects (the analytic scene's ground and box are symmetric about their own
// origins) scaled by -1 are the very same geometry: the reference must not change at all.
TEST(ReferenceMirroring, SymmetricObjectsScaledByMinusOneChangeNothing) {
  const Scene plain = builtinScene("analytic");
  Scene mirrored = plain;
  const glm::vec3 flips[] = {{-1, 1, 1}, {1, 1, -1}};
  for (size_t i = 0; i < mirrored.objects.size(); ++i)
    mirrored.objects[i].model = glm::scale(mirrored.objects[i].model, flips[i % 2]);
  RenderParams p = smallParams();
  p.capturePasses = true;
  const Frame a = renderTechnique(findTechnique("reference.hard"), plain, p);
  const Frame b = renderTechnique(findTechnique("reference.hard"), mirrored, p);
  // The mirrored box and ground split their faces along the other diagonals, so surface points
  // differ in the last bits of float; no shadow ray grazes an edge in this scene (the edge band
  // of AnalyticShadowSquareMatchesSimilarTriangles holds no vertex), so the masks are equal.
  EXPECT_EQ(a.visibility.data, b.visibility.data);
  const Image* ra = mirroring::directLightRegion(a);
  const Image* rb = mirroring::directLightRegion(b);
  ASSERT_TRUE(ra && rb);
  EXPECT_EQ(ra->data, rb->data);
}

// pixel=area rasterises each sub-pixel position (3a) and casts its rays (3b) in turn: each is
// one pass of the frame however many positions there are, its pieces summed (Passes::resume),
// with the names the dump and the benches show. The references' tables are well formed.
TEST(ReferenceArea, SubPixelPassesAreOneEntryEach) {
  const Scene scene = builtinScene("analytic");
  for (const char* name : {"reference.hard", "reference.soft"}) {
    const Technique t = findTechnique(name);
    EXPECT_TRUE(passTableProblems(t.passes).empty()) << name;
    RenderParams p = area::areaParams(3);
    if (std::string(name) == "reference.soft") p.extra["rays"] = "8";
    const std::string rays =
        std::string(name) == "reference.soft" ? "soft shadow rays" : "shadow rays";
    std::vector<std::string> passes;
    for (const PassTime& pass : renderTechnique(t, scene, p).passes)
      passes.push_back(pass.id + ": " + pass.name);
    EXPECT_EQ(passes, (std::vector<std::string>{
                          "1: 1 surface points (GL)", "2: 2 build occluder BVH (Embree)",
                          "3a: 3a sub-pixel surface points (GL, 3x3)",
                          "3b: 3b " + rays + " from 3x3 sub-pixel points (Embree)", "4: 4 shade"}))
        << name;
  }
}

TEST(ReferenceArea, CentreIsTheDefaultAndBadValuesAreInputErrors) {
  const Scene scene = builtinScene("analytic");
  RenderParams centre = smallParams();
  centre.extra[reference::kPixelParam] = reference::kPixelCentre;
  const Frame a = renderTechnique(findTechnique("reference.hard"), scene, smallParams());
  const Frame b = renderTechnique(findTechnique("reference.hard"), scene, centre);
  EXPECT_EQ(a.visibility.data, b.visibility.data);
  RenderParams bad = smallParams();
  bad.extra[reference::kPixelParam] = "corner";
  EXPECT_THROW(renderTechnique(findTechnique("reference.hard"), scene, bad), InputError);
  bad = area::areaParams(reference::kMaxPixelSamplesPerSide + 1);
  EXPECT_THROW(renderTechnique(findTechnique("reference.hard"), scene, bad), InputError);
}

}  // namespace
}  // namespace sl
