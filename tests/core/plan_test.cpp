// The pass planner (core/technique/plan.h) on purpose-built scenes: each test builds a scene in
// which one omission must happen (or must not) and checks it, with the expected numbers computed
// here from the scene's geometry.
#include "core/technique/plan.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "core/scene/primitives.h"

namespace sl {
namespace {

Object object(const std::string& name, Mesh mesh, const glm::mat4& model, bool casts,
              bool receives) {
  Object o;
  o.name = name;
  o.mesh = std::make_shared<const Mesh>(std::move(mesh));
  o.model = model;
  o.castsShadow = casts;
  o.receivesShadow = receives;
  return o;
}

glm::mat4 at(float x, float y, float z) { return glm::translate(glm::mat4(1), {x, y, z}); }

constexpr float kLightHeight = 10.0f;
constexpr float kCasterTop = 5.0f;  // the box's top face: the caster nearest the light

// Light straight down from (0, 10, 0), cone 40 degrees; a ground (receiver only) and a box
// whose top is at y = 5, both inside the light frustum.
Scene column() {
  Scene s;
  s.name = "column";
  s.objects.push_back(object("ground", makePlane(8, 8, 4), glm::mat4(1), false, true));
  s.objects.push_back(object("box", makeBox({1, 1, 1}), at(0, kCasterTop - 0.5f, 0), true, true));
  s.light.position = {0, kLightHeight, 0};
  s.light.target = {0, 0, 0};
  s.light.up = {0, 0, -1};
  s.light.coneDegrees = 40;
  s.camera.position = {0, 6, 8};
  s.camera.target = {0, 0, 0};
  return s;
}

// Techniques described only by what they declare to the planner (core/technique/technique.h
// PlanTraits). Their names are deliberately not those of real techniques: the planner must ask, not
// match.
Technique named(const std::string& name) {
  Technique t;
  t.name = name;
  return t;
}

// Brabec–Seidel §3 (as legacy.pcf declares itself).
Technique fourSamplesPerPass() {
  Technique t = named("test.four-per-pass");
  t.needs.accumulation = true;
  t.plan.samples = PlanTraits::SampleGrouping::kFourPerPass;
  t.plan.colourTableCompare = true;
  t.plan.colourMatrixSum = true;
  return t;
}

// Brabec–Seidel §4 (as legacy.fast-pcf declares itself).
Technique packedPhases() {
  Technique t = fourSamplesPerPass();
  t.name = "test.packed-phases";
  t.plan.samples = PlanTraits::SampleGrouping::kPackedPhases;
  t.plan.packingConvolution = true;
  return t;
}

// Annen et al. 2007 (as modern.csm declares itself).
Technique convolutionPrefiltered() {
  Technique t = named("test.prefiltered");
  t.plan.prefilter = PlanTraits::Prefilter::kConvolution;
  t.params = {integerParam("blur", 3, 0, 7, "taps"),
              choiceParam("storage", "8", {"8", "16", "float"}, "format"),
              choiceParam("filtering", "trilinear", {"trilinear", "anisotropic", "bilinear"}, "f"),
              choiceParam("mipmaps", "auto", {"auto", "always"}, "m")};
  return t;
}

const PlanItem* item(const std::vector<PlanItem>& items, const std::string& prefix) {
  for (const PlanItem& i : items)
    if (i.name.rfind(prefix, 0) == 0) return &i;
  return nullptr;
}

TEST(Plan, CasterInFrustumKeepsShadowPasses) {
  const FramePlan p = planFrame(column(), named("test.plain-map"), RenderParams{});
  EXPECT_TRUE(p.shadowPassesNeeded);
  EXPECT_TRUE(casterReachesLightFrustum(column()));
  ASSERT_TRUE(item(p.passes, "light passes"));
  EXPECT_TRUE(item(p.passes, "light passes")->kept);
}

TEST(Plan, NoCasterInFrustumLeavesShadowPassesOut) {
  Scene s = column();
  // The box moved 6 units sideways: the 40-degree cone reaches 10 tan 20 = 3.6 units at the
  // ground and less above it, so the box (x in [5.5, 6.5]) is outside every lateral plane.
  s.objects[1].model = at(6.0f, kCasterTop - 0.5f, 0);
  EXPECT_FALSE(casterReachesLightFrustum(s));
  const FramePlan p = planFrame(s, named("test.plain-map"), RenderParams{});
  EXPECT_FALSE(p.shadowPassesNeeded);
  ASSERT_TRUE(item(p.passes, "light passes"));
  EXPECT_FALSE(item(p.passes, "light passes")->kept);
  EXPECT_NE(item(p.passes, "light passes")->reason.find("no caster"), std::string::npos);
  EXPECT_TRUE(item(p.passes, "camera pass")->kept);
  ASSERT_TRUE(item(p.lightObjects, "box"));
  EXPECT_FALSE(item(p.lightObjects, "box")->kept);
}

TEST(Plan, CasterBehindTheLightDoesNotCount) {
  Scene s = column();
  s.objects[1].model = at(0, kLightHeight + 2.0f, 0);  // above a light that looks down
  EXPECT_FALSE(casterReachesLightFrustum(s));
}

TEST(Plan, NonCastersLeftOutOfLightPasses) {
  const FramePlan p = planFrame(column(), named("test.plain-map"), RenderParams{});
  ASSERT_TRUE(item(p.lightObjects, "ground"));
  EXPECT_FALSE(item(p.lightObjects, "ground")->kept);
  EXPECT_NE(item(p.lightObjects, "ground")->reason.find("casts no shadow"), std::string::npos);
  EXPECT_TRUE(item(p.lightObjects, "box")->kept);
}

TEST(Plan, DepthRangeFittedToCastersAndReceivers) {
  Scene s = column();
  // A caster far outside the cone and nearer the light: the scene-wide fit starts near it, the
  // planner's fit ignores it (it cannot shadow anything in the frustum).
  s.objects.push_back(
      object("stray", makeBox({1, 1, 1}), at(20, kLightHeight - 1.0f, 0), true, true));
  const FramePlan p = planFrame(s, named("test.plain-map"), RenderParams{});
  // Expected: near = distance to the box top (10 - 5 = 5) less the 2% margin of the span
  // [5, 10] (0.1); far = distance to the ground (10) plus the margin.
  const float casterDistance = kLightHeight - kCasterTop;
  const float span = kLightHeight - casterDistance;
  EXPECT_NEAR(p.fittedRange.nearPlane, casterDistance - 0.02f * span, 1e-3f);
  EXPECT_NEAR(p.fittedRange.farPlane, kLightHeight + 0.02f * span, 1e-3f);
  EXPECT_LT(p.sceneRange.nearPlane, 1.0f) << "the stray box drags the scene-wide fit";
  // Fitted cone: the box's top corners at (+-0.5, +-0.5) seen from 5 units: tan = 0.5 / 5;
  // its bottom corners are 6 units away (tan = 0.5 / 6), so the top decides.
  EXPECT_NEAR(p.fittedConeDegrees, 2.0 * glm::degrees(std::atan(0.5 / 5.0)), 1e-3);
}

TEST(Plan, AccumulationOnlyBeyondTwoByTwo) {
  RenderParams p;
  for (int f : {1, 2, 3, 4}) {
    p.filter = f;
    const FramePlan plan = planFrame(column(), fourSamplesPerPass(), p);
    const PlanItem* acc = item(plan.resources, "accumulation buffer");
    ASSERT_TRUE(acc);
    // Brabec–Seidel §3: four samples per pass (RGBA); more need summing across passes.
    EXPECT_EQ(acc->kept, f * f > 4) << "filter " << f;
  }
}

TEST(Plan, ImagingStagesThatAreIdentityLeftOut) {
  RenderParams p;
  p.filter = 1;
  FramePlan plan = planFrame(column(), packedPhases(), p);
  EXPECT_FALSE(item(plan.resources, "imaging: colour matrix")->kept);
  EXPECT_FALSE(item(plan.resources, "imaging: convolution")->kept);
  p.filter = 2;
  plan = planFrame(column(), packedPhases(), p);
  EXPECT_TRUE(item(plan.resources, "imaging: colour matrix")->kept);
  const PlanItem* conv = item(plan.resources, "imaging: convolution");
  ASSERT_TRUE(conv && conv->kept);
  // Eq. (1): one non-zero tap per channel in a 3x3 RGBA kernel: 36 - 4 = 32 zero taps.
  EXPECT_NE(conv->reason.find("32 zero taps"), std::string::npos) << conv->reason;
}

TEST(Plan, BlurPassLeftOutWithoutKernel) {
  RenderParams p;
  // Without --param blur the technique's declared default (3 taps) is planned.
  EXPECT_TRUE(
      item(planFrame(column(), convolutionPrefiltered(), p).resources, "separable blur pass")
          ->kept);
  p.extra["blur"] = "0";
  FramePlan plan = planFrame(column(), convolutionPrefiltered(), p);
  EXPECT_FALSE(item(plan.resources, "separable blur pass")->kept);
  p.extra["blur"] = "7";
  plan = planFrame(column(), convolutionPrefiltered(), p);
  EXPECT_TRUE(item(plan.resources, "separable blur pass")->kept);
}

// Camera and light both straight down over a receiver plane: one shadow-map texel covers
// 2 H tan(cone/2) / N world units, one pixel 2 h tan(fovy/2) / height units, so the view
// minifies the map by (N / height) (h tan(fovy/2)) / (H tan(cone/2)).
double expectedTexelsPerPixel(const Scene& s, const RenderParams& p) {
  const double h = s.camera.position.y, H = s.light.position.y;
  return (double(p.shadowMapTexels) / p.height) *
         (h * std::tan(glm::radians(s.camera.fovyDegrees / 2.0))) /
         (H * std::tan(glm::radians(s.light.coneDegrees / 2.0)));
}

TEST(Plan, MipChainOnlyWhenTheViewMinifies) {
  Scene s = column();
  s.objects.erase(s.objects.begin() + 1);  // only the ground: one planar receiver
  s.objects[0].castsShadow = true;
  s.camera.position = {0, 6, 0};
  s.camera.target = {0, 0, 0};
  s.camera.up = {0, 0, -1};
  s.camera.fovyDegrees = 30;
  RenderParams p;
  p.width = p.height = 256;
  for (int n : {64, 2048}) {
    p.shadowMapTexels = n;
    const FramePlan plan = planFrame(s, convolutionPrefiltered(), p);
    const double expected = expectedTexelsPerPixel(s, p);
    // Perspective foreshortening is absent (both views look straight down) except for the
    // spotlight's own perspective across the plane: 2% covers the rounding of the sampling.
    EXPECT_NEAR(plan.maxShadowTexelsPerPixel, expected, 0.02 * expected) << "map " << n;
    EXPECT_EQ(item(plan.resources, "mip chain")->kept, expected > 1.0) << "map " << n;
    // Anisotropic filtering reads the chain as tri-linear does; bilinear reads level 0 only;
    // mipmaps=always keeps it whatever the view.
    RenderParams aniso = p;
    aniso.extra["filtering"] = "anisotropic";
    EXPECT_EQ(item(planFrame(s, convolutionPrefiltered(), aniso).resources, "mip chain")->kept,
              expected > 1.0)
        << "map " << n;
    RenderParams bilinear = p;
    bilinear.extra["filtering"] = "bilinear";
    EXPECT_FALSE(
        item(planFrame(s, convolutionPrefiltered(), bilinear).resources, "mip chain")->kept);
    RenderParams always = p;
    always.extra["mipmaps"] = "always";
    EXPECT_TRUE(item(planFrame(s, convolutionPrefiltered(), always).resources, "mip chain")->kept);
  }
}

TEST(Plan, FormatNamesKeptAndLeftOut) {
  Scene s = column();
  s.objects[1].model = at(6.0f, kCasterTop - 0.5f, 0);
  const std::string text = formatPlan(planFrame(s, named("test.plain-map"), RenderParams{}));
  EXPECT_NE(text.find("leave light passes"), std::string::npos) << text;
  EXPECT_NE(text.find("keep  camera pass"), std::string::npos) << text;
}

}  // namespace
}  // namespace sl
