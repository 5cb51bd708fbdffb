// legacy_gl/hardware_shadow_map.h — Everitt, Rege & Cebenoyan 2001 (legacy.hw).
#pragma once

#include <glm/glm.hpp>
#include <string>

#include "core/gl/gl.h"
#include "core/technique/pass_table.h"
#include "core/technique/passes.h"
#include "core/technique/technique.h"

namespace sl::legacy {

Technique hardwareShadowMapTechnique();

// E_po = S · P_light · L^-1 (Everitt Eq. 5 with modelview_po = V^-1): the four EYE_LINEAR
// texgen planes (rows) in world space. Exposed for the test that checks it against GLM.
glm::mat4 worldToShadowMapTexture(const Scene& scene);

// The depth-texture parameters of Everitt's "OpenGL API Details" (ARB_shadow compare mode,
// LEQUAL, NEAREST or LINEAR compare as in Fig. 5, far-plane border) on the bound 2D texture.
void setDepthCompareParameters(bool linearCompare);

// Passes 2-5 of legacy.hw, which legacy.woo and legacy.second-depth share (they differ from
// legacy.hw only in how the map is made), declared with ids from `firstPass` on: texgen planes,
// ambient, direct light x shadow test, and the visibility mask. Each of the three techniques
// lists them in its pass table after meshFeedingPass() and its own light passes.
PassTable shadowMapCameraPasses(int firstPass);

// Runs those passes (and the mesh feeding before them) through `passes` on `shadowMap`, a
// DEPTH_COMPONENT texture of the light's view with setDepthCompareParameters applied. Fills
// frame.color and frame.visibility.
void shadeWithShadowMap(Passes& passes, const Scene& scene, const RenderParams& params,
                        GLuint shadowMap, int firstPass);

}  // namespace sl::legacy
