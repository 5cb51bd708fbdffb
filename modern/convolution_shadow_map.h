// modern/convolution_shadow_map.h — modern.csm: Convolution Shadow Maps (Annen, Mertens,
// Bekaert, Seidel & Kautz 2007).
#pragma once

#include "core/technique/technique.h"

namespace sl::modern {

Technique convolutionShadowMapTechnique();

// The truncated, attenuated Fourier reconstruction of the shadow test as a function of
// t = z - d (Eq. 11 with §3.2.1): 1/2 + sum_{k=1..M} exp(-alpha (k/M)^2) (2/c_k) sin(c_k t),
// c_k = pi (2k - 1). It is what the shader evaluates through Eq. 13 for unfiltered maps.
// (Eq. 11 is printed with sin(c_k (d - z)), the step of H(d - z) = 1 in SHADOW; Eq. 13 and
// Eq. 1's f, 1 = lit, expand sin(c_k (z - d)); we follow Eq. 13.)
double csmReconstructedStep(double t, int order, double alpha);

// §3.2.2 offset used when --param offset is not given: the t > 0 of the first maximum of the
// reconstructed step, so that a lit surface (z = d) reconstructs to the top of the step.
double csmDefaultOffset(int order, double alpha);

// --param offset-rule=through-1: the smallest t >= 0 where the reconstructed step reaches 1
// (§3.2.2: "after offsetting, f(d, z) goes through 1 for (d - z) = 0"). Below csmDefaultOffset
// where the step overshoots 1 (little attenuation: alpha = 0, M = 4: 0.076 against 0.125), so that
// an occluder close to its receiver darkens sooner; where the step tops out below 1, its top.
double csmOffsetThroughOne(int order, double alpha);

// Where the classification pass of modern.csm may skip Eq. 13 (--param skip-error): intervals
// of t = z - d (d already offset, as csmReconstructedStep's t) on which the clamped, scaled
// series clamp(scale * csmReconstructedStep(t), 0, 1) stays within `maxError` of 1 (lit) or of
// 0 (umbra), found on a grid of [-1, 1] whose points must clear the bound by the most the
// series can move between two points (|d/dt| <= 2 M scale), so that the bound holds for every
// t inside. An empty interval has lo > hi. The lit one contains `offset` if any does; the
// umbra one contains t = -1/2 if any does.
struct CsmSkipIntervals {
  double litLo = 1, litHi = 0;
  double umbraLo = 1, umbraHi = 0;
};
CsmSkipIntervals csmSkipIntervals(int order, double alpha, double offset, double scale,
                                  double maxError);

// The light depth range modern.csm normalises linear depth over (Fig. 6: "a tightly fitted
// light frustum"): near at the nearest caster inside the light frustum, far at the farthest
// receiver inside the casters' cone (modern/prefiltered_maps.h, fitShadowingDepthRange).
// `nearestCaster` (optional): the nearest caster's distance along the light axis; receivers
// nearer than it are lit (the camera pass does not evaluate the series for them).
DepthRange csmDepthRange(const Scene& scene, float* nearestCaster = nullptr);

}  // namespace sl::modern
