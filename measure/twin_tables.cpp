// measure/twin_tables.cpp — the legacy/modern agreement table and the pairs' frame times
// (measure/twin_tables.h), as markdown on stdout.
#include "measure/twin_tables.h"

#include <cstdio>
#include <iostream>

#include "core/base/decimal.h"
#include "core/base/errors.h"
#include "core/scene/scene_library.h"
#include "core/technique/frame_timing.h"
#include "registry/registry.h"

namespace sl::measure::twin_tables {

void agreementTable(const Options& o) {
  std::cout << "### Agreement (" << backendName(o.backend) << ", " << o.width << "x" << o.height
            << ", " << o.shadowMap << "^2 map)\n\n"
            << "| pair | scene | bound | max difference | differing pixels | > 1/255 | "
               "> 1/255 off band | within bound | image: > 3/255 (where masks agree) | image: "
               "bound (cone-edge band) | image: max, RMSE | image within bound |\n"
            << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const twins::TwinPair& pair : twins::twinPairs())
    for (const std::string& name : o.scenes) {
      const Scene scene = loadScene(name);
      const RenderParams pl =
          twins::paramsFor(pair, true, o.width, o.height, o.shadowMap, o.backend);
      const RenderParams pm =
          twins::paramsFor(pair, false, o.width, o.height, o.shadowMap, o.backend);
      std::cout << "| " << pair.label << " | " << name << " | "
                << (pair.faithful ? "faithful (ties only)" : "1/255, band") << " | ";
      try {
        if (const std::string why = twins::unavailablePrecision(pair, pl); !why.empty())
          throw InputError(why);
        const Frame legacy = renderTechnique(findTechnique(pair.legacy), scene, pl);
        const Frame modern = renderTechnique(findTechnique(pair.modern), scene, pm);
        const twins::Agreement a = twins::judge(pair, legacy.visibility, modern.visibility);
        std::cout << fixedDecimals(a.all.maxAbs, 4) << " ("
                  << fixedDecimals(a.all.maxAbs * 255.0, 1) << "/255) | " << a.differing << " of "
                  << a.all.pixels << " | " << a.beyondOneStep << " | " << a.beyondOutsideBand
                  << " | " << (a.withinBound ? "yes" : "**no**") << " | ";
        const twins::ImageAgreement im =
            twins::judgeImages(legacy.color, modern.color, legacy.visibility, modern.visibility);
        std::cout << im.beyondSteps << " (" << im.beyondWhereMasksAgree << ") | " << im.boundPixels
                  << " | " << fixedDecimals(im.maxAbs, 3) << ", " << fixedDecimals(im.rmse, 4)
                  << " | " << (im.withinBound ? "yes" : "**no**") << " |\n";
      } catch (const std::exception& e) {
        std::cout << "not run: " << e.what() << " | | | | | | | | |\n";
      }
    }
  for (const std::string& m : twins::missingPairs()) std::cout << "\nnot in this build: " << m;
  std::cout << "\n";
}

void benchTable(const Options& o) {
  std::cout << "### Frame time (" << backendName(o.backend) << ", " << o.benchScene << ", "
            << o.benchWidth << "x" << o.benchHeight << ", " << o.benchShadowMap << "^2 map, "
            << o.frames << " frames each after " << kWarmupFrames << " warm-up)\n\n"
            << "| pair | legacy ms (median / min) | modern ms (median / min) | legacy / modern "
               "(medians) | legacy / modern (minima) |\n| --- | --- | --- | --- | --- |\n";
  const Scene scene = loadScene(o.benchScene);
  for (const twins::TwinPair& pair : twins::twinPairs()) {
    std::cout << "| " << pair.label << " | ";
    try {
      const RenderParams pl =
          twins::paramsFor(pair, true, o.benchWidth, o.benchHeight, o.benchShadowMap, o.backend);
      if (const std::string why = twins::unavailablePrecision(pair, pl); !why.empty())
        throw InputError(why);
      const twins::FrameTimes legacy =
          twins::frameMilliseconds(findTechnique(pair.legacy), scene, pl, o.frames);
      const twins::FrameTimes modern = twins::frameMilliseconds(
          findTechnique(pair.modern), scene,
          twins::paramsFor(pair, false, o.benchWidth, o.benchHeight, o.benchShadowMap, o.backend),
          o.frames);
      std::cout << fixedDecimals(legacy.median, 1) << " / " << fixedDecimals(legacy.minimum, 1)
                << " | " << fixedDecimals(modern.median, 1) << " / "
                << fixedDecimals(modern.minimum, 1) << " | "
                << fixedDecimals(legacy.median / modern.median, 2) << " | "
                << fixedDecimals(legacy.minimum / modern.minimum, 2) << " |\n";
    } catch (const std::exception& e) {
      std::cout << "not run: " << e.what() << " | | |\n";
    }
    std::cout.flush();
  }
}

}  // namespace sl::measure::twin_tables
