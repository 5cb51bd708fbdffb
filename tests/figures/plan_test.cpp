// The planner consulted by legacy.hw and modern.hw, end to end: with no caster in the light
// frustum the light pass is left out, and the result is the one the full pass gives; and the
// `shadowlab plan` command.
#include "core/plan.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>

#include "registry/registry.h"
#include "core/scene_library.h"

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
