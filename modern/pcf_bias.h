// modern/pcf_bias.h — --param bias of the PCF family: how a lit receiver is kept from shadowing
// itself (acne) beyond each technique's own constant bias. GPU Gems PCF (modern.gems16,
// modern.gems4) takes all three methods in the camera pass (pcf_bias.glsl); the Brabec–Seidel
// PCF twins (modern.pcf, modern.fast-pcf) take the normal offset in the vertex stage
// (texgen.vert): their shadow test compares one ramp-encoded depth replicated over the packed
// channels (§3), which has no place for a per-sample receiver-plane depth.
//   constant       — the technique's own bias alone (the default: today's images);
//   receiver-plane — ours, after Isidoro 2006 and Dou et al. 2014: the screen derivatives of the
//                    map coordinate (u, v, depth) give the receiver plane's d(depth)/d(u, v), and
//                    each lookup compares the plane's depth at its own offset;
//   normal-offset  — ours, after Holbert 2011: the point moves along its surface normal by
//                    normal-offset-texels texel footprints at its distance from the light (times
//                    1 - N.L with normal-offset-by-angle) before it is projected into the light.
#pragma once

#include <string>
#include <vector>

#include "core/technique/technique.h"

namespace sl::modern::pcf_bias {

enum class Method {  // the value of pcf_bias.glsl's BIAS_METHOD
  kConstant = 0,
  kReceiverPlane = 1,
  kNormalOffset = 2,
};

struct Settings {
  Method method = Method::kConstant;
  float normalOffsetTexels = 0.0f;   // texel footprints (normal-offset only, else 0)
  bool normalOffsetByAngle = false;  // times 1 - N.L (normal-offset only)
};

// What a technique offers: bias=receiver-plane or not, and the default normal offset (texel
// footprints): the reach of its filter in texels, which the offset covers at any angle.
struct Offer {
  bool receiverPlane = false;
  double defaultNormalOffsetTexels = 1.0;
};

// The declarations.
ParamSpec methodParam(const Offer& offer);
ParamSpec normalOffsetTexelsParam(const Offer& offer);
ParamSpec normalOffsetByAngleParam();
std::vector<ParamSpec> params(const Offer& offer);

// The settings of a render. A normal-offset key given with another method, other than its
// default, is an InputError naming `technique` (it would be ignored).
Settings settings(const std::string& technique, const RenderParams& params, const Offer& offer);

// The width of a map texel's footprint as a fraction of its distance to the light:
// 2 tan(cone / 2) / size.
float footprintPerDistance(const Scene& scene, int shadowMapTexels);

}  // namespace sl::modern::pcf_bias
