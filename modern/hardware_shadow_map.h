// modern/hardware_shadow_map.h — modern.hw (Everitt et al. 2001 as GLSL).
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/technique/passes.h"
#include "core/technique/technique.h"
#include "modern/gl_objects.h"

namespace sl::modern {
Technique hardwareShadowMapTechnique();

// S · P_light · L^-1: world to shadow-map texture coordinates (Everitt Eq. 2 and 5), the
// uniform that replaces legacy.hw's EYE_LINEAR texgen planes.
glm::mat4 worldToShadowMap(const Scene& scene);
// Compare mode LEQUAL, NEAREST or LINEAR (Everitt Fig. 5), far-plane border, on a depth texture.
void setDepthCompareParameters(GLuint depthTexture, bool linear);
// The camera pass of modern.hw on any depth map with setDepthCompareParameters applied:
// hw_shadow.frag shades and writes the visibility mask, run as pass `id` of the technique's
// table, which declares it with cameraPassWithShadowTest. Shared by modern.woo and
// modern.second-depth, which differ from modern.hw only in how the map is made.
void shadeWithShadowMap(Passes& passes, const std::string& id, const GpuScene& gpu,
                        const RenderParams& params, GLuint shadowMap);
// That pass's declaration: its buffers' captions name `source` (the map it reads), `replaces`
// the legacy twin's passes it does (texgen planes, ambient, direct light x test, mask).
PassSpec cameraPassWithShadowTest(const std::string& id, const std::string& source,
                                  std::vector<std::string> replaces);
}  // namespace sl::modern
