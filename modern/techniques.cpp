#include "modern/hardware_shadow_map.h"
#include "modern/hybrid_shadows.h"
#include "modern/modern.h"
#include "modern/shadow_volumes.h"
#include "modern/smoothies.h"

namespace sl::modern {

std::vector<Technique> techniques() {
  return {
      hardwareShadowMapTechnique(),
      shadowVolumesTechnique(),
      hybridShadowsTechnique(),
      smoothiesTechnique(),
  };
}

}  // namespace sl::modern
