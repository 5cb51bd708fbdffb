// core/technique/frame_timing.cpp — the steady-state median (see frame_timing.h).
#include "core/technique/frame_timing.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>

#include "core/technique/pass_run_key.h"

namespace sl {

double median(std::vector<double> values) {
  if (values.empty()) throw std::invalid_argument("median of no values");
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

namespace {
// Each pass as first seen, its time the median of its timed frames.
std::vector<PassTime> medianPasses(const std::vector<PassTime>& order,
                                   std::map<PassRunKey, std::vector<double>>& perPass) {
  std::vector<PassTime> out;
  for (const PassTime& p : order) {
    PassTime m = p;
    m.milliseconds = median(perPass[passRunKey(p)]);
    m.gl = {};
    out.push_back(std::move(m));
  }
  return out;
}
}  // namespace

SteadyTiming timeSteadyState(const std::function<Frame()>& renderFrame, const FrameCounts& counts,
                             Frame* last) {
  if (counts.warmup < 0 || counts.timed < 1 || counts.slowTimed < 1)
    throw std::invalid_argument("frame timing needs warm-up >= 0 and at least one timed frame");
  SteadyTiming out;
  out.warmupFrames = counts.warmup;
  // Step 1: warm-up frames, discarded.
  for (int i = 0; i < counts.warmup; ++i) renderFrame();
  // Step 2: timed frames; after a first timed frame slower than the budget, no more.
  std::vector<double> sums, walls;
  std::vector<PassTime> order;  // each pass as first seen (its id, floor, part, source)
  std::map<PassRunKey, std::vector<double>> perPass;
  Frame frame;
  int frames = counts.timed;
  for (int i = 0; i < frames; ++i) {
    const double start = nowMilliseconds();
    frame = renderFrame();
    walls.push_back(nowMilliseconds() - start);
    if (i == 0 && walls.back() > counts.slowFrameMs) frames = std::min(counts.slowTimed, frames);
    sums.push_back(frame.totalMilliseconds());
    for (const PassTime& p : frame.passes) {
      if (!perPass.count(passRunKey(p))) order.push_back(p);
      perPass[passRunKey(p)].push_back(p.milliseconds);
    }
  }
  out.timedFrames = frames;
  out.frameSamples = sums;
  // Step 3: medians.
  out.frameMs = median(sums);
  out.minimumFrameMs = *std::min_element(sums.begin(), sums.end());
  out.wallMs = median(walls);
  out.passes = medianPasses(order, perPass);
  if (last != nullptr) *last = std::move(frame);
  return out;
}

namespace {
// Step 3 for one source of an interleaved run: medians of what its rounds measured.
SteadyTiming mediansOf(int warmup, const std::vector<Frame>& frames,
                       const std::vector<double>& walls) {
  SteadyTiming out;
  out.warmupFrames = warmup;
  out.timedFrames = int(frames.size());
  std::vector<PassTime> order;
  std::map<PassRunKey, std::vector<double>> perPass;
  for (const Frame& f : frames) {
    out.frameSamples.push_back(f.totalMilliseconds());
    for (const PassTime& p : f.passes) {
      if (!perPass.count(passRunKey(p))) order.push_back(p);
      perPass[passRunKey(p)].push_back(p.milliseconds);
    }
  }
  out.frameMs = median(out.frameSamples);
  out.minimumFrameMs = *std::min_element(out.frameSamples.begin(), out.frameSamples.end());
  out.wallMs = median(walls);
  out.passes = medianPasses(order, perPass);
  return out;
}
}  // namespace

std::vector<SteadyTiming> timeInterleavedSteadyState(
    const std::vector<std::function<Frame()>>& sources, int warmup, int rounds,
    std::vector<Frame>* lasts) {
  if (warmup < 0 || rounds < 1)
    throw std::invalid_argument("interleaved timing needs warm-up >= 0 and at least one round");
  // Step 1: every source's warm-up frames, discarded.
  for (const auto& render : sources)
    for (int i = 0; i < warmup; ++i) render();
  // Step 2: rounds, one timed frame of every source each. Only the pass times of the frames are
  // medians' inputs; the images of all but the last round are dropped as soon as timed.
  std::vector<std::vector<Frame>> timed(sources.size());
  std::vector<std::vector<double>> walls(sources.size());
  for (int round = 0; round < rounds; ++round)
    for (size_t i = 0; i < sources.size(); ++i) {
      const double start = nowMilliseconds();
      Frame frame = sources[i]();
      walls[i].push_back(nowMilliseconds() - start);
      if (round + 1 < rounds) {  // keep the times, not the images
        frame.color = Image();
        frame.visibility = Image();
        frame.intermediates.clear();
      }
      timed[i].push_back(std::move(frame));
    }
  // Step 3: medians per source.
  std::vector<SteadyTiming> out;
  for (size_t i = 0; i < sources.size(); ++i) out.push_back(mediansOf(warmup, timed[i], walls[i]));
  if (lasts != nullptr) {
    lasts->clear();
    for (auto& frames : timed) lasts->push_back(std::move(frames.back()));
  }
  return out;
}

}  // namespace sl
