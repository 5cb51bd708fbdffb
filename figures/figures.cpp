// figures/figures.cpp — `shadowlab figures`: renders every entry of the figure list into one
// folder and writes report.html.
//
// Steps per figure:
//   1. resolvePanel      — the technique from the registry, the scene, the parameters; a panel
//                          whose technique, parameter or buffer does not exist is kept and
//                          reported as missing with the reason (never skipped silently)
//   2. renderPanel       — the frame, the close-ups (crop + nearest magnification + red frame);
//                          a panel whose time stands beside a paper's number is timed at
//                          steady state (timedSteadily, core/technique/frame_timing.h)
//   3. measurePanel      — error of the visibility mask against the figure's reference
//                          (reference.hard / reference.soft) when that exists
//   4. renderTwin        — legacy.X beside modern.X with the difference heat map of the masks
//   5. drawPlots         — gnuplot charts from computed data or the figure's own numbers
#include "figures/figures.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/base/errors.h"
#include "core/base/output_files.h"
#include "core/base/png_text.h"
#include "core/base/provenance.h"
#include "core/scene/scene_library.h"
#include "figures/course.h"
#include "figures/diagnostics.h"
#include "figures/disagreement.h"
#include "figures/figure_composite.h"
#include "figures/measured.h"
#include "figures/overrides.h"
#include "figures/plan.h"
#include "figures/plots.h"
#include "figures/report.h"
#include "measure/bench.h"
#include "measure/bench_report.h"
#include "measure/stability.h"
#include "registry/registry.h"
#include "registry/twins.h"
#include "teach/lesson.h"

namespace sl::figures {
namespace fs = std::filesystem;

namespace {

constexpr int kPlotWidth = 900;  // pixels of a gnuplot chart
constexpr int kPlotHeight = 560;
constexpr float kDiffFullScale = 1.0f;  // heat-map full scale: a whole visibility step
constexpr float kMissingRed = 0.55f;    // a missing panel's block in that PNG
// countDepthErrors's truth (its default: a point sample at each pixel centre's surface point)
// and witness (24-bit depth with polygon offset: no bias leak, no acne of its own).
constexpr const char* kDepthErrorTruth = "reference.hard";
constexpr const char* kDepthErrorWitness = "legacy.hw";
// The lessons of the main job (teach/lesson.h): small, so that ~21 lessons add about a minute.
constexpr int kLessonWidth = 320;
constexpr int kLessonHeight = 240;
constexpr int kLessonShadowMap = 256;

const Technique* lookup(const std::string& name) {
  for (const Technique& t : allTechniques())
    if (t.name == name) return &t;
  return nullptr;
}

std::string slug(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c)))
      out += char(std::tolower(static_cast<unsigned char>(c)));
    else if (!out.empty() && out.back() != '-')
      out += '-';
  }
  while (!out.empty() && out.back() == '-') out.pop_back();
  return out.substr(0, 48);
}

// Everything a panel's render depends on, so that equal renders are made once.
struct Setup {
  std::string sceneName;
  int width = 0, height = 0, texels = 0, filter = 2;
  std::map<std::string, std::string> params;
  std::optional<float> lightRadius;
  std::optional<glm::vec3> lightPosition;
  std::optional<Precision> precision;
  float cameraDistance = 1;
  // The scene knobs (core/scene/scene.h adjustScene) and their part of the keys.
  SceneAdjustments adjustments() const {
    SceneAdjustments a;
    if (cameraDistance != 1.0f) a.cameraDistance = cameraDistance;
    a.lightRadius = lightRadius;
    a.lightPosition = lightPosition;
    return a;
  }
  std::string sceneKey() const {
    std::ostringstream s;
    s << sceneName << "|" << (lightRadius ? *lightRadius : -1.0f) << "|" << cameraDistance;
    if (lightPosition)
      s << "|" << lightPosition->x << "," << lightPosition->y << "," << lightPosition->z;
    return s.str();
  }
  std::string key() const {
    std::ostringstream s;
    s << sceneKey() << "|" << width << "x" << height << "|" << texels << "|" << filter << "|"
      << (precision ? precisionName(*precision) : "default");
    for (const auto& [k, v] : params) s << "|" << k << "=" << v;
    return s.str();
  }
};

Setup setupFor(const FigureSpec& fig, const PanelSpec& p) {
  Setup s;
  s.sceneName = p.scene.empty() ? fig.scene : p.scene;
  s.width = p.width ? p.width : fig.width;
  s.height = p.height ? p.height : fig.height;
  s.texels = p.shadowMapTexels ? p.shadowMapTexels : fig.shadowMapTexels;
  s.filter = p.filter ? p.filter : RenderParams{}.filter;
  s.params = p.params;
  s.lightRadius = p.lightRadius;
  s.lightPosition = p.lightPosition;
  s.precision = p.precision;
  s.cameraDistance = p.cameraDistance;
  return s;
}

// A panel whose time is set beside a paper's number is timed as the
// benches time a technique (core/technique/frame_timing.h: warm-up frames on one context, then the
// median of timed frames), and all such panels of a figure (with their twins) are measured
// interleaved: every context warmed up, then kFigureRounds rounds of one frame of each, so
// that machine load during the figure hits every cell alike. No cell is a median of one frame.
constexpr int kFigureWarmupFrames = kQuickWarmupFrames;
constexpr int kFigureRounds = 3;  // a figure's default (FigureSpec::timingRounds)

int roundsOf(const FigureSpec& fig) {
  return fig.timingRounds > 0 ? fig.timingRounds : kFigureRounds;
}
// Contexts alive at once in one interleaved group (each holds its window's buffers: a 1024x768
// context ~20 MB with Mesa's depth/stencil; a figure of more timed renders is measured in
// groups of this many, grouped by shadow-map size), unless the figure asks for all of them in
// one group (FigureSpec::interleaveAllTimed, CSM Table 1: its 40 cells).
constexpr size_t kInterleavedGroup = 10;

size_t interleavedGroupOf(const FigureSpec& fig, size_t jobs) {
  return fig.interleaveAllTimed ? std::max<size_t>(jobs, 1) : kInterleavedGroup;
}
// Charts whose axis is our frame time: every render panel of their figure is timed steadily.
const std::vector<std::string> kTimeCharts = {"error-vs-time", "chan-3-11"};

// Whether a render panel's time stands beside a paper's number (the panel's or the figure's
// paperNumbers) or on a chart of times; the other panels are rendered once (their time, shown
// as a first frame, is not comparable with anything).
bool timedSteadily(const FigureSpec& fig, const PanelSpec& p) {
  if (p.kind != PanelKind::kRender) return false;
  if (!fig.paperNumbers.empty()) return true;
  for (const PanelSpec& q : fig.panels) {
    if (!q.paperNumbers.empty() && q.kind == PanelKind::kRender) return true;
    if (q.kind == PanelKind::kPlot &&
        std::find(kTimeCharts.begin(), kTimeCharts.end(), q.plot) != kTimeCharts.end())
      return true;
  }
  return false;
}

class Renderer {
 public:
  explicit Renderer(std::string outDir) : outDir_(std::move(outDir)) {}

  const Scene& scene(const Setup& s) {
    const std::string key = s.sceneKey();
    auto it = scenes_.find(key);
    if (it != scenes_.end()) return it->second;
    Scene scene = loadScene(s.sceneName);
    adjustScene(scene, s.adjustments());  // as `render --camera-distance/--light-*` does
    return scenes_.emplace(key, std::move(scene)).first->second;
  }

  RenderParams params(const Setup& s, bool capture) const {
    RenderParams p;
    p.width = s.width;
    p.height = s.height;
    p.shadowMapTexels = s.texels;
    p.filter = s.filter;
    if (s.precision) p.precision = *s.precision;
    p.extra = s.params;
    p.capturePasses = capture;
    return p;
  }

  // Renders (or reuses) a frame. Intermediates are only kept when asked for.
  std::shared_ptr<const Frame> frame(const Technique& t, const Setup& s, bool capture) {
    const std::string key = t.name + "|" + s.key() + (capture ? "|capture" : "");
    auto it = frames_.find(key);
    if (it != frames_.end()) return it->second;
    return frames_[key] = checked(t, renderTechnique(t, scene(s), params(s, capture)));
  }

  // A frame whose time is set beside a paper's number: the steady-state median on one context
  // (core/technique/frame_timing.h, kFigureFrames); the frame kept is the last timed one, and it
  // also serves later plain requests for the same render.
  struct Timed {
    std::shared_ptr<const Frame> frame;
    SteadyTiming timing;
  };
  Timed steadyFrame(const Technique& t, const Setup& s, int rounds) {
    const std::string key = t.name + "|" + s.key();
    auto it = timed_.find(key);
    if (it != timed_.end()) return it->second;
    Frame last;
    const FrameCounts counts{kFigureWarmupFrames, rounds};
    const SteadyTiming timing = timeTechnique(t, scene(s), params(s, false), counts, &last);
    Timed timed{checked(t, std::move(last)), timing};
    frames_[key] = timed.frame;
    return timed_[key] = timed;
  }

  // The timed renders of one figure (its render panels whose time stands beside a paper's
  // number, and their twins), measured interleaved before the panels are made; steadyFrame
  // then finds them. A group that fails (a technique refusing its parameters) is left to
  // steadyFrame, which reports the failing panel alone.
  void timeInterleaved(const std::vector<std::pair<const Technique*, Setup>>& jobs, int rounds,
                       size_t groupSize) {
    std::vector<size_t> todo;
    std::set<std::string> keys;
    for (size_t i = 0; i < jobs.size(); ++i) {
      const std::string key = jobs[i].first->name + "|" + jobs[i].second.key();
      if (!timed_.count(key) && keys.insert(key).second) todo.push_back(i);
    }
    std::stable_sort(todo.begin(), todo.end(), [&](size_t a, size_t b) {
      return jobs[a].second.texels < jobs[b].second.texels;
    });
    for (size_t start = 0; start < todo.size(); start += groupSize) {
      const std::vector<size_t> group(
          todo.begin() + long(start),
          todo.begin() + long(std::min(todo.size(), start + groupSize)));
      try {
        std::vector<TimingJob> timing;
        for (size_t i : group)
          timing.push_back({jobs[i].first, &scene(jobs[i].second), params(jobs[i].second, false)});
        std::vector<Frame> lasts;
        const std::vector<SteadyTiming> timings =
            timeTechniquesInterleaved(timing, kFigureWarmupFrames, rounds, &lasts);
        for (size_t k = 0; k < group.size(); ++k) {
          const Technique& t = *jobs[group[k]].first;
          const std::string key = t.name + "|" + jobs[group[k]].second.key();
          Timed timed{checked(t, std::move(lasts[k])), timings[k]};
          frames_[key] = timed.frame;
          timed_[key] = timed;
        }
      } catch (const std::exception&) {
        // steadyFrame measures each of the group alone and reports the one that fails.
      }
    }
  }

  const DiagnosticViews& diagnostics(const Setup& s) {
    const std::string key = s.key();
    auto it = diagnostics_.find(key);
    if (it != diagnostics_.end()) return it->second;
    return diagnostics_
        .emplace(key, renderDiagnostics(scene(s), s.width, s.height, s.texels, s.height))
        .first->second;
  }

  // Frames are large (a 1024x768 frame is ~12 MB): keep them for one figure only.
  void forgetFrames() {
    frames_.clear();
    timed_.clear();
  }

  // `parameters`: what made the image (its shadowlab:parameters tEXt, as render's PNGs carry).
  std::string write(const std::string& figureId, const std::string& name, const Image& image,
                    const nlohmann::json& parameters, int bitDepth = 8) {
    const std::string rel = figureId + "/" + name + ".png";
    writePng(
        (fs::path(outDir_) / rel).string(), image, bitDepth,
        {commandLine(), parameters.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace)});
    return rel;
  }
  const std::string& outDir() const { return outDir_; }

 private:
  static std::shared_ptr<const Frame> checked(const Technique& t, Frame frame) {
    if (!frame.color.empty() && !allFinite(frame.color))
      throw GlError(t.name + " produced NaN or Inf");
    if (!allFinite(frame.visibility)) throw GlError(t.name + " produced a NaN or Inf visibility");
    return std::make_shared<const Frame>(std::move(frame));
  }

  std::string outDir_;
  std::map<std::string, Scene> scenes_;
  std::map<std::string, std::shared_ptr<const Frame>> frames_;
  std::map<std::string, Timed> timed_;
  std::map<std::string, DiagnosticViews> diagnostics_;
};

// Step 1: why a panel cannot be made now, or "" when it can.
std::string missingReason(const PanelSpec& p) {
  if (p.kind != PanelKind::kRender && p.kind != PanelKind::kIntermediates) return "";
  const Technique* t = lookup(p.technique);
  if (t == nullptr) return "technique " + p.technique + " is not available yet";
  for (const auto& [key, value] : p.params)
    if (!findParam(*t, key))
      return p.technique + " has no parameter '" + key + "' (needed: " + key + "=" + value + ")";
  for (const std::string& name : p.errorsOf)
    if (lookup(name) == nullptr) return "technique " + name + " is not available yet";
  return "";
}

std::vector<std::pair<Image, std::string>> splitIntermediate(const PassImage& pass) {
  std::vector<std::pair<Image, std::string>> out;
  const std::string caption = pass.caption.empty() ? pass.name : pass.caption;
  if (pass.image.channels == 4) {
    // Brabec–Seidel pack four values into R, G, B, A: show each channel on its own.
    const char* names[] = {"R", "G", "B", "A"};
    for (int c = 0; c < 4; ++c) out.push_back({channel(pass.image, c), caption + " — " + names[c]});
  } else {
    out.push_back({pass.image, caption});
  }
  return out;
}

Image closeupOf(const Image& image, const Closeup& c) {
  const int x = std::clamp(int(c.x * image.width), 0, image.width - 1);
  const int y = std::clamp(int(c.y * image.height), 0, image.height - 1);
  const int w = std::clamp(int(c.w * image.width), 1, image.width - x);
  const int h = std::clamp(int(c.h * image.height), 1, image.height - y);
  return magnifyNearest(toRgb(crop(image, x, y, w, h)), c.magnify);
}

Image framed(const Image& image, const std::vector<Closeup>& closeups) {
  Image rgb = toRgb(image);
  for (const Closeup& c : closeups) {
    const int x = std::clamp(int(c.x * rgb.width), 0, rgb.width - 1);
    const int y = std::clamp(int(c.y * rgb.height), 0, rgb.height - 1);
    drawFrame(rgb, x, y, std::clamp(int(c.w * rgb.width), 1, rgb.width - x),
              std::clamp(int(c.h * rgb.height), 1, rgb.height - y), 2);
  }
  return rgb;
}

// The other side of a legacy/modern twin pair (registry/twins.h), "" for a technique without.
std::string twinName(const std::string& name) {
  for (const twins::TwinPair& p : twins::twinPairs()) {
    if (p.legacy == name) return p.modern;
    if (p.modern == name) return p.legacy;
  }
  return "";
}

// The renders of a figure whose times are set beside a paper's number (timedSteadily), with the
// legacy/modern twins makePanel times beside them.
std::vector<std::pair<const Technique*, Setup>> timedRenders(const FigureSpec& fig) {
  std::vector<std::pair<const Technique*, Setup>> jobs;
  for (const PanelSpec& p : fig.panels) {
    if (!timedSteadily(fig, p) || !missingReason(p).empty()) continue;
    const Setup setup = setupFor(fig, p);
    const Technique* t = lookup(p.technique);
    jobs.push_back({t, setup});
    const Technique* twin = fig.twins && !fig.table ? lookup(twinName(t->name)) : nullptr;
    PanelSpec tp = p;
    if (twin != nullptr) tp.technique = twin->name;
    if (twin != nullptr && missingReason(tp).empty()) jobs.push_back({twin, setup});
  }
  return jobs;
}

// Step 3's detail: the error near the reference's edges and the light leaking in its umbra, as
// the bench measures them (registry/shadow_error.h, over the scored pixels).
ErrorDetail errorDetailOf(const Image& mask, const ShadowTruth& truth) {
  const Image& reference = truth.visibility;
  const Image& band = truth.band;
  const ShadowError e = scoreShadow(mask, truth);
  ErrorDetail d;
  d.bandRmse = e.band.rmse;
  d.bandPixels = e.band.pixels;
  d.leakShare = e.leakShare;
  const Image wide = boundaryBand(reference, kDeepUmbraPixels);
  double deepSum = 0;
  long long deepLit = 0;
  for (int y = 0; y < reference.height; ++y)
    for (int x = 0; x < reference.width; ++x) {
      if (reference.at(x, y) != 0.0f || truth.scored.at(x, y) <= 0.5f) continue;
      d.umbraPixels += band.at(x, y) <= 0.5f ? 1 : 0;
      if (wide.at(x, y) > 0.5f) continue;
      ++d.deepUmbraPixels;
      deepSum += mask.at(x, y);
      deepLit += mask.at(x, y) > kDeepLeakThreshold ? 1 : 0;
    }
  if (d.deepUmbraPixels > 0) {
    d.deepUmbraMean = deepSum / double(d.deepUmbraPixels);
    d.deepLeakShare = double(deepLit) / double(d.deepUmbraPixels);
  }
  return d;
}

// Step 3 for Brabec Fig. 8 (PanelSpec::countDepthErrors): the depth bias's leak and acne in
// pixels, as docs/figures.md's table of the trade and
// BrabecSeidel.TeapotContactLeakIsTheEightBitDepthBias count them: the leak where the ray
// tracer and 24-bit legacy.hw both put the pixel in shadow (so that the shadow map's own edge
// aliasing, which legacy.hw shares with the panel, is not counted), acne where the ray tracer
// puts it in light.
void countDepthErrors(Renderer& r, const Technique& t, const Setup& setup, const Frame& f,
                      std::map<std::string, double>* counters) {
  const Technique* truth = lookup(kDepthErrorTruth);
  const Technique* witness = lookup(kDepthErrorWitness);
  if (truth == nullptr || witness == nullptr || witness->name == t.name) return;
  Setup plain = setup;  // the panel's scene, size and map; its technique's own parameters off
  plain.params.clear();
  plain.precision.reset();
  plain.filter = RenderParams{}.filter;
  const Image& ref = r.frame(*truth, plain, false)->visibility;
  const Image& hw = r.frame(*witness, plain, false)->visibility;
  constexpr float kLit = 0.5f;  // visibility above: lit (the masks are 0/1 but at edges)
  long long leak = 0, acne = 0;
  for (int y = 0; y < ref.height; ++y)
    for (int x = 0; x < ref.width; ++x) {
      const bool lit = f.visibility.at(x, y) > kLit;
      const bool refLit = ref.at(x, y) > kLit, hwLit = hw.at(x, y) > kLit;
      leak += lit && !refLit && !hwLit ? 1 : 0;
      acne += !lit && refLit ? 1 : 0;
    }
  (*counters)[kLeakPixelsCounter] = double(leak);
  (*counters)[kAcnePixelsCounter] = double(acne);
}

// What made a panel's images (their PNG provenance): the figure, the panel, and the setup it
// was rendered with; the common options null where the panel's technique does not read them.
nlohmann::json panelParameters(const FigureSpec& fig, const PanelSpec& p, const Setup& s) {
  using Json = nlohmann::json;
  const Technique* t = p.technique.empty() ? nullptr : lookup(p.technique);
  auto reads = [&](CommonOption o) { return t == nullptr || readsOption(*t, o); };
  Json out = {{"figure", fig.id},
              {"panel", p.label},
              {"technique", p.technique.empty() ? Json(nullptr) : Json(p.technique)},
              {"scene", s.sceneName},
              {"size", std::to_string(s.width) + "x" + std::to_string(s.height)},
              {"shadow_map", reads(CommonOption::kShadowMap) ? Json(s.texels) : Json(nullptr)},
              {"filter", reads(CommonOption::kFilter) ? Json(s.filter) : Json(nullptr)},
              {"precision", reads(CommonOption::kPrecision) && s.precision
                                ? Json(precisionName(*s.precision))
                                : Json(nullptr)},
              {"params", s.params},
              {"camera_distance", s.cameraDistance}};
  if (s.lightRadius) out["light_radius"] = *s.lightRadius;
  if (s.lightPosition)
    out["light_position"] = {s.lightPosition->x, s.lightPosition->y, s.lightPosition->z};
  if (!p.overridden.empty()) out["set"] = p.overridden;
  return out;
}

// Steps 2-4 for one panel.
PanelResult makePanel(Renderer& r, const FigureSpec& fig, const PanelSpec& p, int index) {
  PanelResult out;
  out.spec = p;
  const std::string base =
      (index < 10 ? "0" : "") + std::to_string(index) + "-" + slug(p.label) + fig.fileSuffix;
  const Setup setup = setupFor(fig, p);
  if (std::string why = missingReason(p); !why.empty()) {
    out.reason = why;
    return out;
  }
  const std::vector<Closeup>& closeups = p.ownCloseups.empty() ? fig.closeups : p.ownCloseups;
  // `name` tells a buffer panel's images apart ("" for a panel's one image).
  auto addImage = [&](const Image& image, const std::string& caption, bool withCloseups,
                      const std::string& name = "") {
    const bool close = withCloseups && p.closeups && !closeups.empty();
    const std::string file = base + name;
    nlohmann::json made = panelParameters(fig, p, setup);
    made["image"] = caption;
    out.images.push_back(
        {r.write(fig.id, file, close ? framed(image, closeups) : image, made), caption});
    if (!close) return;
    for (size_t i = 0; i < closeups.size(); ++i)
      out.closeups.push_back({r.write(fig.id, file + "-closeup" + std::to_string(i),
                                      closeupOf(image, closeups[i]), made),
                              caption + " magnified " + std::to_string(closeups[i].magnify) + "x"});
  };
  try {
    switch (p.kind) {
      case PanelKind::kRender: {
        const Technique& t = *lookup(p.technique);
        const bool steady = timedSteadily(fig, p);
        std::shared_ptr<const Frame> f;
        if (steady) {
          const Renderer::Timed timed = r.steadyFrame(t, setup, roundsOf(fig));
          f = timed.frame;
          out.milliseconds = timed.timing.frameMs;
          out.passes = timed.timing.passes;
          out.warmupFrames = timed.timing.warmupFrames;
          out.timedFrames = timed.timing.timedFrames;
          out.frameSamples = timed.timing.frameSamples;
        } else {
          f = r.frame(t, setup, false);
          out.milliseconds = f->totalMilliseconds();
          out.passes = f->passes;
        }
        out.counters = f->counters;
        Image shown = p.mask ? f->visibility : f->color;
        if (!p.errorsOf.empty()) {  // the pixels other techniques get wrong (Chan Fig. 3-7)
          // Each compared technique as the figure's panel of it on this scene shows it (its
          // parameters and map, --set included), or with this panel's setup when none does.
          auto compared = [&](const std::string& name) {
            Setup s = setup;
            for (const PanelSpec& q : fig.panels)
              if (q.kind == PanelKind::kRender && q.technique == name && q.errorsOf.empty() &&
                  setupFor(fig, q).sceneKey() == setup.sceneKey()) {
                s = setupFor(fig, q);
                break;
              }
            return r.frame(*lookup(name), s, false);
          };
          const auto first = compared(p.errorsOf[0]);
          const auto second = p.errorsOf.size() > 1 ? compared(p.errorsOf[1]) : nullptr;
          // Only the scored pixels of the one error definition count (docs/error.md): the
          // categories of reference.hard's pixel centres for this scene and size.
          Image scored;
          if (const Technique* hard = lookup("reference.hard")) {
            Setup refSetup = setup;
            refSetup.params.clear();
            refSetup.texels = fig.shadowMapTexels;
            refSetup.filter = RenderParams{}.filter;
            scored = truthFromReferenceFrame(*r.frame(*hard, refSetup, true), ErrorMetric::kPoint,
                                             false, truthName(false, ErrorMetric::kPoint))
                         .scored;
          }
          const Disagreement d = disagreementOverlay(f->color, f->visibility, first->visibility,
                                                     second ? second->visibility : Image(), scored);
          shown = d.overlay;
          out.counters[kWrongPixelsCounter + p.errorsOf[0]] = double(d.firstWrong);
          if (second) {
            out.counters[kWrongPixelsCounter + p.errorsOf[1]] = double(d.secondWrong);
            out.counters[kBothWrongCounter] = double(d.bothWrong);
          }
        }
        if (!fig.table) addImage(shown, p.label, true);
        // Step 3: error against the reference (the panel's own, or the figure's).
        const std::string& referenceName = p.reference.empty() ? fig.reference : p.reference;
        if (referenceName.empty()) {
          out.errorNote = "not measured in this figure";
        } else if (const Technique* ref = lookup(referenceName); ref == nullptr) {
          out.errorNote = referenceName + " not available yet";
        } else if (ref->name != t.name) {
          // The pixel-integrated form of the reference (--param pixel=area), the truth of a
          // displayed pixel, as in the bench (measure/bench.h kPrimaryHardReference), with
          // kFigureReferencePixelSamplesPerSide^2 samples. The reference ignores the shadow
          // map and the footprint: one frame per scene and size.
          Setup refSetup = setup;
          refSetup.params.clear();
          refSetup.texels = fig.shadowMapTexels;
          refSetup.filter = RenderParams{}.filter;
          if (findParam(*ref, reference::kPixelParam)) {
            refSetup.params[reference::kPixelParam] = reference::kPixelArea;
            refSetup.params[reference::kPixelSamplesParam] =
                std::to_string(kFigureReferencePixelSamplesPerSide);
          }
          // With its passes: the pixel categories decide the scored pixels (docs/error.md).
          auto rf = r.frame(*ref, refSetup, true);
          const bool area = refSetup.params.count(reference::kPixelParam) > 0;
          const bool soft = ref->name == "reference.soft";
          const ShadowTruth truth = truthFromReferenceFrame(
              *rf, area ? ErrorMetric::kArea : ErrorMetric::kPoint, soft,
              truthName(soft, area ? ErrorMetric::kArea : ErrorMetric::kPoint));
          const ShadowError score = scoreShadow(f->visibility, truth, kWrongPixelThreshold);
          out.error = score.all;
          out.errorMetric =
              score.metric + " metric vs " + score.truth + "; " + describeLeftOut(score.counts);
          out.errorDetail = errorDetailOf(f->visibility, truth);
          // FigureSpec::bothMetrics: the point metric too, against the reference's default
          // pixel-centre form (docs/error.md "The two truths").
          if (fig.bothMetrics && area) {
            Setup pointSetup = refSetup;
            pointSetup.params[reference::kPixelParam] = reference::kPixelCentre;
            pointSetup.params.erase(reference::kPixelSamplesParam);
            auto pf = r.frame(*ref, pointSetup, true);
            const ShadowTruth pointTruth = truthFromReferenceFrame(
                *pf, ErrorMetric::kPoint, soft, truthName(soft, ErrorMetric::kPoint));
            const ShadowError pointScore =
                scoreShadow(f->visibility, pointTruth, kWrongPixelThreshold);
            out.pointError = pointScore.all;
            out.pointErrorMetric = pointScore.metric + " metric vs " + pointScore.truth + "; " +
                                   describeLeftOut(pointScore.counts);
          }
        }
        if (p.countDepthErrors) countDepthErrors(r, t, setup, *f, &out.counters);
        // Step 4: the legacy/modern twin.
        const Technique* twin = fig.twins && !fig.table ? lookup(twinName(t.name)) : nullptr;
        if (twin != nullptr) {
          PanelSpec tp = p;
          tp.technique = twin->name;
          if (missingReason(tp).empty()) {
            // Timed as the panel is, so that the two times compare.
            std::shared_ptr<const Frame> tf;
            TwinResult tr;
            if (steady) {
              const Renderer::Timed timed = r.steadyFrame(*twin, setup, roundsOf(fig));
              tf = timed.frame;
              tr.milliseconds = timed.timing.frameMs;
              tr.timedFrames = timed.timing.timedFrames;
            } else {
              tf = r.frame(*twin, setup, false);
              tr.milliseconds = tf->totalMilliseconds();
            }
            tr.technique = twin->name;
            nlohmann::json made = panelParameters(fig, tp, setup);
            made["image"] = "GLSL twin of " + p.technique;
            tr.file = r.write(fig.id, base + "-twin", tf->color, made);
            made["image"] = "visibility difference, " + p.technique + " against its twin";
            tr.diffFile =
                r.write(fig.id, base + "-twin-diff",
                        differenceHeatMap(f->visibility, tf->visibility, kDiffFullScale), made);
            tr.difference = compareMasks(f->visibility, tf->visibility, 0.0);
            tr.image = twins::judgeImages(f->color, tf->color, f->visibility, tf->visibility);
            made["image"] = "colour difference, " + p.technique + " against its twin";
            tr.imageDiffFile = r.write(fig.id, base + "-twin-image-diff",
                                       twins::colourDifferenceHeatMap(f->color, tf->color), made);
            out.twin = tr;
          }
        }
        break;
      }
      case PanelKind::kIntermediates: {
        const Technique& t = *lookup(p.technique);
        auto f = r.frame(t, setup, true);
        out.milliseconds = f->totalMilliseconds();
        out.passes = f->passes;
        out.counters = f->counters;
        int n = 0;
        for (const PassImage& pass : f->intermediates) {
          if (!p.intermediate.empty() && pass.name.find(p.intermediate) == std::string::npos)
            continue;
          for (auto& [image, caption] : splitIntermediate(pass))
            addImage(image, p.bufferCaption.empty() ? caption : p.bufferCaption, true,
                     "-" + std::to_string(n++));
        }
        if (out.images.empty()) {
          std::string names;
          for (const PassImage& pass : f->intermediates)
            names += (names.empty() ? "" : ", ") + pass.name;
          out.reason = p.technique + " gives no intermediate buffer named '*" + p.intermediate +
                       "*' (it gives: " + (names.empty() ? "none" : names) + ")";
          return out;
        }
        break;
      }
      case PanelKind::kLightView: addImage(r.diagnostics(setup).lightView, p.label, false); break;
      case PanelKind::kShadowMap: addImage(r.diagnostics(setup).shadowMap, p.label, false); break;
      case PanelKind::kLightDistance:
        addImage(r.diagnostics(setup).lightDistance, p.label, false);
        break;
      case PanelKind::kProjectedMap:
        addImage(r.diagnostics(setup).projectedMap, p.label, false);
        break;
      case PanelKind::kTexelDensity:
        addImage(r.diagnostics(setup).texelDensity, p.label, false);
        break;
      case PanelKind::kLightDensity:
        addImage(r.diagnostics(setup).lightDensity, p.label, false);
        break;
      case PanelKind::kPlot:
        return out;  // drawn in step 5, once the other panels have their numbers
    }
  } catch (const std::exception& e) {
    out.images.clear();
    out.closeups.clear();
    out.reason = std::string("failed: ") + e.what();
    return out;
  }
  out.ok = true;
  return out;
}

// What one panel contributes to figure.png: its images (a buffer panel gives every buffer it
// shows, a chart its chart) or, when it could not be made, one dark red block of its size; each
// under its label (`letter` is "(a) " when the figure's own labels carry no letters).
std::vector<LabelledTile> compositeTiles(const std::string& outDir, const FigureSpec& s,
                                         const PanelResult& p, const std::string& letter) {
  std::string label = letter + p.spec.label;
  // The technique after the label, unless the label names it already ("legacy.pcf (2001)").
  if (!p.spec.technique.empty() && p.spec.label.find(p.spec.technique) == std::string::npos)
    label += " \u2014 " + p.spec.technique;
  // A figure re-made with --set: the overrides that changed this panel, in its drawn label.
  if (!p.spec.overridden.empty()) {
    std::string set;
    for (const std::string& o : p.spec.overridden) set += (set.empty() ? "" : ", ") + o;
    label += " [--set " + set + "]";
  }
  std::vector<LabelledTile> tiles;
  if (p.ok) {
    const bool buffers = p.spec.kind == PanelKind::kIntermediates;
    for (const ImageFile& image : p.images)  // a buffer strip names its panel once
      tiles.push_back({readPng((fs::path(outDir) / image.file).string()),
                       !buffers        ? label
                       : tiles.empty() ? label + ": " + image.caption
                                       : image.caption});
    if (!tiles.empty()) return tiles;
  }
  Image missing(p.spec.width ? p.spec.width : s.width, p.spec.height ? p.spec.height : s.height, 3);
  for (size_t i = 0; i < missing.data.size(); i += 3) missing.data[i] = kMissingRed;
  tiles.push_back({std::move(missing), label + " \u2014 missing: " + p.reason});
  return tiles;
}

void writeComposite(Renderer& r, FigureResult& fig) {
  if (fig.spec.table) return;
  const Image composite = composeFigure(fig, r.outDir());
  if (!composite.empty())
    fig.composite =
        r.write(fig.spec.id, "figure" + fig.spec.fileSuffix, composite,
                {{"figure", fig.spec.id},
                 {"source_figure", fig.spec.sourceId.empty() ? fig.spec.id : fig.spec.sourceId},
                 {"set", fig.spec.overrides},
                 {"panels", fig.panels.size()}});
}

// A CSV field: quoted when it holds a comma, a quote or a line break (RFC 4180).
std::string csvField(const std::string& v) {
  if (v.find_first_of(",\"\n") == std::string::npos) return v;
  std::string out = "\"";
  for (char c : v) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// The figure's timed panels, every interleaved round of each (one row per round, in the order
// rendered), with the median and quartiles the report prints, into FIGURE/rounds.csv.
void writeRoundsCsv(Renderer& r, FigureResult& fig) {
  bool any = false;
  for (const PanelResult& p : fig.panels) any = any || (p.ok && !p.frameSamples.empty());
  if (!any) return;
  const std::string rel = fig.spec.id + "/rounds" + fig.spec.fileSuffix + ".csv";
  writeFileAtomically((fs::path(r.outDir()) / rel).string(), [&](std::ostream& out) {
    out << "panel,technique,scene,shadow_map,params,mip_maps,round,frame_ms,median_ms,q1_ms,"
           "q3_ms,paper\n";
    for (const PanelResult& p : fig.panels) {
      if (!p.ok || p.frameSamples.empty()) continue;
      const Setup s = setupFor(fig.spec, p.spec);
      std::string params;
      for (const auto& [k, v] : s.params) params += (params.empty() ? "" : ";") + k + "=" + v;
      const Quartiles q = quartilesOf(p.frameSamples);
      for (size_t round = 0; round < p.frameSamples.size(); ++round)
        out << csvField(p.spec.label) << "," << p.spec.technique << "," << s.sceneName << ","
            << s.texels << "," << csvField(params) << "," << csvField(mipmapUse(p.counters)) << ","
            << round + 1 << "," << p.frameSamples[round] << "," << p.milliseconds << "," << q.q1
            << "," << q.q3 << "," << csvField(p.spec.paperNumbers) << "\n";
    }
  });
  fig.roundsCsv = rel;
}

// Step 5: charts.
void drawPlot(Renderer& r, FigureResult& fig, PanelResult& plot) {
  std::string why;
  if (!gnuplotAvailable(&why)) {
    plot.reason = why;
    return;
  }
  const std::string rel = fig.spec.id + "/" + slug(plot.spec.plot) + fig.spec.fileSuffix + ".png";
  const std::string png = (fs::path(r.outDir()) / rel).string();
  const std::string& chart = plot.spec.plot;
  std::vector<const PanelResult*> rendered;
  for (const PanelResult& p : fig.panels)
    if (p.ok && p.spec.kind == PanelKind::kRender) rendered.push_back(&p);
  try {
    if (chart == "csm-reconstruction") {
      plotLines(csmFigure3Charts(), 2, png, kPlotWidth, kPlotWidth * 3 / 4);
    } else if (chart == "error-vs-time") {
      // One group per registry shadow group (core/technique/technique.h shadowGroup), in the
      // order the figure lists its panels; each group's reference named in the key.
      std::vector<PointGroup> groups;
      for (const PanelResult* p : rendered) {
        const Technique* t = lookup(p->spec.technique);
        if (!p->error || t == nullptr) continue;
        const std::string reference =
            p->spec.reference.empty() ? fig.spec.reference : p->spec.reference;
        const std::string title = std::string(shadowGroup(*t)) + " (vs " + reference + ")";
        auto g = std::find_if(groups.begin(), groups.end(),
                              [&](const PointGroup& x) { return x.title == title; });
        if (g == groups.end()) g = groups.insert(groups.end(), PointGroup{title, {}});
        g->points.push_back({p->milliseconds, p->error->rmse, p->spec.technique});
      }
      if (groups.empty()) {
        plot.reason = "no technique could be measured against " + fig.spec.reference +
                      " (it or the techniques are not available yet)";
        return;
      }
      const std::vector<std::string> crowded =
          plotGroupedPoints("visibility RMSE against the ray-traced reference vs frame time",
                            "frame time (ms, log scale)", "RMSE of the visibility mask (log scale)",
                            groups, png, kPlotWidth, kPlotHeight);
      for (const std::string& label : crowded)
        std::cerr << "        " << fig.spec.id << ": no free place for the label " << label
                  << std::endl;
    } else if (chart == "chan-3-10") {
      // Shares of the image: shadow-volume coverage (volumes) and silhouette pixels (hybrid),
      // from the counter each panel names; one series (colour) per counter and map size, as
      // Chan's bars are coloured by method and map resolution.
      std::vector<std::string> rows, columns;
      std::vector<std::pair<size_t, double>> cells;  // per row: its series, its value
      for (const PanelResult* p : rendered) {
        const auto it = p->counters.find(p->spec.counter);
        const Technique* t = lookup(p->spec.technique);
        if (p->spec.counter.empty() || it == p->counters.end() || t == nullptr) continue;
        const Setup s = setupFor(fig.spec, p->spec);
        const std::string series =
            p->spec.technique + " " + p->spec.counter +
            (readsOption(*t, CommonOption::kShadowMap) ? ", " + std::to_string(s.texels) + "² map"
                                                       : std::string());
        auto c = std::find(columns.begin(), columns.end(), series);
        if (c == columns.end()) c = columns.insert(columns.end(), series);
        rows.push_back(p->spec.label);
        cells.push_back({size_t(c - columns.begin()), 100.0 * it->second});  // fractions
      }
      if (rows.empty()) {
        plot.reason =
            "no panel reported its counter (modern.hybrid: silhouette_fraction, "
            "modern.volumes: volume_coverage)";
        return;
      }
      std::vector<std::vector<double>> values;
      for (const auto& [column, value] : cells) {
        values.emplace_back(columns.size(), 0.0);
        values.back()[column] = value;
      }
      plotStackedBars("share of pixels drawn (Chan Fig. 3-10)", "% of the image", rows, columns,
                      values, png, kPlotWidth, kPlotHeight);
    } else if (chart == "chan-3-11") {
      std::vector<std::string> rows, columns;
      for (const PanelResult* p : rendered)
        for (const PassTime& pass : p->passes)
          if (std::find(columns.begin(), columns.end(), pass.name) == columns.end())
            columns.push_back(pass.name);
      std::vector<std::vector<double>> values;
      for (const PanelResult* p : rendered) {
        rows.push_back(p->spec.label);
        std::vector<double> v(columns.size(), 0.0);
        for (const PassTime& pass : p->passes)
          v[std::find(columns.begin(), columns.end(), pass.name) - columns.begin()] +=
              pass.milliseconds;
        values.push_back(v);
      }
      if (rows.empty()) {
        plot.reason = "no technique of this figure is available yet";
        return;
      }
      plotStackedBars("time per pass (Chan Fig. 3-11)", "ms per frame", rows, columns, values, png,
                      kPlotWidth, kPlotHeight);
    } else {
      plot.reason = "unknown chart '" + chart + "'";
      return;
    }
  } catch (const std::exception& e) {
    // gnuplot writes the PNG under its final name (figures/plots.cpp): a failed run may have
    // left part of one, which must not pass for the chart.
    std::error_code ec;
    fs::remove(png, ec);
    plot.reason = std::string("failed: ") + e.what();
    return;
  }
  try {  // gnuplot drew it: the same tEXt chunks as our PNGs, added through libpng
    addPngProvenance(
        png, {commandLine(), nlohmann::json{{"figure", fig.spec.id},
                                            {"chart", chart},
                                            {"panel", plot.spec.label},
                                            {"set", fig.spec.overrides}}
                                 .dump(-1, ' ', true, nlohmann::json::error_handler_t::replace)});
  } catch (const InputError& e) {
    plot.reason = std::string("failed: ") + e.what();
    return;
  }
  plot.images.push_back({rel, plot.spec.label});
  plot.ok = true;
}

std::string rendererName() {
  try {
    ContextSpec spec;
    spec.width = spec.height = 16;
    spec.accumulation = false;
    auto ctx = GlContext::create(spec);
    return ctx->caps().renderer + " (" + ctx->caps().version + ")";
  } catch (const std::exception& e) {
    return std::string("unknown: ") + e.what();
  }
}

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof(buf), "%Y-%m-%d %H:%M UTC", std::gmtime(&t));
  return buf;
}

}  // namespace

Image composeFigure(const FigureResult& fig, const std::string& outDir, CompositeLayout* layout) {
  const FigureSpec& s = fig.spec;
  bool lettered = false;
  for (const PanelResult& p : fig.panels) lettered = lettered || p.spec.label.rfind("(", 0) == 0;
  std::vector<LabelledTile> panels, closeups;
  for (size_t i = 0; i < fig.panels.size(); ++i) {
    const PanelResult& p = fig.panels[i];
    const std::string letter = lettered || i >= 26 ? "" : std::string("(") + char('a' + i) + ") ";
    const size_t first = panels.size();
    for (LabelledTile& tile : compositeTiles(outDir, s, p, letter))
      panels.push_back(std::move(tile));
    // A buffer panel's close-ups are shared out over its buffers in order (one each, or
    // several each); a render's all sit under its one image.
    const size_t tiles = panels.size() - first;
    const size_t perTile = std::max<size_t>(1, p.closeups.size() / std::max<size_t>(tiles, 1));
    for (size_t k = 0; k < p.closeups.size(); ++k)
      closeups.push_back({readPng((fs::path(outDir) / p.closeups[k].file).string()),
                          p.closeups[k].caption,
                          int(first + std::min(k / perTile, std::max<size_t>(tiles, 1) - 1))});
  }
  if (panels.empty()) return Image();
  return composeLabelled(panels, closeups, s.columns, layout);
}

std::vector<FigureInfo> listFigures() {
  std::vector<FigureInfo> out;
  for (const FigureSpec& f : figureList())
    out.push_back({f.id, f.paper + ", " + f.paperFigure + ": " + f.title});
  return out;
}

int runFigures(const std::string& outDir, const std::vector<std::string>& only, bool progress,
               const FigureOverrides& overrides) {
  for (const std::string& id : only) {
    if (std::none_of(figureList().begin(), figureList().end(),
                     [&](const FigureSpec& f) { return f.id == id; })) {
      std::string known;
      for (const FigureSpec& f : figureList()) known += (known.empty() ? "" : ", ") + f.id;
      throw InputError("unknown figure '" + id + "' (known: " + known + ")");
    }
  }
  std::vector<FigureSpec> remade;  // the --set version of the one figure, when asked for
  std::vector<const FigureSpec*> selected;
  for (const FigureSpec& f : figureList())
    if (only.empty() || std::find(only.begin(), only.end(), f.id) != only.end())
      selected.push_back(&f);
  if (!overrides.empty()) {
    remade.push_back(applyOverrides(*selected.front(), overrides));  // one --only (overrides.h)
    selected = {&remade.front()};
  }
  std::error_code ec;
  fs::create_directories(outDir, ec);
  if (ec) throw InputError("cannot create " + outDir + ": " + ec.message());
  for (const FigureSpec* f : selected) {
    fs::create_directories(fs::path(outDir) / f->id, ec);
    if (ec)
      throw InputError("cannot create " + (fs::path(outDir) / f->id).string() + ": " +
                       ec.message());
  }

  size_t total = 0, done = 0;
  for (const FigureSpec* f : selected) total += f->panels.size();
  const auto start = std::chrono::steady_clock::now();
  Renderer renderer(outDir);
  std::vector<FigureResult> results;
  for (const FigureSpec* f : selected) {
    const auto figureStart = std::chrono::steady_clock::now();
    FigureResult fr;
    fr.spec = *f;
    const auto timed = timedRenders(*f);
    renderer.timeInterleaved(timed, roundsOf(*f), interleavedGroupOf(*f, timed.size()));
    for (size_t i = 0; i < f->panels.size(); ++i) {
      if (progress)
        std::cerr << "[" << ++done << "/" << total << "] " << f->id << " " << f->panels[i].label
                  << std::endl;
      fr.panels.push_back(makePanel(renderer, *f, f->panels[i], int(i)));
      if (progress && !fr.panels.back().ok && f->panels[i].kind != PanelKind::kPlot)
        std::cerr << "        missing: " << fr.panels.back().reason << std::endl;
    }
    for (PanelResult& p : fr.panels)
      if (p.spec.kind == PanelKind::kPlot) drawPlot(renderer, fr, p);
    writeRoundsCsv(renderer, fr);
    fr.measured = measuredHtml(fr);
    try {
      writeComposite(renderer, fr);
    } catch (const std::exception& e) {
      std::cerr << "        could not compose " << f->id << "/figure.png: " << e.what()
                << std::endl;
    }
    renderer.forgetFrames();
    fr.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - figureStart).count();
    results.push_back(std::move(fr));
  }
  // A lesson per technique (teach/lesson.h), small so that all of them cost about a minute;
  // with --only, the lessons of what the selected figures show (teach/lesson.h figureShows: a
  // figure of legacy.pcf, both PCF lessons). Each links its figures in this report, and each
  // figure its lessons.
  std::vector<std::string> lessonTechniques;
  for (const Technique& t : allTechniques()) {
    bool shown = only.empty();
    const std::vector<std::string> subjects = lessonSubjects(t.name);
    for (const FigureSpec* f : selected)
      shown = shown || figureShows(FigureRef{f->id, f->title, figureTechniques(*f)}, subjects);
    if (shown) lessonTechniques.push_back(t.name);
  }
  const LessonSettings lessonSettings{kDefaultScene, kLessonWidth, kLessonHeight, kLessonShadowMap,
                                      reportLinksTo("../../report.html", selected)};
  ReportInfo info;
  const auto lessonsStart = std::chrono::steady_clock::now();
  info.lessons = writeLessons((fs::path(outDir) / "lessons").string(), lessonTechniques,
                              lessonSettings, progress);
  info.lessonsHtml = lessonIndexHtml(info.lessons, info.lessonsBase);
  if (progress)
    std::cerr << "[lesson] " << lessonTechniques.size() << " lessons in "
              << std::lround(
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - lessonsStart)
                         .count())
              << " s" << std::endl;
  // The whole set: the course over those lessons (figures/course.h), linked from the report.
  if (only.empty())
    info.lessonsHtml +=
        writeCourseForReport(outDir, reportLinksTo("../report.html", selected), progress);
  if (only.empty()) {  // the whole set: the quick bench's table, plots and claims join the report
    if (progress) std::cerr << "[bench] shadowlab bench --quick" << std::endl;
    info.benchHtml = runQuickBenchForReport(outDir, progress);
    if (progress) std::cerr << "[stability] every technique on every stability case" << std::endl;
    info.benchHtml += stability::summaryHtml(progress);
  }
  info.renderer = rendererName();
  info.date = utcNow();
  info.totalSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  writeReport(outDir, results, info);
  int missing = 0, panels = 0;
  for (const FigureResult& fr : results)
    for (const PanelResult& p : fr.panels) {
      ++panels;
      missing += p.ok ? 0 : 1;
    }
  std::cout << "wrote " << (fs::path(outDir) / "report.html").string() << " (" << results.size()
            << " figures, " << panels - missing << "/" << panels << " panels made, " << missing
            << " listed as missing, " << std::lround(info.totalSeconds) << " s)" << std::endl;
  return 0;
}

int runBench(const cli::Args& args) { return runBenchCommand(args); }  // measure/bench.cpp
int runPlan(const cli::Args& args) { return runPlanCommand(args); }    // figures/plan.cpp

}  // namespace sl::figures
