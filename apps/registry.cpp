#include "apps/registry.h"

#include "core/errors.h"
#include "imaging/imaging.h"
#include "legacy_gl/legacy.h"
#include "modern/modern.h"
#ifdef SHADOWLAB_HAVE_REFERENCE
#include "reference/reference.h"
#endif

namespace sl {

const std::vector<Technique>& allTechniques() {
  static const std::vector<Technique> kAll = [] {
    std::vector<Technique> all = legacy::techniques();
    for (Technique& t : modern::techniques()) all.push_back(std::move(t));
#ifdef SHADOWLAB_HAVE_REFERENCE
    for (Technique& t : reference::techniques()) all.push_back(std::move(t));
#endif
    return all;
  }();
  return kAll;
}

const Technique& findTechnique(const std::string& name) {
  for (const Technique& t : allTechniques())
    if (t.name == name) return t;
  std::string known;
  for (const Technique& t : allTechniques()) known += (known.empty() ? "" : ", ") + t.name;
  throw InputError("unknown technique '" + name + "' (known: " + known + ")");
}

namespace {
std::unique_ptr<GlContext> contextForRender(const Technique& technique,
                                            const RenderParams& params) {
  checkParams(technique, params, 0);
  auto context = GlContext::create(contextFor(technique, params));
  checkParams(technique, params, context->caps().maxTextureSize);
  if (technique.needs.profile == Profile::kCompatibility) imaging::install(*context);
  return context;
}
}  // namespace

void checkRenderable(const Technique& technique, const RenderParams& params) {
  contextForRender(technique, params);
}

Frame renderTechnique(const Technique& technique, const Scene& scene, const RenderParams& params) {
  auto context = contextForRender(technique, params);
  return technique.render(*context, scene, params);
}

SteadyTiming timeTechnique(const Technique& technique, const Scene& scene,
                           const RenderParams& params, const FrameCounts& counts, Frame* last) {
  auto context = contextForRender(technique, params);
  return timeSteadyState([&] { return technique.render(*context, scene, params); }, counts, last);
}

}  // namespace sl
