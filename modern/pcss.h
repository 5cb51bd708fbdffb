// modern/pcss.h — modern.pcss: percentage-closer soft shadows, ours, after Fernando 2005 (not in
// shared/papers). The tap patterns and the penumbra formula are public so that tests can check
// them without a GL context.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "core/technique/technique.h"

namespace sl::modern {

// Where the taps of the blocker search and of the filter lie, in units of the region's radius:
// Poisson-disk points inside the unit disk, or the centres of a square grid over [-1, 1]^2.
enum class PcssPattern { kPoisson, kGrid };
// `count` taps (a square number for kGrid); deterministic (the same on every platform).
std::vector<glm::vec2> pcssTaps(int count, PcssPattern pattern);

// Penumbra width w_p = (d_receiver - d_blocker) * w_light / d_blocker (ours, after Fernando 2005,
// not in shared/papers): similar triangles between a light of width w_light at depth 0 and a
// blocker edge at d_blocker, measured at d_receiver; depths are linear light depths (distance
// along the light's axis). 0 where the blocker is not in front of the receiver.
float pcssPenumbraWidth(float receiverDepth, float blockerDepth, float lightWidth);

Technique pcssTechnique();

}  // namespace sl::modern
