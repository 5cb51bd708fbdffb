// legacy_gl/hardware_shadow_map.h — Everitt, Rege & Cebenoyan 2001 (legacy.hw).
#pragma once

#include <glm/glm.hpp>

#include "core/technique.h"

namespace sl::legacy {

Technique hardwareShadowMapTechnique();

// E_po = S · P_light · L^-1 (Everitt Eq. 5 with modelview_po = V^-1): the four EYE_LINEAR
// texgen planes (rows) in world space. Exposed for the test that checks it against GLM.
glm::mat4 worldToShadowMapTexture(const Scene& scene);

}  // namespace sl::legacy
