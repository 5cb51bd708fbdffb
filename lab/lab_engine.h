// lab/lab_engine.h — what the lab's worker thread keeps between requests (loaded scenes, GL
// contexts, reference frames, each cache bounded) and how a job's outcome becomes an answer.
#pragma once

#include <glm/glm.hpp>
#include <list>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "core/base/errors.h"
#include "core/base/image.h"
#include "core/gl/context.h"
#include "core/scene/scene.h"
#include "core/technique/technique.h"
#include "lab/lab_request.h"
#include "lab/worker.h"
#include "registry/shadow_error.h"

namespace sl::lab {

// What only the worker thread touches: loaded scenes, GL contexts and reference frames.
class Engine {
 public:
  const Scene& scene(const std::string& name);

  // Renders on the technique's cached context (made as `shadowlab render` makes one).
  Frame render(const Technique& t, const Scene& scene, const RenderParams& p);

  void clear();

  struct Reference {
    ShadowTruth truth;  // the area metric's truth (registry/shadow_error.h, docs/error.md)
    double milliseconds = 0.0;
  };
  // reference.hard pixel=area (the pixel-integrated truth) for this scene, size and view.
  const Reference& reference(const Scene& scene, const RenderParams& p, bool& cached);

 private:
  static std::string formatVec(const glm::vec3& v);
  std::map<std::string, Scene> scenes_;
  std::list<std::pair<std::string, std::unique_ptr<GlContext>>> contexts_;
  std::list<std::pair<std::string, Reference>> references_;
};

// Runs `body` and turns its exceptions into answers: InputError 400, GlError and the rest 500.
template <typename Body>
JobResult guarded(Body body) {
  JobResult r;
  try {
    return body();
  } catch (const InputError& e) {
    r.httpStatus = 400;
    r.body = oneLine(e.what());
  } catch (const GlError& e) {
    r.httpStatus = 500;
    r.body = oneLine(std::string("GL: ") + e.what());
  } catch (const std::exception& e) {
    r.httpStatus = 500;
    r.body = oneLine(e.what());
  }
  r.contentType = "text/plain";
  return r;
}

// The answers of a frame (a PNG with the request's provenance) and of a JSON document.
JobResult pngResult(const Image& image, int bitDepth, const LabRequest& req);
JobResult jsonResult(const nlohmann::json& j);

}  // namespace sl::lab
