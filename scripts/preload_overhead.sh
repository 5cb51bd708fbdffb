#!/usr/bin/env bash
# scripts/preload_overhead.sh [BUILD_DIR] — what libshadowlab-imaging.so costs a program that
# draws a lot and uses no imaging (tools/preload_overhead.c on Debian's OSMesa): runs with and
# without LD_PRELOAD, alternating, best of ROUNDS each, and prints both times and their ratio.
# A benchmark, not a test: the ratio is read from one run on one machine.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build=${1:-$root/build}
library=$build/lib/libshadowlab-imaging.so
frames=${FRAMES:-40}
objects=${OBJECTS:-4000}
rounds=${ROUNDS:-5}
if [[ ! -f $library ]]; then
  echo "preload_overhead.sh: $library is missing (cmake --build build --target shadowlab-imaging)" >&2
  exit 2
fi
bench=$build/bin/preload_overhead
mkdir -p "$build/bin"
cc -O2 -o "$bench" "$root/tools/preload_overhead.c" $(pkg-config --cflags --libs osmesa)
best_plain=""
best_preloaded=""
for ((r = 0; r < rounds; ++r)); do
  plain=$("$bench" "$frames" "$objects" | awk '{print $2}')
  preloaded=$(LD_PRELOAD=$library "$bench" "$frames" "$objects" | awk '{print $2}')
  best_plain=$(awk -v a="$plain" -v b="${best_plain:-$plain}" 'BEGIN{print (a < b ? a : b)}')
  best_preloaded=$(awk -v a="$preloaded" -v b="${best_preloaded:-$preloaded}" 'BEGIN{print (a < b ? a : b)}')
done
commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
echo "preload_overhead: $objects objects x $frames frames, best of $rounds, commit $commit"
echo "without the library: $best_plain ms/frame"
echo "with the library:    $best_preloaded ms/frame"
awk -v a="$best_plain" -v b="$best_preloaded" 'BEGIN{printf "overhead: %+.2f%%\n", (b / a - 1) * 100}'
