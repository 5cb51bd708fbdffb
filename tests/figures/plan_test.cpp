// The planner consulted by legacy.hw and modern.hw, end to end: with no caster in the light
// frustum the light pass is left out, and the result is the one the full pass gives; and the
// `shadowlab plan` command.
#include "core/technique/plan.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>

#include "core/scene/scene_library.h"
#include "registry/registry.h"

namespace sl {
namespace {

// The brabec scene with the light turned away from every object: it looks straight up.
Scene lightFacingAway() {
  Scene s = builtinScene("brabec");
  s.light.target = s.light.position + glm::vec3(0, 5, 0);
  s.light.up = {0, 0, -1};
  return s;
}

RenderParams small() {
  RenderParams p;
  p.width = 160;
  p.height = 120;
  return p;
}

bool hasPassContaining(const Frame& f, const std::string& text) {
  for (const PassTime& p : f.passes)
    if (p.name.find(text) != std::string::npos) return true;
  return false;
}

TEST(PlanConsulted, HardwareShadowMapsSkipTheLightPassWithoutCasters) {
  const Scene s = lightFacingAway();
  ASSERT_FALSE(casterReachesLightFrustum(s));
  for (const char* name : {"legacy.hw", "modern.hw"}) {
    const Technique& t = findTechnique(name);
    RenderParams off = small();
    off.extra["plan"] = "off";
    const Frame planned = renderTechnique(t, s, small());
    const Frame full = renderTechnique(t, s, off);
    EXPECT_TRUE(hasPassContaining(planned, "left out")) << name;
    EXPECT_FALSE(hasPassContaining(full, "left out")) << name;
    // Nothing can shadow: both give the same mask (bit for bit: the comparison against the
    // cleared far depth passes wherever the full map holds no caster either).
    EXPECT_EQ(planned.visibility.data, full.visibility.data) << name;
  }
}

TEST(PlanConsulted, NormalScenesKeepTheLightPass) {
  const Frame f = renderTechnique(findTechnique("modern.hw"), builtinScene("brabec"), small());
  EXPECT_FALSE(hasPassContaining(f, "left out"));
}

// The planner asks what each registered technique declares. The name-matching
// planner it replaced planned no blur for modern.vsm, whose module blurs with 3 taps by default.
const PlanItem* planned(const FramePlan& plan, const std::string& prefix) {
  for (const PlanItem& i : plan.resources)
    if (i.name.rfind(prefix, 0) == 0) return &i;
  return nullptr;
}

TEST(PlanConsulted, EachTechniqueDeclaresWhatThePlannerNeeds) {
  const Scene s = builtinScene("brabec");
  RenderParams p = small();
  p.filter = 4;
  for (const char* name : {"modern.vsm", "modern.csm"}) {
    const FramePlan plan = planFrame(s, findTechnique(name), p);
    const PlanItem* blur = planned(plan, "separable blur pass");
    ASSERT_TRUE(blur) << name;
    EXPECT_TRUE(blur->kept) << name << ": " << blur->reason;
    EXPECT_NE(blur->reason.find("3 taps"), std::string::npos) << name << ": " << blur->reason;
  }
  for (const char* name : {"legacy.fast-pcf", "legacy.pcf"}) {
    const FramePlan plan = planFrame(s, findTechnique(name), p);
    ASSERT_TRUE(planned(plan, "imaging: colour table")) << name;
    ASSERT_TRUE(planned(plan, "accumulation buffer")) << name;
    EXPECT_TRUE(planned(plan, "accumulation buffer")->kept) << name << ": 4x4 needs summing";
    EXPECT_EQ(planned(plan, "imaging: convolution") != nullptr,
              std::string(name) == "legacy.fast-pcf")
        << name << ": only §4 packs by convolution";
  }
  // The twins plan the same sample grouping as their legacy technique, without its imaging.
  const FramePlan modernFast = planFrame(s, findTechnique("modern.fast-pcf"), p);
  EXPECT_TRUE(planned(modernFast, "accumulation buffer"));
  EXPECT_FALSE(planned(modernFast, "imaging: colour table"));
  // A renamed copy plans exactly as the original: nothing depends on the name (the first line
  // of the formatted plan names the technique, the rest must match).
  const auto body = [&](const Technique& t) {
    const std::string text = formatPlan(planFrame(s, t, p));
    return text.substr(text.find('\n'));
  };
  Technique renamed = findTechnique("legacy.fast-pcf");
  renamed.name = "renamed.technique";
  EXPECT_EQ(body(renamed), body(findTechnique("legacy.fast-pcf")));
}

std::string run(const std::string& args, int& status) {
  std::string out;
  FILE* pipe = popen((std::string(SHADOWLAB_BINARY) + " " + args + " 2>&1").c_str(), "r");
  if (!pipe) return "popen failed";
  std::array<char, 4096> buffer{};
  while (fgets(buffer.data(), int(buffer.size()), pipe)) out += buffer.data();
  status = pclose(pipe);
  return out;
}

TEST(PlanCommand, ExplainsEveryBuiltInScene) {
  for (const std::string& scene : builtinSceneNames()) {
    int status = 0;
    const std::string out = run("plan --scene " + scene + " --technique modern.hw", status);
    EXPECT_EQ(status, 0) << out;
    EXPECT_NE(out.find("plan for modern.hw on scene " + scene), std::string::npos) << out;
    EXPECT_NE(out.find("light depth range"), std::string::npos) << out;
  }
}

TEST(PlanCommand, UnknownTechniqueIsInputError) {
  int status = 0;
  const std::string out = run("plan --scene brabec --technique nope", status);
  EXPECT_EQ(WEXITSTATUS(status), 2) << out;
}

}  // namespace
}  // namespace sl
