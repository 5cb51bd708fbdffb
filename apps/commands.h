// apps/commands.h — the shadowlab command's own handlers, one file per command family beside
// apps/shadowlab.cpp (which parses the command line and dispatches): list (cmd_list.cpp),
// render and compare (cmd_render.cpp), exercise
// (cmd_exercise.cpp). The other commands live in their rooms (figures/, lab/,
// measure/ via figures/) and in apps/run_legacy.cpp.
#pragma once

#include "registry/cli.h"

namespace sl {

// `shadowlab list`: techniques with their --param keys, scenes, figures.
int list();
// `shadowlab render`: one frame to PNG (and --mask, --dump-passes), its JSON line on stdout.
int render(const cli::Args& args);
// `shadowlab compare`: two techniques on one scene, the difference of their masks.
int compare(const cli::Args& args);
// `shadowlab exercise list|show|start|grade ...` (cmd_exercise.cpp, teach/exercise.h): argv
// from "exercise" on; parsed here, as its subcommands take positional arguments.
int exercise(int argc, char** argv);

}  // namespace sl
