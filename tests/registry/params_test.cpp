// tests/registry/params_test.cpp — each technique's --param declarations
// (core/technique/technique.h ParamSpec) are the whole truth: every key its render reads is
// declared, with the default the declaration states, and `list` prints them. The render reads
// through the declarations, so a key read without one (a bare extra.find) or a second, drifting
// default would show here.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "core/base/errors.h"
#include "core/scene/scene_library.h"
#include "core/technique/technique.h"
#include "registry/registry.h"

namespace sl {
namespace {

constexpr int kTinyWidth = 48;  // the smallest window every technique renders quickly
constexpr int kTinyHeight = 36;
constexpr int kTinyMapTexels = 64;

TEST(ParamDeclarations, EveryKeyReadIsDeclaredWithItsDefault) {
  const Scene scene = builtinScene("brabec");
  for (const Technique& t : allTechniques()) {
    RenderParams p;
    p.width = kTinyWidth;
    p.height = kTinyHeight;
    p.shadowMapTexels = kTinyMapTexels;
    p.readLog = std::make_shared<ParamReadLog>();
    if (t.name == "reference.soft") p.extra["rays"] = "8";  // the default's 288 rays: slow
    renderTechnique(t, scene, p);
    std::set<std::string> keys;
    for (const auto& [key, value] : p.readLog->values) {
      keys.insert(key);
      const ParamSpec* spec = findParam(t, key);
      ASSERT_NE(spec, nullptr) << t.name << " reads --param " << key << " without declaring it";
      if (p.extra.count(key) == 0) {
        EXPECT_TRUE(spec->isDefault(value))
            << t.name << " --param " << key << ": read with default " << value << ", declared "
            << spec->defaultText();
      }
    }
    // Keys declared but not read at all are allowed only where they apply to other settings
    // (anisotropy with filtering=anisotropic, mask-pass with a stencil mask, rays with soft...):
    // every declaration still needs a meaning and a default a render accepts.
    for (const ParamSpec& spec : t.params) {
      EXPECT_FALSE(spec.meaning.empty()) << t.name << " --param " << spec.key;
      RenderParams given = p;
      given.readLog.reset();
      given.extra[spec.key] = spec.defaultText();
      EXPECT_NO_THROW(renderTechnique(t, scene, given))
          << t.name << " refuses its own default --param " << spec.key << "=" << spec.defaultText();
    }
  }
}

TEST(ParamDeclarations, DefaultsCompareAsNumbers) {
  const ParamSpec alpha = numberParam("alpha", 1.0, 0.0, 50.0, "test");
  EXPECT_TRUE(alpha.isDefault("1"));
  EXPECT_TRUE(alpha.isDefault("1.0"));
  EXPECT_FALSE(alpha.isDefault("1.5"));
  const ParamSpec remap = flagParam("remap", true, "test");
  EXPECT_TRUE(remap.isDefault("on"));
  EXPECT_FALSE(remap.isDefault("true"));  // a flag takes on|off only
  EXPECT_FALSE(remap.isDefault("off"));
  const ParamSpec offset = autoNumberParam("offset", 0.0, 0.5, "test");
  EXPECT_EQ(offset.defaultText(), "auto");
  EXPECT_FALSE(offset.isDefault("0"));
}

TEST(ParamDeclarations, AutoNumbersAcceptAutoAndTheirRange) {
  RenderParams p;
  const ParamSpec offset = autoNumberParam("offset", 0.0, 0.5, "test");
  EXPECT_FALSE(p.numberOrAuto(offset).has_value());
  p.extra["offset"] = "auto";
  EXPECT_FALSE(p.numberOrAuto(offset).has_value());
  p.extra["offset"] = "0.25";
  EXPECT_EQ(p.numberOrAuto(offset), 0.25);
  p.extra["offset"] = "0.75";
  EXPECT_THROW(p.numberOrAuto(offset), InputError);
}

}  // namespace
}  // namespace sl
