#include "legacy_gl/hardware_shadow_map.h"
#include "legacy_gl/legacy.h"

namespace sl::legacy {

std::vector<Technique> techniques() {
  return {hardwareShadowMapTechnique()};
}

}  // namespace sl::legacy
