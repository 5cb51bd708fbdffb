#include "figures/figures.h"

#include <filesystem>
#include <fstream>
#include <iostream>

#include "apps/registry.h"
#include "core/errors.h"
#include "core/scene_library.h"
#include "figures/bench.h"
#include "figures/plan.h"

namespace sl::figures {
namespace fs = std::filesystem;

std::vector<FigureInfo> listFigures() { return {{"gallery", "every technique on the default scene"}}; }

int runFigures(const std::string& outDir, const std::optional<std::string>& only, bool progress) {
  if (only && *only != "gallery") throw InputError("unknown figure '" + *only + "'");
  std::error_code ec;
  fs::create_directories(outDir, ec);
  if (ec) throw InputError("cannot create " + outDir + ": " + ec.message());
  const Scene scene = loadScene(kDefaultScene);
  std::ofstream html(fs::path(outDir) / "report.html");
  html << "<!doctype html><meta charset=utf-8><title>shadowlab report</title><h1>shadowlab</h1>\n";
  int i = 0;
  const auto& all = allTechniques();
  for (const Technique& t : all) {
    if (progress) std::cerr << "[" << ++i << "/" << all.size() << "] " << t.name << "\n";
    const Frame f = renderTechnique(t, scene, RenderParams{});
    writePng((fs::path(outDir) / (t.name + ".png")).string(), f.color);
    writePng((fs::path(outDir) / (t.name + "-mask.png")).string(), f.visibility, 16);
    html << "<figure><img src=\"" << t.name << ".png\"><figcaption>" << t.name << " ("
         << f.totalMilliseconds() << " ms)</figcaption></figure>\n";
  }
  std::cout << "wrote " << (fs::path(outDir) / "report.html").string() << "\n";
  return 0;
}

int runBench(const cli::Args& args) { return runBenchCommand(args); }  // figures/bench.cpp
int runPlan(const cli::Args& args) { return runPlanCommand(args); }    // figures/plan.cpp

}  // namespace sl::figures
