#include "legacy_gl/brabec_seidel.h"
#include "legacy_gl/depth_layer_shadow_maps.h"
#include "legacy_gl/hardware_shadow_map.h"
#include "legacy_gl/legacy.h"

namespace sl::legacy {

std::vector<Technique> techniques() {
  return {hardwareShadowMapTechnique(), rampShadowMapTechnique(), pcfTechnique(),
          fastPcfTechnique(),           wooShadowMapTechnique(),  secondDepthShadowMapTechnique()};
}

}  // namespace sl::legacy
