#!/usr/bin/env bash
# tests/browser/run_lab_page.sh — the ctest entry of the lab's end-to-end test (lab_page.mjs).
# Exit 77 (ctest: skipped) only when node or Debian's chromium is absent; a missing
# node_modules is a failure: scripts/setup.sh installs it with `npm ci`.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
if ! command -v node >/dev/null 2>&1; then echo "SKIP: node is not installed"; exit 77; fi
if [[ ! -x /usr/bin/chromium ]]; then echo "SKIP: /usr/bin/chromium is not installed"; exit 77; fi
if [[ ! -d "$here/node_modules/puppeteer-core" ]]; then
  echo "tests/browser/node_modules is missing: run scripts/setup.sh (npm ci in tests/browser)" >&2
  exit 1
fi
exec node "$here/lab_page.mjs"
