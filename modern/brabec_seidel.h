// modern/brabec_seidel.h — what modern.ramp, modern.pcf and modern.fast-pcf share (Brabec &
// Seidel 2001 as shaders): the two arithmetic modes, the 1D ramp that encodes depth as colour
// (§2, Figure 1), the jittered light passes (§3, Figure 3) and the camera pass uniforms
// (module-internal header).
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "core/technique/technique.h"
#include "modern/gl_objects.h"
#include "modern/pcf_bias.h"

namespace sl::modern::bs {

// --param arithmetic=faithful|float. 'faithful' repeats the legacy quantisation step by step
// (ramp texel, 8- or 12-bit channels, colour table, colour matrix, 16-bit accumulation) so the
// mask can match legacy_gl bit for bit; 'float' shows the technique without the 2001 limits.
enum class Arithmetic { kFaithful, kFloat };
Arithmetic arithmeticOf(const RenderParams& params);

// Bits per channel of the encoded depth: 8 or 12 (RenderParams::precision) in 'faithful'
// arithmetic; 0 for float channels ('float' arithmetic, or --precision float).
int depthBits(const RenderParams& params);
// 'faithful' arithmetic at --precision float: legacy's float pipeline (float colour buffer,
// 2-texel LINEAR ramp giving d itself, RGBA32F maps, colour table and accumulation as at 8 bits).
bool legacyFloatBuffer(const RenderParams& params);
// Colour format of the maps that hold encoded depth: RGBA8, RGBA16 (holding 12-bit values) or
// RGBA32F.
GLenum encodedDepthFormat(const RenderParams& params);

// The 1D linear ramp of §2: N = 2^bits texels (256 or 4096; 256 for 'float' arithmetic, where
// it is not read), texel k = k / (N - 1), GL_NEAREST, clamped, 8- or 16-bit like legacy_gl's
// ramp; at --precision float with 'faithful' arithmetic legacy's 2 texels, R32F, GL_LINEAR.
int rampTexels(const RenderParams& params);
Texture makeRampTexture(const RenderParams& params);

// World position -> d = (-z_light_eye - near) / (far - near), the light depth over the light's
// depth range (legacy_gl's lightEyeToRamp before it places d on the ramp's texel centres).
glm::vec4 depthPlane(const Scene& scene);

// The depth bias of §2 (--param depth-bias, in 8-bit steps of d at every precision, as
// legacy_gl), subtracted from d in the camera pass.
constexpr double kDefaultDepthBiasSteps = 2.0;  // as legacy_gl/brabec_seidel_passes.h
float depthBias(const RenderParams& params);

// Sets the uniforms of 'faithful' arithmetic that describe the legacy colour buffer and its
// pipeline: uBufferMax, uReadScale, uSaturateScale, uTableScale, uTableLastIndex, uAccumMode,
// uAccumReturnScale (see ramp_shadow.frag and pcf_shadow.frag).
void setLegacyArithmeticUniforms(const Program& program, const RenderParams& params);

// The texture matrices of texgen.vert, computed exactly as legacy_gl computes the matrices it
// loads (same formulas, same order of products, so the same floats):
//   light eye -> ramp coordinate s = (0.5 + (N - 1)(d - bias)) / N  (legacy lightEyeToRamp)
glm::mat4 eyeToRamp(const Scene& scene, int rampTexels, double bias);
//   camera eye -> ramp coordinate of the camera pass (§2 "from camera to light source space")
glm::mat4 cameraEyeToRamp(const Scene& scene, const RenderParams& params);
//   camera eye -> projective map coordinates, + offsetTexels / texels (§4 Fig. 6)
glm::mat4 cameraEyeToShadowMap(const Scene& scene, int texels, glm::vec2 offsetTexels);
// uModel, uModelView = view · model and uModelViewProjection = projection · (view · model), as
// the fixed-function pipeline forms them from glLoadMatrix(view) + glMultMatrix(model).
void setTexgenObjectUniforms(const Program& program, const Object& object, const glm::mat4& view,
                             const glm::mat4& projection);

// Renders the casters from the light, the image plane moved by `offsetTexels` map texels
// (Figure 3 jitter), with texgen.vert + bs_encode_depth.frag into
// the channels of `target` that `channels` enables (glColorMask); the target stays bound.
void renderEncodedDepth(const GpuScene& gpu, const RenderParams& params, const Texture& ramp,
                        const RenderTarget& target, glm::bvec4 channels, glm::vec2 offsetTexels);

// A colour target for encoded depth, cleared to the far plane (1) and depth 1.
RenderTarget makeEncodedDepthTarget(const RenderParams& params);
// GL_NEAREST and a far-plane border (1: lit) on a map texture, as legacy_gl allocates maps.
void setMapSampling(GLuint texture);

// One group of up to four samples packed in one map (§3 channel packing, §4 phases).
struct SampleGroup {
  GLuint map = 0;
  int samples = 4;
  glm::vec2 offsetTexels{0.0f};  // texture-coordinate offset of the lookup (§4, Figure 6)
};

// --param bias of modern.pcf and modern.fast-pcf (modern/pcf_bias.h): the normal offset only,
// one footprint by default (their default 2x2 footprint reaches about a texel from the lookup;
// --filter 4 reaches further and may want more).
inline constexpr pcf_bias::Offer kBiasOffer = {.receiverPlane = false,
                                               .defaultNormalOffsetTexels = 1.0};

// The DEVIATION of texgen.vert's normal offset, for the camera passes' tables.
inline constexpr const char* kNormalOffsetDeviation =
    "DEVIATION (Brabec & Seidel §2-§4 bias the depth by a constant only): with --param "
    "bias=normal-offset (ours, after Holbert 2011) the camera pass's point moves along its "
    "surface normal by normal-offset-texels texel footprints at its distance from the light "
    "before texgen, so the ramp and map coordinates are those of the moved point.";

// The camera pass shared by modern.pcf and modern.fast-pcf: pcf_shadow.frag over the groups
// (colour table, colour matrix, accumulation), shading and visibility into the camera target.
// `bias`: --param bias=normal-offset moves the point along its normal in texgen.vert (ours,
// after Holbert 2011); the default (constant) moves nothing.
void shadowTestAndShade(const GpuScene& gpu, const RenderParams& params, const Texture& ramp,
                        const std::vector<SampleGroup>& groups, Frame& frame,
                        const pcf_bias::Settings& bias = {});

// The --param keys every Brabec–Seidel twin understands.
// The --params every Brabec–Seidel twin declares (modern.ramp, modern.pcf, modern.fast-pcf).
ParamSpec arithmeticParam();
ParamSpec depthBiasParam();  // as legacy_gl's bs::depthBiasParam
std::vector<ParamSpec> params();

// §3 Figure 4 / footnote 2: the colour-table output of each channel for a group of `samples`
// samples, as a share of the channel maximum M: ceil(M / samples) each, the last channel the
// rest, so a fully shadowed group sums to M exactly.
glm::vec4 shadowShares(const RenderParams& params, int samples);

}  // namespace sl::modern::bs
