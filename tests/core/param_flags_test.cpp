// One vocabulary for flag --params: `shadowlab list` says on|off, so on and off are
// the only words a flag takes; true/false/1/0 are refused with a message naming the two.
#include <gtest/gtest.h>

#include <string>

#include "core/base/errors.h"
#include "core/technique/technique.h"

namespace sl {
namespace {

std::string flagError(const RenderParams& p, const ParamSpec& spec) {
  try {
    p.flag(spec);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(ParamFlags, OnlyOnAndOff) {
  const ParamSpec remap = flagParam("remap", true, "test");
  RenderParams p;
  EXPECT_TRUE(p.flag(remap));  // not given: the default
  p.extra["remap"] = "off";
  EXPECT_FALSE(p.flag(remap));
  p.extra["remap"] = "on";
  EXPECT_TRUE(p.flag(remap));
  for (const char* word : {"true", "false", "1", "0", "yes", "ON", ""}) {
    p.extra["remap"] = word;
    EXPECT_EQ(flagError(p, remap), std::string("--param remap=") + word + ": expected on or off");
  }
  EXPECT_EQ(describeParam(remap), "remap=on (on|off): test");
  EXPECT_TRUE(remap.isDefault("on"));
  EXPECT_FALSE(remap.isDefault("true"));  // not a flag's word: a variant, not the default
  EXPECT_FALSE(remap.isDefault("off"));
}

// checkParams refuses a wrong word before anything renders, even where a frame would not read
// the flag (modern.hw reads plan only when the scene might let it leave a pass out).
TEST(ParamFlags, CheckedBeforeRendering) {
  Technique t;
  t.name = "test.flags";
  t.params = {flagParam("plan", true, "test")};
  RenderParams p;
  p.extra["plan"] = "off";
  EXPECT_NO_THROW(checkParams(t, p, 0));
  p.extra["plan"] = "false";
  try {
    checkParams(t, p, 0);
    FAIL() << "plan=false accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "--param plan=false: expected on or off");
  }
}

}  // namespace
}  // namespace sl
