// measure/stability.h — the stability suite's stiff and extreme cases as a
// library: tests/stability asserts on them, and the report (`shadowlab figures`) summarises
// every technique's behaviour on them in a table.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/base/metrics.h"
#include "core/technique/technique.h"

namespace sl::figures::stability {

constexpr int kWidth = 160;  // small windows keep the suite within minutes on two cores
constexpr int kHeight = 120;
constexpr int kBandPixels = 2;             // errors this close to a reference edge are allowed
constexpr double kWellConditioned = 0.02;  // share of pixels wrong by > 0.5 outside the band
constexpr double kDegradedButSane = 0.5;   // where a resource runs out: "not garbage"

struct Case {
  std::string name;
  std::function<Scene()> scene;
  std::function<void(RenderParams&)> params;
  // Empty when the case applies to the technique; otherwise why it is skipped.
  std::function<std::string(const Technique&)> skip;
  double bound;     // share of pixels with |v - reference| > 0.5 outside the band
  std::string why;  // why the bound is right
};

// Per-technique exceptions, each with its reason: the bound replaces the case's bound (a
// documented limitation of the technique; a bug is fixed, not listed here).
// A limitation that predicts its own failure states the prediction: with selfShadowedAtLeast
// > 0 (a depth bias too small for the receiver's slope: the lit receiver shadows itself), at
// least that share of the counted pixels the reference shows lit must be shadowed, and `bound`
// bounds only the pixels lit where the reference is in shadow (too small a bias only adds
// shadow). A fix of the limitation then fails the case and its entry is removed.
struct KnownIssue {
  double bound;
  std::string why;
  double selfShadowedAtLeast = 0.0;
};

const std::vector<Case>& cases();
const Case& findCase(const std::string& name);
const std::map<std::pair<std::string, std::string>, KnownIssue>& knownIssues();
// The (case, technique) pairs that must refuse the case with an InputError, each with a part of
// the expected message; any other refusal is a failure, and so is one of these rendering.
const std::map<std::pair<std::string, std::string>, std::string>& expectedRefusals();
Scene stage();  // the baseline scene
// The stage plus a slab over the sphere; `mirrored`: the same geometry with three of its four
// objects mirrored by their model matrices.
Scene mirroringStage(bool mirrored);
bool isReference(const Technique& t);
RenderParams baseParams();
// The ray-traced reference of a case (cached). `withoutOpenCasters`: every open caster made a
// non-caster (the documented fallback of techniques that need closed meshes).
const Frame& referenceFor(const Case& c, bool soft, bool withoutOpenCasters = false);
// The error counted by a case: outside the reference's edge band, on surfaces the light reaches.
MaskDifference errorWhereItMatters(const Image& visibility, const Frame& reference);

// One (case, technique) run and what it measured.
struct Outcome {
  enum class Kind { kNotApplicable, kRefused, kMeasured };
  Kind kind = Kind::kMeasured;
  std::string note;  // why not applicable, or the InputError
  Frame frame;
  bool finite = true;   // no NaN/Inf in colour, visibility or any intermediate
  float lowest = 0.0f;  // visibility range
  float highest = 1.0f;
  MaskDifference error;  // errorWhereItMatters (the better of the two references on fallback)
  // `error` split by direction, against `reference`: errorWhereItMatters of max(v, reference)
  // keeps only pixels lit where the reference is not, of min(v, reference) only pixels shadowed
  // where the reference is lit; referenceLit: the share of the counted pixels the reference
  // shows lit (> 0.5).
  MaskDifference wronglyLit, wronglyShadowed;
  double referenceLit = 0.0;
  double bound = 0.0;
  double selfShadowedAtLeast = 0.0;  // KnownIssue::selfShadowedAtLeast
  std::string why;
  std::string expectedRefusal;  // expectedRefusals(): part of the expected message, or ""
  const Frame* reference = nullptr;
  // The share of the reference's lit counted pixels that the technique shadows.
  double selfShadowed() const {
    return referenceLit > 0.0 ? wronglyShadowed.shareAboveHalf / referenceLit : 0.0;
  }
  bool predictsSelfShadowing() const { return selfShadowedAtLeast > 0.0; }
  bool withinBound() const {
    if (predictsSelfShadowing())
      return wronglyLit.shareAboveHalf <= bound && selfShadowed() >= selfShadowedAtLeast;
    return error.shareAboveHalf <= bound;
  }
  // A refusal is right only where expectedRefusals() declares it, with its message.
  bool refusedAsExpected() const {
    return kind == Kind::kRefused && !expectedRefusal.empty() &&
           note.find(expectedRefusal) != std::string::npos;
  }
};
// Renders the case with the technique; a GlError propagates (it is a failure).
Outcome evaluate(const Case& c, const Technique& t);

// The report's table: every case x every technique (runs them all, ~30 s on two cores).
std::string summaryHtml(bool progress);

}  // namespace sl::figures::stability
