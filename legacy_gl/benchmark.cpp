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

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

const Technique& technique(const std::string& name) {
  static const std::vector<Technique> all = techniques();
  for (const Technique& t : all)
    if (t.name == name) return t;
  throw InputError("unknown legacy technique '" + name + "'");
}

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
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
    imaging::install(*context);
    std::vector<double> frames, sums;
    std::vector<std::string> order;
    std::map<std::string, std::vector<double>> perPass;
    for (int i = 0; i < options.warmupFrames + options.timedFrames; ++i) {
      const double start = nowMilliseconds();
      const Frame f = t.render(*context, scene, p);
      const double wall = nowMilliseconds() - start;
      if (i < options.warmupFrames) continue;
      frames.push_back(wall);
      sums.push_back(f.totalMilliseconds());
      for (const PassTime& pass : f.passes) {
        if (!perPass.count(pass.name)) order.push_back(pass.name);
        perPass[pass.name].push_back(pass.milliseconds);
      }
    }
    BenchmarkResult r;
    r.variant = v;
    r.backend = options.backend;
    r.medianFrameMs = median(frames);
    r.medianPassSumMs = median(sums);
    for (const std::string& name : order) r.medianPasses.push_back({name, median(perPass[name])});
    results.push_back(std::move(r));
  }
  return results;
}

std::string benchmarkMarkdown(const std::vector<BenchmarkResult>& results) {
  std::ostringstream s;
  s << "| variant | GL | paper, Octane VPro/8 (fps) | ours (fps) | ours (ms/frame) |\n"
    << "| --- | --- | --- | --- | --- |\n";
  for (const BenchmarkResult& r : results)
    s << "| " << r.variant.label << " | " << backendName(r.backend) << " | "
      << (r.variant.paperFps.empty() ? "-" : r.variant.paperFps) << " | "
      << fixed(1000.0 / r.medianFrameMs, 1) << " | " << fixed(r.medianFrameMs, 1) << " |\n";
  for (const BenchmarkResult& r : results) {
    s << "\n"
      << r.variant.label << " on " << backendName(r.backend) << " (median ms per pass):\n\n"
      << "| pass | ms |\n| --- | --- |\n";
    for (const PassTime& p : r.medianPasses)
      s << "| " << p.name << " | " << fixed(p.milliseconds, 2) << " |\n";
  }
  return s.str();
}

}  // namespace sl::legacy
