// measure/twin_tables.h — shadowlab-twins' tables (tools/twins_main.cpp is its command line):
// the legacy/modern agreement of every pair of registry/twins.h on every scene, judged against
// the pair's bound, and each pair's frame times at Brabec–Seidel §5's configuration, as markdown
// (docs/twins.md is the program's output).
#pragma once

#include <string>
#include <vector>

#include "core/gl/context.h"
#include "registry/twins.h"

namespace sl::measure::twin_tables {

struct Options {
  int width = 320, height = 240, shadowMap = 256;  // as tests/modern/equivalence_test.cpp
  int benchWidth = 800, benchHeight = 600, benchShadowMap = 512;  // Brabec–Seidel §5
  std::string benchScene = "brabec";
  int frames = 5;
  Backend backend = Backend::kOsmesa;
  std::vector<std::string> scenes = twins::equivalenceScenes();
  bool agreement = true;
  bool bench = true;
};

// The agreement table on stdout: per pair and scene, the masks' and the images' differences
// against the pair's bound (a pair that cannot run says why in its row).
void agreementTable(const Options& o);
// The frame-time table on stdout: per pair, the legacy and modern medians and minima and their
// ratios.
void benchTable(const Options& o);

}  // namespace sl::measure::twin_tables
