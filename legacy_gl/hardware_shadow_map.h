// legacy_gl/hardware_shadow_map.h — Everitt, Rege & Cebenoyan 2001 (legacy.hw).
#pragma once

#include <glm/glm.hpp>

#include "core/technique.h"

namespace sl::legacy {

Technique hardwareShadowMapTechnique();

// E_po = S · P_light · L^-1 (Everitt Eq. 5 with modelview_po = V^-1): the four EYE_LINEAR
// texgen planes (rows) in world space. Exposed for the test that checks it against GLM.
glm::mat4 worldToShadowMapTexture(const Scene& scene);

// The depth-texture parameters of Everitt's "OpenGL API Details" (ARB_shadow compare mode,
// LEQUAL, NEAREST or LINEAR compare as in Fig. 5, far-plane border) on the bound 2D texture.
void setDepthCompareParameters(bool linearCompare);

// Passes 2-5 of legacy.hw on `shadowMap`, a DEPTH_COMPONENT texture of the light's view with
// setDepthCompareParameters applied: texgen planes, ambient, direct light x shadow test, and
// the visibility mask. Fills frame.color and frame.visibility; pass names start at
// `firstPass`. legacy.woo and legacy.second-depth share it: they differ from legacy.hw only
// in how the map is made.
void shadeWithShadowMap(const Scene& scene, const RenderParams& params, unsigned shadowMap,
                        int firstPass, Frame& frame);

}  // namespace sl::legacy
