// core/gl/gl_objects.h on a real OSMesa context: owned names are deleted when their owner goes
// (also after a move), and the scoped state helpers undo their change when the scope is left by
// an exception, as a failing pass leaves it.
#include "core/gl/gl_objects.h"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <utility>

#include "core/gl/context.h"

namespace sl {
namespace {
using namespace sl::gl;

std::unique_ptr<GlContext> smallContext() {
  ContextSpec spec;
  spec.width = 16;
  spec.height = 16;
  return GlContext::create(spec);
}

// A texture name is a texture once bound (glIsTexture is false for a name never bound).
bool isTexture(GLuint id) { return glIsTexture(id) == GL_TRUE; }

TEST(GlObjects, TextureIsDeletedWithItsOwner) {
  auto context = smallContext();
  GLuint id = 0;
  {
    const Texture texture = makeTexture();
    id = texture.id();
    ASSERT_NE(id, 0u);
    glBindTexture(GL_TEXTURE_2D, id);
    glBindTexture(GL_TEXTURE_2D, 0);
    EXPECT_TRUE(isTexture(id));
  }
  EXPECT_FALSE(isTexture(id));
}

TEST(GlObjects, MovedNameHasOneOwnerAndAssignmentDeletesTheOldOne) {
  auto context = smallContext();
  Texture a = makeTexture();
  const GLuint first = a.id();
  glBindTexture(GL_TEXTURE_2D, first);
  Texture b = std::move(a);
  EXPECT_EQ(a.id(), 0u);  // NOLINT(bugprone-use-after-move): the moved-from owner is empty
  EXPECT_EQ(b.id(), first);
  Texture c = makeTexture();
  const GLuint second = c.id();
  glBindTexture(GL_TEXTURE_2D, second);
  glBindTexture(GL_TEXTURE_2D, 0);
  b = std::move(c);  // b's first name is deleted, b owns the second
  EXPECT_FALSE(isTexture(first));
  EXPECT_TRUE(isTexture(second));
  EXPECT_EQ(b.id(), second);
}

TEST(GlObjects, ScopedEnableIsOffAfterAnException) {
  auto context = smallContext();
  ASSERT_EQ(glIsEnabled(GL_BLEND), GL_FALSE);
  try {
    const ScopedEnable blend(GL_BLEND);
    EXPECT_EQ(glIsEnabled(GL_BLEND), GL_TRUE);
    throw std::runtime_error("a pass fails");
  } catch (const std::runtime_error&) {}
  EXPECT_EQ(glIsEnabled(GL_BLEND), GL_FALSE);
}

TEST(GlObjects, ScopedClientStateAndPushMatrixRestoreAfterAnException) {
  auto context = smallContext();
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  ASSERT_EQ(glIsEnabled(GL_VERTEX_ARRAY), GL_FALSE);
  try {
    const ScopedClientState vertices(GL_VERTEX_ARRAY);
    const ScopedPushMatrix model;
    glTranslatef(1.0f, 2.0f, 3.0f);
    EXPECT_EQ(glIsEnabled(GL_VERTEX_ARRAY), GL_TRUE);
    throw std::runtime_error("a draw fails");
  } catch (const std::runtime_error&) {}
  EXPECT_EQ(glIsEnabled(GL_VERTEX_ARRAY), GL_FALSE);
  GLfloat modelview[16];
  glGetFloatv(GL_MODELVIEW_MATRIX, modelview);
  EXPECT_EQ(modelview[12], 0.0f);  // the translation went with the popped matrix
}

TEST(GlObjects, ScopedAttribAndMatricesRestoreAfterAnException) {
  auto context = smallContext();
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glDepthFunc(GL_LESS);
  try {
    const ScopedAttrib state(GL_ALL_ATTRIB_BITS);
    const ScopedMatrices matrices;
    glDepthFunc(GL_GREATER);
    glMatrixMode(GL_MODELVIEW);
    glTranslatef(1.0f, 2.0f, 3.0f);
    throw std::runtime_error("a pass fails");
  } catch (const std::runtime_error&) {}
  GLint depthFunc = 0, mode = 0;
  glGetIntegerv(GL_DEPTH_FUNC, &depthFunc);
  glGetIntegerv(GL_MATRIX_MODE, &mode);
  EXPECT_EQ(depthFunc, GL_LESS);
  EXPECT_EQ(mode, GL_MODELVIEW);  // the attribute stack gave the mode back
  GLfloat modelview[16];
  glGetFloatv(GL_MODELVIEW_MATRIX, modelview);
  EXPECT_EQ(modelview[12], 0.0f);  // the translation is gone with the popped matrix
  EXPECT_EQ(modelview[13], 0.0f);
  EXPECT_EQ(modelview[14], 0.0f);
}

}  // namespace
}  // namespace sl
