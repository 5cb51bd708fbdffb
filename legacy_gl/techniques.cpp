#include "legacy_gl/brabec_seidel.h"
#include "legacy_gl/hardware_shadow_map.h"
#include "legacy_gl/legacy.h"

namespace sl::legacy {

std::vector<Technique> techniques() {
  return {hardwareShadowMapTechnique(), rampShadowMapTechnique(), pcfTechnique(),
          fastPcfTechnique()};
}

}  // namespace sl::legacy
