// lab/lab_engine.cpp — the lab worker's caches (lab/lab_engine.h) and the answers of a job.
#include "lab/lab_engine.h"

#include <algorithm>

#include "core/base/metrics.h"
#include "core/base/provenance.h"
#include "core/scene/scene_library.h"
#include "registry/registry.h"
#ifdef SHADOWLAB_HAVE_REFERENCE
#include "reference/reference.h"
#endif

namespace sl::lab {
namespace {
using json = nlohmann::json;

constexpr int kCachedContexts = 4;    // GL contexts the worker keeps (one per technique/size)
constexpr int kCachedReferences = 8;  // reference frames (scene/size/light/camera)

std::string contextKey(const Technique& t, const RenderParams& p) {
  const ContextSpec spec = contextFor(t, p);
  return t.name + "|" + std::to_string(spec.width) + "x" + std::to_string(spec.height) + "|" +
         colorFormatName(spec.color) + "|" + std::to_string(int(p.imaging));
}

}  // namespace

const Scene& Engine::scene(const std::string& name) {
  auto it = scenes_.find(name);
  if (it == scenes_.end()) it = scenes_.emplace(name, loadScene(name)).first;
  return it->second;
}

Frame Engine::render(const Technique& t, const Scene& scene, const RenderParams& p) {
  const std::string key = contextKey(t, p);
  auto it = std::find_if(contexts_.begin(), contexts_.end(),
                         [&](const auto& c) { return c.first == key; });
  if (it == contexts_.end()) {
    checkParams(t, p, 0);
    contexts_.emplace_front(key, makeRenderContext(t, p));
    while (int(contexts_.size()) > kCachedContexts) contexts_.pop_back();
  } else {
    contexts_.splice(contexts_.begin(), contexts_, it);
  }
  GlContext& context = *contexts_.front().second;
  try {
    checkParams(t, p, context.caps().maxTextureSize);
    context.makeCurrent();
    Frame frame = t.render(context, scene, p);
    if (!frame.color.empty() && !allFinite(frame.color)) throw GlError("the image has NaN or Inf");
    if (!allFinite(frame.visibility)) throw GlError("the visibility mask has NaN or Inf");
    return frame;
  } catch (...) {
    contexts_.pop_front();  // a failed frame may leave GL state behind: a fresh context next
    throw;
  }
}

void Engine::clear() {
  contexts_.clear();
  references_.clear();
  scenes_.clear();
}

const Engine::Reference& Engine::reference(const Scene& scene, const RenderParams& p,
                                           bool& cached) {
  const auto& c = scene.camera;
  const auto& l = scene.light.position;
  const std::string key = scene.name + "|" + std::to_string(p.width) + "x" +
                          std::to_string(p.height) + "|" + formatVec(l) + "|" +
                          formatVec(c.position);
  auto it = std::find_if(references_.begin(), references_.end(),
                         [&](const auto& r) { return r.first == key; });
  cached = it != references_.end();
  if (cached) {
    references_.splice(references_.begin(), references_, it);
    return references_.front().second;
  }
#ifdef SHADOWLAB_HAVE_REFERENCE
  RenderParams rp;
  rp.width = p.width;
  rp.height = p.height;
  Reference r;
  r.truth = renderShadowTruth(scene, rp, ErrorMetric::kArea, false);
  r.milliseconds = r.truth.frame.totalMilliseconds();
  references_.emplace_front(key, std::move(r));
  while (int(references_.size()) > kCachedReferences) references_.pop_back();
  return references_.front().second;
#else
  throw GlError("this build has no ray-traced reference (Embree)");
#endif
}

std::string Engine::formatVec(const glm::vec3& v) {
  return formatNumber(v.x) + "," + formatNumber(v.y) + "," + formatNumber(v.z);
}

JobResult pngResult(const Image& image, int bitDepth, const LabRequest& req) {
  JobResult r;
  r.contentType = "image/png";
  r.body =
      encodePng(image, bitDepth,
                {req.command, req.parameters.dump(-1, ' ', true, json::error_handler_t::replace)});
  return r;
}

JobResult jsonResult(const json& j) {
  JobResult r;
  r.contentType = "application/json";
  r.body = j.dump(-1, ' ', false, json::error_handler_t::replace);
  return r;
}

}  // namespace sl::lab
