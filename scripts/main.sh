#!/usr/bin/env bash
# scripts/main.sh — the main job: set up, build, render every figure and the report.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh shadowlab   # only the program this job runs (the tests build in scripts/test.sh)
build/bin/shadowlab figures --out out/figures "$@"
