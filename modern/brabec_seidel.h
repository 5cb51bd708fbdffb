// modern/brabec_seidel.h — what modern.ramp, modern.pcf and modern.fast-pcf share (Brabec &
// Seidel 2001 as shaders): the two arithmetic modes, the 1D ramp that encodes depth as colour
// (§2, Figure 1), the jittered light passes (§3, Figure 3) and the camera pass uniforms
// (module-internal header).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "core/technique.h"
#include "modern/gl_objects.h"

namespace sl::modern::bs {

// --param arithmetic=faithful|float. 'faithful' repeats the legacy quantisation step by step
// (ramp texel, 8- or 12-bit channels, colour table, colour matrix, 16-bit accumulation) so the
// mask can match legacy_gl bit for bit; 'float' shows the technique without the 2001 limits.
enum class Arithmetic { kFaithful, kFloat };
Arithmetic arithmeticOf(const RenderParams& params);

// Bits per channel of the encoded depth: 8 or 12 (RenderParams::precision) in 'faithful'
// arithmetic; 0 for float (the ramp is not used then).
int depthBits(const RenderParams& params);
// Colour format of the maps that hold encoded depth: RGBA8, RGBA16 (holding 12-bit values) or
// RGBA32F.
GLenum encodedDepthFormat(const RenderParams& params);

// The 1D linear ramp of §2: 2^bits texels, texel k = k / (2^bits - 1), GL_NEAREST, clamped.
// (For float arithmetic an 8-bit ramp is bound but not read.)
Texture makeRampTexture(int bits);

// World position -> ramp coordinate s: the light's eye-space depth mapped from [near, far] to
// [0, 1] (the texgen plane of §2, given in world space).
glm::vec4 rampPlane(const Scene& scene);

// The depth bias of §2, in units of the ramp coordinate (--param bias, default two 8-bit steps),
// subtracted from the fragment's coordinate in the camera pass.
constexpr float kDefaultBiasSteps = 2.0f;  // two 8-bit ramp steps
float bias(const RenderParams& params);

// S · P_light · L^-1 (projective lookup of the map).
glm::mat4 worldToShadowMap(const Scene& scene);

// The light's view-projection with the image plane moved by `offsetTexels` map texels
// (Figure 3: the jittered passes of §3).
glm::mat4 jitteredLightViewProjection(const Scene& scene, glm::vec2 offsetTexels, int texels);

// Renders the casters from the light (jittered by `offsetTexels`) with bs_encode_depth.frag into
// the channels of `target` that `channels` enables (glColorMask); the target stays bound.
void renderEncodedDepth(const GpuScene& gpu, const RenderParams& params, const Texture& ramp,
                        const RenderTarget& target, glm::bvec4 channels, glm::vec2 offsetTexels);

// A colour target for encoded depth, cleared to the far plane (1) and depth 1.
RenderTarget makeEncodedDepthTarget(const RenderParams& params);
// GL_NEAREST, clamp to edge on a map texture.
void setMapSampling(GLuint texture);

// One group of up to four samples packed in one map (§3 channel packing, §4 phases).
struct SampleGroup {
  GLuint map = 0;
  int samples = 4;
  glm::vec2 offsetTexels{0.0f};  // texture-coordinate offset of the lookup (§4, Figure 6)
};

// The camera pass shared by modern.pcf and modern.fast-pcf: pcf_shadow.frag over the groups
// (colour table, colour matrix, accumulation), shading and visibility into the camera target.
void shadowTestAndShade(const GpuScene& gpu, const RenderParams& params, const Texture& ramp,
                        const std::vector<SampleGroup>& groups, Frame& frame);

// The --param keys every Brabec–Seidel twin understands.
std::vector<std::string> paramKeys();

}  // namespace sl::modern::bs
