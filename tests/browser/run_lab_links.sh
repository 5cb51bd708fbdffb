#!/usr/bin/env bash
# tests/browser/run_lab_links.sh SHADOWLAB OUT — the ctest `browser.lab_links`: writes the
# artefact gallery (shadowlab gallery --out OUT) and loads it (check_pages.mjs: every picture
# loads, no console error), then opens every one of its lab links and the lab's URL round trip
# in headless Chromium (lab_links.mjs). Screenshots: OUT/shots/.
# Exit 77 (ctest: skipped) only when node or Debian's chromium is absent; a missing
# node_modules is a failure: scripts/setup.sh installs it with `npm ci`.
set -euo pipefail
bin=$1
out=$(realpath -m "$2")
here="$(cd "$(dirname "$0")" && pwd)"
if ! command -v node >/dev/null 2>&1; then echo "SKIP: node is not installed"; exit 77; fi
if [[ ! -x /usr/bin/chromium ]]; then echo "SKIP: /usr/bin/chromium is not installed"; exit 77; fi
if [[ ! -d "$here/node_modules/puppeteer-core" ]]; then
  echo "tests/browser/node_modules is missing: run scripts/setup.sh (npm ci in tests/browser)" >&2
  exit 1
fi
mkdir -p "$out"
"$bin" gallery --out "$out"
# The gallery page itself: every picture loads, no console error (check_pages.mjs).
(cd "$out" && node "$here/check_pages.mjs" --shots "$out/shots" gallery/index.html)
SHADOWLAB_BINARY="$bin" SHADOWLAB_SCREENSHOT_DIR="$out/shots" exec node "$here/lab_links.mjs" "$out/gallery"
