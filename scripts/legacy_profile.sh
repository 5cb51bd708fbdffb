#!/usr/bin/env bash
# scripts/legacy_profile.sh [TECHNIQUE...] — where a legacy frame's CPU time goes, per pass:
# records build/bin/legacy_bench under perf (call graphs through DWARF) for each technique and
# prints scripts/legacy_profile.py's table of it (docs/legacy.md "Where the frame time goes";
# scripts/perf_tables.sh legacy-profile writes them there). Needs perf (Debian: linux-perf).
#   default techniques: legacy.ramp legacy.fast-pcf legacy.pcf
set -euo pipefail
cd "$(dirname "$0")/.."
command -v perf >/dev/null || { echo "legacy_profile.sh: perf not found (apt-get install linux-perf)" >&2; exit 2; }
[ -x build/bin/legacy_bench ] || { echo "legacy_profile.sh: build/bin/legacy_bench not built" >&2; exit 2; }
readonly kWarmupFrames=2 kTimedFrames=8  # legacy_bench's warm-up (frame_timing.h) and --frames
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
[ $# -gt 0 ] || set -- legacy.ramp legacy.fast-pcf legacy.pcf
for t in "$@"; do
  perf record -q --call-graph dwarf,16384 -o "$tmp/perf.data" \
    build/bin/legacy_bench --technique "$t" --frames "$kTimedFrames" >/dev/null 2>"$tmp/err" ||
    { cat "$tmp/err" >&2; exit 2; }
  echo "\`$t\` (the first variant legacy_bench times for it):"
  echo
  perf script -i "$tmp/perf.data" -F comm,tid,time,ip,sym,dso 2>/dev/null |
    python3 scripts/legacy_profile.py "$kWarmupFrames" "$kTimedFrames"
  echo
done
