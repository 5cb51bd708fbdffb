#!/usr/bin/env bash
# scripts/build.sh [TARGET...] — configures (Release) and builds into build/: every target
# (the program, the developer tools and the test suites), or only the TARGETs named
# (scripts/main.sh builds `shadowlab`, the one program the main job runs, and the Python module).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset release >/dev/null
if [[ $# -gt 0 ]]; then
  targets=()
  for t in "$@"; do targets+=(--target "$t"); done
  cmake --build build -j"$(nproc)" "${targets[@]}"
else
  cmake --build build -j"$(nproc)"
fi
