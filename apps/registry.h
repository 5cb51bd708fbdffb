// apps/registry.h — every technique of every module, and the one way to run one.
#pragma once

#include <string>
#include <vector>

#include "core/technique.h"

namespace sl {

const std::vector<Technique>& allTechniques();
const Technique& findTechnique(const std::string& name);  // throws InputError if unknown

// Creates the context the technique needs (installing the imaging subset, emulated or
// native, for legacy techniques), validates the parameters against it and renders.
Frame renderTechnique(const Technique& technique, const Scene& scene, const RenderParams& params);

}  // namespace sl
