#include "measure/volumes_bench.h"

#include <algorithm>

#include "core/base/errors.h"
#include "core/technique/frame_timing.h"
#include "modern/modern.h"

namespace sl::modern {

std::vector<VolumesBenchRow> benchmarkShadowVolumes(const Scene& scene, const RenderParams& params,
                                                    const std::vector<std::string>& techniques,
                                                    int frames, int warmup) {
  if (frames < 1) throw InputError("benchmark needs at least one frame");
  std::vector<VolumesBenchRow> rows;
  const std::vector<Technique> all = modern::techniques();
  for (const std::string& name : techniques) {
    auto it =
        std::find_if(all.begin(), all.end(), [&](const Technique& t) { return t.name == name; });
    if (it == all.end()) throw InputError("unknown modern technique '" + name + "'");
    const Technique& t = *it;
    checkParams(t, params, 0);
    auto context = GlContext::create(contextFor(t, params));
    checkParams(t, params, context->caps().maxTextureSize);
    VolumesBenchRow row;
    row.technique = name;
    row.scene = scene.name;
    row.device = context->caps().renderer;
    row.width = params.width;
    row.height = params.height;
    row.shadowMapTexels = params.shadowMapTexels;
    row.frames = frames;
    // The steady-state median (core/technique/frame_timing.h).
    Frame last;
    const SteadyTiming timing = timeSteadyState([&] { return t.render(*context, scene, params); },
                                                FrameCounts{warmup, frames}, &last);
    row.medianMs = timing.frameMs;
    row.minMs = timing.minimumFrameMs;
    for (const PassTime& p : timing.passes) row.passMedianMs[p.name] = p.milliseconds;
    row.counters = last.counters;
    rows.push_back(row);
  }
  return rows;
}

nlohmann::json toJson(const VolumesBenchRow& r) {
  return {{"technique", r.technique}, {"scene", r.scene},
          {"device", r.device},       {"width", r.width},
          {"height", r.height},       {"shadow_map", r.shadowMapTexels},
          {"frames", r.frames},       {"median_ms", r.medianMs},
          {"min_ms", r.minMs},        {"passes_median_ms", r.passMedianMs},
          {"counters", r.counters}};
}

}  // namespace sl::modern
