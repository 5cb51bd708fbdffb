// core/gl/gl_fault.h: a GL error or a missing entry point injected at a chosen pass or GL call,
// caught by the project's own error handling (checkGl, PassTimer's end-of-pass check, the
// dispatch's entry-point check); and core/technique/technique.h PassTimer, whose destructor notes
// the end-of-pass error instead of throwing.
#include "core/gl/gl_fault.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <type_traits>

#include "core/base/errors.h"
#include "core/gl/context.h"
#include "core/gl/gl.h"
#include "core/gl/gl_trace.h"
#include "core/technique/passes.h"
#include "core/technique/technique.h"

namespace sl {
namespace {
using namespace sl::gl;

std::unique_ptr<GlContext> smallContext() {
  ContextSpec spec;
  spec.width = 32;
  spec.height = 32;
  return GlContext::create(spec);
}

// Two passes of a pass table that clear the colour buffer: "1 clear" and "2 clear again".
const PassTable kTwoPassTable = {{.id = "1", .name = "clear"}, {.id = "2", .name = "clear again"}};

const RenderFunction kTwoPasses = [](GlContext&, const Scene&, const RenderParams& params) {
  Frame frame;
  Passes passes(frame, params, kTwoPassTable);
  passes.run("1", [] { glClear(GL_COLOR_BUFFER_BIT); });
  passes.run("2", [] { glClear(GL_COLOR_BUFFER_BIT); });
  return frame;
};

// The message of the GlError `body` throws, or "no GlError".
template <class Body>
std::string glErrorOf(Body body) {
  try {
    body();
  } catch (const GlError& e) {
    return e.what();
  }
  return "no GlError";
}

// Every test disarms what it armed, fired or not.
class GlFaultTest : public ::testing::Test {
 protected:
  void TearDown() override { clearGlFault(); }
  void arm(const std::string& spelling) {
    injectGlFault(parseGlFault(spelling));
    context_->makeCurrent();  // the fault takes effect at makeCurrent
  }
  std::unique_ptr<GlContext> context_ = smallContext();
  Scene scene_;
  RenderParams params_;
};

TEST(GlFaultParse, ReadsEveryKindAndTrigger) {
  const GlFault a = parseGlFault("error@pass=5b");
  EXPECT_EQ(a.kind, GlFault::Kind::kError);
  EXPECT_EQ(a.trigger, GlFault::Trigger::kPassId);
  EXPECT_EQ(a.passId, "5b");
  const GlFault b = parseGlFault("missing@pass#12");
  EXPECT_EQ(b.kind, GlFault::Kind::kMissingEntryPoint);
  EXPECT_EQ(b.trigger, GlFault::Trigger::kPassNumber);
  EXPECT_EQ(b.number, 12);
  const GlFault c = parseGlFault("error@call#1");
  EXPECT_EQ(c.trigger, GlFault::Trigger::kCallNumber);
  EXPECT_EQ(c.number, 1);
  EXPECT_EQ(c.spelling, "error@call#1");
}

TEST(GlFaultParse, RefusesMalformedSpellingsNamingTheVariable) {
  for (const char* bad :
       {"error", "crash@pass#1", "error@pass=", "error@pass=3 projective", "error@pass#0",
        "error@call#x", "error@call#-3", "error@frame#1", "@pass#1", "missing@call#1.5"}) {
    try {
      parseGlFault(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("SHADOWLAB_INJECT_GL_FAULT"), std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

// Nothing armed: makeCurrent makes the context's own table current, so every GL call goes
// straight to it (no layer, no count).
TEST_F(GlFaultTest, UnarmedTheContextsOwnTableIsCurrent) {
  context_->makeCurrent();
  EXPECT_EQ(&currentGl(), &context_->dispatch());
  EXPECT_FALSE(glFaultArmed());
}

TEST_F(GlFaultTest, ErrorAtAPassByIdEndsTheRenderNamingThePass) {
  const int fired = glFaultsFired();
  arm("error@pass=2");
  EXPECT_NE(&currentGl(), &context_->dispatch()) << "armed: the fault table is current";
  const std::string what = glErrorOf([&] { kTwoPasses(*context_, scene_, params_); });
  EXPECT_EQ(what,
            "2 clear again: GL_INVALID_OPERATION (injected GL fault error@pass=2, in pass "
            "'2 clear again')");
  EXPECT_EQ(glFaultsFired(), fired + 1);
  EXPECT_FALSE(glFaultArmed()) << "a fault fires once";
  // The next render on the same context is clean.
  EXPECT_EQ(kTwoPasses(*context_, scene_, params_).passes.size(), 2u);
}

TEST_F(GlFaultTest, ErrorIsReportedByTheFirstErrorCheckInsideThePass) {
  arm("error@pass#1");
  Frame frame;
  const std::string what = glErrorOf([&] {
    PassTimer timer(frame, "1 read back");
    readColorBuffer(0, 0, 4, 4);  // checkGl("read colour buffer") inside the pass
  });
  EXPECT_EQ(what,
            "read colour buffer: GL_INVALID_OPERATION (injected GL fault error@pass#1, in "
            "pass '1 read back')");
}

TEST_F(GlFaultTest, MissingEntryPointAtTheNthPassIsTheDispatchsOwnError) {
  arm("missing@pass#2");
  const std::string what = glErrorOf([&] { kTwoPasses(*context_, scene_, params_); });
  EXPECT_EQ(what,
            "the current GL implementation has no entry point glClear (injected GL fault "
            "missing@pass#2, in pass '2 clear again')");
}

// A pass with no GL call of its own: the missing entry point is PassTimer's own glFinish at
// the end of the pass, which the destructor notes instead of throwing. (A hand-timed pass has
// no pass-table id: pass#N meets it, pass=ID cannot.)
TEST_F(GlFaultTest, MissingEntryPointInAPassWithoutCallsIsNotedByThePassEnd) {
  arm("missing@pass#1");
  Frame frame;
  const RenderFunction render = [&](GlContext&, const Scene&, const RenderParams&) {
    { PassTimer timer(frame, "1 CPU only"); }
    return frame;
  };
  EXPECT_EQ(glErrorOf([&] { render(*context_, scene_, params_); }),
            "1 CPU only: the current GL implementation has no entry point glFinish (injected GL "
            "fault missing@pass#1, in pass '1 CPU only')");
}

// The Nth call is glGetError itself: it reports the error.
TEST_F(GlFaultTest, ErrorAtTheNthCallWhenItIsGlGetError) {
  arm("error@call#3");
  glClear(GL_COLOR_BUFFER_BIT);
  glClear(GL_COLOR_BUFFER_BIT);
  EXPECT_EQ(glGetError(), GLenum(GL_INVALID_OPERATION));
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  EXPECT_FALSE(glFaultArmed());
}

TEST_F(GlFaultTest, ErrorAtTheNthCallFailsThatCall) {
  arm("error@call#2");
  glClear(GL_COLOR_BUFFER_BIT);
  glClearColor(0, 0, 0, 1);  // the second call: made, then reported as failed
  EXPECT_EQ(glGetError(), GLenum(GL_INVALID_OPERATION));
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  EXPECT_EQ(takeGlFaultNote(), " (injected GL fault error@call#2, outside any pass)");
}

TEST_F(GlFaultTest, MissingAtTheNthCallNamesThePassItFallsIn) {
  arm("missing@call#3");  // glFinish (pass 1 begins), glClear, glFinish (pass 1 ends)
  EXPECT_EQ(glErrorOf([&] { kTwoPasses(*context_, scene_, params_); }),
            "the current GL implementation has no entry point glFinish (injected GL fault "
            "missing@call#3, in pass '1 clear')");
}

// --dump-passes traces on top of the fault table: the fault still fires, the trace sees the
// calls, and the context's table is current again afterwards.
TEST_F(GlFaultTest, FiresUnderAGlTrace) {
  arm("error@pass=1");
  {
    GlTrace trace;
    EXPECT_NE(glErrorOf([&] { kTwoPasses(*context_, scene_, params_); }).find("in pass '1 clear'"),
              std::string::npos);
  }
  context_->makeCurrent();
  EXPECT_EQ(&currentGl(), &context_->dispatch()) << "fired: no fault table at makeCurrent";
}

// An armed fault whose trigger is never met changes nothing: same passes, no error. A display
// name's prefix is not an id: pass=1 does not meet a hand-timed pass named "1 ...".
TEST_F(GlFaultTest, AnUnmetFaultChangesNothing) {
  arm("error@pass=1");
  {
    Frame frame;
    PassTimer timer(frame, "1 hand-timed");
    glClear(GL_COLOR_BUFFER_BIT);
  }
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  context_->makeCurrent();
  arm("error@pass=9");
  const Frame frame = kTwoPasses(*context_, scene_, params_);
  EXPECT_EQ(frame.passes.size(), 2u);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  EXPECT_TRUE(glFaultArmed());
}

static_assert(std::is_nothrow_destructible_v<PassTimer>, "PassTimer's destructor does not throw");

// A real GL error at the end of a pass (no injection): the render still ends with GlError
// naming the pass, and the pass is recorded.
TEST_F(GlFaultTest, PassTimerNotesARealErrorAndTheRenderThrowsIt) {
  context_->makeCurrent();
  Frame seen;
  const RenderFunction render = [&](GlContext&, const Scene&, const RenderParams&) {
    Frame frame;
    {
      PassTimer timer(frame, "1 bad enum");
      glEnable(GLenum(0x1234));  // GL_INVALID_ENUM
    }
    seen = frame;
    return frame;
  };
  EXPECT_EQ(glErrorOf([&] { render(*context_, scene_, params_); }), "1 bad enum: GL_INVALID_ENUM");
  ASSERT_EQ(seen.passes.size(), 1u);
  EXPECT_EQ(seen.passes[0].name, "1 bad enum");
  EXPECT_FALSE(glErrorNoted());
}

// The next pass does not run after a failed one, and the failure met first wins over a later
// exception.
TEST_F(GlFaultTest, ANotedErrorStopsTheNextPassAndWinsOverALaterException) {
  context_->makeCurrent();
  bool secondRan = false;
  const RenderFunction twoPassesThenThrow = [&](GlContext&, const Scene&, const RenderParams&) {
    Frame frame;
    {
      PassTimer timer(frame, "1 bad enum");
      glEnable(GLenum(0x1234));
    }
    {
      PassTimer timer(frame, "2 next");
      secondRan = true;
    }
    return frame;
  };
  EXPECT_EQ(glErrorOf([&] { twoPassesThenThrow(*context_, scene_, params_); }),
            "1 bad enum: GL_INVALID_ENUM");
  EXPECT_FALSE(secondRan);
  const RenderFunction failThenThrow = [&](GlContext&, const Scene&, const RenderParams&) -> Frame {
    Frame frame;
    {
      PassTimer timer(frame, "1 bad enum");
      glEnable(GLenum(0x1234));
    }
    throw std::runtime_error("later");
  };
  EXPECT_EQ(glErrorOf([&] { failThenThrow(*context_, scene_, params_); }),
            "1 bad enum: GL_INVALID_ENUM");
}

}  // namespace
}  // namespace sl
