#!/usr/bin/env bash
# tests/browser/run_course.sh SHADOWLAB OUT — the ctest `browser.course`: writes the course
# (shadowlab course --out OUT/course), loads its pages, the gallery's and every lesson's
# (check_pages.mjs: every picture loads, no console error, every relative link names a file and
# its #fragment an id of the page it opens), then opens every lab link against
# `shadowlab serve` (course_links.mjs), and prints the course, the teacher's page and the gallery
# to PDF to count their pages (course_print.mjs). Screenshots: OUT/shots/.
# Exit 77 (ctest: skipped) only when node or Debian's chromium is absent; a missing
# node_modules is a failure: scripts/setup.sh installs it with `npm ci`.
set -euo pipefail
bin=$(realpath "$1")
out=$(realpath -m "$2")
here="$(cd "$(dirname "$0")" && pwd)"
if ! command -v node >/dev/null 2>&1; then echo "SKIP: node is not installed"; exit 77; fi
if [[ ! -x /usr/bin/chromium ]]; then echo "SKIP: /usr/bin/chromium is not installed"; exit 77; fi
if [[ ! -d "$here/node_modules/puppeteer-core" ]]; then
  echo "tests/browser/node_modules is missing: run scripts/setup.sh (npm ci in tests/browser)" >&2
  exit 1
fi
rm -rf "$out"
mkdir -p "$out"
"$bin" course --out "$out/course" --no-progress
cd "$out/course"
node "$here/check_pages.mjs" --shots "$out/shots" index.html teacher.html scope.html gallery/index.html lessons/*/index.html
node "$here/course_print.mjs" "$out/course"
SHADOWLAB_BINARY="$bin" exec node "$here/course_links.mjs" "$out/course"
