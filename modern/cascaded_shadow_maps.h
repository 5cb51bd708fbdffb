// modern/cascaded_shadow_maps.h — modern.cascades: parallel-split (cascaded) shadow maps, ours,
// after Zhang et al. 2006 (not in shared/papers). The split distances and the crops are public so
// that tests can check them without a GL context.
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <vector>

#include "core/technique/technique.h"

namespace sl::modern {

// The most cascades the camera pass (cascades.frag) samples.
constexpr int kMaxCascades = 4;

// The split distances C_0 = near < C_1 < ... < C_count = far along the camera's view axis:
// C_i = lambda C_log + (1 - lambda) C_uni with C_log = n (f / n)^(i / N) and
// C_uni = n + (f - n) i / N (ours, after Zhang et al. 2006). count + 1 values.
std::vector<float> cascadeSplitDistances(float nearPlane, float farPlane, int count, float lambda);

// The 8 world-space corners of the camera frustum between view depths nearDepth and farDepth
// (near quad first: lower left, lower right, upper right, upper left; then the far quad).
std::array<glm::vec3, 8> frustumSliceCorners(const Camera& camera, float aspect, float nearDepth,
                                             float farDepth);

// One cascade: its slice of the view frustum and the crop in the light's clip space that makes
// the slice fill the cascade's map.
struct CascadeCrop {
  float nearDepth = 0.0f;  // view depth, world units
  float farDepth = 0.0f;
  glm::vec2 centre{0.0f};    // the crop's centre in the light's NDC (x, y)
  glm::vec2 halfSize{1.0f};  // its half extent in the light's NDC
  glm::mat4 crop{1.0f};  // light clip -> cascade clip: [centre - half, centre + half] -> [-1, 1]
  glm::mat4 viewProjection{1.0f};  // crop * P_light * V_light
};

struct CascadeSettings {
  int count = 4;
  float lambda = 0.75f;
  bool stabilize = true;
  int texels = 512;  // side of each cascade's map
};

// The cascades of `scene` seen by its camera in a window of `aspect` (width / height).
std::vector<CascadeCrop> cascadeCrops(const Scene& scene, float aspect, const CascadeSettings& s);

Technique cascadedShadowMapTechnique();

}  // namespace sl::modern
