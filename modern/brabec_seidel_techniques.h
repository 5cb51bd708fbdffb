// modern/brabec_seidel_techniques.h — modern.ramp (§2), modern.pcf (§3), modern.fast-pcf (§4):
// Brabec & Seidel 2001 as shaders, twins of legacy_gl's legacy.ramp, legacy.pcf and
// legacy.fast-pcf.
#pragma once

#include "core/technique/technique.h"

namespace sl::modern {

Technique rampShadowMapTechnique();
Technique percentageCloserFilteringTechnique();
Technique fastPercentageCloserFilteringTechnique();

}  // namespace sl::modern
