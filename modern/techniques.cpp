#include "modern/brabec_seidel_techniques.h"
#include "modern/cascaded_shadow_maps.h"
#include "modern/convolution_shadow_map.h"
#include "modern/depth_layer_shadow_maps.h"
#include "modern/exponential_shadow_map.h"
#include "modern/exponential_variance_shadow_map.h"
#include "modern/gems_pcf.h"
#include "modern/hardware_shadow_map.h"
#include "modern/hybrid_shadows.h"
#include "modern/modern.h"
#include "modern/moment_shadow_map.h"
#include "modern/pcss.h"
#include "modern/shadow_volumes.h"
#include "modern/smoothies.h"
#include "modern/variance_shadow_map.h"

namespace sl::modern {

// One line per technique, grouped by paper (the order `shadowlab list` prints).
std::vector<Technique> techniques() {
  return {
      // Everitt, Rege & Cebenoyan 2001 and the depth-layer variants
      hardwareShadowMapTechnique(),
      wooShadowMapTechnique(),
      secondDepthShadowMapTechnique(),
      // Brabec & Seidel 2001 (twins of legacy_gl/)
      rampShadowMapTechnique(),
      percentageCloserFilteringTechnique(),
      fastPercentageCloserFilteringTechnique(),
      // Bunnell & Pellacini, GPU Gems ch. 11
      gems16Technique(),
      gems4Technique(),
      // Annen et al. 2007 and Donnelly & Lauritzen 2006
      convolutionShadowMapTechnique(),
      varianceShadowMapTechnique(),
      // The filtered-map baselines after VSM (ours, after papers not in shared/papers)
      exponentialShadowMapTechnique(),
      evsm2Technique(),
      evsm4Technique(),
      momentShadowMapTechnique(),
      // Chan 2004
      shadowVolumesTechnique(),
      hybridShadowsTechnique(),
      smoothiesTechnique(),
      // Fernando 2005 (not in shared/papers): percentage-closer soft shadows
      pcssTechnique(),
      // Zhang et al. 2006 (not in shared/papers): parallel-split (cascaded) shadow maps
      cascadedShadowMapTechnique(),
  };
}

}  // namespace sl::modern
