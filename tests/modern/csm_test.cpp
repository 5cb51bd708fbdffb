// modern.csm (Annen et al. 2007) against the paper's formulas, evaluated here in C++.
//
// The analytic scene makes the expected shadow test exact: the light looks straight down, so
// every point of the ground has the same light depth, and so does every point of the top of
// the occluder. In the umbra the map holds the occluder's depth z, in the open the ground's
// own depth (z = d). The reconstruction there is then a number we can compute from Eq. 11:
//   f(t) = 1/2 + sum_{k=1..M} exp(-alpha (k/M)^2) (2/c_k) sin(c_k t),  c_k = pi (2k - 1),
// with t = z - d (the sign of Eq. 13 and of Eq. 1's f, 1 = lit) after the offset of §3.2.2
// (d -> d - offset), and visibility = clamp(scale f, 0, 1) (§3.2.2, §4.1). modern.csm stores
// linear depth (§4.1) scaled by (1 - offset) (docs/csm.md explains why), so
//   t = (1 - offset) (z_lin - d_lin) + offset.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <iostream>
#include <numbers>
#include <stdexcept>

#include "core/base/errors.h"
#include "core/scene/primitives.h"
#include "core/technique/pass_table.h"
#include "filtered_shadows_util.h"
#include "modern/convolution_shadow_map.h"
#include "modern/prefiltered_maps.h"

namespace sl {
namespace {
using namespace sl::testing_filtered;

// Eq. 11 with the attenuation of §3.2.1, written independently of modern/.
double eq11(double t, int order, double alpha) {
  double f = 0.5;
  for (int k = 1; k <= order; ++k) {
    const double ck = std::numbers::pi * (2 * k - 1);
    f += std::exp(-alpha * std::pow(double(k) / order, 2.0)) * 2.0 / ck * std::sin(ck * t);
  }
  return f;
}

// Bound on |f_8bit - f| when each basis value sin, cos in [-1, 1] is stored as an 8-bit
// unsigned normalised 0.5 + 0.5 v: the decoded v is off by at most 1/255 (half a step of
// 2/255), and each term weighs sin and cos by |cos(c_k d)| + |sin(c_k d)| <= sqrt(2).
double eightBitBound(int order, double alpha) {
  double bound = 0.0;
  for (int k = 1; k <= order; ++k) {
    const double ck = std::numbers::pi * (2 * k - 1);
    bound += std::exp(-alpha * std::pow(double(k) / order, 2.0)) * 2.0 / ck * std::sqrt(2.0);
  }
  return bound / 255.0;
}

struct AnalyticDepths {
  double ground = 0.0;    // linear light depth of the ground, d
  double open = 1.0;      // z where nothing blocks: the ground, or far (1) if it casts none
  double occluder = 0.0;  // linear light depth of the top of the occluder, z in the umbra
};

AnalyticDepths analyticDepths(const Scene& scene) {
  const DepthRange range = modern::csmDepthRange(scene);
  auto linear = [&](float y) {
    const glm::vec4 v = lightView(scene.light) * glm::vec4(0.0f, y, 0.0f, 1.0f);
    return (double(-v.z) - range.nearPlane) / (double(range.farPlane) - range.nearPlane);
  };
  AnalyticDepths d;
  for (const Object& o : scene.objects) {
    if (o.name == "ground") d.ground = linear(worldBounds(o).hi.y);
    if (o.name == "ground") d.open = o.castsShadow ? d.ground : 1.0;
    if (o.name == "occluder") d.occluder = linear(worldBounds(o).hi.y);
  }
  return d;
}

struct Case {
  int order;
  double alpha;
  double offset;
  double scale;
  std::string storage;
  std::string blur;
  std::string filtering;
};

// Eq. 11 itself: rendered with skip-error=0 (Eq. 13 at every pixel). With the default
// classification, a pixel the depth bounds decide gets the series at the depths around it,
// within the skip error of the filtered reconstruction wherever the footprint's
// depth varies, so `skipped` is also checked against the same value within the skip error
// (0.025, the default; docs/csm.md).
void expectMatchesEq11(const Case& c) {
  constexpr double kDefaultSkipError = 0.025;
  const Scene scene = builtinScene("analytic");
  RenderParams p = smallParams(160, 120, 256,
                               {{"order", std::to_string(c.order)},
                                {"alpha", std::to_string(c.alpha)},
                                {"offset", std::to_string(c.offset)},
                                {"scale", std::to_string(c.scale)},
                                {"storage", c.storage},
                                {"blur", c.blur},
                                {"filtering", c.filtering}});
  const Frame skipped = renderByName("modern.csm", scene, p);
  p.extra["skip-error"] = "0";
  const Frame frame = renderByName("modern.csm", scene, p);
  const AnalyticDepths depth = analyticDepths(scene);
  auto visibility = [&](double t) {
    return std::clamp(c.scale * eq11(t, c.order, c.alpha), 0.0, 1.0);
  };
  const double tUmbra = (1.0 - c.offset) * (depth.occluder - depth.ground) + c.offset;
  const double tLit = (1.0 - c.offset) * (depth.open - depth.ground) + c.offset;
  // Float storage: the shader's float32 sin/cos of arguments up to c_M ~ 400 and the float
  // linear depths (~1e-7 relative) give errors far below 1e-3 even where the step is
  // steepest (slope ~ M); 8-bit adds the quantisation bound.
  const double tolerance = 1e-3 + (c.storage == "8" ? eightBitBound(c.order, c.alpha) : 0.0);
  // (0, 0, 0.25): in the umbra (|x|, |z| < 2/3), 0.42 from its edge (19 texels at 256^2),
  // and seen by the camera in front of the occluder.
  const glm::ivec2 umbra = pixelOf(scene, p, {0.0f, 0.0f, 0.25f});
  const glm::ivec2 lit = pixelOf(scene, p, {1.8f, 0.0f, 0.3f});  // > 1 unit from its edge
  ASSERT_TRUE(umbra.x > 0 && umbra.x < p.width && umbra.y > 0 && umbra.y < p.height);
  ASSERT_TRUE(lit.x > 0 && lit.x < p.width && lit.y > 0 && lit.y < p.height);
  const std::string what = "M=" + std::to_string(c.order) + " alpha=" + std::to_string(c.alpha) +
                           " offset=" + std::to_string(c.offset) + " storage=" + c.storage +
                           " blur=" + c.blur + " filtering=" + c.filtering;
  EXPECT_NEAR(frame.visibility.at(umbra.x, umbra.y), visibility(tUmbra), tolerance)
      << what << " umbra, t=" << tUmbra;
  EXPECT_NEAR(frame.visibility.at(lit.x, lit.y), visibility(tLit), tolerance)
      << what << " lit, t=" << tLit;
  EXPECT_NEAR(skipped.visibility.at(umbra.x, umbra.y), visibility(tUmbra),
              tolerance + kDefaultSkipError)
      << what << " umbra, default skip-error";
  EXPECT_NEAR(skipped.visibility.at(lit.x, lit.y), visibility(tLit), tolerance + kDefaultSkipError)
      << what << " lit, default skip-error";
}

TEST(Csm, UmbraAndLitMatchEq11FloatStorage) {
  expectMatchesEq11({4, 1.0, 1.0 / 6.0, 1.0, "float", "0", "nearest"});
  expectMatchesEq11({16, 0.0, 0.05, 2.0, "float", "0", "nearest"});
}

TEST(Csm, UmbraInsideTheStepMatchesEq11) {
  // offset 0.49 puts the umbra at t ~ 0, in the middle of the reconstructed step, where a wrong
  // sign, c_k or attenuation would show at once.
  expectMatchesEq11({16, 1.0, 0.49, 1.0, "float", "0", "nearest"});
  expectMatchesEq11({8, 2.0, 0.49, 1.0, "8", "0", "nearest"});
}

TEST(Csm, BlurAndTrilinearKeepConstantRegionsExact) {
  // The blur weights sum to 1 and mip-maps average: inside a region of constant depth (the
  // umbra pixel is 19 texels from its edge at 256^2, the 7x7 kernel reaches 3) nothing changes.
  expectMatchesEq11({8, 1.0, 0.1, 1.0, "float", "7", "trilinear"});
  expectMatchesEq11({64, 1.0, 0.02, 1.0, "8", "5", "trilinear"});
}

TEST(Csm, DefaultOffsetIsTheTopOfTheStep) {
  for (int order : {4, 8, 16, 64}) {
    const double o = modern::csmDefaultOffset(order, 1.0);
    const double h = 1e-3;
    EXPECT_GT(o, 0.0);
    // A maximum: not lower than its neighbours (within the search step 5e-5).
    EXPECT_GE(eq11(o, order, 1.0) + 1e-6, eq11(o - h, order, 1.0)) << order;
    EXPECT_GE(eq11(o, order, 1.0) + 1e-6, eq11(o + h, order, 1.0)) << order;
    // And the top of the step, close to fully lit (alpha = 1 leaves < 3% below 1, §3.2.1).
    EXPECT_GT(eq11(o, order, 1.0), 0.97) << order;
  }
}

// offset-rule=through-1 (§3.2.2: "after offsetting, f(d, z) goes through 1"): the first t where the
// step reaches 1. With alpha = 0 the step overshoots (Gibbs), so it reaches 1 before its top;
// with alpha = 1 and M = 4 it tops out at 0.98 and the offset falls back to the top.
TEST(Csm, OffsetThroughOneIsWhereTheStepFirstReachesOne) {
  constexpr double kSearchStep = 1.0 / 20000;  // the search's resolution on (0, 1]
  for (int order : {2, 4, 8, 16}) {
    const double o = modern::csmOffsetThroughOne(order, 0.0);
    EXPECT_GE(eq11(o, order, 0.0), 1.0) << order;
    EXPECT_LT(eq11(o - kSearchStep, order, 0.0), 1.0) << order;
    EXPECT_LT(o, modern::csmDefaultOffset(order, 0.0)) << order;
  }
  EXPECT_EQ(modern::csmOffsetThroughOne(4, 1.0), modern::csmDefaultOffset(4, 1.0));
}

// The figure csm-fig6 (c), M = 4 on the squares scene, showed the slanted square's shadow light
// over half its length, where Annen et al. §5 say that "even the slanted plane in Figure 6(c)
// which touches the receiver plane achieves good shadowing quality using only 4 terms". Along
// the slanted square's centre line, the ground point behind each square point must match Eq. 11
// at that point's height above the ground (t = -(1 - offset) h / span + offset), and with the
// figure's settings (alpha = 0: the caption's ringing; offset-rule=through-1) the shadow is dark
// (< 0.1) over more than 60% of the square's length; with the defaults (alpha = 1, offset at
// the step's top) Eq. 11 predicts less than 40%: what the figure showed.
TEST(Csm, SlantedSquareShadowAtOrderFourIsDarkOverMostOfItsLength) {
  const Scene scene = loadScene("squares");
  const Object* slanted = nullptr;
  for (const Object& o : scene.objects)
    if (o.name == "slanted square") slanted = &o;
  ASSERT_NE(slanted, nullptr);
  constexpr int kOrder = 4;
  constexpr double kDark = 0.1;
  const DepthRange range = modern::csmDepthRange(scene);
  const double span = double(range.farPlane) - range.nearPlane;
  const glm::vec3 light = scene.light.position;
  ASSERT_NEAR(scene.light.target.y, 0.0f, 1e-6f) << "the light must look straight down";
  ASSERT_NEAR(scene.light.target.x, light.x, 1e-6f);
  ASSERT_NEAR(scene.light.target.z, light.z, 1e-6f);
  // Square points along the centre line of its top face (the mesh's local x range, y at its
  // top), leaving out a sixteenth at each end (the shadow's outline, softened by the blur).
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& v : slanted->mesh->positions) {
    lo = glm::min(lo, v);
    hi = glm::max(hi, v);
  }
  std::vector<glm::vec3> points;
  for (int i = 0; i <= 20; ++i) {
    const float u = lo.x + (hi.x - lo.x) * (1.0f + 14.0f * float(i) / 20.0f) / 16.0f;
    points.push_back(glm::vec3(slanted->model * glm::vec4(u, hi.y, 0.0f, 1.0f)));
  }
  const auto darkShare = [&](double alpha, double offset) {
    const double scale = std::max(1.0, 1.0 / eq11(offset, kOrder, alpha));
    int dark = 0;
    for (const glm::vec3& s : points) {
      const double t = -(1.0 - offset) * double(s.y) / span + offset;
      dark += std::clamp(scale * eq11(t, kOrder, alpha), 0.0, 1.0) < kDark ? 1 : 0;
    }
    return double(dark) / double(points.size());
  };
  const double throughOne = modern::csmOffsetThroughOne(kOrder, 0.0);
  EXPECT_GT(darkShare(0.0, throughOne), 0.6) << "derived: the figure's settings";
  EXPECT_LT(darkShare(1.0, modern::csmDefaultOffset(kOrder, 1.0)), 0.4) << "derived: defaults";

  // The figure's camera sees the shadow mostly through the square; this one looks from the far
  // side, low, under the square's raised end, at the ground behind each square point (heights
  // from 0.1 up, where the line of sight passes below the square's edge).
  constexpr float kVisibleAbove = 0.1f;
  Scene seen = scene;
  seen.camera.position = {0.97f, 0.35f, -1.8f};
  seen.camera.target = {0.97f, 0.0f, -0.45f};
  const RenderParams p =
      smallParams(320, 240, 512, {{"order", "4"}, {"alpha", "0"}, {"offset-rule", "through-1"}});
  const Frame frame = renderByName("modern.csm", seen, p);
  // Eq. 11 at the point's height, plus the 8-bit bound and the 3x3 blur, which mixes in the
  // basis of depths up to one map texel (0.009 units) along the square, 0.006 units of height
  // (t changes by 0.006 / span; the M = 4 step's slope is below 8 per unit t): 0.05.
  const double tolerance = eightBitBound(kOrder, 0.0) + 0.05;
  int checked = 0;
  for (const glm::vec3& s : points) {
    if (s.y < kVisibleAbove) continue;
    ++checked;
    const glm::vec3 ground = light + (s - light) * (light.y / (light.y - s.y));
    const glm::ivec2 px = pixelOf(seen, p, ground);
    const double t = -(1.0 - throughOne) * double(s.y) / span + throughOne;
    const double expected = std::clamp(eq11(t, kOrder, 0.0), 0.0, 1.0);
    const double measured = frame.visibility.at(px.x, px.y);
    EXPECT_NEAR(measured, expected, tolerance) << "height " << s.y;
  }
  EXPECT_GE(checked, 15);
}

TEST(Csm, LitGroundIsLitForEveryOrderWithDefaults) {
  // §3.2.2: with the default offset (and, for small M, the default scale) a lit surface,
  // z = d, reconstructs to 1. The analytic ground is made to cast so that the map holds its
  // own depth (otherwise z = far and t lies past the step's top, on the attenuated ripple).
  Scene scene = builtinScene("analytic");
  for (Object& o : scene.objects) o.castsShadow = true;
  for (int order : {1, 2, 4, 16, 64}) {
    const RenderParams p = smallParams(160, 120, 128, {{"order", std::to_string(order)}});
    const Frame frame = renderByName("modern.csm", scene, p);
    const glm::ivec2 lit = pixelOf(scene, p, {1.8f, 0.0f, 0.3f});
    // 8-bit storage (the default) moves f by at most eightBitBound (< 0.012 for M <= 64).
    EXPECT_NEAR(frame.visibility.at(lit.x, lit.y), 1.0, eightBitBound(order, 1.0) + 1e-3) << order;
  }
}

TEST(Csm, HighOrdersStayFiniteAndInRange) {
  const Scene scene = builtinScene("fence");
  for (const std::string storage : {"8", "float"}) {
    const Frame frame = renderByName(
        "modern.csm", scene, smallParams(128, 96, 128, {{"order", "64"}, {"storage", storage}}));
    ASSERT_TRUE(allFinite(frame.visibility)) << storage;
    float lo = 1, hi = 0;
    for (float v : frame.visibility.data) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    EXPECT_GE(lo, 0.0f) << storage;
    EXPECT_LE(hi, 1.0f) << storage;
    EXPECT_LT(lo, 0.1f) << storage << ": the fence must cast a shadow";
    EXPECT_GT(hi, 0.9f) << storage << ": lit ground must be lit";
  }
}

TEST(Csm, SpellingsTheFiguresUse) {
  // blur=1 is a 1x1 kernel, i.e. no blur; offset=auto is the default offset; filtering=
  // trilinear is the default. Each must give the same image as its plain spelling.
  const Scene scene = builtinScene("analytic");
  auto mask = [&](std::map<std::string, std::string> extra) {
    return renderByName("modern.csm", scene, smallParams(64, 48, 64, std::move(extra))).visibility;
  };
  EXPECT_EQ(mask({{"blur", "1"}}).data, mask({{"blur", "0"}}).data);
  EXPECT_EQ(mask({{"offset", "auto"}}).data, mask({}).data);
  EXPECT_EQ(mask({{"scale", "auto"}}).data, mask({}).data);
  EXPECT_EQ(mask({{"filtering", "trilinear"}}).data, mask({}).data);
}

TEST(Csm, BadParametersAreInputErrors) {
  const Scene scene = builtinScene("analytic");
  for (const auto& [key, value] :
       std::vector<std::pair<std::string, std::string>>{{"order", "0"},
                                                        {"order", "65"},
                                                        {"blur", "4"},
                                                        {"blur", "9"},
                                                        {"storage", "12"},
                                                        {"alpha", "-1"},
                                                        {"offset", "0.8"},
                                                        {"filtering", "cubic"},
                                                        {"anisotropy", "0"}}) {
    EXPECT_THROW(renderByName("modern.csm", scene, smallParams(32, 32, 32, {{key, value}})),
                 InputError)
        << key << "=" << value;
  }
}

}  // namespace
}  // namespace sl

namespace sl {
namespace {
using namespace sl::testing_filtered;

// Box-filters `image` (one channel) by `factor` in each direction.
Image downsample(const Image& image, int factor) {
  Image out(image.width / factor, image.height / factor, 1, 0.0f);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      double sum = 0;
      for (int j = 0; j < factor; ++j)
        for (int i = 0; i < factor; ++i) sum += image.at(x * factor + i, y * factor + j);
      out.at(x, y) = float(sum / (factor * factor));
    }
  return out;
}

double rmse(const Image& a, const Image& b) {
  double sum = 0;
  for (size_t i = 0; i < a.data.size(); ++i)
    sum += double(a.data[i] - b.data[i]) * (a.data[i] - b.data[i]);
  return std::sqrt(sum / double(a.data.size()));
}

TEST(Csm, MipMapsAntialiasMinifiedShadows) {
  // Fig. 1 and 10: trees far away, many shadow-map texels per pixel. The ground truth of the
  // pixel's shadow is the fraction of it that is lit: a hard shadow map (nearest compare) at
  // 4x4 the resolution, box-filtered. The pixel-rate hard test aliases; CSM with mip-maps
  // (tri-linear) pre-filters the basis and comes closer; without mip-maps it aliases too.
  Scene scene = builtinScene("trees");
  // Three times the scene's camera distance. The claim is about strong minification: nearer
  // (1.5x) CSM's own reconstruction error near contact (§3.2.2) outweighs the aliasing it
  // removes (measured RMSE with the earlier foliage trees: hard 0.056, CSM 0.067); at 2x they
  // are close (0.054 / 0.049); at 3x: hard 0.042, CSM tri-linear 0.027, CSM without mip-maps
  // 0.036. (The branched trees pass the same two comparisons.)
  constexpr float kDistance = 3.0f;
  scene.camera.position =
      scene.camera.target + kDistance * (scene.camera.position - scene.camera.target);
  constexpr int kFactor = 4;
  const int w = 128, h = 96, texels = 2048;
  const Image truth = downsample(
      renderByName("modern.hw", scene,
                   smallParams(w * kFactor, h * kFactor, texels, {{"compare", "nearest"}}))
          .visibility,
      kFactor);
  const Image hard =
      renderByName("modern.hw", scene, smallParams(w, h, texels, {{"compare", "nearest"}}))
          .visibility;
  const Image mip =
      renderByName("modern.csm", scene, smallParams(w, h, texels, {{"order", "16"}, {"blur", "0"}}))
          .visibility;
  const Image flat =
      renderByName(
          "modern.csm", scene,
          smallParams(w, h, texels, {{"order", "16"}, {"blur", "0"}, {"filtering", "bilinear"}}))
          .visibility;
  const double eHard = rmse(hard, truth), eMip = rmse(mip, truth), eFlat = rmse(flat, truth);
  writePng(outputPath("csm-minification-truth-hard-mip-flat.png"),
           sideBySide({truth, hard, mip, flat}));
  EXPECT_LT(eMip, eHard) << "CSM tri-linear " << eMip << ", hard " << eHard;
  EXPECT_LT(eMip, eFlat) << "CSM tri-linear " << eMip << ", bilinear " << eFlat;
}

}  // namespace
}  // namespace sl

namespace sl {
namespace {
using namespace sl::testing_filtered;

// M = 4 "yields satisfactory shadows" (Annen §5, Fig. 6) "when using a tightly
// fitted light frustum". A caster outside the light frustum, beside the light, used to pull
// the near end of the depth range to the light: the occluder-to-ground distance then covered
// a quarter of the range and M = 4 reconstructed the umbra as 0.27 (grey). modern.csm now fits the
// range to the casters inside the frustum and the receivers they can shadow.
TEST(Csm, OrderFourUmbraIsDarkWithTheFittedRange) {
  Scene scene = builtinScene("analytic");
  Object beside = scene.objects.back();  // the occluder's mesh and colour
  beside.name = "caster beside the light";
  // 3.5 units sideways at 0.2 below the light: the 70-degree frustum is 0.14 wide there.
  beside.model = glm::translate(glm::mat4(1.0f), glm::vec3(3.5f, 3.8f, 0.0f));
  scene.objects.push_back(beside);
  constexpr int kOrder = 4;
  constexpr double kAlpha = 1.0;  // the default attenuation
  const RenderParams p = smallParams(160, 120, 256, {{"order", std::to_string(kOrder)}});
  const Frame frame = renderByName("modern.csm", scene, p);

  const double offset = modern::csmDefaultOffset(kOrder, kAlpha);
  const double scale = std::max(1.0, 1.0 / eq11(offset, kOrder, kAlpha));  // scale=auto
  auto umbraT = [&](const DepthRange& range) {
    // Linear depths of the occluder's top (y = 1.01) and the ground under the light.
    const double span = double(range.farPlane) - range.nearPlane;
    const double occluder = (4.0 - 1.01 - range.nearPlane) / span;
    const double ground = (4.0 - range.nearPlane) / span;
    return (1.0 - offset) * (occluder - ground) + offset;
  };
  const DepthRange fitted = modern::csmDepthRange(scene);
  const DepthRange whole = lightDepthRange(scene);
  ASSERT_LT(whole.nearPlane, 0.5f) << "the caster beside the light must widen the scene range";
  EXPECT_GT(fitted.nearPlane, 2.9f) << "the fitted range starts at the occluder (depth 2.99)";
  EXPECT_LT(fitted.farPlane, 4.1f) << "and ends just past the ground (depth 4)";
  // The bound: Eq. 11 truncated at M = 4 at the umbra's t, scaled and clamped (§3.2.2), plus
  // the 8-bit quantisation bound and float arithmetic (as expectMatchesEq11).
  const double bound = std::clamp(scale * eq11(umbraT(fitted), kOrder, kAlpha), 0.0, 1.0) +
                       eightBitBound(kOrder, kAlpha) + 1e-3;
  EXPECT_LT(bound, 0.05) << "derived: with the fitted range the M = 4 umbra is dark";
  EXPECT_GT(scale * eq11(umbraT(whole), kOrder, kAlpha), 0.2)
      << "derived: over the scene's whole range it would be grey";
  const glm::ivec2 umbra = pixelOf(scene, p, {0.0f, 0.0f, 0.25f});
  EXPECT_LE(frame.visibility.at(umbra.x, umbra.y), bound);
}

// The figure csm-fig7 (c)-(f) showed a row of isolated white specks inside a tree's shadow with
// 16x anisotropic filtering (Mesa llvmpipe's anisotropic path with explicit gradients,
// textureGrad; csm_shadow.frag now samples with implicit derivatives in uniform control flow).
// An isolated lit pixel: visibility > 0.5 with at most one 2x2 quad of such pixels in its 5x5
// neighbourhood, inside the hard shadow map's umbra eroded by one pixel. The trees carry the
// foliage of the earlier trees scene (core/primitives makeTree), whose wide umbrae the row of dots
// crossed.
TEST(Csm, NoIsolatedLitPixelsInTheUmbra) {
  Scene scene = builtinScene("trees");
  constexpr float kTreeHeight = 2.5f, kHeightVariation = 0.3f;  // as the trees scene
  for (Object& o : scene.objects)
    if (o.name.rfind("tree ", 0) == 0)
      o.mesh = std::make_shared<const Mesh>(
          makeTree(kTreeHeight + kHeightVariation * float(std::stoi(o.name.substr(5)) % 3)));
  constexpr int kW = 512, kH = 384, kTexels = 2048;  // Fig. 7's map, the figure's panel size
  const Image hard =
      renderByName("modern.hw", scene, smallParams(kW, kH, kTexels, {{"compare", "nearest"}}))
          .visibility;
  const Image csm =
      renderByName(
          "modern.csm", scene,
          smallParams(
              kW, kH, kTexels,
              {{"order", "16"}, {"filtering", "anisotropic"}, {"anisotropy", "16"}, {"blur", "0"}}))
          .visibility;
  constexpr int kErosion = 1;  // pixel: the umbra's interior, away from CSM's soft edges
  constexpr int kQuadPixels = 4;
  int umbraPixels = 0, isolated = 0;
  for (int y = kErosion + 2; y < kH - kErosion - 2; ++y)
    for (int x = kErosion + 2; x < kW - kErosion - 2; ++x) {
      bool inside = true;
      for (int j = -kErosion; j <= kErosion && inside; ++j)
        for (int i = -kErosion; i <= kErosion && inside; ++i)
          inside = hard.at(x + i, y + j) == 0.0f;
      if (!inside) continue;
      ++umbraPixels;
      if (csm.at(x, y) <= 0.5f) continue;
      // A speck: at most one 2x2 quad of lit pixels in the 5x5 window around it (llvmpipe
      // shades in 2x2 quads, and the dots were whole quads).
      int litAround = 0;
      for (int j = -2; j <= 2; ++j)
        for (int i = -2; i <= 2; ++i)
          if (csm.at(x + i, y + j) > 0.5f) ++litAround;
      const bool alone = litAround <= kQuadPixels;
      if (alone) ++isolated;
    }
  EXPECT_GT(umbraPixels, 5000) << "the trees must cast umbrae on the ground";
  // Measured with the textureGrad shader: 26 such pixels (the dot row); now 0.
  EXPECT_EQ(isolated, 0) << "isolated lit pixels in " << umbraPixels << " umbra pixels";

  if (isolated > 0) writePng(outputPath("csm-isolated-lit-pixels.png"), sideBySide({hard, csm}));
}

// The faster path: GL objects and programs kept in the context from one frame to
// the next, and the mip chain left out where the view does not minify the map.
TEST(Csm, SecondFrameInTheSameContextEqualsTheFirst) {
  const Scene scene = builtinScene("fence");
  const Technique& csm = findTechnique("modern.csm");
  for (const std::string blur : {"0", "5"}) {
    const RenderParams p = smallParams(128, 96, 256, {{"blur", blur}});
    auto context = GlContext::create(contextFor(csm, p));
    const Frame first = csm.render(*context, scene, p);
    const Frame second = csm.render(*context, scene, p);
    // Same inputs, same objects reused: bit-identical (no state may leak between frames).
    EXPECT_EQ(first.visibility.data, second.visibility.data) << "blur " << blur;
    EXPECT_EQ(first.color.data, second.color.data) << "blur " << blur;
  }
}

// The basis pass (sin and cos by rotation) and the blur (compile-time taps and
// layers) against Eq. 14 and the binomial kernel evaluated here from the captured
// linear depth: B_k = 0.5 + 0.5 sin(c_k z), stored in 8 bits, blurred horizontally then
// vertically with clamped borders, stored in 8 bits again. The first path computed the same
// numbers with 2M sin/cos calls and uniform loop bounds.
TEST(Csm, BasisAndBlurMatchEq14AndTheBinomialKernel) {
  const Scene scene = builtinScene("fence");
  constexpr int kOrder = 16, kTexels = 64;
  for (const int taps : {3, 5}) {
    RenderParams p = smallParams(
        64, 48, kTexels, {{"order", std::to_string(kOrder)}, {"blur", std::to_string(taps)}});
    p.capturePasses = true;
    const Frame frame = renderByName("modern.csm", scene, p);
    auto find = [&](const std::string& name) -> const Image& {
      for (const PassImage& i : frame.intermediates)
        if (i.name == name) return i.image;
      throw std::runtime_error("no intermediate " + name);
    };
    const Image& depth = find("1-linear-depth");
    ASSERT_EQ(depth.width, kTexels);
    // Binomial weights, row taps-1 of Pascal's triangle over 2^(taps-1).
    std::vector<double> w(size_t(taps), 1.0);
    for (int i = 1; i < taps; ++i) w[size_t(i)] = w[size_t(i - 1)] * (taps - i) / i;
    for (double& v : w) v /= std::ldexp(1.0, taps - 1);
    auto quantise = [](double v) { return std::round(v * 255.0) / 255.0; };
    auto clampTexel = [&](int v) { return std::clamp(v, 0, kTexels - 1); };
    double worst = 0.0;
    for (int layer = 0; layer < kOrder / 4; ++layer) {
      // The blurred basis is what pass 3 (the vertical half) leaves.
      const std::string name =
          "3-basis-sin-k" + std::to_string(4 * layer + 1) + "-" + std::to_string(4 * layer + 4);
      const Image& stored = find(name);
      for (int c = 0; c < 4; ++c) {
        const int k = 4 * layer + c + 1;
        const double ck = std::numbers::pi * (2 * k - 1);
        Image basis(kTexels, kTexels, 1), horizontal(kTexels, kTexels, 1);
        for (int y = 0; y < kTexels; ++y)
          for (int x = 0; x < kTexels; ++x)
            basis.at(x, y) = float(quantise(0.5 + 0.5 * std::sin(ck * depth.at(x, y))));
        for (int y = 0; y < kTexels; ++y)
          for (int x = 0; x < kTexels; ++x) {
            double sum = 0.0;
            for (int t = 0; t < taps; ++t)
              sum += w[size_t(t)] * basis.at(clampTexel(x + t - taps / 2), y);
            horizontal.at(x, y) = float(quantise(sum));
          }
        for (int y = 0; y < kTexels; ++y)
          for (int x = 0; x < kTexels; ++x) {
            double sum = 0.0;
            for (int t = 0; t < taps; ++t)
              sum += w[size_t(t)] * horizontal.at(x, clampTexel(y + t - taps / 2));
            worst = std::max(worst, std::fabs(quantise(sum) - stored.at(x, y, c)));
          }
      }
    }
    // Each of the three 8-bit stores rounds to the nearest of 255 steps; a float32 sin that
    // lands on the other side of a rounding boundary moves one value by 1/255, and the
    // weights (summing to 1) carry that through each blur pass: at most 3 steps in all
    // (measured: 1 step, 1/255, for 3x3 and 5x5).
    EXPECT_LE(worst, 3.0 / 255.0 + 1e-6) << taps << "x" << taps;
  }
}

// The basis pass applies the blur's horizontal half itself (computeBasisTextures): with float
// storage nothing is rounded, so the stored layers must equal the separable binomial blur of
// sin(c_k z) (Eq. 14, §4.1), first along x then along y, evaluated here in double precision.
TEST(Csm, FusedBasisAndHorizontalBlurEqualStoreThenBlurInFloat) {
  const Scene scene = builtinScene("fence");
  constexpr int kOrder = 16, kTexels = 64;
  for (const int taps : {0, 3, 7}) {
    RenderParams p = smallParams(
        64, 48, kTexels,
        {{"order", std::to_string(kOrder)}, {"blur", std::to_string(taps)}, {"storage", "float"}});
    p.capturePasses = true;
    const Frame frame = renderByName("modern.csm", scene, p);
    auto find = [&](const std::string& name) -> const Image& {
      for (const PassImage& i : frame.intermediates)
        if (i.name == name) return i.image;
      throw std::runtime_error("no intermediate " + name);
    };
    const Image& depth = find("1-linear-depth");
    ASSERT_EQ(depth.width, kTexels);
    const int n = std::max(taps, 1);
    std::vector<double> w(size_t(n), 1.0);
    for (int i = 1; i < n; ++i) w[size_t(i)] = w[size_t(i - 1)] * (n - i) / i;
    for (double& v : w) v /= std::ldexp(1.0, n - 1);
    auto clampTexel = [&](int v) { return std::clamp(v, 0, kTexels - 1); };
    double worst = 0.0;
    for (int layer = 0; layer < kOrder / 4; ++layer) {
      // Pass 3 leaves the blurred basis; without a blur there is no pass 3.
      const Image& stored =
          find((taps > 0 ? "3" : "2") + std::string("-basis-sin-k") +
               std::to_string(4 * layer + 1) + "-" + std::to_string(4 * layer + 4));
      for (int c = 0; c < 4; ++c) {
        const double ck = std::numbers::pi * (2 * (4 * layer + c + 1) - 1);
        std::vector<double> horizontal(size_t(kTexels * kTexels));
        for (int y = 0; y < kTexels; ++y)
          for (int x = 0; x < kTexels; ++x) {
            double sum = 0.0;
            for (int t = 0; t < n; ++t)
              sum += w[size_t(t)] * std::sin(ck * depth.at(clampTexel(x + t - n / 2), y));
            horizontal[size_t(y * kTexels + x)] = sum;
          }
        for (int y = 0; y < kTexels; ++y)
          for (int x = 0; x < kTexels; ++x) {
            double sum = 0.0;
            for (int t = 0; t < n; ++t)
              sum += w[size_t(t)] * horizontal[size_t(clampTexel(y + t - n / 2) * kTexels + x)];
            // capturePasses shows float layers as 0.5 + 0.5 v.
            worst = std::max(worst, std::fabs(0.5 + 0.5 * sum - stored.at(x, y, c)));
          }
      }
    }
    std::cout << "blur " << taps << ": largest difference " << worst << "\n";
    // float32: c_k z up to 31 pi, by 15 rotations of a float32 sin/cos pair (~1e-7 each) and
    // float32 weights and sums: a few 1e-6. 1e-4 is still 40 times below one 8-bit step.
    EXPECT_LE(worst, 1e-4) << "blur " << taps;
  }
}

TEST(Csm, MipChainLeftOutOnlyWhereNothingMinifies) {
  // Magnified: the analytic scene at 320x240 with a 64-texel map (every pixel < 1 texel).
  const Scene analytic = builtinScene("analytic");
  const RenderParams near = smallParams(320, 240, 64);
  RenderParams nearAlways = near;
  nearAlways.extra["mipmaps"] = "always";
  const Frame skipped = renderByName("modern.csm", analytic, near);
  const Frame built = renderByName("modern.csm", analytic, nearAlways);
  EXPECT_EQ(skipped.counters.at("mip-maps"), 0.0);
  EXPECT_EQ(built.counters.at("mip-maps"), 1.0);
  // Where lambda <= 0 GL reads level 0 with the magnification filter either way; the planner
  // leaves the chain out at the 95th percentile, so grazing pixels (at most 5% of the
  // receivers') may differ, by what one mip level changes a tri-linear blend.
  int differing = 0;
  for (size_t i = 0; i < skipped.visibility.data.size(); ++i)
    if (std::fabs(skipped.visibility.data[i] - built.visibility.data[i]) > 1.0f / 255.0f)
      ++differing;
  EXPECT_LE(double(differing), 0.05 * double(skipped.visibility.data.size()));
  // Minified (trees from three times the distance, 2048 map): the chain is built.
  Scene trees = builtinScene("trees");
  trees.camera.position =
      trees.camera.target + 3.0f * (trees.camera.position - trees.camera.target);
  const Frame far = renderByName("modern.csm", trees, smallParams(128, 96, 2048, {{"blur", "0"}}));
  EXPECT_EQ(far.counters.at("mip-maps"), 1.0);
}

// The passes run under the ids of modern.csm's pass table: the classified camera pass as 5a
// (depth bounds), 5b (classification) and 5c (Eq. 13 where undecided), each its own pass with
// its own name; skip-error = 0 runs pass 5 alone. The declared table is well formed.
TEST(Csm, ClassifiedCameraPassRunsAsPasses5aTo5c) {
  const Technique csm = findTechnique("modern.csm");
  EXPECT_TRUE(passTableProblems(csm.passes).empty());
  const Scene scene = builtinScene("analytic");
  auto idsAndNames = [&](const RenderParams& p) {
    std::vector<std::string> out;
    for (const PassTime& t : renderByName("modern.csm", scene, p).passes)
      out.push_back(t.id + ": " + t.name);
    return out;
  };
  EXPECT_EQ(idsAndNames(smallParams(160, 120, 64, {{"mipmaps", "always"}})),
            (std::vector<std::string>{"1: 1 linear depth from light",
                                      "2: 2 basis textures + horizontal Gaussian (MRT)",
                                      "3: 3 vertical Gaussian 3x3", "4: 4 mip-maps",
                                      "5a: 5a depth bounds (min/max pyramid of z)",
                                      "5b: 5b camera pass: classification (depth bounds)",
                                      "5c: 5c camera pass, Eq. 13 where undecided"}));
  EXPECT_EQ(idsAndNames(smallParams(160, 120, 64,
                                    {{"skip-error", "0"}, {"blur", "0"}, {"mipmaps", "always"}})),
            (std::vector<std::string>{"1: 1 linear depth from light", "2: 2 basis textures (MRT)",
                                      "4: 4 mip-maps", "5: 5 camera pass, Eq. 13 reconstruction"}));
}

// The mip chain drawn with layered_downsample.frag (instead of glGenerateMipmap):
// every texel of level L is the 2x2 box mean of level L - 1, for every layer, in 8-bit and
// float storage (Annen §4.1's mip-map, glGenerateMipmap's filter on power-of-two maps).
TEST(Csm, DrawnMipChainIsTheBoxFilterOfEachLevel) {
  using namespace sl::gl;
  const Technique& csm = findTechnique("modern.csm");
  const RenderParams p = smallParams(16, 16, 64);
  auto context = GlContext::create(contextFor(csm, p));
  constexpr int kSize = 32, kLayers = 10;  // 10: more layers than one MRT pass writes (8)
  for (const GLenum format : {GLenum(GL_RGBA8), GLenum(GL_RGBA32F)}) {
    const modern::LayeredMap map = modern::makeLayeredMap(kSize, kLayers, format, true);
    // Level 0: a different value in every texel and channel (a fixed linear congruential
    // sequence), written texel by texel with scissored clears.
    const modern::Framebuffer fbo = modern::makeFramebuffer();
    unsigned state = 12345u;
    glEnable(GL_SCISSOR_TEST);
    for (int layer = 0; layer < kLayers; ++layer) {
      modern::attachLayers(fbo, map, layer, 1);
      for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
          float value[4];
          for (float& v : value) {
            state = state * 1664525u + 1013904223u;
            v = float(state >> 24) / 255.0f;
          }
          glScissor(x, y, 1, 1);
          glClearBufferfv(GL_COLOR, 0, value);
        }
    }
    glDisable(GL_SCISSOR_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    modern::MapFiltering filtering;  // tri-linear: the chain is built
    modern::buildMipmapsAndSetFiltering(map, filtering);
    auto level = [&](int l) {
      const int side = kSize >> l;
      std::vector<float> v(size_t(side) * side * kLayers * 4);
      glBindTexture(GL_TEXTURE_2D_ARRAY, map.texture.id());
      glPixelStorei(GL_PACK_ALIGNMENT, 1);
      glGetTexImage(GL_TEXTURE_2D_ARRAY, l, GL_RGBA, GL_FLOAT, v.data());
      return v;
    };
    double worst = 0.0;
    for (int l = 1; l < map.levels; ++l) {
      const std::vector<float> above = level(l - 1), here = level(l);
      const int side = kSize >> l;
      for (int layer = 0; layer < kLayers; ++layer)
        for (int y = 0; y < side; ++y)
          for (int x = 0; x < side; ++x)
            for (int c = 0; c < 4; ++c) {
              auto at = [&](const std::vector<float>& v, int s, int i, int j) {
                return double(v[((size_t(layer) * s + j) * s + i) * 4 + size_t(c)]);
              };
              const double mean = 0.25 * (at(above, 2 * side, 2 * x, 2 * y) +
                                          at(above, 2 * side, 2 * x + 1, 2 * y) +
                                          at(above, 2 * side, 2 * x, 2 * y + 1) +
                                          at(above, 2 * side, 2 * x + 1, 2 * y + 1));
              worst = std::max(worst, std::fabs(mean - at(here, side, x, y)));
            }
    }
    std::cout << (format == GL_RGBA8 ? "RGBA8" : "RGBA32F") << ": largest difference " << worst
              << "\n";
    // 8-bit: one rounding of the mean to the nearest of 255 steps (half a step), plus float
    // arithmetic; float: float32 sums of four values in [0, 1].
    EXPECT_LE(worst, format == GL_RGBA8 ? 0.5 / 255.0 + 1e-5 : 1e-6);
  }
}

// The classification (skip-error > 0, the default) decides pixels whose footprint's
// depth bounds put every z - d in an interval where the clamped series is within skip-error of
// 1 or 0 (csmSkipIntervals), and reconstructs Eq. 13 at the others only. Against skip-error=0
// (Eq. 13 at every pixel), float storage (no 8-bit rounding in either) on brabec and fence,
// tri-linear and 16x anisotropic (Table 1): visibility within skip-error (the bound the
// intervals guarantee through Eq. 8's convex combination) plus 1e-3 for float32 rounding of the
// series, at all pixels but those where two faces of one object meet at nearly equal depth (box
// edges, sphere silhouettes): there the classification's program and the full program
// interpolate depth in different llvmpipe code, so a different face can win the depth test and
// its own (correct) visibility is shown. Measured at 256x192: 122-151 such pixels (0.25-0.31%),
// all on object edges (looked at); bound 0.5%.
TEST(Csm, SkippedPixelsMatchTheFullReconstructionWithinTheSkipError) {
  constexpr double kSkipError = 0.025;
  constexpr double kFloatSlack = 1e-3;
  constexpr double kEdgeTieFraction = 0.005;
  for (const std::string sceneName : {"brabec", "fence"})
    for (const std::string filtering : {"trilinear", "anisotropic"}) {
      const Scene scene = builtinScene(sceneName);
      RenderParams skip = smallParams(
          256, 192, 512, {{"storage", "float"}, {"filtering", filtering}, {"skip-error", "0.025"}});
      RenderParams full = skip;
      full.extra["skip-error"] = "0";
      const Frame a = renderByName("modern.csm", scene, skip);
      const Frame b = renderByName("modern.csm", scene, full);
      ASSERT_EQ(a.visibility.data.size(), b.visibility.data.size());
      size_t beyond = 0;
      for (size_t i = 0; i < a.visibility.data.size(); ++i)
        if (std::fabs(a.visibility.data[i] - b.visibility.data[i]) > kSkipError + kFloatSlack)
          ++beyond;
      std::cout << sceneName << " " << filtering << ": " << beyond
                << " pixels beyond skip-error + 1e-3\n";
      EXPECT_LE(double(beyond), kEdgeTieFraction * double(a.visibility.data.size()))
          << sceneName << " " << filtering;
      EXPECT_GT(a.counters.at("skip lit t to"), a.counters.at("skip lit t from"));
    }
}

// Whether the segment from `a` to `b` meets the box `box` grown by `margin` on every side
// (slab test).
bool segmentMeetsBox(const glm::vec3& a, const glm::vec3& b, const Bounds& box, float margin) {
  float enter = 0.0f, leave = 1.0f;
  for (int i = 0; i < 3; ++i) {
    const float lo = box.lo[i] - margin, hi = box.hi[i] + margin, d = b[i] - a[i];
    if (std::fabs(d) < 1e-12f) {
      if (a[i] < lo || a[i] > hi) return false;
      continue;
    }
    float t0 = (lo - a[i]) / d, t1 = (hi - a[i]) / d;
    if (t0 > t1) std::swap(t0, t1);
    enter = std::max(enter, t0);
    leave = std::min(leave, t1);
    if (enter > leave) return false;
  }
  return true;
}

// A pixel the classification decided got exactly 1 or 0, where Eq. 13 gives the
// series' ringing around them (the lit ground of squares at M = 16: 0.992), so decided and
// reconstructed pixels drew tiles around every shadow (63% of the mask more than 1/255 from
// skip-error=0, lit ground brighter where decided). Now a decided pixel gets the series at the
// depths around it (csm_shadow.frag, reconstructFromDepth). The command (squares,
// M = 16, 5x5 blur, 512x384, 8-bit storage), with the default skip-error and with 0:
// - the masks agree within one 8-bit grey level at all pixels but those where the two programs'
//   depth tests pick different faces of a square (its edges; measured 0.15% here, 0.17-0.94%
//   on brabec, fence and trees): at most 1%;
// - on the lit ground seen past every square, no edge that the full reconstruction does not
//   have: of the pairs of neighbouring pixels that skip-error=0 shades within half a grey level
//   of each other, those more than one grey level apart with the default. The tiles' edges
//   follow the depth-bounds pyramid's blocks, not a fixed 4x4 phase of the screen (looked at:
//   blocks of 6-9 pixels on squares), so the test counts edges rather than phases. The ground
//   pixels whose ray from the camera passes within kSilhouetteMargin of a square's box are left
//   out: a square's edge is where the two programs' depth tests may pick different faces.
TEST(Csm, DecidedPixelsEqualTheReconstructionSoLitGroundShowsNoTiles) {
  constexpr double kGreyLevel = 1.0 / 255.0;     // one step of an 8-bit grey image of the mask
  constexpr double kSmoothInFull = 0.5 / 255.0;  // neighbours that skip-error=0 shades alike
  constexpr double kLit = 0.95;                  // visibility of lit ground (0.992 at M = 16)
  constexpr double kFaceTieFraction = 0.01;      // pixels where different faces win (above)
  // world units: two pixels at the squares' distance from the camera (5 units, 40 degrees over
  // 384 pixels: 0.0095 a pixel), so that a square's rasterised edge is left out with it
  constexpr float kSilhouetteMargin = 0.02f;
  // Share of the smooth lit ground pairs that may differ by more than a grey level: none is
  // expected (the ground casts nothing, so its footprints' depth is the cleared far value, the
  // same at every texel, where the decided pixels' series differs from the reconstruction by
  // the 8-bit rounding of the basis only: measured 0.0013, a third of a grey level); 0.1% allows
  // a few pixels whose value rounds across a grey level. Main (exactly 1 where decided) had 3498
  // of 313464 (1.1%), the tiles' edges.
  constexpr double kTileEdgeFraction = 0.001;
  const Scene scene = loadScene("squares");
  RenderParams skip = smallParams(512, 384, 512, {{"order", "16"}, {"blur", "5"}});
  RenderParams full = skip;
  full.extra["skip-error"] = "0";
  const Frame a = renderByName("modern.csm", scene, skip);
  const Frame b = renderByName("modern.csm", scene, full);
  ASSERT_GT(a.counters.at("skip lit t to"), a.counters.at("skip lit t from"));  // classified
  ASSERT_EQ(b.counters.at("skip error"), 0.0);
  const Image& da = a.visibility;
  const Image& db = b.visibility;
  ASSERT_EQ(da.data.size(), db.data.size());
  ASSERT_EQ(da.channels, 1);
  size_t apart = 0;
  for (size_t i = 0; i < da.data.size(); ++i)
    if (std::fabs(da.data[i] - db.data[i]) > kGreyLevel) ++apart;
  // Lit ground seen past every square.
  Bounds ground;
  std::vector<Bounds> squares;
  for (const Object& o : scene.objects) {
    if (o.name == "ground")
      ground = worldBounds(o);
    else
      squares.push_back(worldBounds(o));
  }
  std::vector<char> open(da.data.size(), 0);
  for (int y = 0; y < skip.height; ++y)
    for (int x = 0; x < skip.width; ++x) {
      const glm::vec3 g = groundPointOf(scene, skip, float(x), float(y), ground.hi.y);
      if (g.x < ground.lo.x || g.x > ground.hi.x || g.z < ground.lo.z || g.z > ground.hi.z)
        continue;
      if (db.at(x, y) < kLit) continue;
      bool seen = true;
      for (const Bounds& box : squares)
        seen = seen && !segmentMeetsBox(scene.camera.position, g, box, kSilhouetteMargin);
      open[size_t(y) * skip.width + x] = seen;
    }
  size_t pairs = 0, edges = 0;
  for (int y = 0; y < skip.height; ++y)
    for (int x = 0; x < skip.width; ++x)
      for (const glm::ivec2 step : {glm::ivec2(1, 0), glm::ivec2(0, 1)}) {
        const int x2 = x + step.x, y2 = y + step.y;
        if (x2 >= skip.width || y2 >= skip.height) continue;
        if (!open[size_t(y) * skip.width + x] || !open[size_t(y2) * skip.width + x2]) continue;
        if (std::fabs(db.at(x2, y2) - db.at(x, y)) > kSmoothInFull) continue;
        ++pairs;
        if (std::fabs(da.at(x2, y2) - da.at(x, y)) > kGreyLevel) ++edges;
      }
  std::cout << "squares M=16 blur=5: " << apart << " of " << da.data.size()
            << " pixels more than 1/255 from skip-error=0; " << edges << " of " << pairs
            << " smooth lit ground pairs with an edge\n";
  EXPECT_LE(double(apart), kFaceTieFraction * double(da.data.size()));
  ASSERT_GT(pairs, da.data.size() / 4);  // the lit ground is most of the image
  EXPECT_LE(double(edges), kTileEdgeFraction * double(pairs));
}

TEST(Csm, SkipIntervalsHoldTheBoundOnTheSeries) {
  for (int order : {4, 8, 16, 32}) {
    const double offset = modern::csmDefaultOffset(order, 1.0);
    const modern::CsmSkipIntervals k = modern::csmSkipIntervals(order, 1.0, offset, 1.0, 0.025);
    ASSERT_LT(k.litLo, k.litHi) << order;
    EXPECT_LE(k.litLo, offset);
    // Dense check of the guarantee (finer than the grid that found the intervals).
    for (double t = k.litLo; t <= k.litHi; t += 1e-5)
      ASSERT_GE(std::clamp(modern::csmReconstructedStep(t, order, 1.0), 0.0, 1.0), 1.0 - 0.025)
          << t;
    for (double t = k.umbraLo; t <= k.umbraHi; t += 1e-5)
      ASSERT_LE(std::clamp(modern::csmReconstructedStep(t, order, 1.0), 0.0, 1.0), 0.025) << t;
  }
  EXPECT_GT(modern::csmSkipIntervals(4, 1.0, 0.1, 1.0, 0.0).litLo,
            modern::csmSkipIntervals(4, 1.0, 0.1, 1.0, 0.0).litHi);  // 0: never skip
}

}  // namespace
}  // namespace sl
