// modern/hardware_shadow_map.h — modern.hw (Everitt et al. 2001 as GLSL).
#pragma once

#include "core/technique.h"

namespace sl::modern {
Technique hardwareShadowMapTechnique();
}  // namespace sl::modern
