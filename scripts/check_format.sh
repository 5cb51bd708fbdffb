#!/usr/bin/env bash
# scripts/check_format.sh — every C and C++ file git knows is formatted as .clang-format says.
# With --fix it formats them in place instead. ctest runs the check as style.clang_format.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format >/dev/null || { echo "check_format.sh: clang-format is not installed (scripts/setup.sh installs it)" >&2; exit 2; }
mapfile -t files < <(git ls-files '*.c' '*.cpp' '*.h' '*.hpp')
if [[ ${1:-} == --fix ]]; then
  clang-format -i "${files[@]}"
  exit 0
fi
# --dry-run -Werror names each file and line that differs, and exits non-zero on the first file.
if ! clang-format --dry-run -Werror "${files[@]}"; then
  echo "check_format.sh: files above are not formatted; run: bash scripts/check_format.sh --fix" >&2
  exit 1
fi
echo "check_format.sh: ${#files[@]} files formatted as .clang-format says"
