#include "figures/plan.h"

#include <iostream>

#include "core/scene/scene_library.h"
#include "core/technique/plan.h"
#include "registry/registry.h"

namespace sl::figures {

int runPlanCommand(const cli::Args& args) {
  Scene scene = loadScene(args.value("scene").value_or(kDefaultScene));
  cli::viewScene(args, scene);
  const Technique& technique = findTechnique(args.required("technique"));
  const RenderParams params = cli::renderParams(args);
  checkRenderable(technique, params);  // render's checks, the GL's limits included
  std::cout << formatPlan(planFrame(scene, technique, params));
  return 0;
}

}  // namespace sl::figures
