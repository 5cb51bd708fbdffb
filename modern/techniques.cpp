#include "modern/brabec_seidel_techniques.h"
#include "modern/depth_layer_shadow_maps.h"
#include "modern/hardware_shadow_map.h"
#include "modern/modern.h"

namespace sl::modern {

std::vector<Technique> techniques() {
  return {hardwareShadowMapTechnique(),  rampShadowMapTechnique(),
          percentageCloserFilteringTechnique(), fastPercentageCloserFilteringTechnique(),
          wooShadowMapTechnique(),        secondDepthShadowMapTechnique()};
}

}  // namespace sl::modern
