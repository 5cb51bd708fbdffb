// registry/registry.h — every technique of every module, and the one way to run one.
#pragma once

#include <string>
#include <vector>

#include "core/technique/frame_timing.h"
#include "core/technique/technique.h"

namespace sl {

const std::vector<Technique>& allTechniques();
const Technique& findTechnique(const std::string& name);  // throws InputError if unknown
// The technique named `name`, or nullptr when this build has none (a bench row of another build).
const Technique* techniqueNamed(const std::string& name);

// Options a technique ignores are input errors. `given` are the common
// options (core/technique/technique.h CommonOption) given explicitly on the command line; throws
// InputError for the first one `technique` does not read: "legacy.ramp does not filter:
// --filter has no effect on it (techniques that read --filter: ...)".
void rejectIgnoredOptions(const Technique& technique, const std::vector<CommonOption>& given);
// For two techniques rendered with one set of options (`compare`): an option neither reads is
// an InputError; the lines returned warn of each option that one of them ignores.
std::vector<std::string> checkOptionsOfPair(const Technique& a, const Technique& b,
                                            const std::vector<CommonOption>& given);

// Creates the context the technique needs (installing the imaging subset, emulated or
// native, for legacy techniques), validates the parameters against it and renders.
Frame renderTechnique(const Technique& technique, const Scene& scene, const RenderParams& params);

// The context renderTechnique makes for a technique (parameters checked against its limits,
// imaging subset installed), for callers that render many frames on one context (lab/).
std::unique_ptr<GlContext> makeRenderContext(const Technique& technique,
                                             const RenderParams& params);

// The checks renderTechnique makes before it renders, against a context made as it makes one
// (the GL's limits, e.g. GL_MAX_TEXTURE_SIZE for --shadow-map): `shadowlab plan` refuses what
// `shadowlab render` refuses. Throws InputError.
void checkRenderable(const Technique& technique, const RenderParams& params);

// The steady-state frame time (core/technique/frame_timing.h) of a technique on one context made as
// renderTechnique makes it; `last` receives the last timed frame. `traceGl`: with the GL trace
// of --dump-passes running (core/gl/gl_trace.h), to measure what it costs (legacy_bench
// --trace-overhead).
SteadyTiming timeTechnique(const Technique& technique, const Scene& scene,
                           const RenderParams& params, const FrameCounts& counts,
                           Frame* last = nullptr, bool traceGl = false);

// Several renders timed interleaved (core/technique/frame_timing.h timeInterleavedSteadyState),
// each on its own context made as renderTechnique makes it, all contexts alive at once (switched
// with makeCurrent between frames). `lasts` receives every job's last frame.
struct TimingJob {
  const Technique* technique = nullptr;
  const Scene* scene = nullptr;
  RenderParams params;
};
std::vector<SteadyTiming> timeTechniquesInterleaved(const std::vector<TimingJob>& jobs, int warmup,
                                                    int rounds,
                                                    std::vector<Frame>* lasts = nullptr);

}  // namespace sl
