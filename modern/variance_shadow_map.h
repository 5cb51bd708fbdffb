// modern/variance_shadow_map.h — modern.vsm: Variance Shadow Maps (Donnelly & Lauritzen 2006),
// the comparison of Annen et al. 2007 (§2, Fig. 9).
#pragma once

#include "core/technique/technique.h"

namespace sl::modern {
Technique varianceShadowMapTechnique();
}  // namespace sl::modern
