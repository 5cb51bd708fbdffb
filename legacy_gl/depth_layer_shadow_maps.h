// legacy_gl/depth_layer_shadow_maps.h — two alternatives to polygon offset that Everitt et al.
// 2001 discuss in "Advantages and Limitations": Woo's midpoint shadow map (legacy.woo) and
// Wang & Molnar's second-depth shadow map (legacy.second-depth).
#pragma once

#include "core/technique/technique.h"

namespace sl::legacy {

Technique wooShadowMapTechnique();
Technique secondDepthShadowMapTechnique();

}  // namespace sl::legacy
