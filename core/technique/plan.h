// core/technique/plan.h — the pass planner: for a scene, a technique and its parameters, which
// passes, objects and resources a frame needs, and what can be left out and why.
//
// Pure computation on the scene's data (no GL): techniques may consult it cheaply, e.g.
// legacy.hw and modern.hw skip the light pass when no caster reaches the light frustum.
#pragma once

#include <string>
#include <vector>

#include "core/technique/technique.h"

namespace sl {

struct PlanItem {
  std::string name;
  bool kept = true;
  std::string reason;
};

struct FramePlan {
  std::string technique;
  std::string scene;
  std::vector<PlanItem> passes;        // shadow passes and the camera pass
  std::vector<PlanItem> lightObjects;  // objects drawn in (or left out of) the light passes
  std::vector<PlanItem> resources;     // accumulation buffer, imaging stages, blur, mip chain
  bool shadowPassesNeeded = true;      // some caster reaches the light frustum (and a receiver)
  int castersInFrustum = 0;
  int receiversInFrustum = 0;
  float sceneConeDegrees = 0.0f;   // the light's cone (the square frustum's full angle)
  float fittedConeDegrees = 0.0f;  // the cone through the casters inside it
  DepthRange sceneRange;           // lightDepthRange(scene): what the techniques use
  DepthRange fittedRange;          // casters (near) and receivers + casters (far) inside
  // Shadow-map texels one camera pixel covers (GL's rho, the larger footprint axis), 95th
  // percentile over camera-facing receiver points inside both frusta: > 1 means the view
  // minifies (silhouettes, where rho grows without bound, are the excluded 5%).
  double maxShadowTexelsPerPixel = 0.0;
};

FramePlan planFrame(const Scene& scene, const Technique& technique, const RenderParams& params);

// The cheap test techniques consult: does any caster have a triangle inside the light's
// frustum (lateral planes and in front of the light)? Conservative: true when unsure.
bool casterReachesLightFrustum(const Scene& scene);

// Human-readable plan: kept and left-out items with their reasons.
std::string formatPlan(const FramePlan& plan);

}  // namespace sl
