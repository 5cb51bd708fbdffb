// legacy_gl/benchmark.cpp — Brabec & Seidel 2001 §5 timings (see benchmark.h).
#include "legacy_gl/benchmark.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>

#include "core/errors.h"
#include "imaging/imaging.h"
#include "legacy_gl/legacy.h"

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
    r.timing = timeSteadyState([&] { return t.render(*context, scene, p); }, options.frames);
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
       "(ms) |\n"
    << "| --- | --- | --- | --- | --- | --- |\n";
  for (const BenchmarkResult& r : results)
    s << "| " << r.variant.label << " | " << glName(r) << " | "
      << (r.variant.paperFps.empty() ? "-" : r.variant.paperFps) << " | "
      << fixed(r.timing.fps(), 1) << " | " << fixed(r.timing.frameMs, 1) << " | "
      << fixed(r.timing.wallMs, 1) << " |\n";
  for (const BenchmarkResult& r : results) {
    s << "\n"
      << r.variant.label << " on " << glName(r) << " (median ms per pass):\n\n"
      << "| pass | ms |\n| --- | --- |\n";
    for (const PassTime& p : r.timing.passes)
      s << "| " << p.name << " | " << fixed(p.milliseconds, 2) << " |\n";
  }
  return s.str();
}

}  // namespace sl::legacy
