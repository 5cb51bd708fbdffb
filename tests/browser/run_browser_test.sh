#!/usr/bin/env bash
# tests/browser/run_browser_test.sh SHADOWLAB OUT — the ctest `browser.pages`:
# makes the pages a reader opens, then loads every one in headless Chromium
# (tests/browser/check_pages.mjs, puppeteer-core from npm, /usr/bin/chromium):
#   OUT/dumps/<technique>/index.html    render --dump-passes of every technique in `shadowlab list`
#   OUT/lessons/<technique>/index.html  shadowlab lesson of every technique
#   OUT/figures/report.html             figures --only two cheap figures, with the lessons the
#                                       report links (OUT/figures/lessons/*/index.html), which
#                                       link the figures back
# check_pages.mjs also checks every relative link and #fragment of every page, and the links
# between the report's figures and its lessons both ways.
# Small sizes keep it under a minute. Screenshots of every page: OUT/shots/.
# Exit 77 (ctest: skipped) without node or Chromium; 1 when tests/browser/node_modules is
# missing (scripts/setup.sh runs `npm ci` there).
set -euo pipefail
bin=$1
out=$(realpath -m "$2")
here=$(cd "$(dirname "$0")" && pwd)
chromium=${SHADOWLAB_CHROMIUM:-/usr/bin/chromium}
if ! command -v node >/dev/null || [[ ! -x $chromium ]]; then
  echo "browser test skipped: node or $chromium is not installed (scripts/setup.sh installs both)"
  exit 77
fi
if [[ ! -d $here/node_modules/puppeteer-core ]]; then
  echo "tests/browser/node_modules is missing: run scripts/setup.sh (or: cd tests/browser && npm ci)" >&2
  exit 1
fi

rm -rf "$out"
mkdir -p "$out/dumps" "$out/lessons"
techniques=$("$bin" list | awk '/^techniques:/ {f = 1; next} /^scenes:/ {f = 0} f && /^  [a-z]/ {print $1}')
[[ -n $techniques ]] || { echo "shadowlab list printed no technique" >&2; exit 1; }
# Small renders: what is checked (images load, cards present, no script error) does not depend
# on the size.
# Two jobs at a time (the dumps, then the report; the lessons), for the machine's two cores.
(
  for t in $techniques; do
    "$bin" render --technique "$t" --size 160x120 --out "$out/dumps/$t.png" \
      --dump-passes "$out/dumps/$t" >/dev/null
  done
  "$bin" figures --out "$out/figures" --only brabec-fig5-packing --only everitt-fig5 \
    --no-progress >/dev/null
) &
dumps=$!
for t in $techniques; do
  "$bin" lesson "$t" --out "$out/lessons/$t" --size 160x120 --shadow-map 128 >/dev/null
done
wait "$dumps"

mapfile -t pages < <(find "$out" -name index.html -o -name report.html | sort)
echo "checking ${#pages[@]} pages"
cd "$out"
node "$here/check_pages.mjs" --require-state-cards --shots "$out/shots" "${pages[@]}"
