// apps/cmd_list.cpp — `shadowlab list`: techniques, scenes, figures (apps/commands.h).
#include <iostream>
#include <string>

#include "apps/commands.h"
#include "core/scene/scene_library.h"
#include "figures/figures.h"
#include "registry/registry.h"

namespace sl {

int list() {
  std::cout << "techniques:\n";
  for (const Technique& t : allTechniques()) {
    std::cout << "  " << t.name << std::string(t.name.size() < 22 ? 22 - t.name.size() : 1, ' ')
              << t.paper << " — " << t.summary << " [" << t.status << "]\n";
    for (const ParamSpec& p : t.params)
      std::cout << std::string(24, ' ') << "--param " << describeParam(p) << "\n";
  }
  std::cout << "scenes:\n";
  for (const std::string& s : builtinSceneNames()) std::cout << "  " << s << " (built in)\n";
  for (const std::string& s : sceneFileNames()) std::cout << "  " << s << " (assets/scenes)\n";
  std::cout << "figures:\n";
  for (const figures::FigureInfo& f : figures::listFigures())
    std::cout << "  " << f.id << "  " << f.title << "\n";
  return 0;
}

}  // namespace sl
