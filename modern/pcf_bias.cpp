// modern/pcf_bias.cpp — --param bias of the PCF family (modern/pcf_bias.h).
#include "modern/pcf_bias.h"

#include <cmath>
#include <glm/glm.hpp>

#include "core/base/errors.h"

namespace sl::modern::pcf_bias {

namespace {
constexpr const char* kConstant = "constant";
constexpr const char* kReceiverPlane = "receiver-plane";
constexpr const char* kNormalOffset = "normal-offset";
// Lifted k footprints f off a plane, a point lies k f / cos(a) in front of it along the light
// ray, while the plane's depth changes by f tan(a) per texel: k footprints cover a filter
// reaching k / sin(a) texels, at least k, at any angle a (each technique's default, Offer).
// Beyond 8 the point leaves thin casters altogether (peter-panning by construction).
constexpr double kMaxNormalOffsetTexels = 8.0;  // texel footprints along the normal
}  // namespace

ParamSpec methodParam(const Offer& offer) {
  std::vector<std::string> choices = {kConstant};
  if (offer.receiverPlane) choices.push_back(kReceiverPlane);
  choices.push_back(kNormalOffset);
  return choiceParam(
      "bias", kConstant, choices,
      std::string("what keeps a lit receiver from shadowing itself beyond the technique's own "
                  "constant bias: constant (that bias alone)") +
          (offer.receiverPlane
               ? ", receiver-plane (each lookup compares the receiver plane's depth at "
                 "its offset, from screen derivatives; ours, after Isidoro 2006, Dou "
                 "et al. 2014)"
               : "") +
          " or normal-offset (the point moves along its normal by normal-offset-texels; ours, "
          "after Holbert 2011)");
}

ParamSpec normalOffsetTexelsParam(const Offer& offer) {
  return numberParam("normal-offset-texels", offer.defaultNormalOffsetTexels, 0,
                     kMaxNormalOffsetTexels,
                     "bias=normal-offset: how far the lookup point moves along the surface "
                     "normal, in shadow-map texel footprints at its distance from the light");
}

ParamSpec normalOffsetByAngleParam() {
  return flagParam("normal-offset-by-angle", false,
                   "bias=normal-offset: scale the normal offset by 1 - N.L (none facing the "
                   "light, all of it edge-on)");
}

std::vector<ParamSpec> params(const Offer& offer) {
  return {methodParam(offer), normalOffsetTexelsParam(offer), normalOffsetByAngleParam()};
}

Settings settings(const std::string& technique, const RenderParams& params, const Offer& offer) {
  Settings s;
  const std::string method = params.text(methodParam(offer));
  if (method == kReceiverPlane) s.method = Method::kReceiverPlane;
  if (method == kNormalOffset) s.method = Method::kNormalOffset;
  // Their defaults are accepted with any method (a render takes every declared default).
  for (const ParamSpec& spec : {normalOffsetTexelsParam(offer), normalOffsetByAngleParam()}) {
    const auto given = params.extra.find(spec.key);
    if (s.method != Method::kNormalOffset && given != params.extra.end() &&
        !spec.isDefault(given->second))
      throw InputError(technique + ": --param " + spec.key + "=" + given->second +
                       " needs bias=" + kNormalOffset + " (bias=" + method + ")");
  }
  if (s.method == Method::kNormalOffset) {
    s.normalOffsetTexels = float(params.number(normalOffsetTexelsParam(offer)));
    s.normalOffsetByAngle = params.flag(normalOffsetByAngleParam());
  }
  return s;
}

float footprintPerDistance(const Scene& scene, int shadowMapTexels) {
  const float halfCone = glm::radians(scene.light.coneDegrees) * 0.5f;
  return 2.0f * std::tan(halfCone) / float(shadowMapTexels);
}

}  // namespace sl::modern::pcf_bias
