// modern/hardware_shadow_map.h — modern.hw (Everitt et al. 2001 as GLSL).
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "core/technique.h"
#include "modern/gl_objects.h"

namespace sl::modern {
Technique hardwareShadowMapTechnique();

// S · P_light · L^-1: world to shadow-map texture coordinates (Everitt Eq. 2 and 5), the
// uniform that replaces legacy.hw's EYE_LINEAR texgen planes.
glm::mat4 worldToShadowMap(const Scene& scene);
// Compare mode LEQUAL, NEAREST or LINEAR (Everitt Fig. 5), far-plane border, on a depth texture.
void setDepthCompareParameters(GLuint depthTexture, bool linear);
// The camera pass of modern.hw on any depth map with setDepthCompareParameters applied:
// hw_shadow.frag shades and writes the visibility mask. Shared by modern.woo and
// modern.second-depth, which differ from modern.hw only in how the map is made.
void shadeWithShadowMap(const GpuScene& gpu, const RenderParams& params, GLuint shadowMap,
                        const std::string& passName, Frame& frame);
}  // namespace sl::modern
