// figures/plan.h — `shadowlab plan --scene S --technique T`: prints the pass planner's result
// (core/technique/plan.h): the passes, light-pass objects and resources kept and left out, and why.
#pragma once

#include "registry/cli.h"

namespace sl::figures {

int runPlanCommand(const cli::Args& args);

}  // namespace sl::figures
