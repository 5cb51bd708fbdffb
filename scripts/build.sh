#!/usr/bin/env bash
# scripts/build.sh — configures (Release) and builds into build/.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset release >/dev/null
cmake --build build -j"$(nproc)"
