// core/technique/frame_timing.h — the one way a technique's frame time is measured wherever it is
// set beside a paper's number (shadowlab figures, legacy_bench, csm_bench, volumes_bench,
// shadowlab-twins): the steady-state median.
//
// A first frame in a fresh context is not a frame of the technique: it pays for shader
// compilation, first-use allocation of textures and render targets, and llvmpipe's code
// generation for every new combination of state. So, in one context:
//   1. warm-up  — FrameCounts::warmup frames are rendered and thrown away;
//   2. timed    — FrameCounts::timed frames are rendered;
//   3. medians  — the frame time is the median over the timed frames of the sum of the
//                 technique's pass times (core/technique/technique.h PassTimer: glFinish() before
//                 and after each pass, so each pass is its own GPU+CPU work); each pass's time is
//                 the median of that pass over the timed frames (so the per-pass medians need
//                 not add up to the frame median); the wall time of the whole render() call
//                 (which also reads the colour image and the mask back for us) is kept beside.
// The median, not the mean: a frame disturbed by another process on a shared machine moves
// the mean, not the median. Speed is never asserted in tests (it is measured and reported).
#pragma once

#include <functional>
#include <limits>
#include <vector>

#include "core/technique/technique.h"

namespace sl {

struct FrameCounts {
  int warmup = 0;  // frames rendered and discarded first
  int timed = 1;   // frames whose median is reported
  // A technique whose first timed frame took longer than this (wall time, ms) is timed over
  // slowTimed frames instead of `timed` (a run-time budget for 1-2 s frames; still after the
  // warm-up, still a median). Infinity: never.
  double slowFrameMs = std::numeric_limits<double>::infinity();
  int slowTimed = 1;
};

// The benches' counts (legacy_bench, csm_bench, volumes_bench, shadowlab-twins): two warm-up
// frames (the first compiles and allocates, the second catches state first met at the end of
// the first), then the median of five (robust to two disturbed frames).
constexpr int kWarmupFrames = 2;
constexpr int kTimedFrames = 5;
constexpr FrameCounts kSteadyFrames{kWarmupFrames, kTimedFrames};
// The quick modes (--quick, and shadowlab figures, which renders every figure in one job): one
// warm-up frame, then the median of three; a technique whose first frame after the warm-up
// took longer than kQuickSlowFrameMs (CSM with a 2048² map at 1024x768 on llvmpipe: 1-2 s) is
// timed over that one frame. The bound is well above the papers' configurations on llvmpipe
// (Brabec–Seidel 800x600: 40-600 ms per steady frame from a quiet to a heavily loaded
// machine); a first frame (shader compilation, llvmpipe's code generation) can pass it.
constexpr int kQuickWarmupFrames = 1;
constexpr int kQuickTimedFrames = 3;
constexpr double kQuickSlowFrameMs = 1000.0;
constexpr FrameCounts kQuickFrames{kQuickWarmupFrames, kQuickTimedFrames, kQuickSlowFrameMs, 1};

struct SteadyTiming {
  int warmupFrames = 0, timedFrames = 0;  // as rendered (slowTimed may have applied)
  double frameMs = 0.0;                   // median of the pass-time sums
  double minimumFrameMs = 0.0;            // least disturbed timed frame
  double wallMs = 0.0;                    // median wall time of one render() call
  std::vector<PassTime> passes;           // median per pass, in the order the passes ran
  // The pass-time sums of the timed frames in the order rendered (interleaved: one per round),
  // so that a reader can see the spread and compare two configurations round by round.
  std::vector<double> frameSamples;
  double fps() const { return frameMs > 0.0 ? 1000.0 / frameMs : 0.0; }
};

// The median: the middle value, the mean of the two middle values for an even count.
// Throws std::invalid_argument for no values (there is no median of nothing).
double median(std::vector<double> values);

// Steps 1-3 on any source of frames (a technique bound to its context, or a test's sequence):
// calls renderFrame counts.warmup + timed times and returns the medians. `last`, when given,
// receives the last timed frame (its images and counters go with the timing). Throws
// std::invalid_argument for a negative warm-up or fewer than one timed frame.
SteadyTiming timeSteadyState(const std::function<Frame()>& renderFrame, const FrameCounts& counts,
                             Frame* last = nullptr);

// Interleaved timing: several configurations measured round-robin, so that a
// change of machine load during the measurement hits every configuration alike instead of the
// ones that happened to run during it. Each source is warmed up (`warmup` frames each, in
// turn), then `rounds` rounds render one timed frame of every source in turn; each source's
// SteadyTiming is the median over its rounds (frameSamples in round order). `lasts`, when given,
// receives every source's last frame. Throws std::invalid_argument for a negative warm-up or
// fewer than one round.
std::vector<SteadyTiming> timeInterleavedSteadyState(
    const std::vector<std::function<Frame()>>& sources, int warmup, int rounds,
    std::vector<Frame>* lasts = nullptr);

// For a technique on its own context: registry/registry.h timeTechnique (it installs the imaging
// subset for the legacy techniques, which core/ cannot see).

}  // namespace sl
