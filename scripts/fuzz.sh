#!/usr/bin/env bash
# scripts/fuzz.sh [SECONDS] [TARGET...] — coverage-guided fuzzing of the input loaders with
# libFuzzer: the targets of tests/fuzz/targets (scene_file: the scene-file loader; mesh: the
# OBJ/PLY/.gz mesh loaders; lab_request: the lab's request parser, see below), built with clang,
# -fsanitize=fuzzer,address,undefined in build-fuzz/ (CMake option SHADOWLAB_FUZZ; only the
# targets and the libraries they link), each run for SECONDS (default 600) on a copy of its
# corpus (tests/fuzz/corpus/<target>/) with a 10 s limit per input. Fails when a target crashes,
# leaks, hangs, runs out of memory, throws anything but InputError or a sanitizer reports: the
# input that did it is left in build-fuzz/fuzz-runs/<target>/ (crash-*, leak-*, timeout-*,
# oom-*); add it to the corpus once fixed (tests/fuzz replays the corpus in every build).
# FUZZ_MERGE=1: afterwards, the inputs the run found that add coverage are merged into the
# repository's corpus (libFuzzer -merge=1). FUZZ_DOC=1: the runs' numbers (each target's last
# run in build-fuzz/fuzz-runs/) replace docs/validation.md's generated block fuzz-runs. Installs clang with apt-get when it is missing
# (as scripts/setup.sh does for its packages). docs/validation.md "Fuzzing".
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-600}
shift || true
targets=("$@")
# lab_request (the lab's request parser) is left out by default: it links the whole renderer,
# and imaging/color_matrix_groups.cpp uses GCC's __builtin_shuffle, which clang lacks; its
# corpus is replayed by tests/fuzz in the gcc and sanitizer builds.
[[ ${#targets[@]} -gt 0 ]] || targets=(scene_file mesh)
# Per-input limit (s): the seeds load in milliseconds; a hang is a finding.
per_input_timeout=10
# Memory limit (MB) of a fuzzing process: the mesh caps (core/scene/mesh_io.h) bound any one
# file well below it.
rss_limit_mb=4096
# Most inputs one FUZZ_MERGE adds to a target's corpus (the replay test runs them all).
max_merged_inputs=40

if ! command -v clang++ >/dev/null 2>&1; then
  if [[ $(id -u) -ne 0 ]]; then
    echo "scripts/fuzz.sh needs clang (libFuzzer); run as root: apt-get install -y clang" >&2
    exit 1
  fi
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq clang >/dev/null
fi

CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSHADOWLAB_FUZZ=ON -DSHADOWLAB_BUILD_TESTS=OFF >/dev/null
build_targets=()
for t in "${targets[@]}"; do build_targets+=(--target "${t}_fuzz"); done
cmake --build build-fuzz -j"$(nproc)" "${build_targets[@]}"

failed=0
for t in "${targets[@]}"; do
  run_dir=build-fuzz/fuzz-runs/$t
  rm -rf "$run_dir"
  mkdir -p "$run_dir/corpus"
  seeds=$(find "tests/fuzz/corpus/$t" -type f | wc -l)
  started="$(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores ($(sed -n 's/^model name\s*: //p' \
    /proc/cpuinfo | head -1)), load average $(cut -d' ' -f1 /proc/loadavg) at the start"
  echo "== $t: ${seconds} s from $seeds corpus files; $started"
  status=0
  # New inputs go to the run's own corpus directory (the first); the repository's is read only.
  "build-fuzz/bin/${t}_fuzz" -max_total_time="$seconds" -timeout="$per_input_timeout" \
    -rss_limit_mb="$rss_limit_mb" -print_final_stats=1 -artifact_prefix="$run_dir/" \
    "$run_dir/corpus" "tests/fuzz/corpus/$t" >"$run_dir/log.txt" 2>&1 || status=$?
  grep -E '^#[0-9]+[[:space:]]+(INITED|DONE)' "$run_dir/log.txt" | sed "s/^/$t: /"
  grep -E '^stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb)' "$run_dir/log.txt" |
    sed "s/^/$t: /"
  kept=$(find "$run_dir/corpus" -type f | wc -l)
  echo "$t: new inputs kept: $kept"
  # libFuzzer's last status line: "#RUNS DONE cov: C ft: F corp: N/SIZE ... exec/s: E rss: MMb".
  done_line=$(grep -E '^#[0-9]+[[:space:]]+DONE' "$run_dir/log.txt" | tail -1 || true)
  field() { sed -nE "s#.* $1: ([^ ]+).*#\1#p" <<<"$done_line"; }
  printf -- '- `%s`: %s s, %s; %s inputs run (%s/s), coverage %s edges and %s features, %s\n' \
    "$t" "$seconds" "$started" "$(sed -nE 's/^#([0-9]+).*/\1/p' <<<"$done_line")" \
    "$(field 'exec/s')" "$(field cov)" "$(field ft)" \
    "corpus of $seeds files grown by $kept inputs, peak memory $(field rss)" \
    >"$run_dir/summary.md"
  artifacts=$(find "$run_dir" -maxdepth 1 -type f \( -name 'crash-*' -o -name 'leak-*' -o \
    -name 'timeout-*' -o -name 'oom-*' \) | wc -l)
  if [[ $status -ne 0 || $artifacts -ne 0 ]]; then
    echo "$t: FAILED (exit $status); log and input: $run_dir/" >&2
    grep -E 'ERROR|runtime error|terminate|what\(\)' "$run_dir/log.txt" | head -5 >&2 || true
    echo "  findings: $artifacts (exit status $status)" >>"$run_dir/summary.md"
    failed=1
    continue
  fi
  echo "  nothing found (no crash, leak, hang, out-of-memory or sanitizer report)" \
    >>"$run_dir/summary.md"
  if [[ ${FUZZ_MERGE:-0} == 1 ]]; then
    # A set cover of the run's inputs over the corpus's edges (not hit counts or comparisons),
    # of which the smallest max_merged_inputs join the repository's corpus.
    merged=$run_dir/merged
    rm -rf "$merged" && mkdir -p "$merged" && cp "tests/fuzz/corpus/$t"/* "$merged/"
    "build-fuzz/bin/${t}_fuzz" -set_cover_merge=1 -use_counters=0 -use_cmp=0 \
      -timeout="$per_input_timeout" "$merged" "$run_dir/corpus" >"$run_dir/merge.txt" 2>&1
    (cd "$merged" && find . -type f -printf '%s %f\n' | sort -n | cut -d' ' -f2) |
      while read -r f; do [[ -e "tests/fuzz/corpus/$t/$f" ]] || echo "$f"; done |
      head -n "$max_merged_inputs" | while read -r f; do cp "$merged/$f" "tests/fuzz/corpus/$t/"; done
    echo "$t: corpus after merge: $(find "tests/fuzz/corpus/$t" -type f | wc -l) files"
  fi
done
if [[ ${FUZZ_DOC:-0} == 1 ]]; then
  python3 - <<'PY'
import pathlib, re
runs = pathlib.Path("build-fuzz/fuzz-runs")
lines = [(runs / t / "summary.md").read_text()
         for t in ("scene_file", "mesh", "lab_request") if (runs / t / "summary.md").exists()]
doc = pathlib.Path("docs/validation.md")
block = "<!-- fuzz-runs:begin -->\n" + "".join(lines) + "<!-- fuzz-runs:end -->"
doc.write_text(re.sub(r"<!-- fuzz-runs:begin -->.*?<!-- fuzz-runs:end -->", lambda m: block,
                      doc.read_text(), flags=re.S))
PY
fi
exit $failed
