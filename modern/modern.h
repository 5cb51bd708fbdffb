// modern/modern.h — every technique as GLSL shaders in a core-profile context (public header).
//
//   modern.hw, modern.ramp, modern.pcf, modern.fast-pcf, modern.woo, modern.second-depth:
//       shader twins of the legacy_gl/ techniques (Brabec–Seidel 2001, Everitt et al. 2001)
//   modern.gems16, modern.gems4: Bunnell & Pellacini, GPU Gems ch. 11
//   modern.csm, modern.vsm: Annen et al. 2007 (and Donnelly & Lauritzen 2006)
//   modern.volumes, modern.hybrid, modern.smoothies: Chan 2004
//   modern.pcss: percentage-closer soft shadows (ours, after Fernando 2005; not in shared/papers)
//   modern.cascades: parallel-split shadow maps (ours, after Zhang et al. 2006; not in
//       shared/papers)
#pragma once

#include <vector>

#include "core/technique/technique.h"

namespace sl::modern {

std::vector<Technique> techniques();

}  // namespace sl::modern
