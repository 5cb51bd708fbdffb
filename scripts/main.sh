#!/usr/bin/env bash
# scripts/main.sh — the main job: set up, build, render every figure and the report.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
# The program this job runs and the Python module (build/python); the tests build in
# scripts/test.sh.
scripts/build.sh shadowlab shadowlab_python
build/bin/shadowlab figures --out out/figures "$@"
