// modern/filtered_map_passes.h — the light pass and the camera pass that the filtered-map
// baselines after VSM share (modern.esm, modern.evsm2, modern.evsm4, modern.msm): each stores
// some function of the linear light depth (Annen et al. 2007 §4.1, linear depth) in one RGBA
// float layer of a LayeredMap, filters it with the blur and mip-map passes of
// modern/prefiltered_maps.h, and reconstructs visibility from the filtered values in a camera
// pass. Only the two shaders and their uniforms differ. Module-internal header.
#pragma once

#include <functional>

#include "core/technique/passes.h"
#include "modern/gl_objects.h"
#include "modern/prefiltered_maps.h"

namespace sl::modern {

// Renders every shadow caster from the light into a fresh one-layer map of `format` (`mipmaps`:
// with a mip chain), cleared to `clear` (the value of "no caster": depth 1 warped), with
// scene.vert.glsl and `fragmentShader`, which receives uLightView, uLightNear, uLightFar and
// whatever `uniforms` sets. The pass function of the technique runs this inside its pass.
LayeredMap renderWarpedDepthFromLight(const GpuScene& gpu, const RenderParams& params,
                                      GLenum format, bool mipmaps, const char* fragmentShader,
                                      const float clear[4],
                                      const std::function<void(const Program&)>& uniforms);

// Draws the scene in the camera view with scene.vert.glsl and `fragmentShader` (which includes
// lighting.glsl and samples uMap, unit 0), with the shadow-map and lighting uniforms and
// whatever `uniforms` sets, and reads the colour and visibility into `frame`.
void shadeWithFilteredMap(const GpuScene& gpu, const RenderParams& params, const LayeredMap& map,
                          const char* fragmentShader,
                          const std::function<void(const Program&)>& uniforms, Frame& frame);

}  // namespace sl::modern
