// Context creation on every back end and colour precision the project relies on
// (docs/design.md "Platform facts").
#include "core/gl/context.h"

#include <gtest/gtest.h>

#include "core/base/errors.h"

namespace sl {
namespace {
using namespace sl::gl;

TEST(Context, OsmesaCompatibilityHasAccumulationAndNoImaging) {
  ContextSpec spec;
  spec.width = 64;
  spec.height = 48;
  auto ctx = GlContext::create(spec);
  EXPECT_NE(ctx->caps().version.find("Compatibility"), std::string::npos) << ctx->caps().version;
  EXPECT_EQ(ctx->caps().accumRedBits, 16);
  EXPECT_EQ(ctx->caps().redBits, 8);
  EXPECT_EQ(ctx->caps().depthBits, 24);
  EXPECT_EQ(ctx->caps().stencilBits, 8);
  EXPECT_FALSE(ctx->caps().nativeImaging());  // Mesa removed ARB_imaging (docs/design.md)
  EXPECT_TRUE(ctx->caps().hasExtension("GL_ARB_shadow"));
  EXPECT_GE(ctx->caps().maxTextureSize, 2048);
}

TEST(Context, OsmesaCoreProfile) {
  ContextSpec spec;
  spec.profile = Profile::kCore;
  spec.width = 32;
  spec.height = 32;
  auto ctx = GlContext::create(spec);
  EXPECT_NE(ctx->caps().version.find("Core"), std::string::npos) << ctx->caps().version;
  EXPECT_TRUE(ctx->caps().hasExtension("GL_ARB_framebuffer_object") ||
              ctx->caps().version.rfind("4.", 0) == 0);
}

TEST(Context, ColourPrecisions) {
  const struct {
    ColorFormat format;
    int redBits;
  } cases[] = {{ColorFormat::kRgba8, 8}, {ColorFormat::kRgba16, 16}, {ColorFormat::kRgba32f, 32}};
  for (const auto& c : cases) {
    ContextSpec spec;
    spec.width = 16;
    spec.height = 16;
    spec.color = c.format;
    auto ctx = GlContext::create(spec);
    EXPECT_EQ(ctx->caps().redBits, c.redBits) << colorFormatName(c.format);
    // A cleared value survives at the buffer's precision: 0.3 in float is exact to 1e-7,
    // in 16 bits to 1/65535, in 8 bits to 1/255 (half a step of rounding each).
    glClearColor(0.3f, 0.3f, 0.3f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    float v = 0;
    glReadPixels(0, 0, 1, 1, GL_RED, GL_FLOAT, &v);
    const float step = c.redBits == 32 ? 1e-6f : 1.0f / float((1 << c.redBits) - 1);
    EXPECT_NEAR(v, 0.3f, 0.5f * step + 1e-7f) << colorFormatName(c.format);
  }
}

TEST(Context, TwoContextsKeepTheirOwnDispatch) {
  ContextSpec spec;
  spec.width = 8;
  spec.height = 8;
  auto a = GlContext::create(spec);
  spec.profile = Profile::kCore;
  auto b = GlContext::create(spec);
  EXPECT_EQ(GlContext::current(), b.get());
  a->makeCurrent();
  EXPECT_EQ(GlContext::current(), a.get());
  EXPECT_NE(std::string(reinterpret_cast<const char*>(glGetString(GL_VERSION))).find("Compat"),
            std::string::npos);
}

TEST(Context, ImpossibleSizesAreInputErrors) {
  ContextSpec spec;
  spec.width = 0;
  EXPECT_THROW(GlContext::create(spec), InputError);
  spec.width = -5;
  EXPECT_THROW(GlContext::create(spec), InputError);
  spec.width = 100000;
  EXPECT_THROW(GlContext::create(spec), InputError);
}

TEST(Context, CallingGlWithoutAContextThrows) {
  setCurrentGl(nullptr);
  EXPECT_THROW(glGetError(), GlError);
}

TEST(Context, ReferenceGlWhenPresent) {
  if (referenceGlPath().empty()) GTEST_SKIP() << "reference GL not configured";
  ContextSpec spec;
  spec.backend = Backend::kReference;
  spec.width = 16;
  spec.height = 16;
  auto ctx = GlContext::create(spec);
  EXPECT_EQ(ctx->caps().version, "2.1 Mesa 7.8.2");
  EXPECT_TRUE(ctx->caps().nativeImaging());
  EXPECT_EQ(ctx->caps().accumRedBits, 16);
  // Side by side with a Debian context in one process (reference-gl README).
  ContextSpec debian;
  debian.width = 16;
  debian.height = 16;
  auto other = GlContext::create(debian);
  ctx->makeCurrent();
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(glGetString(GL_VERSION))), "2.1 Mesa 7.8.2");
}

}  // namespace
}  // namespace sl
