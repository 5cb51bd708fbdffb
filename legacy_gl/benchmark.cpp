// legacy_gl/benchmark.cpp — Brabec & Seidel 2001 §5 timings (see benchmark.h).
#include "legacy_gl/benchmark.h"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <map>
#include <sstream>

#include "core/errors.h"
#include "imaging/imaging.h"
#include "legacy_gl/legacy.h"
#include "legacy_gl/roofline.h"

namespace sl::legacy {
namespace {

const Technique& technique(const std::string& name) {
  static const std::vector<Technique> all = techniques();
  for (const Technique& t : all)
    if (t.name == name) return t;
  throw InputError("unknown legacy technique '" + name + "'");
}

// The GL column: the back end, and "imaging/" where the emulation replaced native imaging.
std::string glName(const BenchmarkResult& r) {
  return std::string(backendName(r.backend)) + (r.imagingReplaced ? " + imaging/" : "");
}

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

// time / floor, "-" without a floor.
std::string ratio(double ms, double floorMs) {
  return floorMs > 0.0 ? fixed(ms / floorMs, 1) + "x" : "-";
}

// Installs the imaging subset options.imaging asks for (as registry/registry.cpp does for render).
imaging::Mode installImaging(GlContext& context, ImagingChoice choice) {
  switch (choice) {
    case ImagingChoice::kNative:
      if (!context.caps().nativeImaging())
        throw InputError(std::string("--imaging native: the ") +
                         backendName(context.spec().backend) +
                         " back end has no native ARB_imaging (only --backend reference has "
                         "one); use --imaging emulated");
      return imaging::install(context, imaging::Mode::kNative);
    case ImagingChoice::kEmulated:
      return imaging::install(context, imaging::Mode::kEmulated);
    case ImagingChoice::kBackendDefault:
      break;
  }
  return imaging::install(context);
}

}  // namespace

std::vector<BenchmarkVariant> paperVariants() {
  return {{"unfiltered (§2)", "legacy.ramp", 1, "25-30"},
          {"PCF 2x2 (§3)", "legacy.pcf", 2, "~10"},
          {"fast PCF 2x2 (§4)", "legacy.fast-pcf", 2, "15-20"},
          {"fast PCF 4x4 (§4)", "legacy.fast-pcf", 4, "~5"},
          {"PCF 4x4 (§3, \"not practical\")", "legacy.pcf", 4, ""}};
}

std::vector<BenchmarkResult> benchmarkBrabecSeidel(const Scene& scene,
                                                   const BenchmarkOptions& options,
                                                   const std::vector<BenchmarkVariant>& variants) {
  std::vector<BenchmarkResult> results;
  for (const BenchmarkVariant& v : variants) {
    const Technique& t = technique(v.technique);
    RenderParams p;
    p.width = options.width;
    p.height = options.height;
    p.shadowMapTexels = options.shadowMapTexels;
    p.filter = v.filter;
    p.backend = options.backend;
    checkParams(t, p, 0);
    auto context = GlContext::create(contextFor(t, p));
    const imaging::Mode mode = installImaging(*context, options.imaging);
    BenchmarkResult r;
    r.variant = v;
    r.backend = options.backend;
    r.imagingReplaced = mode == imaging::Mode::kEmulated && context->caps().nativeImaging();
    // The floors of the passes the frames ran (known once the first frame has rendered: the
    // technique's frames come first in the warm-up and in every round).
    std::vector<std::string> passNames;
    std::vector<FloorTerm> terms;
    auto resources = makeFloorResources(p.shadowMapTexels, p.width, p.height);
    const std::function<Frame()> frameSource = [&] {
      Frame f = t.render(*context, scene, p);
      if (passNames.empty())
        for (const PassTime& pass : f.passes) passNames.push_back(pass.name);
      return f;
    };
    const std::function<Frame()> floorSource = [&] {
      if (terms.empty())
        for (const std::string& name : passNames) {
          const std::vector<FloorTerm> passTerms =
              passFloor(name, p).value_or(std::vector<FloorTerm>{});
          for (const FloorTerm& term : passTerms) {
            const std::string key = floorName(term);
            if (std::none_of(terms.begin(), terms.end(),
                             [&](const FloorTerm& x) { return floorName(x) == key; }))
              terms.push_back(term);
          }
        }
      return renderFloors(*resources, terms);
    };
    const auto timings = timeInterleavedSteadyState({frameSource, floorSource},
                                                    options.frames.warmup, options.frames.timed);
    r.timing = timings[0];
    r.floors = timings[1].passes;
    std::map<std::string, double> floorMs;
    for (const PassTime& f : r.floors) floorMs[f.name] = f.milliseconds;
    for (const PassTime& pass : r.timing.passes) {
      const auto passTerms = passFloor(pass.name, p);
      if (!passTerms) {
        r.passFloorMs.push_back(std::nullopt);
        continue;
      }
      double ms = 0.0;
      for (const FloorTerm& term : *passTerms) ms += term.count * floorMs[floorName(term)];
      r.passFloorMs.push_back(ms);
      r.frameFloorMs += ms;
    }
    results.push_back(std::move(r));
  }
  return results;
}

std::string benchmarkMarkdown(const std::vector<BenchmarkResult>& results) {
  std::ostringstream s;
  if (!results.empty())
    s << "Steady state: " << results.front().timing.warmupFrames
      << " warm-up frames, then the median of " << results.front().timing.timedFrames
      << " frames (core/frame_timing.h); ms/frame is the sum of the passes, render() adds the "
         "read-back of the colour image and the mask.\n\n";
  s << "| variant | GL | paper, Octane VPro/8 (fps) | ours (fps) | ours (ms/frame) | render() "
       "(ms) | floor (ms/frame) | time / floor |\n"
    << "| --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const BenchmarkResult& r : results)
    s << "| " << r.variant.label << " | " << glName(r) << " | "
      << (r.variant.paperFps.empty() ? "-" : r.variant.paperFps) << " | "
      << fixed(r.timing.fps(), 1) << " | " << fixed(r.timing.frameMs, 1) << " | "
      << fixed(r.timing.wallMs, 1) << " | " << fixed(r.frameFloorMs, 1) << " | "
      << ratio(r.timing.frameMs, r.frameFloorMs) << " |\n";
  for (const BenchmarkResult& r : results) {
    s << "\n"
      << r.variant.label << " on " << glName(r)
      << " (median ms per pass; floor: legacy_gl/roofline.h, measured interleaved):\n\n"
      << "| pass | ms | floor (ms) | time / floor |\n| --- | --- | --- | --- |\n";
    for (size_t i = 0; i < r.timing.passes.size(); ++i) {
      const PassTime& p = r.timing.passes[i];
      const bool known = i < r.passFloorMs.size() && r.passFloorMs[i].has_value();
      const double floor = known ? r.passFloorMs[i].value_or(0.0) : 0.0;
      s << "| " << p.name << " | " << fixed(p.milliseconds, 2) << " | "
        << (!known         ? "no rule"
            : floor == 0.0 ? "- (no GL work)"
                           : fixed(floor, 2))
        << " | " << ratio(p.milliseconds, floor) << " |\n";
    }
    s << "\nFloors measured (median ms):\n\n| floor | ms |\n| --- | --- |\n";
    for (const PassTime& f : r.floors)
      s << "| " << f.name.substr(std::string("floor: ").size()) << " | " << fixed(f.milliseconds, 2)
        << " |\n";
  }
  return s.str();
}

}  // namespace sl::legacy
