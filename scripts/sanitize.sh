#!/usr/bin/env bash
# scripts/sanitize.sh — the input-hardening suites (scene validation, mesh loading and its
# fuzz test, the command line's bad inputs and output guarantees, the stability cases, the live
# lab's API and its fuzz test of malformed requests, the libFuzzer targets' corpora replayed
# (tests/fuzz; the coverage-guided runs are scripts/fuzz.sh), the drop-in imaging library under
# the C clients on OSMesa: tests/interpose DropIn.*) built
# with AddressSanitizer + UndefinedBehaviorSanitizer (CMake preset asan, build-asan/) and run
# with ctest. Sized for CI: two cores, well under half an hour with the release build done.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset asan >/dev/null
cmake --build build-asan -j"$(nproc)" --target shadowlab lab_bench test_core test_apps test_stability test_lab \
  test_fuzz shadowlab-imaging test_interpose
# Only the suites above are built: the others' ctest entries would be "not found" here.
# reference.soft's stability cases are left out: 288 Embree rays a pixel take ~20 s each under
# ASan and exercise no input handling that reference.hard's cases do not.
# The stability matrix runs whole for the techniques whose C++ does work that depends on the
# case (legacy.*: the imaging emulation; reference.hard; modern.volumes, modern.hybrid and
# modern.smoothies: silhouettes and volumes built on the CPU). The shader techniques' C++ makes
# the same GL objects and sets the same uniforms on every case, so under ASan they run the cases
# that change sizes, ranges and geometry (map_1x1, map_2x2, degenerate_triangles, open_caster,
# scaled_1e6, scaled_1e_3, cone_160, near_far_1e_7, camera_near_far_1e_5,
# behind_and_around_light); the cases below only check their accuracy, which the release suite
# (scripts/test.sh) checks for every technique.
accuracy_cases='baseline|grazing80|grazing89|grazing89_9|dueling|contact|mirrored|distant_overhead_light'
accuracy_cases+='|scaled_1e4|near_far_1e_3|near_far_1e_6|ramp_8bit_limit|csm_order_64_8bit'
accuracy_cases+='|csm_order_64_float|vsm_zero_variance'
shader_techniques='modern_(hw|woo|second_depth|ramp|pcf|fast_pcf|gems16|gems4|csm|vsm|esm|evsm2'
shader_techniques+='|evsm4|msm|pcss)'
ctest --preset asan -j"$(nproc)" -L 'core|apps|stability|lab|fuzz' \
  -E "reference_soft|Stability[.]FiniteBoundedAndWithinErrorBound/(${accuracy_cases})__${shader_techniques}" "$@"
# The drop-in library preloaded into plain C programs (the sanitizer runtime first): only the
# OSMesa clients; the X and run-legacy cases preload their own libraries ahead of it.
ctest --preset asan -j"$(nproc)" -R '^interpose\.DropIn\.' "$@"
