// reference/reference.h — ray-traced ground truth for every error figure (public header).
//
//   reference.hard  exact visibility of the point light per camera pixel (Embree shadow rays)
//   reference.soft  Monte Carlo visibility of a spherical light of SpotLight::radius
//
// Each comes in two forms (--param pixel=...):
//   centre (default)  the visibility at the pixel centre's surface point: a point sample,
//                     itself aliased at shadow edges (what every test and figure panel that
//                     shows "the reference" uses)
//   area              the visibility integrated over the part of the pixel's area that shows
//                     the surface its centre sees (box filter): N x N stratified sub-pixel
//                     surface points (--param pixel-samples=N per side), each rasterised at
//                     its own sub-pixel position; only the samples on that surface (same
//                     object, within kSameSurfacePixelFootprints of the centre point's tangent
//                     plane, facing the light, inside its frustum) are averaged, so that a
//                     geometry edge or a terminator inside the pixel is not counted as shadow
//                     (docs/error.md); hard: one shadow ray per such sample; soft: the light's
//                     rays start from those sub-pixel points instead of the pixel centre. At
//                     pixels that are not scored (see kPixelCategoriesPass) every sample is
//                     averaged, the plain box filter. The antialiasing metric measures every
//                     technique against this form (docs/error.md).
//
// Both rasterise the camera's surface points with GL (the same camera and the same vertex
// transform as the modern camera pass), so every technique's mask lines up pixel for pixel
// with the reference, and then cast shadow rays from those points with Embree 3.
#pragma once

#include <vector>

#include "core/technique/technique.h"

namespace sl::reference {

std::vector<Technique> techniques();

// The conventions every reference mask follows (tests and the bench rely on them):
//  * a pixel that sees no geometry is lit (1), like the cleared visibility of the techniques;
//  * a pixel on an object with receivesShadow == false is lit (1);
//  * a pixel outside the light's square frustum (cone x cone, in front of the light) is lit
//    (1): the spotlight sends nothing there and the shadow-map techniques clamp to a lit
//    border there too;
//  * only objects with castsShadow occlude.
constexpr float kNoGeometryVisibility = 1.0f;

// With RenderParams::capturePasses the references add this intermediate: 1 where a surface
// point faces the light (geometric normal) inside the light's frustum, 0 elsewhere and where no
// geometry is seen. Error metrics count these pixels: elsewhere visibility changes nothing.
constexpr const char* kDirectLightRegionPass = "2-direct-light-region";

// With RenderParams::capturePasses the references also add this intermediate: every pixel's
// category under the error definition of docs/error.md (registry/shadow_error.h reads it), one
// grey level each so that the dump shows them apart:
//   scored        a receiver's surface point inside the light's frustum whose geometric
//                 (triangle) normal faces the light: the pixels every error score counts
//   faces away    a receiver's point inside the frustum whose surface faces away from the
//                 light (the self-shadowed side of a caster, its terminator): unlit by the
//                 lighting term whatever the visibility says, reported apart, not scored
//   outside light a receiver's point outside the light's frustum (the spotlight sends nothing)
//   no receiver   no geometry, or an object with receivesShadow == false
// The categories come from the pixel-centre surface points, so they are the same for every
// technique and both forms (pixel=centre and pixel=area).
constexpr const char* kPixelCategoriesPass = "2-pixel-categories";
constexpr float kCategoryScored = 1.0f;
constexpr float kCategoryFacesAway = 2.0f / 3.0f;
constexpr float kCategoryOutsideLight = 1.0f / 3.0f;
constexpr float kCategoryNoReceiver = 0.0f;

// Shadow rays start this far (times the scene's bounding-box diagonal) along the surface's
// geometric normal, so that a surface does not shadow itself through float round-off. The
// offset is a bias: it moves every shadow edge on a receiver by about offset / tan(elevation of
// the light) and lights a band offset / sin(angle) wide on a caster's faces that turn away from
// the light at a grazing angle. Measured against modern.volumes (exact at pixel centres) on the
// 14 closed-caster scenes at 400x300: 1e-4 moved whole pixel rows (bleeding: 0.36% of
// the scored pixels; trees 0.22%) and lit terminator bands (all pixels: up to 0.7%); 1e-5 left
// at most 17 scored pixels apart (0.02%); 1e-6 at most 5; at 1e-7 the surface starts to shadow
// itself (6-12 lit pixels shadowed on brabec, dueling, bunny): the GL-rasterised point lies off
// its triangle by float round-off, and 1e-6 stays a factor 10 above where that shows.
constexpr float kRayOffsetPerSceneDiagonal = 1e-6f;

// pixel=area: a sub-pixel sample shows "the surface the centre sees" when it lies on the same
// object within this many pixel footprints (the world size of one pixel at the centre point's
// distance from the camera) of the centre point's tangent plane. On one planar face the
// distance is round-off; across a curved face within a pixel it is second order in the
// footprint (well under one); a surface behind a silhouette (another picket, the ground behind
// a sphere) lies many footprints off the plane in every scene here.
constexpr float kSameSurfacePixelFootprints = 2.0f;

// reference.soft: rays per pixel, 2 n^2 (two independent stratified halves of n x n strata
// on the light's disk, whose difference estimates the standard error; see reference.cpp).
// --param rays=N is rounded to the nearest 2 n^2. With n = 12 the estimated standard error is
// at most 1 / (2 n^1.5) = 0.012 at a straight shadow edge (tests/reference/reference_test.cpp
// derives the bound and checks the measured value).
constexpr int kDefaultSoftStrataPerSide = 12;
constexpr int kDefaultSoftRays = 2 * kDefaultSoftStrataPerSide * kDefaultSoftStrataPerSide;  // 288

// --param pixel=centre|area and --param pixel-samples=N (sub-pixel strata per side, N x N
// samples; 1 = the pixel centre, so pixel=area with N = 1 equals pixel=centre bit for bit).
constexpr const char* kPixelParam = "pixel";
constexpr const char* kPixelCentre = "centre";
constexpr const char* kPixelArea = "area";
constexpr const char* kPixelSamplesParam = "pixel-samples";
// Hard: 8 x 8 = 64 sub-pixel samples. The samples sit at the strata's centres (an ordered
// grid: deterministic, no noise), so at a straight shadow edge crossing a pixel every column
// of N samples errs by at most half a sample (the midpoint rule is exact for the linear edge):
// |area visibility - covered fraction| <= 1 / (2N) = 0.0625 for N = 8
// (tests/reference/reference_test.cpp checks it on the analytic scene).
constexpr int kDefaultHardPixelSamplesPerSide = 8;
// Soft: 4 x 4 = 16 sub-pixel points, each the origin of 288 / 16 = 18 of the light's rays (the
// light's strata are dealt out to the sub-pixel points, see reference.cpp): the same ray count
// as pixel=centre, so the area form costs 16 extra rasterisations, not more rays.
constexpr int kDefaultSoftPixelSamplesPerSide = 4;
constexpr int kMaxPixelSamplesPerSide = 16;

}  // namespace sl::reference
