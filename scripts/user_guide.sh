#!/usr/bin/env bash
# scripts/user_guide.sh [--check] — writes the generated parts of docs/user-guide.md from the
# built binary, so that no option, default or column in the guide is typed by hand.
#
# A generated part lives between two marker lines:
#   <!-- generated:ID -->
#   ...everything here is replaced...
#   <!-- /generated:ID -->
# IDs: help-main and help-COMMAND (`shadowlab [COMMAND] --help`), list (`shadowlab list`), and,
# from small runs written under build/user-guide/: render-json, compare-json, passes-json,
# png-text, bench-csv.
#
#   scripts/user_guide.sh           every part (needs build/bin/shadowlab; about a minute)
#   scripts/user_guide.sh --check   only the --help and list parts, compared with the guide;
#                                   exit 1 when they differ (the CTest docs.user_guide_help)
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${SHADOWLAB_BINARY:-build/bin/shadowlab}
guide=docs/user-guide.md
[[ -x $bin ]] || { echo "user_guide.sh: build first (scripts/build.sh shadowlab)" >&2; exit 2; }
check=""
[[ "${1:-}" == "--check" ]] && check=1

commands=(list render compare bench plan figures lesson serve gallery course exercise run-legacy)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

fenced() { echo '```'; cat; echo '```'; }
"$bin" --help | fenced >"$tmp/help-main"
for c in "${commands[@]}"; do "$bin" "$c" --help | fenced >"$tmp/help-$c"; done
"$bin" list | fenced >"$tmp/list"
help_ids=(help-main "${commands[@]/#/help-}" list)

# Replaces the lines between GUIDE's markers of ID by the file $tmp/ID.
replace_block() {
  local id=$1
  grep -qx "<!-- generated:$id -->" "$guide" || { echo "user_guide.sh: $guide has no marker $id" >&2; exit 2; }
  awk -v id="$id" -v blockfile="$tmp/$id" '
    $0 == "<!-- generated:" id " -->" { print; while ((getline line < blockfile) > 0) print line; skip = 1; next }
    $0 == "<!-- /generated:" id " -->" { skip = 0 }
    !skip { print }
  ' "$guide" >"$tmp/guide.new"
  cp "$tmp/guide.new" "$guide"
}

# The text between GUIDE's markers of ID.
current_block() {
  awk -v id="$1" '
    $0 == "<!-- /generated:" id " -->" { inside = 0 }
    inside { print }
    $0 == "<!-- generated:" id " -->" { inside = 1 }
  ' "$guide"
}

if [[ -n $check ]]; then
  status=0
  for id in "${help_ids[@]}"; do
    if ! diff -u <(current_block "$id") "$tmp/$id" >"$tmp/diff"; then
      echo "user_guide.sh: $guide part '$id' differs from the binary's output:" >&2
      cat "$tmp/diff" >&2
      status=1
    fi
  done
  [[ $status == 0 ]] || echo "user_guide.sh: run scripts/user_guide.sh to refresh the guide" >&2
  exit $status
fi

# Small runs whose output shows each format (written under build/user-guide/, kept for a look).
runs=build/user-guide
rm -rf "$runs" && mkdir -p "$runs"
"$bin" render --scene brabec --technique legacy.fast-pcf --size 160x120 --shadow-map 128 \
  --out "$runs/image.png" --mask "$runs/mask.png" --dump-passes "$runs/passes" >"$tmp/render.jsonl"
python3 -m json.tool <"$tmp/render.jsonl" | fenced >"$tmp/render-json"
"$bin" compare --scene brabec --size 160x120 --a modern.hw --b reference.hard --b-param pixel=area \
  | python3 -m json.tool | fenced >"$tmp/compare-json"
python3 - "$runs/passes/passes.json" <<'PY' | fenced >"$tmp/passes-json"
import json, sys
d = json.load(open(sys.argv[1]))
# One pass and one channel image in full, the rest elided.
d["passes"] = [p for p in d["passes"] if p["number"] == 3][:1]
for p in d["passes"]:
    p["state"] = p["state"][:4] + ["... (one object per GL call of the pass)"]
d["images"] = [i for i in d["images"] if "legend" in i][:1] + ["... (one object per PNG)"]
print(json.dumps(d, indent=2, ensure_ascii=False))
PY
python3 - "$runs/image.png" <<'PY' | fenced >"$tmp/png-text"
import sys, zlib, struct
data = open(sys.argv[1], "rb").read()[8:]
while data:
    n, kind = struct.unpack(">I4s", data[:8])
    body = data[8:8 + n]
    if kind == b"tEXt":
        key, _, value = body.partition(b"\0")
        print(f"{key.decode('latin-1')}: {value.decode('latin-1')}")
    data = data[12 + n:]
PY
"$bin" bench --quick --scene brabec --technique modern.hw --csv "$runs/bench.csv" \
  --out "$runs/bench" >/dev/null 2>&1
head -1 "$runs/bench.csv" | tr ',' '\n' | fenced >"$tmp/bench-csv"

for id in "${help_ids[@]}" render-json compare-json passes-json png-text bench-csv; do
  replace_block "$id"
done
echo "user_guide.sh: $guide written; review with git diff" >&2
