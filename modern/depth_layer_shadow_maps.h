// modern/depth_layer_shadow_maps.h — modern.woo (Woo's midpoint shadow map) and
// modern.second-depth (Wang & Molnar), the shader twins of legacy_gl/woo_shadow_map.cpp and
// legacy_gl/second_depth_shadow_map.cpp.
#pragma once

#include "core/technique/technique.h"

namespace sl::modern {

Technique wooShadowMapTechnique();
Technique secondDepthShadowMapTechnique();

}  // namespace sl::modern
