// legacy_gl/projected_spotlight.h — the spotlight's cone as a texture projected from the light,
// as 2001 programs lit spotlights: Segal, Korobkin, van Widenfelt, Foran & Haeberli 1992, "Fast
// Shadows and Lighting Effects Using Texture Mapping" (projected-texture spotlights), and
// Everitt 2001, "Projective Texture Mapping" (EYE_LINEAR texgen planes given under the view
// matrix; the reverse projection behind the projector removed by a clip plane). The texgen
// planes are those of the shadow map (S · P_light · L, Everitt et al. 2001 Eq. 5) with the map's
// [0, 1] square widened to hold the cone's disc and a margin. Per vertex, GL_SPOT_CUTOFF lights
// a vertex or not and a triangle across the cone's edge ramps between its vertices; the
// projected texture decides per pixel, at any tessellation (module-internal header).
//
// DEVIATION (Segal et al. 1992; Everitt 2001): their projected spotlight texture modulates the
// light's colour with a soft image; ours has the hard edge of GL_SPOT_CUTOFF and of the modern
// twins' per-pixel test, kept per pixel by the alpha test on a bilinearly filtered distance to the
// cone's edge.
// (The edge of a bilinear interpolation of a distance is a smooth curve within a small fraction
// of a pixel of the circle, where a binary texture would show its texels.)
#pragma once

#include <string>
#include <vector>

#include "core/gl/gl.h"
#include "core/gl/gl_objects.h"
#include "core/scene/scene.h"

namespace sl::legacy {

// The departure above, as the lighting passes' tables declare it (PassSpec::deviations).
inline const std::string kProjectedConeDeviation =
    "DEVIATION (Segal et al. 1992; Everitt 2001): their projected spotlight texture modulates the "
    "light's colour with a soft image; ours has the hard edge of GL_SPOT_CUTOFF and of the modern "
    "twins' per-pixel test, kept per pixel by the alpha test on a bilinearly filtered distance to "
    "the "
    "cone's edge.";

// The cone texture: kConeTextureTexels^2 texels of GL_ALPHA16 over [-kConeTextureExtent,
// kConeTextureExtent]^2 of the light's normalised image plane, where the cone is the unit disc
// (the circle inscribed in the light frustum, fixed_function.cpp enableSpotlight).
constexpr int kConeTextureTexels = 64;
// Half the side the texture covers, in light NDC: the disc (radius 1) plus a margin of more than
// kConeRampTexels texels, so that the clamped lookups beyond the light frustum read "outside".
constexpr double kConeTextureExtent = 1.125;
// The distance over which alpha goes from 1 (inside) to 0 (outside), in texels on either side
// of the edge: wide enough that every bilinear lookup near the edge reads four unclamped texels.
constexpr double kConeRampTexels = 2.0;
// The alpha test's reference: alpha 0.5 is the cone's edge; at it a point counts as lit, as
// the modern twins' test `dot >= cos(cutoff)`.
constexpr float kConeEdgeAlpha = 0.5f;

// The cone's alpha at a point (x, y) of the light's normalised image plane (what the texel
// there holds): 0.5 + (1 - |(x, y)|) / (2 w), clamped to [0, 1], w the ramp's half width.
float coneTextureAlpha(double x, double y);
// Fills the 2D texture `texture` with kConeTextureTexels^2 alphas (row by row) in the cone
// texture's format, filter and wrap (GL_ALPHA16, GL_LINEAR, GL_CLAMP_TO_EDGE); the active
// unit's 2D binding is restored. SpotlightConeTexture and the lighting pass's floor
// (measure/roofline.h) both make theirs with it, so the floor samples what the pass samples.
void uploadConeTexture(GLuint texture, const std::vector<float>& alpha);

// The world-to-texture planes of the cone (rows s, t, -, q of the matrix): s/q, t/q in [0, 1]
// over the texture's square; q is the light eye-space depth scaled by tan(cone / 2) (q > 0 in
// front of the light). Exposed for the test.
glm::mat4 worldToConeTexture(const Scene& scene);

class SpotlightConeTexture {
 public:
  SpotlightConeTexture();  // makes and fills it (GL_LINEAR, clamped); the binding is kept
  GLuint id() const { return texture_.id(); }

 private:
  Texture texture_;
};

// While alive: texture unit `unit` projects the cone texture from the light (EYE_LINEAR S, T, Q
// planes, given while the modelview holds the camera's view matrix, which the caller must have
// loaded), GL_MODULATE (alpha = lighting alpha x cone alpha), the alpha test keeps alpha >=
// kConeEdgeAlpha, and user clip plane 0 keeps what lies in front of the light (q >= 0; behind
// it s/q and t/q mirror the cone, Everitt 2001 "reverse projection"). The destructor turns all
// of it off again and leaves GL_TEXTURE0 active. For the passes that add the direct light.
class ProjectedSpotlightCone {
 public:
  ProjectedSpotlightCone(const Scene& scene, const SpotlightConeTexture& texture, GLenum unit);
  ~ProjectedSpotlightCone();
  ProjectedSpotlightCone(const ProjectedSpotlightCone&) = delete;
  ProjectedSpotlightCone& operator=(const ProjectedSpotlightCone&) = delete;

 private:
  GLenum unit_;
};

}  // namespace sl::legacy
