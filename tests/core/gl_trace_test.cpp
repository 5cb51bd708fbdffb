// core/gl/gl_trace.h: the tracing layer on the dispatch table. Off, the context's
// own table is current and untouched; on, calls go through a second table that records them per
// pass and forwards to the first; afterwards the first is current again, unchanged.
#include "core/gl/gl_trace.h"

#include <gtest/gtest.h>

#include <cstring>

#include "core/base/errors.h"
#include "core/gl/context.h"
#include "core/gl/gl.h"
#include "core/technique/technique.h"

namespace sl {
namespace {
using namespace sl::gl;

std::unique_ptr<GlContext> smallContext() {
  ContextSpec spec;
  spec.width = 64;
  spec.height = 64;
  return GlContext::create(spec);
}

bool sameTable(const GlDispatch& a, const GlDispatch& b) {
  return std::memcmp(&a, &b, sizeof(GlDispatch)) == 0;
}

std::string joined(const std::vector<GlStateLine>& lines) {
  std::string out;
  for (const GlStateLine& l : lines) out += l.group + ": " + l.text + "\n";
  return out;
}

// Tracing off: rendering passes (PassTimer) never swaps or edits the dispatch table.
TEST(GlTrace, OffLeavesTheDispatchTableUntouched) {
  auto ctx = smallContext();
  const GlDispatch before = ctx->dispatch();
  ASSERT_EQ(&currentGl(), &ctx->dispatch());
  Frame frame;
  {
    PassTimer timer(frame, "1 clear");
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
  }
  EXPECT_FALSE(glTraceActive());
  EXPECT_EQ(&currentGl(), &ctx->dispatch()) << "calls go straight to the context's table";
  EXPECT_TRUE(sameTable(before, ctx->dispatch()));
  ASSERT_EQ(frame.passes.size(), 1u);
  EXPECT_TRUE(frame.passes[0].gl.state.empty()) << joined(frame.passes[0].gl.state);
}

// On: a second table is current, the context's own is not edited, and it is current again after.
TEST(GlTrace, OnWrapsTheTableAndRestoresIt) {
  auto ctx = smallContext();
  const GlDispatch before = ctx->dispatch();
  {
    GlTrace trace;
    EXPECT_TRUE(glTraceActive());
    EXPECT_NE(&currentGl(), &ctx->dispatch());
    EXPECT_NE(currentGl().Clear, ctx->dispatch().Clear) << "the traced entry wraps the driver's";
    EXPECT_TRUE(sameTable(before, ctx->dispatch()));
    EXPECT_THROW(GlTrace second, GlError) << "one trace per thread";
  }
  EXPECT_FALSE(glTraceActive());
  EXPECT_EQ(&currentGl(), &ctx->dispatch());
  EXPECT_TRUE(sameTable(before, ctx->dispatch()));
}

// Lines per pass: state changes with their arguments by name, immediate-mode draws counted, the
// calls made before a pass kept as its setup, queries and paused readbacks left out.
TEST(GlTrace, RecordsStatePerPassAndSummarisesDraws) {
  auto ctx = smallContext();
  GlTrace trace;
  Frame frame;
  glDepthFunc(GL_LEQUAL);  // before the pass: its setup
  {
    PassTimer timer(frame, "1 planes", "a section");
    const GLfloat plane[4] = {1.0f, 0.0f, 0.5f, 2.0f};
    glTexGeni(GL_S, GL_TEXTURE_GEN_MODE, GL_EYE_LINEAR);
    glTexGenfv(GL_S, GL_EYE_PLANE, plane);
    glBlendFunc(GL_ONE, GL_ZERO);
    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);  // a query: not state
    for (int object = 0; object < 3; ++object) {
      glBegin(GL_TRIANGLES);
      for (int v = 0; v < 6; ++v) glVertex3f(0.0f, 0.0f, 0.0f);
      glEnd();
    }
    {
      const GlTracePause dumpOnly;
      glClear(GL_COLOR_BUFFER_BIT);
    }
  }
  ASSERT_EQ(frame.passes.size(), 1u);
  const PassTime& pass = frame.passes[0];
  EXPECT_EQ(pass.section, "a section");
  EXPECT_EQ(pass.sourceFile, "tests/core/gl_trace_test.cpp");
  EXPECT_EQ(pass.sourceFunction, "TestBody");
  ASSERT_EQ(pass.gl.setup.size(), 1u) << joined(pass.gl.setup);
  EXPECT_EQ(pass.gl.setup[0].group, "depth");
  EXPECT_EQ(pass.gl.setup[0].text, "glDepthFunc(GL_LEQUAL)");
  const std::string state = joined(pass.gl.state);
  EXPECT_NE(state.find("texgen: GL_S: GL_TEXTURE_GEN_MODE = GL_EYE_LINEAR"), std::string::npos)
      << state;
  EXPECT_NE(state.find("texgen: GL_S: GL_EYE_PLANE = (1, 0, 0.5, 2)"), std::string::npos) << state;
  EXPECT_NE(state.find("blend: glBlendFunc(GL_ONE, GL_ZERO)"), std::string::npos) << state;
  EXPECT_NE(state.find("draw: glBegin(GL_TRIANGLES) x 3 objects, 18 vertices"), std::string::npos)
      << state;
  EXPECT_EQ(state.find("glGetIntegerv"), std::string::npos) << state;
  EXPECT_EQ(state.find("clear"), std::string::npos) << "paused: " << state;
  EXPECT_EQ(pass.gl.state.size(), 4u) << state;
}

// A scene's vertex arrays filled and described before a pass (dozens of calls) read as one
// line saying how many arrays, buffers and bytes; the draw that follows keeps its own line.
TEST(GlTrace, MeshUploadIsOneLine) {
  ContextSpec spec;
  spec.width = 64;
  spec.height = 64;
  spec.profile = Profile::kCore;
  auto ctx = GlContext::create(spec);
  constexpr int kMeshes = 3;
  constexpr GLsizeiptr kPositionBytes = 9 * sizeof(GLfloat);
  constexpr GLsizeiptr kIndexBytes = 3 * sizeof(GLuint);
  GLuint arrays[kMeshes];
  GLuint buffers[2 * kMeshes];
  glGenVertexArrays(kMeshes, arrays);
  glGenBuffers(2 * kMeshes, buffers);
  const GLfloat positions[9] = {};
  const GLuint indices[3] = {0, 1, 2};
  GlTrace trace;
  Frame frame;
  {
    PassTimer timer(frame, "1 upload and draw");
    for (int m = 0; m < kMeshes; ++m) {
      glBindVertexArray(arrays[m]);
      glBindBuffer(GL_ARRAY_BUFFER, buffers[2 * m]);
      glBufferData(GL_ARRAY_BUFFER, kPositionBytes, positions, GL_STATIC_DRAW);
      glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
      glEnableVertexAttribArray(0);
      glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers[2 * m + 1]);
      glBufferData(GL_ELEMENT_ARRAY_BUFFER, kIndexBytes, indices, GL_STATIC_DRAW);
      glBindVertexArray(0);
    }
    glBindVertexArray(arrays[0]);
    glDrawElements(GL_TRIANGLES, 3, GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
  }
  const std::string state = joined(frame.passes.at(0).gl.state);
  const std::string expected = "vertex arrays: mesh upload: " + std::to_string(kMeshes) +
                               " vertex arrays, " + std::to_string(2 * kMeshes) + " buffers, " +
                               std::to_string(kMeshes * (kPositionBytes + kIndexBytes)) + " bytes";
  EXPECT_NE(state.find(expected), std::string::npos) << state;
  EXPECT_EQ(state.find("glBufferData("), std::string::npos) << state;
  EXPECT_NE(state.find("draw: glDrawElements"), std::string::npos) << state;
}

// Matrices by matrix mode (the colour matrix is its own group), rows first.
TEST(GlTrace, MatricesAreNamedByModeAndPrintedAsRows) {
  auto ctx = smallContext();
  GlTrace trace;
  Frame frame;
  {
    PassTimer timer(frame, "1 matrices");
    const GLfloat translate[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 1};
    glMatrixMode(GL_TEXTURE);
    glLoadMatrixf(translate);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
  }
  const std::string state = joined(frame.passes.at(0).gl.state);
  EXPECT_NE(
      state.find("matrix: texture matrix (unit 0): load [1 0 0 5; 0 1 0 6; 0 0 1 7; 0 0 0 1]"),
      std::string::npos)
      << state;
  EXPECT_NE(state.find("matrix: modelview: identity"), std::string::npos) << state;
}

TEST(GlTrace, EnumNames) {
  EXPECT_EQ(glEnumName(GL_EYE_LINEAR), "GL_EYE_LINEAR");
  EXPECT_EQ(glEnumName(GL_FUNC_REVERSE_SUBTRACT), "GL_FUNC_REVERSE_SUBTRACT");
  // Two names of one value (OpenGL 3.0 renamed ARB_shadow's) are both given.
  EXPECT_NE(glEnumName(GL_COMPARE_R_TO_TEXTURE).find("GL_COMPARE_R_TO_TEXTURE"), std::string::npos);
  EXPECT_EQ(glEnumName(0x7FFF), "0x7FFF");
}

}  // namespace
}  // namespace sl
