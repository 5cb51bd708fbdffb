#include "legacy_gl/brabec_seidel.h"
#include "legacy_gl/depth_layer_shadow_maps.h"
#include "legacy_gl/fixed_function.h"
#include "legacy_gl/hardware_shadow_map.h"
#include "legacy_gl/legacy.h"

namespace sl::legacy {

// One line per technique, grouped by paper (the order `shadowlab list` prints). Each renders
// inside a ScopedLegacyState (legacy_gl/fixed_function.h): the context as the frame found it.
std::vector<Technique> techniques() {
  std::vector<Technique> list = {
      // Everitt, Rege & Cebenoyan 2001 and the depth-layer variants
      hardwareShadowMapTechnique(),
      wooShadowMapTechnique(),
      secondDepthShadowMapTechnique(),
      // Brabec & Seidel 2001
      rampShadowMapTechnique(),
      pcfTechnique(),
      fastPcfTechnique(),
  };
  for (Technique& t : list) t.render = withScopedLegacyState(t.render);
  return list;
}

}  // namespace sl::legacy
