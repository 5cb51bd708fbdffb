// legacy_bench — Brabec & Seidel 2001 §5 in the paper's configuration, per pass, beside the
// paper's Octane VPro/8 frame rates. Prints a markdown table (docs/legacy.md).
//   legacy_bench [--backend osmesa|reference] [--imaging native|emulated] [--frames N]
//                [--quick] [--technique T]
#include <CLI/CLI.hpp>
#include <iostream>
#include <string>
#include <vector>

#include "registry/cli.h"
#include "core/errors.h"
#include "core/provenance.h"
#include "core/scene_library.h"
#include "legacy_gl/benchmark.h"

namespace {
constexpr int kMaxTimedFrames = 1000;  // --frames: more would take hours at 800x600
}

int main(int argc, char** argv) {
  sl::recordCommandLine(argc, argv);  // PNG text chunks name the command (core/provenance.h)
  try {
    sl::legacy::BenchmarkOptions options;
    std::string backend, imaging, frames;
    std::string only;  // --technique: keep the variants of one technique
    bool quick = false;
    CLI::App app{"Brabec & Seidel 2001 §5 per pass, beside the paper's frame rates (markdown)",
                 "legacy_bench"};
    app.add_option("--backend", backend, "osmesa or reference (Mesa 7.8.2) [osmesa]")
        ->type_name("NAME");
    app.add_option("--imaging", imaging,
                   "native (reference only) or emulated (imaging/) [native where the back end "
                   "has it, else emulated]")
        ->type_name("native|emulated");
    app.add_option("--frames", frames, "timed frames per variant, after the warm-up frames")
        ->type_name("N");
    app.add_flag("--quick", quick, "the quick frame counts (core/frame_timing.h kQuickFrames)");
    app.add_option("--technique", only, "only legacy.ramp, legacy.pcf or legacy.fast-pcf")
        ->type_name("T");
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
