// measure/legacy_benchmark.cpp — Brabec & Seidel 2001 §5 timings (see benchmark.h).
#include "measure/legacy_benchmark.h"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <map>
#include <sstream>

#include "core/base/decimal.h"
#include "core/base/errors.h"
#include "core/gl/gl.h"
#include "core/gl/gl_objects.h"
#include "core/gl/gl_trace.h"
#include "core/scene/scene_library.h"
#include "core/technique/frame_timing.h"
#include "imaging/imaging.h"
#include "legacy_gl/fixed_function.h"
#include "legacy_gl/legacy.h"
#include "legacy_gl/spotlight_tessellation.h"
#include "measure/roofline.h"
#include "registry/registry.h"

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

// time / floor, "-" without a floor.
std::string ratio(double ms, double floorMs) {
  return floorMs > 0.0 ? fixedDecimals(ms / floorMs, 1) + "x" : "-";
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
    case ImagingChoice::kEmulated: return imaging::install(context, imaging::Mode::kEmulated);
    case ImagingChoice::kBackendDefault: break;
  }
  return imaging::install(context);
}

}  // namespace

std::vector<BenchmarkVariant> paperVariants() {
  return {{"unfiltered (§2)", "legacy.ramp", 1, "25-30"},
          {"PCF 2x2 (§3)", "legacy.pcf", 2, "~10"},
          {"fast PCF 2x2 (§4)", "legacy.fast-pcf", 2, "15-20"},
          {"fast PCF 4x4 (§4)", "legacy.fast-pcf", 4, "~5"},
          {"PCF 4x4 (§3, \"not practical\")", "legacy.pcf", 4, ""},
          // Everitt et al. 2001 report no frame rate; its passes stand against the same floors.
          {"hardware shadow map (Everitt et al.)", "legacy.hw", 2, ""}};
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
    std::vector<PassTime> framePasses;
    std::vector<FloorTerm> terms;
    auto resources = makeFloorResources(p.shadowMapTexels, p.width, p.height);
    const std::function<Frame()> frameSource = [&] {
      Frame f = t.render(*context, scene, p);
      if (framePasses.empty()) framePasses = f.passes;
      return f;
    };
    const std::function<Frame()> floorSource = [&] {
      if (terms.empty())
        for (const PassTime& pass : framePasses) {
          const std::vector<FloorTerm> passTerms =
              passFloor(pass, p).value_or(std::vector<FloorTerm>{});
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
      const auto passTerms = passFloor(pass, p);
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

namespace {

constexpr int kSplitCostRampTexels = 256;  // the 8-bit ramp of §2

// §2's camera pass as it draws (clear; the scene white under the ramp on eye-linear texgen;
// depth LESS and write), timed as one pass named `name`. The texgen plane picks eye depth, so
// the fragments do the camera pass's work (one 1D lookup each); the values are not the pass's.
void timeCameraPassDraw(Frame& frame, const std::string& name, const Scene& scene,
                        const RenderParams& p, unsigned ramp, bool onePixel = false) {
  using namespace sl::gl;
  const ScopedAttrib state(GL_ALL_ATTRIB_BITS);
  const ScopedMatrices matrices;
  for (const GLenum mode : {GLenum(GL_PROJECTION), GLenum(GL_MODELVIEW), GLenum(GL_TEXTURE)}) {
    glMatrixMode(mode);
    glLoadIdentity();
  }
  {
    PassTimer timer(frame, name);
    setCameraMatrices(scene, p.width, p.height);
    // One pixel of the window, the clear's too: the vertices, clipping, setup and binning
    // without the fill.
    if (onePixel) {
      glScissor(p.width / 2, p.height / 2, 1, 1);
      glEnable(GL_SCISSOR_TEST);  // restored by the attribute scope
    }
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    const float plane[4] = {0.0f, 0.0f, -1.0f / scene.camera.farPlane, 0.0f};
    glMatrixMode(GL_MODELVIEW);
    {
      const ScopedPushMatrix eyeSpace;
      glLoadIdentity();  // eye-linear planes are taken through the modelview at specification
      glTexGeni(GL_S, GL_TEXTURE_GEN_MODE, GL_EYE_LINEAR);
      glTexGenfv(GL_S, GL_EYE_PLANE, plane);
    }
    glEnable(GL_TEXTURE_GEN_S);
    glEnable(GL_TEXTURE_1D);
    glBindTexture(GL_TEXTURE_1D, ramp);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
    drawScene(scene, Draw::kAll, Colors::kWhite);
  }
}

size_t triangles(const Scene& scene) {
  size_t n = 0;
  for (const Object& o : scene.objects) n += o.mesh->triangleCount();
  return n;
}

}  // namespace

std::string splitCostMarkdown(const Scene& scene, const BenchmarkOptions& options) {
  const Technique& t = technique("legacy.ramp");
  RenderParams p;
  p.width = options.width;
  p.height = options.height;
  p.shadowMapTexels = options.shadowMapTexels;
  p.filter = 1;
  p.backend = options.backend;
  checkParams(t, p, 0);
  auto context = GlContext::create(contextFor(t, p));
  const Scene split = tessellateForSpotlight(scene, p.width, p.height);
  Scene culled = split;  // as the camera passes draw it (cameraPassScene)
  markHiddenBackFaces(culled, scene);
  const Texture ramp = makeTexture();
  {
    using namespace sl::gl;
    std::vector<float> texels(kSplitCostRampTexels);
    for (int i = 0; i < kSplitCostRampTexels; ++i)
      texels[size_t(i)] = float(i) / float(kSplitCostRampTexels - 1);
    glBindTexture(GL_TEXTURE_1D, ramp.id());
    glTexImage1D(GL_TEXTURE_1D, 0, GL_INTENSITY8, kSplitCostRampTexels, 0, GL_LUMINANCE, GL_FLOAT,
                 texels.data());
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_1D, 0);
  }
  auto resources = makeFloorResources(p.shadowMapTexels, p.width, p.height);
  const std::vector<FloorTerm> floor = *passFloor(PassFloor::kCameraDepth, 0, p);
  const std::string ownName = "the scene's own meshes";
  const std::string splitName = "the split meshes, both faces";
  const std::string culledName =
      "the split meshes, hidden back faces culled (as the camera passes draw them)";
  const std::string geometryName =
      "the split meshes, one pixel drawn (scissor): vertices and setup";
  const std::vector<std::function<Frame()>> draws = {
      [&] { return renderFloors(*resources, floor); },
      [&] {
        Frame f;
        timeCameraPassDraw(f, ownName, scene, p, ramp.id());
        return f;
      },
      [&] {
        Frame f;
        timeCameraPassDraw(f, splitName, split, p, ramp.id());
        return f;
      },
      [&] {
        Frame f;
        timeCameraPassDraw(f, geometryName, split, p, ramp.id(), true);
        return f;
      },
      [&] {
        Frame f;
        timeCameraPassDraw(f, culledName, culled, p, ramp.id());
        return f;
      }};
  const auto timings =
      timeInterleavedSteadyState(draws, options.frames.warmup, options.frames.timed);
  // Counted once after the timing, so that the query does not sit in the timed draws.
  std::vector<double> fragments;
  for (const auto& draw : draws) fragments.push_back(countFragmentInvocations([&] { draw(); }));
  checkGl("split cost");
  const double floorMs = timings[0].frameMs;
  const auto shaded = [&](size_t i) {
    return fragments[i] < 0 ? std::string("-") : std::to_string(size_t(fragments[i]));
  };
  std::ostringstream s;
  s << "Camera pass draw (clear, ramp-textured scene, depth LESS) of the " << scene.name
    << " scene at " << p.width << "x" << p.height << " on " << backendName(p.backend)
    << ", interleaved with its floor: " << timings[0].warmupFrames
    << " warm-up rounds, then the median of " << timings[0].timedFrames
    << " rounds. Fragments shaded: GL_ARB_pipeline_statistics_query's fragment-shader "
       "invocations (llvmpipe counts whole 4x4 blocks)\n\n"
    << "| draw | triangles | fragments shaded | ms | / floor |\n| --- | --- | --- | --- | --- |\n"
    << "| floor: clear + one ramp-textured full-window quad | 2 | " << shaded(0) << " | "
    << fixedDecimals(floorMs, 2) << " | 1.0x |\n";
  const std::string names[] = {ownName, splitName, geometryName, culledName};
  const size_t counts[] = {triangles(scene), triangles(split), triangles(split), triangles(split)};
  for (size_t i = 1; i < draws.size(); ++i)
    s << "| " << names[i - 1] << " | " << counts[i - 1] << " | " << shaded(i) << " | "
      << fixedDecimals(timings[i].frameMs, 2) << " | " << ratio(timings[i].frameMs, floorMs)
      << " |\n";
  if (fragments[0] > 0 && fragments[2] > 0 && fragments[4] > 0)
    s << "\nThe split meshes shade " << fixedDecimals(fragments[2] / fragments[0], 2)
      << "x the floor's fragments with both faces and "
      << fixedDecimals(fragments[4] / fragments[0], 2)
      << "x with their hidden back faces culled (what is left: surfaces hidden behind other "
         "objects and the 4x4 blocks that small triangles cover partly); their vertices and "
         "setup alone take "
      << fixedDecimals(timings[3].frameMs, 2) << " ms.\n";
  return s.str();
}

std::string benchmarkMarkdown(const std::vector<BenchmarkResult>& results) {
  std::ostringstream s;
  if (!results.empty())
    s << "Steady state: " << results.front().timing.warmupFrames
      << " warm-up frames, then the median of " << results.front().timing.timedFrames
      << " frames (core/technique/frame_timing.h); ms/frame is the sum of the passes, render() "
         "adds the "
         "read-back of the colour image and the mask.\n\n";
  s << "| variant | GL | paper, Octane VPro/8 (fps) | ours (fps) | ours (ms/frame) | render() "
       "(ms) | floor (ms/frame) | time / floor |\n"
    << "| --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const BenchmarkResult& r : results)
    s << "| " << r.variant.label << " | " << glName(r) << " | "
      << (r.variant.paperFps.empty() ? "-" : r.variant.paperFps) << " | "
      << fixedDecimals(r.timing.fps(), 1) << " | " << fixedDecimals(r.timing.frameMs, 1) << " | "
      << fixedDecimals(r.timing.wallMs, 1) << " | " << fixedDecimals(r.frameFloorMs, 1) << " | "
      << ratio(r.timing.frameMs, r.frameFloorMs) << " |\n";
  for (const BenchmarkResult& r : results) {
    s << "\n"
      << r.variant.label << " on " << glName(r)
      << " (median ms per pass; floor: measure/roofline.h, measured interleaved):\n\n"
      << "| pass | ms | floor (ms) | time / floor |\n| --- | --- | --- | --- |\n";
    for (size_t i = 0; i < r.timing.passes.size(); ++i) {
      const PassTime& p = r.timing.passes[i];
      const bool known = i < r.passFloorMs.size() && r.passFloorMs[i].has_value();
      const double floor = known ? r.passFloorMs[i].value_or(0.0) : 0.0;
      s << "| " << p.name << " | " << fixedDecimals(p.milliseconds, 2) << " | "
        << (!known         ? "no rule"
            : floor == 0.0 ? "- (no GL work)"
                           : fixedDecimals(floor, 2))
        << " | " << ratio(p.milliseconds, floor) << " |\n";
    }
    s << "\nFloors measured (median ms):\n\n| floor | ms |\n| --- | --- |\n";
    for (const PassTime& f : r.floors)
      s << "| " << f.name.substr(std::string("floor: ").size()) << " | "
        << fixedDecimals(f.milliseconds, 2) << " |\n";
  }
  return s.str();
}

// The cost of the GL trace (core/gl/gl_trace.h): off, every call goes through the context's own
// table (the trace is not there at all); on, through the recording table. The two are timed
// interleaved (core/technique/frame_timing.h timeInterleavedSteadyState), each on its own context,
// so that a change of the machine's load hits both alike; the ratio is of the two medians.
std::string traceOverheadMarkdown(const BenchmarkOptions& options,
                                  const std::vector<BenchmarkVariant>& variants) {
  std::ostringstream out;
  out << "GL trace of --dump-passes (core/gl/gl_trace.h), brabec scene " << options.width << "x"
      << options.height << ", shadow map " << options.shadowMapTexels << ", "
      << backendName(options.backend) << ", off and on interleaved: median of "
      << options.frames.timed << " rounds after " << options.frames.warmup
      << " warm-up frames each\n\n"
      << "| variant | trace off: frame ms | trace on: frame ms | on / off | median of the rounds' "
         "on "
         "/ off |\n|---|---|---|---|---|\n";
  for (const auto& v : variants) {
    RenderParams p;
    p.width = options.width;
    p.height = options.height;
    p.shadowMapTexels = options.shadowMapTexels;
    p.filter = v.filter;
    p.backend = options.backend;
    p.imaging = options.imaging;
    const Technique& t = findTechnique(v.technique);
    const Scene scene = builtinScene("brabec");
    const auto offContext = makeRenderContext(t, p);
    const auto onContext = makeRenderContext(t, p);
    const std::vector<std::function<Frame()>> sources = {
        [&] {
          offContext->makeCurrent();
          return t.render(*offContext, scene, p);
        },
        [&] {
          onContext->makeCurrent();
          const GlTrace trace;  // as render --dump-passes runs it
          return t.render(*onContext, scene, p);
        }};
    const auto timings =
        timeInterleavedSteadyState(sources, options.frames.warmup, options.frames.timed);
    const double off = timings[0].frameMs, on = timings[1].frameMs;
    // Round by round (the two frames of a round ran back to back, under nearly the same load).
    std::vector<double> roundRatios;
    for (size_t r = 0; r < timings[0].frameSamples.size(); ++r)
      if (timings[0].frameSamples[r] > 0.0)
        roundRatios.push_back(timings[1].frameSamples[r] / timings[0].frameSamples[r]);
    char row[200];
    std::snprintf(row, sizeof row, "| %s | %.2f | %.2f | %.3f | %.3f |\n", v.label.c_str(), off, on,
                  off > 0.0 ? on / off : 0.0, roundRatios.empty() ? 0.0 : median(roundRatios));
    out << row;
  }
  out << "\nOff, the trace costs nothing: no GlTrace exists, the context's own table is current "
         "and each call is the one indirect call it always is (tests/core/gl_trace_test.cpp "
         "checks the table is untouched).\n";
  return out.str();
}

}  // namespace sl::legacy
