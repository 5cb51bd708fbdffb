#include "modern/hardware_shadow_map.h"
#include "modern/modern.h"

namespace sl::modern {

std::vector<Technique> techniques() {
  return {hardwareShadowMapTechnique()};
}

}  // namespace sl::modern
