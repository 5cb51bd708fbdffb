// apps/registry.h — every technique of every module, and the one way to run one.
#pragma once

#include <string>
#include <vector>

#include "core/frame_timing.h"
#include "core/technique.h"

namespace sl {

const std::vector<Technique>& allTechniques();
const Technique& findTechnique(const std::string& name);  // throws InputError if unknown

// Creates the context the technique needs (installing the imaging subset, emulated or
// native, for legacy techniques), validates the parameters against it and renders.
Frame renderTechnique(const Technique& technique, const Scene& scene, const RenderParams& params);

// The checks renderTechnique makes before it renders, against a context made as it makes one
// (the GL's limits, e.g. GL_MAX_TEXTURE_SIZE for --shadow-map): `shadowlab plan` refuses what
// `shadowlab render` refuses. Throws InputError.
void checkRenderable(const Technique& technique, const RenderParams& params);

// The steady-state frame time (core/frame_timing.h) of a technique on one context made as
// renderTechnique makes it; `last` receives the last timed frame.
SteadyTiming timeTechnique(const Technique& technique, const Scene& scene,
                           const RenderParams& params, const FrameCounts& counts,
                           Frame* last = nullptr);

}  // namespace sl
