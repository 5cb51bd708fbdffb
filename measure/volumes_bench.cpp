#include "measure/volumes_bench.h"

#include <algorithm>
#include <filesystem>
#include <map>

#include "core/base/errors.h"
#include "core/base/image.h"
#include "core/base/output_files.h"
#include "core/scene/scene_library.h"
#include "core/technique/frame_timing.h"
#include "modern/modern.h"
#include "registry/registry.h"

namespace sl::modern {

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
    // The steady-state median (core/technique/frame_timing.h).
    Frame last;
    const SteadyTiming timing = timeSteadyState([&] { return t.render(*context, scene, params); },
                                                FrameCounts{warmup, frames}, &last);
    row.medianMs = timing.frameMs;
    row.minMs = timing.minimumFrameMs;
    for (const PassTime& p : timing.passes) row.passMedianMs[p.name] = p.milliseconds;
    row.counters = last.counters;
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

namespace fs = std::filesystem;

// docs/images: close-ups of the brabec sphere's shadow (hw 256^2, hybrid 256^2, volumes,
// smoothies) and the cubes and fill-bound scenes with their volume overdraw (Chan Fig. 3-9a)
// and the hybrid's classification (Fig. 3-5b).
// The three files are checked before rendering and renamed into place together at the end
// (core/base/output_files.h): all three or none.
void writeVolumesDocImages(const std::string& dir) {
  const std::string crops = "volumes-brabec-crops-hw256-hybrid256-volumes-smoothies.png";
  const std::string cubes = "volumes-cubes-image-overdraw-classification.png";
  const std::string fillBound = "volumes-fill-bound-image-overdraw-classification.png";
  OutputSet outputs;
  std::map<std::string, std::string> temporary;
  for (const std::string& file : {crops, cubes, fillBound})
    temporary[file] = outputs.addFile("--doc-images", (fs::path(dir) / file).string());
  constexpr int kWidth = 640, kHeight = 480, kCropX = 380, kCropTop = 190, kCropW = 160,
                kCropH = 90, kMagnify = 3;
  RenderParams p;
  p.width = kWidth;
  p.height = kHeight;
  p.shadowMapTexels = 256;
  std::vector<Image> cropped;
  for (const char* t : {"modern.hw", "modern.hybrid", "modern.volumes", "modern.smoothies"}) {
    const Frame f = renderTechnique(findTechnique(t), builtinScene("brabec"), p);
    cropped.push_back(magnifyNearest(
        crop(f.color, kCropX, kHeight - kCropTop - kCropH, kCropW, kCropH), kMagnify));
  }
  std::map<std::string, Image> images;
  images[crops] = sideBySide(cropped);
  p.shadowMapTexels = 1024;
  p.capturePasses = true;
  // A scene's image, its volume overdraw and the hybrid's classification, side by side.
  const auto imageOverdrawClassification = [&](const std::string& sceneName,
                                               const std::string& file) {
    const Scene scene = loadScene(sceneName);
    const Frame v = renderTechnique(findTechnique("modern.volumes"), scene, p);
    const Frame h = renderTechnique(findTechnique("modern.hybrid"), scene, p);
    std::vector<Image> panels = {v.color};
    for (const PassImage& i : v.intermediates)
      if (i.name == "3-volume-overdraw") panels.push_back(i.image);
    for (const PassImage& i : h.intermediates)
      if (i.name == "6-classification") panels.push_back(i.image);
    images[file] = sideBySide(panels);
  };
  imageOverdrawClassification("cubes", cubes);
  // fill-bound (Chan's setting).
  imageOverdrawClassification("fill-bound", fillBound);
  for (const auto& [file, image] : images) writePng(temporary.at(file), image);
  outputs.commit();
}

}  // namespace sl::modern
