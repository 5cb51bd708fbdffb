#!/usr/bin/env bash
# scripts/perf_tables.sh [--list] [ID...] — re-measures every performance table in docs/
# (docs/performance.md lists them all) and writes each into its place, so that no number in
# them is typed by hand.
#
# A table lives between two marker lines in a markdown file:
#   <!-- perf-table ID -->
#   ...everything here is replaced...
#   <!-- /perf-table ID -->
# The table list below names, for each ID, the file and the command. Each table is written with
# the command, the commit, the date and the load average before and after its run (these
# machines are shared: the benchmarks interleave their configurations and report ratios within
# one run, and the load says how much to trust the absolute times). Every ID whose markers are
# missing is an error (exit 2): a table is never silently skipped.
#
#   scripts/perf_tables.sh            every table (builds the tools first; ~15-25 min)
#   scripts/perf_tables.sh ID...      only these tables
#   scripts/perf_tables.sh --list     the IDs, files and commands
set -euo pipefail
cd "$(dirname "$0")/.."

# ID | files | command (run from the repository root). A file written as FILE:first receives
# only the command's first paragraph and first table (the summary); other files get it all.
TABLES=(
  "legacy|docs/performance.md:first docs/legacy.md|build/bin/legacy_bench --frames 9"
  "legacy-split|docs/legacy.md|build/bin/legacy_bench --split-cost --frames 9"
  "legacy-profile|docs/legacy.md|scripts/legacy_profile.sh"
  "legacy-reference|docs/legacy.md:first|build/bin/legacy_bench --backend reference --frames 9"
  "twins-time|docs/performance.md|build/bin/shadowlab-twins --no-agreement --frames 7"
  "imaging|docs/imaging.md|build/bin/imaging_bench"
  "csm-ratio|docs/csm.md|build/bin/csm_bench --part ratio"
  "csm-table1|docs/csm.md|build/bin/csm_bench --part table1 --quick"
  "volumes|docs/volumes.md|build/bin/volumes_bench --scene fill-bound --shadow-map 256"
  "lab-latency|docs/performance.md|build/bin/lab_bench --requests 20 --burst 8"
  "preload-overhead|docs/legacy-programs.md|scripts/preload_overhead.sh"
)
TOOLS=(shadowlab legacy_bench imaging_bench csm_bench volumes_bench shadowlab-twins lab_bench
  shadowlab-imaging)

die() { echo "perf_tables.sh: $*" >&2; exit 2; }
field() { local IFS='|'; read -r -a parts <<<"$1"; echo "${parts[$2]}"; }

if [[ "${1:-}" == "--list" ]]; then
  for t in "${TABLES[@]}"; do
    printf '%-16s %-18s %s\n' "$(field "$t" 0)" "$(field "$t" 1)" "$(field "$t" 2)"
  done
  exit 0
fi

# The tables asked for (all by default); an unknown ID is an error before anything runs.
selected=()
if [[ $# -eq 0 ]]; then
  selected=("${TABLES[@]}")
else
  for id in "$@"; do
    found=""
    for t in "${TABLES[@]}"; do [[ "$(field "$t" 0)" == "$id" ]] && found="$t"; done
    [[ -n "$found" ]] || die "unknown table '$id' (scripts/perf_tables.sh --list names them)"
    selected+=("$found")
  done
fi
for t in "${selected[@]}"; do
  id=$(field "$t" 0)
  for spec in $(field "$t" 1); do
    file=${spec%:first}
    grep -qx "<!-- perf-table $id -->" "$file" || die "$file has no '<!-- perf-table $id -->' line"
    grep -qx "<!-- /perf-table $id -->" "$file" || die "$file has no '<!-- /perf-table $id -->' line"
  done
done

scripts/build.sh "${TOOLS[@]}" >/dev/null
commit=$(git rev-parse --short HEAD)
git diff --quiet HEAD -- . ':(exclude)README.md' ':(exclude)docs' || commit="$commit+local changes"
load() { cut -d' ' -f1-3 /proc/loadavg; }

# The first paragraph and the first table of a command's output (the summary).
first_table() { awk 'started && /^\|/ { in_table = 1 } in_table && !/^\|/ { exit } { print } /./ { started = 1 }' "$1"; }

# Replaces the lines between FILE's markers of ID (inclusive) by BLOCKFILE.
replace_block() {
  local file=$1 id=$2 blockfile=$3
  awk -v id="$id" -v blockfile="$blockfile" '
    $0 == "<!-- perf-table " id " -->" { while ((getline line < blockfile) > 0) print line; skip = 1; next }
    $0 == "<!-- /perf-table " id " -->" { skip = 0; next }
    !skip { print }
  ' "$file" >"$file.perf-tmp"
  mv "$file.perf-tmp" "$file"
}

for t in "${selected[@]}"; do
  id=$(field "$t" 0) files=$(field "$t" 1) command=$(field "$t" 2)
  echo "== $id: $command" >&2
  body=$(mktemp) part=$(mktemp) block=$(mktemp)
  before=$(load)
  # The command's own output is the table (markdown); its stderr shows progress.
  if ! $command >"$body"; then
    rm -f "$body" "$part" "$block"
    die "'$command' failed; $files unchanged"
  fi
  after=$(load)
  for spec in $files; do
    file=${spec%:first}
    if [[ "$spec" == *:first ]]; then first_table "$body" >"$part"; else cp "$body" "$part"; fi
    # JSON lines (volumes_bench) are shown as they are, in a code block.
    if grep -m1 . "$part" | grep -q '^{'; then
      { echo '```json'; cat "$part"; echo '```'; } >"$part.fenced" && mv "$part.fenced" "$part"
    fi
    {
      echo "<!-- perf-table $id -->"
      echo "\`$command\` (commit $commit, $(date -u +%Y-%m-%d), $(nproc) cores; load average" \
           "$before before, $after after; written by \`scripts/perf_tables.sh $id\`):"
      echo
      cat "$part"
      echo
      echo "<!-- /perf-table $id -->"
    } >"$block"
    replace_block "$file" "$id" "$block"
  done
  rm -f "$body" "$part" "$block"
done
echo "perf_tables.sh: ${#selected[@]} table(s) written; review with git diff" >&2
