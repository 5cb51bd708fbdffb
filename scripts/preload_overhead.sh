#!/usr/bin/env bash
# scripts/preload_overhead.sh [BUILD_DIR] — what libshadowlab-imaging.so costs a program that
# draws a lot and uses no imaging (tools/preload_overhead.c on Debian's OSMesa: per object a
# matrix push, translate, rotate, enable or disable, a short glBegin/glEnd run and a pop;
# five of those calls go through the library). Prints a markdown table:
#   * time: ROUNDS rounds, each one run without and one with LD_PRELOAD back to back (the
#     order alternates between rounds, so that neither side always runs first); wall time
#     and the process's CPU time per frame (on a shared machine wall time also counts the wait
#     for a core), best of each side, and the median of the rounds' own with/without ratios
#     (each pair ran seconds apart, so a change in the machine's load hits both alike);
#   * instructions: when valgrind is installed, the instructions executed in the timed frames
#     (callgrind, --toggle-collect=timed_frames), llvmpipe on the program's own thread
#     (LP_NUM_THREADS=0) so that all the frame's work is counted: the same on a quiet and on
#     a loaded machine.
# A benchmark, not a test: the numbers are read from one run on one machine; the load average
# before and after is printed with them (scripts/perf_tables.sh preload-overhead writes the
# table into docs/legacy-programs.md).
# Environment: FRAMES (40), OBJECTS (4000), ROUNDS (9), COUNTED_FRAMES (2), INSTRUCTIONS (1:
# count them when valgrind is there; 0: do not).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build=${1:-$root/build}
library=$build/lib/libshadowlab-imaging.so
frames=${FRAMES:-40}
objects=${OBJECTS:-4000}
rounds=${ROUNDS:-9}
counted_frames=${COUNTED_FRAMES:-2}
if [[ ! -f $library ]]; then
  echo "preload_overhead.sh: $library is missing (cmake --build build --target shadowlab-imaging)" >&2
  exit 2
fi
bench=$build/bin/preload_overhead
mkdir -p "$build/bin"
cc -O2 -g -o "$bench" "$root/tools/preload_overhead.c" $(pkg-config --cflags --libs osmesa)

wall_plain=() wall_preloaded=() wall_ratios=()
cpu_plain=() cpu_preloaded=() cpu_ratios=()
plain() { "$bench" "$frames" "$objects"; }
preloaded() { LD_PRELOAD=$library "$bench" "$frames" "$objects"; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN{printf "%.6f", b / a}'; }
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
for ((r = 0; r < rounds; ++r)); do
  if ((r % 2 == 0)); then
    a=$(plain)
    b=$(preloaded)
  else
    b=$(preloaded)
    a=$(plain)
  fi
  # "ms_per_frame WALL cpu_ms_per_frame CPU"
  read -r _ aw _ ac <<<"$a"
  read -r _ bw _ bc <<<"$b"
  wall_plain+=("$aw") wall_preloaded+=("$bw") wall_ratios+=("$(ratio "$aw" "$bw")")
  cpu_plain+=("$ac") cpu_preloaded+=("$bc") cpu_ratios+=("$(ratio "$ac" "$bc")")
  echo "round $((r + 1))/$rounds: without $aw ms wall $ac ms CPU, with $bw ms wall $bc ms CPU" >&2
done
load_after=$(cut -d' ' -f1-3 /proc/loadavg)

best() { printf '%s\n' "$@" | sort -g | head -1; }
median() {
  printf '%s\n' "$@" | sort -g |
    awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'
}
row() {  # LABEL WITHOUT WITH RATIO
  awk -v l="$1" -v a="$2" -v b="$3" -v r="$4" 'BEGIN{printf "| %s | %.3f | %.3f | %+.2f%% |\n", l, a, b, (r - 1) * 100}'
}

commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
echo "preload_overhead: $objects objects x $frames frames a run, $rounds rounds (one run without and one with the library each, order alternating); commit $commit; load average $load_before before, $load_after after"
echo
echo "| per frame | without the library | with the library | overhead |"
echo "| --- | --- | --- | --- |"
bp=$(best "${wall_plain[@]}") bq=$(best "${wall_preloaded[@]}")
row "wall ms, best of $rounds" "$bp" "$bq" "$(ratio "$bp" "$bq")"
row "wall ms, median; overhead: median of the rounds' ratios" \
  "$(median "${wall_plain[@]}")" "$(median "${wall_preloaded[@]}")" "$(median "${wall_ratios[@]}")"
bp=$(best "${cpu_plain[@]}") bq=$(best "${cpu_preloaded[@]}")
row "CPU ms, best of $rounds" "$bp" "$bq" "$(ratio "$bp" "$bq")"
row "CPU ms, median; overhead: median of the rounds' ratios" \
  "$(median "${cpu_plain[@]}")" "$(median "${cpu_preloaded[@]}")" "$(median "${cpu_ratios[@]}")"

if [[ ${INSTRUCTIONS:-1} != 0 ]] && command -v valgrind >/dev/null; then
  counted() {  # instructions in timed_frames, in millions per frame
    local out
    out=$(mktemp)
    env LP_NUM_THREADS=0 "$@" valgrind --tool=callgrind --toggle-collect=timed_frames \
      --callgrind-out-file="$out" "$bench" "$counted_frames" "$objects" 2>&1 >/dev/null |
      awk -v n="$counted_frames" '/Collected :/ {gsub(",", "", $4); printf "%.3f", $4 / n / 1e6}'
    rm -f "$out"
  }
  echo "counting instructions (valgrind, $counted_frames frames each)" >&2
  ip=$(counted)
  iq=$(counted LD_PRELOAD="$library")
  row "million instructions (callgrind, $counted_frames frames, llvmpipe on the program's thread)" \
    "$ip" "$iq" "$(ratio "$ip" "$iq")"
fi
