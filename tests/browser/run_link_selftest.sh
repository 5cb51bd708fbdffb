#!/usr/bin/env bash
# tests/browser/run_link_selftest.sh OUT — the ctest `browser.link_check`: the link check of
# check_pages.mjs (harness.mjs LinkChecker and the figure/lesson links both ways) on pages made
# here, broken on purpose, must fail with exactly the broken links named; the same pages
# mended must pass. The generated pages are checked by browser.pages, browser.course and
# browser.lab_links; this test shows that check can fail.
# Exit 77 (ctest: skipped) only when node or Debian's chromium is absent.
set -euo pipefail
out=$(realpath -m "$1")
here="$(cd "$(dirname "$0")" && pwd)"
if ! command -v node >/dev/null 2>&1; then echo "SKIP: node is not installed"; exit 77; fi
if [[ ! -x /usr/bin/chromium ]]; then echo "SKIP: /usr/bin/chromium is not installed"; exit 77; fi
if [[ ! -d "$here/node_modules/puppeteer-core" ]]; then
  echo "tests/browser/node_modules is missing: run scripts/setup.sh (npm ci in tests/browser)" >&2
  exit 1
fi
rm -rf "$out"

# pages DIR BROKEN: a page, a report with two figures and a lesson beside it; BROKEN=1 adds one
# fault of each kind the check knows.
pages() {
  local d=$1 broken=$2
  mkdir -p "$d/lessons/x"
  cat >"$d/b.html" <<'HTML'
<!doctype html><html><body><h1 id="there">b</h1></body></html>
HTML
  {
    echo '<!doctype html><html><body><h1 id="self">a</h1>'
    echo '<a href="b.html#there">ok</a> <a href="#self">ok</a> <a href="https://example.org/#x">absolute</a>'
    if [[ $broken == 1 ]]; then
      echo '<a href="b.html#nowhere">1</a> <a href="missing.html">2</a> <a href="#absent">3</a>'
    fi
    echo '</body></html>'
  } >"$d/a.html"
  {
    echo '<!doctype html><html><body>'
    echo '<article id="fig1"><p class=lessons><a class=lesson href="lessons/x/index.html">x</a></p></article>'
    if [[ $broken == 1 ]]; then
      echo '<article id="fig2"><p>no lesson</p></article>'  # 4: links no lesson, 5: not back
    else
      echo '<article id="fig2"><p class=lessons><a class=lesson href="lessons/x/index.html">x</a></p></article>'
    fi
    echo '</body></html>'
  } >"$d/report.html"
  {
    echo '<!doctype html><html><body><ul class="report-figures">'
    echo '<li><a href="../../report.html#fig1">fig1</a></li><li><a href="../../report.html#fig2">fig2</a></li>'
    echo '</ul></body></html>'
  } >"$d/lessons/x/index.html"
}

pages "$out/broken" 1
pages "$out/mended" 0
cd "$out/broken"
set +e
node "$here/check_pages.mjs" a.html b.html report.html lessons/x/index.html >"$out/broken.log" 2>&1
status=$?
set -e
cat "$out/broken.log"
[[ $status == 1 ]] || { echo "FAIL: the check passed (status $status) pages with broken links" >&2; exit 1; }
expected=(
  'a.html: link to #nowhere, which b.html does not have: b.html#nowhere'
  'a.html: link to a missing file: missing.html'
  'a.html: link to #absent, which a.html does not have: #absent'
  'report.html: figure fig2 links no lesson'
  'lessons/x/index.html: links ../../report.html#fig2, whose figure does not link this page back'
)
for line in "${expected[@]}"; do
  grep -qxF "$line" "$out/broken.log" || { echo "FAIL: not reported: $line" >&2; exit 1; }
done
grep -q "^4 pages, .* ${#expected[@]} failures" "$out/broken.log" ||
  { echo "FAIL: the check reported other failures than the ${#expected[@]} made" >&2; exit 1; }
cd "$out/mended"
node "$here/check_pages.mjs" a.html b.html report.html lessons/x/index.html
echo "link check: fails on each broken link, passes the mended pages"
