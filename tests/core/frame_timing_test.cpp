// The steady-state median (core/technique/frame_timing.h) on a scripted frame source: each call
// returns the next Frame of a list whose pass times are chosen here, so which frames were discarded
// and which median was taken can be read from the result exactly. No GL is involved: the
// helper only sees Frames.
#include "core/technique/frame_timing.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace sl {
namespace {

// A frame of two passes, "shadow" and "camera", and a counter naming its place in the list.
Frame frameOf(double shadowMs, double cameraMs, int index) {
  Frame f;
  f.passes = {{"shadow", shadowMs}, {"camera", cameraMs}};
  f.counters["index"] = index;
  return f;
}

// Hands out the frames in order and counts the calls.
struct Script {
  std::vector<Frame> frames;
  int calls = 0;
  std::function<Frame()> source() {
    return [this] { return frames.at(size_t(calls++)); };
  }
};

TEST(Median, OddCountIsTheMiddleValue) { EXPECT_EQ(median({9.0, 1.0, 5.0}), 5.0); }

TEST(Median, EvenCountIsTheMeanOfTheTwoMiddleValues) {
  EXPECT_EQ(median({4.0, 1.0, 3.0, 100.0}), 3.5);
}

TEST(Median, NoValuesIsAnError) { EXPECT_THROW(median({}), std::invalid_argument); }

// The first frames of a fresh context are slow (compilation, first use): they must not count.
TEST(SteadyState, DiscardsTheWarmupFramesAndTakesTheMedianOfTheRest) {
  Script s;
  s.frames = {frameOf(900, 100, 0),  // warm-up: 1000 ms
              frameOf(300, 100, 1),  // warm-up: 400 ms
              frameOf(6, 4, 2),      // 10
              frameOf(20, 30, 3),    // 50: a disturbed frame
              frameOf(5, 7, 4),      // 12
              frameOf(4, 5, 5),      // 9
              frameOf(8, 3, 6)};     // 11
  Frame last;
  const SteadyTiming t = timeSteadyState(s.source(), FrameCounts{2, 5}, &last);
  EXPECT_EQ(s.calls, 7);
  EXPECT_EQ(t.warmupFrames, 2);
  EXPECT_EQ(t.timedFrames, 5);
  EXPECT_EQ(t.frameMs, 11.0);  // median of 10, 50, 12, 9, 11
  EXPECT_EQ(t.minimumFrameMs, 9.0);
  EXPECT_EQ(t.fps(), 1000.0 / 11.0);
  ASSERT_EQ(t.passes.size(), 2u);
  EXPECT_EQ(t.passes[0].name, "shadow");
  EXPECT_EQ(t.passes[0].milliseconds, 6.0);  // median of 6, 20, 5, 4, 8
  EXPECT_EQ(t.passes[1].name, "camera");
  EXPECT_EQ(t.passes[1].milliseconds, 5.0);  // median of 4, 30, 7, 5, 3
  EXPECT_EQ(last.counters.at("index"), 6);   // the last timed frame is handed back
  EXPECT_GE(t.wallMs, 0.0);
}

TEST(SteadyState, NoWarmupTimesEveryFrame) {
  Script s;
  s.frames = {frameOf(90, 10, 0), frameOf(1, 1, 1), frameOf(2, 2, 2)};
  const SteadyTiming t = timeSteadyState(s.source(), FrameCounts{0, 3});
  EXPECT_EQ(s.calls, 3);
  EXPECT_EQ(t.frameMs, 4.0);  // median of 100, 2, 4
}

// A pass that runs in only some frames has the median of the frames it ran in.
TEST(SteadyState, PassMissingFromSomeFramesKeepsItsOwnMedian) {
  Script s;
  Frame a = frameOf(1, 1, 0), b = frameOf(1, 1, 1), c = frameOf(1, 1, 2);
  b.passes.push_back({"blur", 8});
  c.passes.push_back({"blur", 4});
  s.frames = {a, b, c};
  const SteadyTiming t = timeSteadyState(s.source(), FrameCounts{0, 3});
  ASSERT_EQ(t.passes.size(), 3u);
  EXPECT_EQ(t.passes[2].name, "blur");
  EXPECT_EQ(t.passes[2].milliseconds, 6.0);
}

// The slow-frame budget: when the first timed frame's wall time exceeds slowFrameMs, only
// slowTimed frames are timed (after the warm-up all the same). The scripted frames return at
// once, so a budget of -1 ms is always exceeded and one of +infinity never.
TEST(SteadyState, SlowBudgetTimesFewerFramesAfterTheWarmup) {
  Script s;
  s.frames = {frameOf(500, 0, 0), frameOf(3, 0, 1), frameOf(4, 0, 2), frameOf(5, 0, 3)};
  const SteadyTiming t = timeSteadyState(s.source(), FrameCounts{1, 3, -1.0, 1});
  EXPECT_EQ(s.calls, 2);
  EXPECT_EQ(t.timedFrames, 1);
  EXPECT_EQ(t.frameMs, 3.0);
  EXPECT_EQ(t.warmupFrames, 1);

  Script quick;
  quick.frames = s.frames;
  const SteadyTiming u = timeSteadyState(quick.source(), FrameCounts{1, 3});
  EXPECT_EQ(quick.calls, 4);
  EXPECT_EQ(u.frameMs, 4.0);
}

TEST(SteadyState, RejectsCountsWithoutATimedFrame) {
  Script s;
  s.frames = {frameOf(1, 1, 0)};
  EXPECT_THROW(timeSteadyState(s.source(), FrameCounts{0, 0}), std::invalid_argument);
  EXPECT_THROW(timeSteadyState(s.source(), FrameCounts{-1, 1}), std::invalid_argument);
  EXPECT_EQ(s.calls, 0);
}

// The frame source's errors reach the caller (a GL error in a pass is not a timing).
TEST(SteadyState, PassesTheSourcesExceptionOn) {
  auto failing = []() -> Frame { throw std::runtime_error("pass 2 raised GL_INVALID_OPERATION"); };
  EXPECT_THROW(timeSteadyState(failing, kSteadyFrames), std::runtime_error);
}

}  // namespace
}  // namespace sl
