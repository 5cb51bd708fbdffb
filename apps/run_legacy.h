// apps/run_legacy.h — `shadowlab run-legacy`: an unchanged GLUT program with the drop-in
// imaging library, its frames as PNG (apps/run_legacy.cpp, docs/legacy-programs.md).
#pragma once

namespace sl {

// argv[0] is "run-legacy". Returns the program's exit status; throws InputError / GlError.
int runLegacy(int argc, char** argv);

}  // namespace sl
