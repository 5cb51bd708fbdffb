// legacy_bench — Brabec & Seidel 2001 §5 in the paper's configuration, per pass, beside the
// paper's Octane VPro/8 frame rates and beside each pass's llvmpipe floor; legacy.hw (Everitt et
// al. 2001) in the same configuration against its floors. Prints markdown tables
// (docs/legacy.md).
// Roofline (always printed): in the same context as the frames, and interleaved with them
// round by round so that load hits both alike, each pass's floor is measured: the least GL work
// of its kind at its size (measure/roofline.h: a clear, one full-window quad with the pass's
// class of fragment work, the same glCopyTexSubImage2D / glCopyPixels / glDrawPixels size, the
// same glAccum). Each pass prints its median time, its floor and time / floor; the first
// table the frame's sum of floors and time / floor.
//   legacy_bench [--backend osmesa|reference] [--imaging native|emulated] [--frames N]
//                [--quick] [--technique T] [--trace-overhead] [--split-cost]
// --trace-overhead: instead, each technique's frame time with the GL trace of --dump-passes off
// (the context's own dispatch table, as every render runs) and on (core/gl/gl_trace.h), as a ratio.
// --split-cost: instead, the camera pass's draw of brabec's own meshes and of the split meshes
// the camera passes draw (spotlight_tessellation.h), beside the pass's floor, with the fragments
// each shades and the split meshes' vertex-and-setup cost alone (docs/legacy.md "Feeding the
// passes").
#include <CLI/CLI.hpp>
#include <iostream>
#include <string>
#include <vector>

#include "core/base/errors.h"
#include "core/base/provenance.h"
#include "core/scene/scene_library.h"
#include "core/technique/frame_timing.h"
#include "measure/legacy_benchmark.h"
#include "registry/cli.h"
#include "registry/registry.h"

namespace {
constexpr int kMaxTimedFrames = 1000;  // --frames: more would take hours at 800x600
}  // namespace

int main(int argc, char** argv) {
  sl::recordCommandLine(argc, argv);  // PNG text chunks name the command (core/base/provenance.h)
  try {
    sl::legacy::BenchmarkOptions options;
    std::string backend, imaging, frames;
    std::string only;  // --technique: keep the variants of one technique
    bool quick = false, traceOverhead = false, splitCost = false;
    CLI::App app{
        "Brabec & Seidel 2001 §5 per pass, beside the paper's frame rates and each "
        "pass's llvmpipe floor (time / floor; floors measured interleaved in the same "
        "context, measure/roofline.h) (markdown)",
        "legacy_bench"};
    app.add_option("--backend", backend, "osmesa or reference (Mesa 7.8.2) [osmesa]")
        ->type_name("NAME");
    app.add_option("--imaging", imaging,
                   "native (reference only) or emulated (imaging/) [native where the back end "
                   "has it, else emulated]")
        ->type_name("native|emulated");
    app.add_option("--frames", frames, "timed frames per variant, after the warm-up frames")
        ->type_name("N");
    app.add_flag("--quick", quick,
                 "the quick frame counts (core/technique/frame_timing.h kQuickFrames)");
    app.add_option("--technique", only,
                   "only legacy.ramp, legacy.pcf, legacy.fast-pcf or legacy.hw")
        ->type_name("T");
    app.add_flag("--trace-overhead", traceOverhead,
                 "frame time with the --dump-passes GL trace off and on (core/gl/gl_trace.h)");
    app.add_flag("--split-cost", splitCost,
                 "the camera pass's draw of the scene's own and of its spotlight-split meshes, "
                 "beside the pass's floor, with the fragments each shades");
    if (!sl::cli::parseTool(app, argc, argv)) return 0;
    if (!backend.empty()) options.backend = sl::parseBackend(backend);
    if (!imaging.empty()) options.imaging = sl::cli::parseImaging(imaging);
    if (quick) options.frames = sl::kQuickFrames;
    if (!frames.empty())
      options.frames.timed = sl::cli::parsePositiveInt("--frames", frames, kMaxTimedFrames);

    std::vector<sl::legacy::BenchmarkVariant> variants;
    for (const auto& v : sl::legacy::paperVariants())
      if (only.empty() || v.technique == only) variants.push_back(v);
    if (variants.empty()) throw sl::InputError("no benchmark variant of technique '" + only + "'");
    if (splitCost) {
      std::cout << sl::legacy::splitCostMarkdown(sl::builtinScene("brabec"), options);
      return 0;
    }
    if (traceOverhead) {
      std::cout << sl::legacy::traceOverheadMarkdown(options, variants);
      return 0;
    }
    const auto results =
        sl::legacy::benchmarkBrabecSeidel(sl::builtinScene("brabec"), options, variants);
    std::cout << sl::legacy::benchmarkMarkdown(results);
    return 0;
  } catch (const sl::InputError& e) {
    std::cerr << "legacy_bench: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "legacy_bench: " << e.what() << "\n";
    return 1;
  }
}
