// core/frame_timing.cpp — the steady-state median (see frame_timing.h).
#include "core/frame_timing.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>

namespace sl {

double median(std::vector<double> values) {
  if (values.empty()) throw std::invalid_argument("median of no values");
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

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
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> perPass;
  Frame frame;
  int frames = counts.timed;
  for (int i = 0; i < frames; ++i) {
    const double start = nowMilliseconds();
    frame = renderFrame();
    walls.push_back(nowMilliseconds() - start);
    if (i == 0 && walls.back() > counts.slowFrameMs) frames = std::min(counts.slowTimed, frames);
    sums.push_back(frame.totalMilliseconds());
    for (const PassTime& p : frame.passes) {
      if (!perPass.count(p.name)) order.push_back(p.name);
      perPass[p.name].push_back(p.milliseconds);
    }
  }
  out.timedFrames = frames;
  // Step 3: medians.
  out.frameMs = median(sums);
  out.minimumFrameMs = *std::min_element(sums.begin(), sums.end());
  out.wallMs = median(walls);
  for (const std::string& name : order) out.passes.push_back({name, median(perPass[name])});
  if (last != nullptr) *last = std::move(frame);
  return out;
}

}  // namespace sl
