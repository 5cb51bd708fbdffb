// legacy_gl/brabec_seidel.h — Stefan Brabec and Hans-Peter Seidel, "Hardware-accelerated
// Rendering of Antialiased Shadows with Shadow Maps", CGI 2001 (public part of the module).
//
//   legacy.ramp      §2 (after Heidrich): depth as colour through a 1D ramp texture, shadow test
//                    by subtractive blending, mask in the alpha channel
//   legacy.pcf       §3: jittered light passes packed one per colour channel, colour table +
//                    colour matrix count the shadowed samples (Fig. 3, Fig. 4)
//   legacy.fast-pcf  §4: one light pass, the 3x3 convolution of Eq. (1) packs four neighbours
//                    (Fig. 5), texture coordinates offset by (ds/2, dt/2) (Fig. 6); 4x4 in four
//                    phases summed in the accumulation buffer
//
// VISIBILITY SEMANTICS (what Frame::visibility holds, for the modern twins to match):
//   The shadow term is the framebuffer ALPHA after the last pass: A = 0 lit, A = M fully
//   shadowed, where M is the channel maximum of the precision (255 at 8 bits, 4095 at 12 bits
//   as 12-bit steps stored in a 16-bit buffer, 65535/65535 at float). visibility = 1 - A / M,
//   read back as float. At 8 bits:
//     legacy.ramp            A in {0, 255}                          -> visibility {1, 0}
//     legacy.pcf 2x2 / fast  A = 64 per shadowed sample (63 for the alpha-channel sample, so
//                            four sum to 255, footnote 2)            -> {1, 191/255, 127/255,
//                                                                        63/255, 0}
//     3x3 and 4x4 footprints: groups of at most four samples, each group's alpha weighted by
//                            (samples in group)/(samples in footprint) in the accumulation
//                            buffer and returned to 8 bits (GL_RETURN rounds).
//   Pixels that show no receiver (background, objects with receivesShadow = false) are 1.
#pragma once

#include <glm/glm.hpp>

#include "core/scene/scene.h"
#include "core/technique/technique.h"

namespace sl::legacy {

Technique rampShadowMapTechnique();  // legacy.ramp
Technique pcfTechnique();            // legacy.pcf
Technique fastPcfTechnique();        // legacy.fast-pcf

// Camera eye coordinates -> shadow-map texture coordinates (s, t, r, q) for the projective
// pass: S · P_light · L^-1 · V in Everitt's notation (L^-1 = lightView, V = cameraView^-1),
// with the texture coordinate offset of §4 / Fig. 6 added (in texels, (0.5, 0.5) for fast PCF).
// The techniques load exactly this as the texture matrix over identity EYE_LINEAR planes.
glm::mat4 cameraEyeToShadowMap(const Scene& scene, int shadowMapTexels,
                               glm::vec2 offsetTexels = glm::vec2(0.0f));

// Light eye coordinates -> the 1D ramp coordinate s (§2, Fig. 1): the linear depth
// d = (-z_eye - near) / (far - near), minus `bias` (same units as d), placed on the centres of
// a ramp of `rampTexels` texels: s = (0.5 + (rampTexels - 1) d) / rampTexels.
glm::mat4 lightEyeToRamp(const Scene& scene, int rampTexels, double bias);

}  // namespace sl::legacy
