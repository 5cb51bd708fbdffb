#include "modern/volumes_bench.h"

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>

#include "core/errors.h"
#include "core/primitives.h"
#include "modern/modern.h"

namespace sl::modern {

namespace {
constexpr int kCubesPerSide = 5;  // per layer
constexpr int kLayers = 3;
constexpr float kCubeSide = 0.45f;  // world units
constexpr float kCubeSpacing = 1.1f;
constexpr float kLowestLayer = 1.2f;  // height of the first layer's centres
constexpr float kLayerStep = 0.8f;

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}
}  // namespace

Scene fillHeavyScene() {
  Scene s;
  s.name = "cubes";
  s.description = "three layers of floating cubes over a ground plane (after Chan Fig. 3-6)";
  Object ground;
  ground.name = "ground";
  ground.mesh = std::make_shared<const Mesh>(makePlane(14, 14, 4));
  ground.diffuse = glm::vec3(0.75f, 0.75f, 0.72f);
  ground.castsShadow = false;
  s.objects.push_back(ground);
  auto cube = std::make_shared<const Mesh>(makeBox(glm::vec3(kCubeSide)));
  for (int layer = 0; layer < kLayers; ++layer)
    for (int i = 0; i < kCubesPerSide; ++i)
      for (int j = 0; j < kCubesPerSide; ++j) {
        Object o;
        o.name =
            "cube " + std::to_string(layer) + "/" + std::to_string(i) + "/" + std::to_string(j);
        o.mesh = cube;
        const float half = 0.5f * (kCubesPerSide - 1) * kCubeSpacing;
        // Each layer shifted by a third of the spacing so that the columns interleave.
        const float shift = kCubeSpacing * float(layer) / kLayers;
        const glm::vec3 at(i * kCubeSpacing - half + shift, kLowestLayer + layer * kLayerStep,
                           j * kCubeSpacing - half + shift);
        o.model = glm::rotate(glm::translate(glm::mat4(1), at), glm::radians(20.0f * layer + 10.0f),
                              glm::vec3(0.3f, 1, 0.2f));
        o.diffuse = glm::vec3(0.3f + 0.2f * layer, 0.5f, 0.8f - 0.2f * layer);
        s.objects.push_back(o);
      }
  s.camera.position = {0.5f, 5.0f, 7.0f};
  s.camera.target = {0, 0.8f, 0};
  s.camera.fovyDegrees = 50;
  s.camera.nearPlane = 0.3f;
  s.camera.farPlane = 40;
  s.light.position = {1.0f, 9.0f, -1.0f};
  s.light.target = {0, 0, 0};
  s.light.up = {0, 0, -1};
  s.light.coneDegrees = 75;
  return s;
}

std::vector<VolumesBenchRow> benchmarkShadowVolumes(const Scene& scene, const RenderParams& params,
                                                    const std::vector<std::string>& techniques,
                                                    int frames, int warmup) {
  if (frames < 1) throw InputError("benchmark needs at least one frame");
  std::vector<VolumesBenchRow> rows;
  const std::vector<Technique> all = modern::techniques();
  for (const std::string& name : techniques) {
    auto it =
        std::find_if(all.begin(), all.end(), [&](const Technique& t) { return t.name == name; });
    if (it == all.end()) throw InputError("unknown modern technique '" + name + "'");
    const Technique& t = *it;
    checkParams(t, params, 0);
    auto context = GlContext::create(contextFor(t, params));
    checkParams(t, params, context->caps().maxTextureSize);
    VolumesBenchRow row;
    row.technique = name;
    row.scene = scene.name;
    row.device = context->caps().renderer;
    row.width = params.width;
    row.height = params.height;
    row.shadowMapTexels = params.shadowMapTexels;
    row.frames = frames;
    std::vector<double> totals;
    std::map<std::string, std::vector<double>> passes;
    for (int i = 0; i < warmup + frames; ++i) {
      const Frame f = t.render(*context, scene, params);
      if (i < warmup) continue;
      totals.push_back(f.totalMilliseconds());
      for (const PassTime& p : f.passes) passes[p.name].push_back(p.milliseconds);
      row.counters = f.counters;
    }
    row.medianMs = median(totals);
    row.minMs = *std::min_element(totals.begin(), totals.end());
    for (auto& [pass, times] : passes) row.passMedianMs[pass] = median(times);
    rows.push_back(row);
  }
  return rows;
}

nlohmann::json toJson(const VolumesBenchRow& r) {
  return {{"technique", r.technique}, {"scene", r.scene},
          {"device", r.device},       {"width", r.width},
          {"height", r.height},       {"shadow_map", r.shadowMapTexels},
          {"frames", r.frames},       {"median_ms", r.medianMs},
          {"min_ms", r.minMs},        {"passes_median_ms", r.passMedianMs},
          {"counters", r.counters}};
}

}  // namespace sl::modern
