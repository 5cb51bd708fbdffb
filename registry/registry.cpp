#include "registry/registry.h"

#include <optional>

#include "core/base/errors.h"
#include "core/gl/gl_trace.h"
#include "imaging/imaging.h"
#include "legacy_gl/legacy.h"
#include "modern/modern.h"
#ifdef SHADOWLAB_HAVE_REFERENCE
#include "reference/reference.h"
#endif

namespace sl {

const std::vector<Technique>& allTechniques() {
  static const std::vector<Technique> kAll = [] {
    std::vector<Technique> all;
    // The family is the module that declares the technique (Technique::family).
    const auto add = [&all](std::vector<Technique> declared, TechniqueFamily family) {
      for (Technique& t : declared) {
        t.family = family;
        all.push_back(std::move(t));
      }
    };
    add(legacy::techniques(), TechniqueFamily::kLegacy);
    add(modern::techniques(), TechniqueFamily::kModern);
#ifdef SHADOWLAB_HAVE_REFERENCE
    add(reference::techniques(), TechniqueFamily::kReference);
#endif
    return all;
  }();
  return kAll;
}

const Technique* techniqueNamed(const std::string& name) {
  for (const Technique& t : allTechniques())
    if (t.name == name) return &t;
  return nullptr;
}

const Technique& findTechnique(const std::string& name) {
  if (const Technique* t = techniqueNamed(name)) return *t;
  std::string known;
  for (const Technique& t : allTechniques()) known += (known.empty() ? "" : ", ") + t.name;
  throw InputError("unknown technique '" + name + "' (known: " + known + ")");
}

namespace {
// What a technique that does not read the option is not doing, for the message.
std::string doesNot(CommonOption o) {
  switch (o) {
    case CommonOption::kShadowMap: return "renders no shadow map";
    case CommonOption::kFilter: return "does not filter";
    case CommonOption::kPrecision: return "encodes no depth in colour";
    case CommonOption::kImaging: return "draws nothing through the OpenGL 1.2 imaging subset";
  }
  return "ignores " + std::string(optionFlag(o));
}

std::string techniquesThatRead(CommonOption o) {
  std::string list;
  for (const Technique& t : allTechniques())
    if (readsOption(t, o)) list += (list.empty() ? "" : ", ") + t.name;
  return list.empty() ? "none" : list;
}
}  // namespace

void rejectIgnoredOptions(const Technique& technique, const std::vector<CommonOption>& given) {
  for (CommonOption o : given)
    if (!readsOption(technique, o))
      throw InputError(technique.name + " " + doesNot(o) + ": " + optionFlag(o) +
                       " has no effect on it (techniques that read " + optionFlag(o) + ": " +
                       techniquesThatRead(o) + ")");
}

std::vector<std::string> checkOptionsOfPair(const Technique& a, const Technique& b,
                                            const std::vector<CommonOption>& given) {
  std::vector<std::string> warnings;
  for (CommonOption o : given) {
    const bool readA = readsOption(a, o), readB = readsOption(b, o);
    if (!readA && !readB)
      throw InputError("neither " + a.name + " nor " + b.name + " reads " + optionFlag(o) +
                       ": it has no effect on them (techniques that read " + optionFlag(o) + ": " +
                       techniquesThatRead(o) + ")");
    if (!readA || !readB) {
      const Technique& ignoring = readA ? b : a;
      warnings.push_back(ignoring.name + " " + doesNot(o) + ": " + optionFlag(o) + " applies to " +
                         (readA ? a : b).name + " only");
    }
  }
  return warnings;
}

namespace {
// Installs the imaging subset --imaging asks for on a legacy technique's context.
void installImaging(GlContext& context, ImagingChoice choice) {
  switch (choice) {
    case ImagingChoice::kBackendDefault: imaging::install(context); return;
    case ImagingChoice::kEmulated: imaging::install(context, imaging::Mode::kEmulated); return;
    case ImagingChoice::kNative:
      if (!context.caps().nativeImaging())
        throw InputError(std::string("--imaging native: the ") +
                         backendName(context.spec().backend) +
                         " back end has no native ARB_imaging (only --backend reference has "
                         "one); use --imaging emulated");
      imaging::install(context, imaging::Mode::kNative);
      return;
  }
}

std::unique_ptr<GlContext> contextForRender(const Technique& technique,
                                            const RenderParams& params) {
  checkParams(technique, params, 0);
  auto context = GlContext::create(contextFor(technique, params));
  checkParams(technique, params, context->caps().maxTextureSize);
  if (technique.needs.profile == Profile::kCompatibility) installImaging(*context, params.imaging);
  return context;
}
}  // namespace

std::unique_ptr<GlContext> makeRenderContext(const Technique& technique,
                                             const RenderParams& params) {
  return contextForRender(technique, params);
}

void checkRenderable(const Technique& technique, const RenderParams& params) {
  contextForRender(technique, params);
}

Frame renderTechnique(const Technique& technique, const Scene& scene, const RenderParams& params) {
  auto context = contextForRender(technique, params);
  if (!params.capturePasses) return technique.render(*context, scene, params);
  // --dump-passes: the GL state of every pass (core/gl/gl_trace.h), traced on top of the
  // context's table as the imaging subset left it, so the trace sees the technique's calls.
  GlTrace trace;
  return technique.render(*context, scene, params);
}

SteadyTiming timeTechnique(const Technique& technique, const Scene& scene,
                           const RenderParams& params, const FrameCounts& counts, Frame* last,
                           bool traceGl) {
  auto context = contextForRender(technique, params);
  std::optional<GlTrace> trace;
  if (traceGl) trace.emplace();
  return timeSteadyState([&] { return technique.render(*context, scene, params); }, counts, last);
}

std::vector<SteadyTiming> timeTechniquesInterleaved(const std::vector<TimingJob>& jobs, int warmup,
                                                    int rounds, std::vector<Frame>* lasts) {
  std::vector<std::unique_ptr<GlContext>> contexts;
  std::vector<std::function<Frame()>> sources;
  for (const TimingJob& job : jobs)
    contexts.push_back(contextForRender(*job.technique, job.params));
  for (size_t i = 0; i < jobs.size(); ++i)
    sources.push_back([&, i] {
      contexts[i]->makeCurrent();
      return jobs[i].technique->render(*contexts[i], *jobs[i].scene, jobs[i].params);
    });
  return timeInterleavedSteadyState(sources, warmup, rounds, lasts);
}

}  // namespace sl
