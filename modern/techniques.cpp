#include "modern/convolution_shadow_map.h"
#include "modern/gems_pcf.h"
#include "modern/hardware_shadow_map.h"
#include "modern/modern.h"
#include "modern/variance_shadow_map.h"

namespace sl::modern {

std::vector<Technique> techniques() {
  return {hardwareShadowMapTechnique(),
          gems16Technique(),
          gems4Technique(),
          convolutionShadowMapTechnique(),
          varianceShadowMapTechnique()};
}

}  // namespace sl::modern
