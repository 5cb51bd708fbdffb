#!/usr/bin/env bash
# scripts/preload_overhead.sh [BUILD_DIR] — what libshadowlab-imaging.so costs a program that
# draws a lot and uses no imaging (tools/preload_overhead.c on Debian's OSMesa): ROUNDS rounds,
# each one run without and one with LD_PRELOAD, back to back (the order alternates between
# rounds, so that neither side always runs first); prints a markdown table of the best and the
# median frame time of each side, and the overhead two ways: best against best, and the
# median of the rounds' own with/without ratios (each pair ran a few seconds apart, so a
# change in the machine's load hits both sides of a pair alike).
# A benchmark, not a test: the ratio is read from one run on one machine; the load average
# before and after is printed with it (scripts/perf_tables.sh preload-overhead writes it into
# docs/legacy-programs.md).
# Environment: FRAMES (40), OBJECTS (4000), ROUNDS (9).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build=${1:-$root/build}
library=$build/lib/libshadowlab-imaging.so
frames=${FRAMES:-40}
objects=${OBJECTS:-4000}
rounds=${ROUNDS:-9}
if [[ ! -f $library ]]; then
  echo "preload_overhead.sh: $library is missing (cmake --build build --target shadowlab-imaging)" >&2
  exit 2
fi
bench=$build/bin/preload_overhead
mkdir -p "$build/bin"
cc -O2 -o "$bench" "$root/tools/preload_overhead.c" $(pkg-config --cflags --libs osmesa)
plain_times=()
preloaded_times=()
ratios=()
plain() { "$bench" "$frames" "$objects" | awk '{print $2}'; }
preloaded() { LD_PRELOAD=$library "$bench" "$frames" "$objects" | awk '{print $2}'; }
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
for ((r = 0; r < rounds; ++r)); do
  if ((r % 2 == 0)); then
    a=$(plain)
    b=$(preloaded)
  else
    b=$(preloaded)
    a=$(plain)
  fi
  plain_times+=("$a")
  preloaded_times+=("$b")
  ratios+=("$(awk -v a="$a" -v b="$b" 'BEGIN{printf "%.6f", b / a}')")
  echo "round $((r + 1))/$rounds: without $a ms, with $b ms" >&2
done
load_after=$(cut -d' ' -f1-3 /proc/loadavg)
best() { printf '%s\n' "$@" | sort -g | head -1; }
median() { printf '%s\n' "$@" | sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
best_plain=$(best "${plain_times[@]}")
best_preloaded=$(best "${preloaded_times[@]}")
echo "preload_overhead: $objects objects x $frames frames a run, $rounds rounds (one run without and one with the library each, order alternating), wall time per frame; commit $commit; load average $load_before before, $load_after after"
echo
echo "| | without the library | with the library | overhead |"
echo "| --- | --- | --- | --- |"
awk -v a="$best_plain" -v b="$best_preloaded" \
  'BEGIN{printf "| best of %d (ms/frame) | %.3f | %.3f | %+.2f%% |\n", '"$rounds"', a, b, (b / a - 1) * 100}'
awk -v a="$(median "${plain_times[@]}")" -v b="$(median "${preloaded_times[@]}")" \
  -v r="$(median "${ratios[@]}")" \
  'BEGIN{printf "| median (ms/frame); overhead: median of the rounds'"'"' ratios | %.3f | %.3f | %+.2f%% |\n", a, b, (r - 1) * 100}'
