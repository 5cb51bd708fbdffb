// measure/stability.cpp — the stability cases (see measure/stability.h). The scenes are small
// purpose-built stages; each case states its bound and why the bound is right.
#include "measure/stability.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <sstream>

#include "core/base/errors.h"
#include "core/scene/primitives.h"
#include "core/scene/scene_library.h"
#include "reference/reference.h"
#include "registry/registry.h"
#include "registry/shadow_error.h"

namespace sl::figures::stability {

// Errors within this many pixels of a reference shadow edge are the techniques' business
// (aliasing, filtering, bias); beyond it a wrong pixel is a failure of the case.
// The bound of a well-conditioned case: at 160x120 a 512 shadow map has at least one texel per
// pixel on these scenes (core/technique/plan.h estimate 1-4 texels per pixel), so a correct
// technique errs only near edges; 2% leaves room for the contact line and the curved casters'
// terminators (self-shadowing where the surface turns away from the light).
// A case that exhausts a resource (depth precision, map size, 8-bit channels) cannot be right
// in general; it must still not be garbage: wrong on at most half of the pixels outside the
// band is "better than an inverted or random mask".

std::shared_ptr<const Mesh> share(Mesh m) { return std::make_shared<const Mesh>(std::move(m)); }

Object object(const std::string& name, Mesh mesh, const glm::mat4& model, bool casts,
              bool receives) {
  Object o;
  o.name = name;
  o.mesh = share(std::move(mesh));
  o.model = model;
  o.castsShadow = casts;
  o.receivesShadow = receives;
  return o;
}

glm::mat4 at(float x, float y, float z) { return glm::translate(glm::mat4(1), {x, y, z}); }

// The stage: a tessellated ground (receiver), a floating box and a sphere (closed casters),
// large in the window so that their shadows are wide compared with the edge band.
Scene stage() {
  Scene s;
  s.name = "stage";
  s.objects.push_back(object("ground", makePlane(4, 4, 8), glm::mat4(1), false, true));
  s.objects.push_back(
      object("box", makeBox({0.8f, 0.8f, 0.8f}), at(-0.6f, 0.8f, -0.2f), true, true));
  s.objects.push_back(
      object("sphere", makeSphere(0.45f, 32, 16), at(0.7f, 0.6f, 0.4f), true, true));
  s.camera.position = {0, 3.2f, 2.6f};
  s.camera.target = {0, 0.0f, -0.2f};
  s.camera.fovyDegrees = 50;
  s.camera.nearPlane = 0.5f;
  s.camera.farPlane = 20;
  s.light.position = {1.5f, 3.5f, -2.0f};  // shadows fall towards the camera, in view
  s.light.target = {0, 0, 0};
  s.light.up = {0, 1, 0};
  s.light.coneDegrees = 70;
  s.light.radius = 0.05f;
  return s;
}

// A post standing on a ground that casts too (self-shadowing is the stiff part), lit at
// `degrees` from the ground's normal.
Scene grazing(float degrees) {
  Scene s = stage();
  s.name = "grazing";
  s.objects.clear();
  s.objects.push_back(object("ground", makePlane(4, 4, 8), glm::mat4(1), true, true));
  s.objects.push_back(object("post", makeBox({0.2f, 1.2f, 0.2f}), at(0, 0.6f, 0), true, true));
  const float a = glm::radians(degrees);
  constexpr float kLightDistance = 5.0f;
  s.light.position = {kLightDistance * std::sin(a), kLightDistance * std::cos(a), 0};
  s.light.target = {0, 0, 0};
  s.light.coneDegrees = 90;
  return s;
}

Scene scaled(float factor) {
  Scene s = stage();
  s.name = "scaled";
  const glm::mat4 scale = glm::scale(glm::mat4(1), glm::vec3(factor));
  for (Object& o : s.objects) o.model = scale * o.model;
  s.camera.position *= factor;
  s.camera.target *= factor;
  s.camera.nearPlane *= factor;
  s.camera.farPlane *= factor;
  s.light.position *= factor;
  s.light.target *= factor;
  s.light.radius *= factor;
  return s;
}

// The light's depth range forced to near/far = ratio (far fixed beyond the scene).
Scene nearFar(float ratio) {
  Scene s = stage();
  constexpr float kFar = 8.0f;
  s.light.farPlane = kFar;
  s.light.nearPlane = kFar * ratio;
  return s;
}

// The light's cone widened to `degrees` (the light frustum's full opening angle).
Scene wideCone(float degrees) {
  Scene s = stage();
  s.light.coneDegrees = degrees;
  return s;
}

// The camera's near plane at `ratio` times its far plane.
Scene cameraNearFar(float ratio) {
  Scene s = stage();
  s.camera.nearPlane = s.camera.farPlane * ratio;
  return s;
}

// A caster behind the light (negative projection: it must not shadow anything in front) and
// A light far straight above a ground that casts too, the commonest setup there is: the depth
// range fitted to the stage is narrow compared with its distance (near/far 0.96), where the
// projective depth r/q loses about 2n/(f-n) = 50 times its float precision to cancellation.
// With a constant polygon offset of 4 depth units hw, woo, GPU Gems PCF and the hybrid put the
// whole ground in umbra (core/scene/scene.h lightDepthRoundoffScale).
Scene distantOverheadLight() {
  Scene s = stage();
  s.name = "distant_overhead_light";
  s.objects[0].castsShadow = true;
  s.light.position = {0, 20, 0};
  s.light.up = {0, 0, -1};
  s.light.coneDegrees = 20;  // frames the 4x4 ground: 20 tan 10 = 3.5 units half-width
  return s;
}

// a torus around the light (the light inside its bounds; the ring itself is out of the cone).
Scene behindAndAround() {
  Scene s = stage();
  s.objects.push_back(object("behind", makeBox({1, 1, 1}), at(1.6f, 6.5f, 1.6f), true, true));
  s.objects.push_back(object("ring", makeTorus(0.8f, 0.1f, 24, 12),
                             glm::translate(glm::mat4(1), s.light.position), true, true));
  return s;
}

// Zero-area (repeated index, collinear) and degenerate triangles appended to a caster.
Scene degenerate() {
  Scene s = stage();
  Mesh box = makeBox({0.8f, 0.8f, 0.8f});
  const unsigned base = unsigned(box.positions.size());
  box.positions.push_back({0.0f, 0.0f, 0.0f});
  box.positions.push_back({0.1f, 0.0f, 0.0f});
  box.positions.push_back({0.2f, 0.0f, 0.0f});                   // collinear with the two before
  for (int i = 0; i < 3; ++i) box.normals.push_back({0, 0, 0});  // no usable normal
  for (unsigned i : {base, base + 1, base + 2, base, base, base, 0u, 0u, 1u})
    box.indices.push_back(i);
  box.closed = false;
  s.objects[1] = object("degenerate box", box, at(-0.6f, 0.8f, -0.2f), true, true);
  return s;
}

// An open caster (a single quad, not closed) for techniques that need closed meshes.
Scene openCaster() {
  Scene s = stage();
  s.objects[1] =
      object("open quad", makeQuad(0.8f, 0.8f),
             glm::rotate(at(-0.6f, 1.2f, -0.2f), glm::radians(-90.0f), {1, 0, 0}), true, true);
  return s;
}

// Contact: the box rests on the ground (and b/r -> 1 for smoothies: blocker at the receiver).
Scene contact() {
  Scene s = stage();
  s.objects[1].model = at(-0.6f, 0.4f, -0.2f);
  s.objects[2].model = at(0.7f, 0.45f, 0.4f);
  return s;
}

// A receiver parallel to the light's image plane (zero depth variance over every filter
// footprint) under a caster that is also flat: VSM's Chebyshev bound divides by the variance.
Scene flatDepth() {
  Scene s = stage();
  s.light.position = {0, 4.0f, 0};
  s.light.up = {0, 0, -1};
  s.objects[1] = object("slab", makeBox({0.8f, 0.02f, 0.8f}), at(0, 1.0f, 0), true, false);
  s.objects.erase(s.objects.begin() + 2);
  return s;
}

// The stage with a slab between the light and the sphere, so that the two casters' shadow
// volumes overlap. `mirrored`: the ground, the box and the slab mirrored by their model
// matrices (a negative determinant reverses every triangle's winding), the
// sphere not, so mirrored and unmirrored volumes overlap. The meshes are mirror-symmetric about
// their own origins: the geometry does not depend on `mirrored`.
Scene mirroringStage(bool mirrored) {
  Scene s = stage();
  s.name = mirrored ? "mirrored" : "mirroring";
  s.objects.push_back(
      object("slab", makeBox({0.5f, 0.05f, 0.5f}), at(1.2f, 2.3f, -1.0f), true, true));
  if (!mirrored) return s;
  const glm::mat4 flipX = glm::scale(glm::mat4(1), {-1, 1, 1});
  for (size_t i : {0, 1, 3}) s.objects[i].model = s.objects[i].model * flipX;
  return s;
}

bool declares(const Technique& t, const std::string& key) { return findParam(t, key) != nullptr; }
std::string always(const Technique&) { return ""; }
void noChange(RenderParams&) {}
bool isReference(const Technique& t) {  // ray traced: renders no shadow map
  return t.plan.shadowWork == PlanTraits::ShadowWork::kRays;
}

const std::vector<Case>& cases() {
  static const std::vector<Case> kCases = {
      {"baseline", stage, noChange, always, kWellConditioned, "well conditioned"},
      {"grazing80", [] { return grazing(80); }, noChange, always, kWellConditioned,
       "80 degrees: slope-scaled offset still covers the ground's depth slope (cot 80 = 0.18)"},
      {"grazing89", [] { return grazing(89); }, noChange, always, kDegradedButSane,
       "89 degrees: one texel spans 57x its size along the ground; acne or a displaced edge is "
       "expected, garbage is not"},
      {"grazing89_9", [] { return grazing(89.9f); }, noChange, always, kDegradedButSane,
       "89.9 degrees: the ground is edge-on to the light (573x stretch)"},
      {"dueling", [] { return builtinScene("dueling"); }, noChange, always, 0.05,
       "Everitt Fig. 6: the light faces the camera; far-from-light texels are magnified several "
       "times on screen, so edges alias over more than the band: 5%"},
      {"near_far_1e-3", [] { return nearFar(1e-3f); }, noChange, always, kWellConditioned,
       "near/far 1e-3: a 24-bit depth buffer still resolves 1e-4 of the range at the far end"},
      {"near_far_1e-6", [] { return nearFar(1e-6f); }, noChange, always, kWellConditioned,
       "near/far 1e-6 would put all geometry into the last ~20 steps of a 24-bit depth buffer: "
       "lightDepthRange narrows a range below 1e-4 to the geometry, which moves no fragment"},
      {"near_far_1e-7", [] { return nearFar(1e-7f); }, noChange, always, kWellConditioned,
       "near 8e-7, far 8 (unnarrowed, hw and GPU Gems PCF were all lit): narrowed to the "
       "geometry like near_far_1e-6"},
      {"cone_160", [] { return wideCone(160); }, noChange, always, 0.05,
       "the widest cone validateScene accepts: the central texels span 5.7x those of a "
       "90-degree cone, so edges alias over several pixels beyond the band (measured: at most "
       "3.4%, Brabec-Seidel fast PCF): 5%"},
      {"camera_near_far_1e-5", [] { return cameraNearFar(1e-5f); }, noChange, always,
       kWellConditioned,
       "the stiffest camera range validateScene accepts: a 24-bit depth buffer still resolves "
       "0.6% of far at far, and the stage lies within a third of far"},
      {"map_1x1", stage, [](RenderParams& p) { p.shadowMapTexels = 1; },
       [](const Technique& t) { return isReference(t) ? "no shadow map" : ""; }, kDegradedButSane,
       "one texel holds one depth for the whole light view: all lit or all shadowed"},
      {"map_2x2", stage, [](RenderParams& p) { p.shadowMapTexels = 2; },
       [](const Technique& t) { return isReference(t) ? "no shadow map" : ""; }, kDegradedButSane,
       "four texels for the whole light view"},
      {"scaled_1e-3", [] { return scaled(1e-3f); }, noChange, always, kWellConditioned,
       "a uniform scale changes no angle and no depth ratio: same as the baseline"},
      {"scaled_1e4", [] { return scaled(1e4f); }, noChange, always, kWellConditioned,
       "a uniform scale changes no angle and no depth ratio: same as the baseline"},
      {"mirrored", [] { return mirroringStage(true); }, noChange, always, kWellConditioned,
       "mirrored objects are the stage's geometry: front faces, culling, stencil counts and "
       "silhouette orientation must follow the outside, not the winding"},
      {"scaled_1e6", [] { return scaled(1e6f); }, noChange, always, kWellConditioned,
       "a uniform scale changes no angle and no depth ratio: same as the baseline (the legacy "
       "negative-projection step once overflowed llvmpipe's integer texel coordinate here)"},
      {"distant_overhead_light", distantOverheadLight, noChange, always, kWellConditioned,
       "a flat ground that casts, under a light 20 units up: offsets scaled by the depth's "
       "round-off keep it lit (it was all umbra in hw, woo, GPU Gems PCF and the hybrid)"},
      {"behind_and_around_light", behindAndAround, noChange, always, kWellConditioned,
       "geometry behind the light must not shadow anything in front of it (negative projection)"},
      {"degenerate_triangles", degenerate, noChange, always, kWellConditioned,
       "zero-area triangles cover no pixel and block no ray"},
      {"open_caster", openCaster, noChange, always, kWellConditioned,
       "an open quad casts the same shadow as a closed slab; techniques that need closed meshes "
       "must refuse it (InputError) or fall back and still be right"},
      {"contact", contact, noChange, always, kWellConditioned,
       "the contact line lies on the edge band; elsewhere contact is an ordinary shadow"},
      {"ramp_8bit_limit", [] { return nearFar(2e-2f); },
       [](RenderParams& p) { p.precision = Precision::k8; },
       [](const Technique& t) {
         return t.needs.colorFromPrecision ? "" : "no colour-encoded depth";
       },
       kDegradedButSane,
       "8-bit depth through the ramp: 256 steps over the forced light range [0.16, 8] are 0.03 "
       "units apart, the size of the stage's gaps"},
      {"csm_order_64_8bit", stage,
       [](RenderParams& p) {
         p.extra = {{"order", "64"}, {"storage", "8"}};
       },
       [](const Technique& t) {
         return declares(t, "order") && declares(t, "storage") ? "" : "no order/storage parameters";
       },
       kDegradedButSane,
       "M = 64 in 8 bits: the basis sin(c_k z) changes by more than one 8-bit step per depth step "
       "for k > 20, so the reconstruction rings"},
      {"csm_order_64_float", stage,
       [](RenderParams& p) {
         p.extra = {{"order", "64"}, {"storage", "float"}};
       },
       [](const Technique& t) {
         return declares(t, "order") && declares(t, "storage") ? "" : "no order/storage parameters";
       },
       kWellConditioned, "M = 64 in float: the expansion converges to the step (Eq. 11)"},
      {"vsm_zero_variance", flatDepth,
       [](RenderParams& p) {
         p.extra = {{"min-variance", "0"}};
       },
       [](const Technique& t) {
         return declares(t, "min-variance") ? "" : "no min-variance parameter";
       },
       kWellConditioned,
       "flat caster over a flat receiver: sigma^2 = 0 and the Chebyshev bound must not divide by "
       "it"},

  };
  return kCases;
}

const Case& findCase(const std::string& name) {
  for (const Case& c : cases())
    if (c.name == name) return c;
  throw std::logic_error("no case " + name);
}

RenderParams baseParams() {
  RenderParams p;
  p.width = kWidth;
  p.height = kHeight;
  p.capturePasses = true;  // every intermediate buffer is checked for NaN/Inf too
  return p;
}

// The references of a case, rendered once per case and technique kind. `withoutOpenCasters`:
// the scene with every open (non-closed) caster made a non-caster, the documented fallback of
// the techniques that need closed meshes (they report Frame::counters["open_casters_skipped"]).
const Frame& referenceFor(const Case& c, bool soft, bool withoutOpenCasters) {
  static std::map<std::string, Frame> cache;
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  const std::string key =
      c.name + (soft ? "|soft" : "|hard") + (withoutOpenCasters ? "|closed" : "");
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  Scene scene = c.scene();
  if (withoutOpenCasters)
    for (Object& o : scene.objects)
      if (!o.mesh->closed) o.castsShadow = false;
  RenderParams p = baseParams();  // with capturePasses: the reference's faces-light mask
  return cache[key] =
             renderTechnique(findTechnique(soft ? "reference.soft" : "reference.hard"), scene, p);
}

// The pixels a case's bound counts: the scored pixels of the one error definition
// (registry/shadow_error.h: receivers facing the light inside its frustum; elsewhere visibility
// does not change the image) outside the reference's edge band (the point metric, share of
// pixels off by more than 0.5).
MaskDifference errorWhereItMatters(const Image& visibility, const Frame& ref) {
  const ShadowTruth truth =
      truthFromReferenceFrame(ref, ErrorMetric::kPoint, false, "the case's reference");
  const Image band = boundaryBand(ref.visibility, kBandPixels);
  Image region(kWidth, kHeight, 1);
  for (size_t i = 0; i < band.data.size(); ++i)
    region.data[i] = band.data[i] <= 0.5f && truth.scored.data[i] > 0.5f ? 1.0f : 0.0f;
  return compareMasksWithin(visibility, ref.visibility, region, 0.5);
}

// Per-technique exceptions, each with its reason: the bound replaces the case's bound (a
// documented limitation of the technique; a bug is fixed, not listed here).
// Brabec–Seidel §2-§4 compare colour-encoded depth with a constant bias (no slope-scaled
// offset): a receiver that casts too self-shadows where its depth changes by more than the
// bias per texel. At 80 degrees that is tan 80 = 5.7 texel widths per texel; at 89, 57: the
// lit ground self-shadows over much of its area. The entries assert what the limitation
// predicts (KnownIssue::selfShadowedAtLeast) instead of an error bound: the lit ground shadows
// itself, and too small a bias only adds shadow, so no pixel is lit where the reference is in
// shadow (bound 0; a weak check here: 99.9% of the counted pixels are lit in the reference, the
// post's thin shadow lying mostly in the edge band).
// Measured (160x120, 512 map; share of the reference's lit counted pixels shadowed; legacy and
// modern twins alike to 0.01%): 80 degrees ramp 12.3%, PCF 31.8%, fast PCF 55.0%; 89 degrees
// ramp 43.6%, PCF 65.5%, fast PCF 90.0% (the filters reach neighbour texels, deeper by tan a
// texel widths each). hw, GPU Gems PCF and the hybrid (polygon offset with a slope factor) and
// second-depth (by construction) shadow 0% of it, so a fix of the limitation falls far below
// these floors, which sit under the least measured share of each angle by about a fifth
// (rounding of the ramp on another driver moves a few rows of texels, not a fifth of the lit
// ground).
// The entries hold for the techniques' defaults (--param bias=constant); the modern twins'
// --param bias=normal-offset removes the self-shadowing (measure/bias_table.h, docs/bias.md).
constexpr double kSelfShadowedAt80 = 0.10;     // least measured: 12.3% (ramp)
constexpr double kSelfShadowedAt89 = 0.35;     // least measured: 43.6% (ramp)
constexpr double kNothingShadowedIsLit = 0.0;  // measured 0 in all twelve; bias only darkens
const char* const kConstantBias =
    "constant depth bias only (Brabec–Seidel §2, no slope-scaled offset): a grazing receiver "
    "that also casts self-shadows";
const std::map<std::pair<std::string, std::string>, KnownIssue>& knownIssues() {
  static const std::map<std::pair<std::string, std::string>, KnownIssue> kIssues = {
      {{"grazing80", "legacy.ramp"}, {kNothingShadowedIsLit, kConstantBias, kSelfShadowedAt80}},
      {{"grazing80", "legacy.pcf"}, {kNothingShadowedIsLit, kConstantBias, kSelfShadowedAt80}},
      {{"grazing80", "legacy.fast-pcf"}, {kNothingShadowedIsLit, kConstantBias, kSelfShadowedAt80}},
      {{"grazing80", "modern.ramp"}, {kNothingShadowedIsLit, kConstantBias, kSelfShadowedAt80}},
      {{"grazing80", "modern.pcf"}, {kNothingShadowedIsLit, kConstantBias, kSelfShadowedAt80}},
      {{"grazing80", "modern.fast-pcf"}, {kNothingShadowedIsLit, kConstantBias, kSelfShadowedAt80}},
      {{"grazing89", "legacy.ramp"}, {kNothingShadowedIsLit, kConstantBias, kSelfShadowedAt89}},
      {{"grazing89", "legacy.pcf"}, {kNothingShadowedIsLit, kConstantBias, kSelfShadowedAt89}},
      {{"grazing89", "legacy.fast-pcf"}, {kNothingShadowedIsLit, kConstantBias, kSelfShadowedAt89}},
      {{"grazing89", "modern.ramp"}, {kNothingShadowedIsLit, kConstantBias, kSelfShadowedAt89}},
      {{"grazing89", "modern.pcf"}, {kNothingShadowedIsLit, kConstantBias, kSelfShadowedAt89}},
      {{"grazing89", "modern.fast-pcf"}, {kNothingShadowedIsLit, kConstantBias, kSelfShadowedAt89}},
      {{"cone_160", "modern.smoothies"},
       {0.12,
        "the smoothie width t is a light-space constant (Chan §4.2): under a 160-degree cone "
        "the stage's receivers sit where a map texel spans 5.7x its 90-degree size, and the "
        "penumbra widens with it (measured 10%): at most 12%"}},
      {{"cone_160", "modern.esm"},
       {0.12,
        "the positive exponential warp weighs a texel behind the receiver by exp(c (z - d)) "
        "(ours, after Annen et al. 2008, not in shared/papers): the stage's ground casts no "
        "shadow, so the map around the casters holds depth 1, and one such texel in the 3x3 "
        "blur and tri-linear footprint lights a pixel of the umbra (exp(80 * 0.3) = 3e10 to 1). "
        "Under a 160-degree cone each texel covers 5.7x the ground and the shadows shrink by "
        "the footprint (measured 10.5%; with blur=0 and nearest filtering 1.0%): at most 12%"}},
      {{"cone_160", "modern.evsm2"},
       {0.12,
        "the same property of the positive warp as modern.esm's (ours, after Lauritzen & McCool "
        "2008, not in shared/papers): an empty-map texel (depth 1) in the footprint weighs "
        "exp(2 c (1 - d)) against the blockers' near-zero warped depths, the filtered mean passes "
        "the receiver's and Chebyshev says lit; modern.evsm4's negative warp removes it (0.1%). "
        "Measured 10.5%; lit where shadowed with blur=0 1.4%, with blur=0 and nearest filtering "
        "0.06%: at most 12%"}},
      {{"grazing80", "modern.smoothies"},
       {0.05,
        "the smoothie width t is a light-space constant (Chan §4.2): on ground lit at 80 degrees "
        "its penumbra stretches 1/cos 80 = 5.8x, about 2.5x the 2-pixel band around the post's "
        "shadow outline (~2% of the pixels): at most 5%"}},
  };
  return kIssues;
}

// No case is refused today: every technique renders every case that applies to it (the whole
// suite run). A case that must be refused goes here with a part of its
// message, e.g. {{"open_caster", "modern.x"}, "needs closed casters"}.
const std::map<std::pair<std::string, std::string>, std::string>& expectedRefusals() {
  static const std::map<std::pair<std::string, std::string>, std::string> kRefusals = {};
  return kRefusals;
}

Outcome evaluate(const Case& c, const Technique& t) {
  Outcome out;
  if (std::string why = c.skip(t); !why.empty()) {
    out.kind = Outcome::Kind::kNotApplicable;
    out.note = why;
    return out;
  }
  out.bound = c.bound;
  out.why = c.why;
  if (auto refusal = expectedRefusals().find({c.name, t.name}); refusal != expectedRefusals().end())
    out.expectedRefusal = refusal->second;
  auto issue = knownIssues().find({c.name, t.name});
  RenderParams params = baseParams();
  c.params(params);
  const Scene scene = c.scene();
  try {
    out.frame = renderTechnique(t, scene, params);
  } catch (const InputError& e) {
    // A configuration that cannot work: the clear refusal is the expected behaviour.
    out.kind = Outcome::Kind::kRefused;
    out.note = e.what();
    return out;
  }
  const Frame& f = out.frame;
  out.finite = allFinite(f.visibility) && (f.color.empty() || allFinite(f.color));
  for (const PassImage& p : f.intermediates) out.finite = out.finite && allFinite(p.image);
  out.lowest = 1.0f;
  out.highest = 0.0f;
  for (float v : f.visibility.data) {
    out.lowest = std::min(out.lowest, v);
    out.highest = std::max(out.highest, v);
  }
  const bool soft = t.light == Technique::Light::kArea;
  out.reference = &referenceFor(c, soft);
  out.error = errorWhereItMatters(f.visibility, *out.reference);
  auto skipped = f.counters.find("open_casters_skipped");
  if (skipped != f.counters.end() && skipped->second > 0) {
    // Documented fallback: open casters left out. Right if it matches either reference.
    const MaskDifference without = errorWhereItMatters(f.visibility, referenceFor(c, soft, true));
    if (without.shareAboveHalf < out.error.shareAboveHalf) out.error = without;
  }
  // The same count split by direction (Outcome::wronglyLit, wronglyShadowed, referenceLit).
  const Image& truth = out.reference->visibility;
  if (truth.data.size() != f.visibility.data.size())
    throw std::logic_error("stability: reference and technique masks differ in size");
  Image lighter = f.visibility, darker = f.visibility, unlit = f.visibility;
  for (size_t i = 0; i < truth.data.size(); ++i) {
    lighter.data[i] = std::max(f.visibility.data[i], truth.data[i]);
    darker.data[i] = std::min(f.visibility.data[i], truth.data[i]);
    unlit.data[i] = 0.0f;
  }
  out.wronglyLit = errorWhereItMatters(lighter, *out.reference);
  out.wronglyShadowed = errorWhereItMatters(darker, *out.reference);
  out.referenceLit = errorWhereItMatters(unlit, *out.reference).shareAboveHalf;
  if (issue != knownIssues().end()) {
    out.bound = issue->second.bound;
    out.why = issue->second.why;
    out.selfShadowedAtLeast = issue->second.selfShadowedAtLeast;
  }
  return out;
}

std::string summaryHtml(bool progress) {
  std::ostringstream h;
  h << "<h2 id=stability>Numerical stability on stiff and extreme cases</h2>\n"
    << "<p>Every technique on every case of the stability suite (tests/stability, "
       "measure/stability.cpp), "
    << kWidth << "x" << kHeight
    << ": the share of pixels (%) "
       "whose visibility differs from the ray-traced reference by more than 0.5, counted "
       "outside a "
    << kBandPixels
    << "-pixel band around the reference's shadow edges on "
       "surfaces the light reaches. Green: within the case's bound; red: above it or a NaN/Inf "
       "or a value outside [0, 1]; <em>refused</em>: a clear InputError (the expected answer "
       "for a configuration that cannot work); &ndash;: the case does not apply.</p>\n"
    << "<table><tr><th>technique</th>";
  for (const Case& c : cases())
    h << "<th>" << c.name << "<br>(bound " << 100 * c.bound << "%)</th>";
  h << "</tr>\n";
  for (const Technique& t : allTechniques()) {
    h << "<tr><td><code>" << t.name << "</code></td>";
    for (const Case& c : cases()) {
      if (progress) std::cerr << "[stability] " << c.name << " " << t.name << std::endl;
      Outcome o;
      try {
        o = evaluate(c, t);
      } catch (const std::exception& e) {
        h << "<td class=bad title=\"" << e.what() << "\">GL error</td>";
        continue;
      }
      switch (o.kind) {
        case Outcome::Kind::kNotApplicable: h << "<td>&ndash;</td>"; break;
        case Outcome::Kind::kRefused:
          h << "<td class=" << (o.refusedAsExpected() ? "ok" : "bad") << ">refused</td>";
          break;
        case Outcome::Kind::kMeasured: {
          const bool good = o.finite && o.lowest >= 0.0f && o.highest <= 1.0f && o.withinBound() &&
                            o.expectedRefusal.empty();
          std::ostringstream v;
          v << std::setprecision(2) << 100.0 * o.error.shareAboveHalf;
          const bool ownBound = o.bound != c.bound;  // a documented limitation of t
          h << "<td class=" << (good ? "ok" : "bad") << ">" << v.str() << (o.finite ? "" : " NaN")
            << (ownBound ? "*" : "") << "</td>";
        }
      }
    }
    h << "</tr>\n";
  }
  h << "</table>\n<p>* a bound of the technique's own, for a documented limitation: the "
       "Brabec–Seidel techniques compare colour-encoded depth with a constant bias (no "
       "slope-scaled offset), so a grazing receiver that also casts shadows itself (green "
       "where it does as predicted: at least the stated share of the lit ground self-shadowed, "
       "nothing that the reference shadows lit); smoothies "
       "keep a light-space width that stretches on grazing receivers "
       "(measure/stability.cpp, knownIssues).</p>\n";
  return h.str();
}

}  // namespace sl::figures::stability
