// tools/bias_table.cpp — the depth-bias methods of the GPU Gems PCF family (--param bias) on the
// stability suite's acne-prone cases: acne and peter-panning against the ray-traced reference,
// as a markdown table (measure/bias_table.h; docs/bias.md is its output). Built to
// build/bin/bias_table.
//
//   bias_table [--progress]
#include "measure/bias_table.h"

#include <CLI/CLI.hpp>
#include <iostream>
#include <optional>

#include "core/base/errors.h"
#include "registry/cli.h"

namespace sl {
namespace {

int run(int argc, char** argv) {
  bool progress = false;
  CLI::App app{
      "acne and peter-panning of each --param bias of the GPU Gems PCF family on the "
      "stability suite's grazing and contact cases (markdown)",
      "bias_table"};
  app.add_flag("--progress", progress, "name each render on stderr");
  if (!cli::parseTool(app, argc, argv)) return 0;  // --help
  std::cout << measure::bias::markdown(measure::bias::measureAll(progress));
  return 0;
}

}  // namespace
}  // namespace sl

int main(int argc, char** argv) { return sl::runProgram("bias_table", argc, argv, sl::run); }
