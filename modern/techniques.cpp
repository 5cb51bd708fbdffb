#include "modern/hardware_shadow_map.h"
#include "modern/modern.h"
#include "modern/shadow_volumes.h"

namespace sl::modern {

std::vector<Technique> techniques() {
  return {
      hardwareShadowMapTechnique(),
      shadowVolumesTechnique(),
  };
}

}  // namespace sl::modern
