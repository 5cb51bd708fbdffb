#!/usr/bin/env bash
# scripts/build_legacy_client.sh SOURCE.c OUTDIR — builds an unchanged GLUT program (the Red
# Book's, as the Mesa demos ship them) into OUTDIR/NAME, NAME = SOURCE without .c.
# The two headers those programs include, glad/gl.h and glut_wrap.h, are the project's
# (interpose/include/); the program links Debian's freeglut and libGL (freeglut3-dev, from
# scripts/setup.sh). Run it with the imaging subset: shadowlab run-legacy (docs/legacy-programs.md).
# Exit status: 0 built, 2 bad arguments, 3 no compiler or no freeglut, else the compiler's.
set -euo pipefail

if [[ $# -ne 2 ]]; then
  echo "usage: $0 SOURCE.c OUTDIR" >&2
  exit 2
fi
source_file=$1
out_dir=$2
if [[ ! -f "$source_file" || "$source_file" != *.c ]]; then
  echo "build_legacy_client.sh: '$source_file' is not a C source file" >&2
  exit 2
fi
include_dir="$(cd "$(dirname "$0")/.." && pwd)/interpose/include"
cc=${CC:-cc}
if ! command -v "$cc" >/dev/null 2>&1; then
  echo "build_legacy_client.sh: no C compiler ($cc)" >&2
  exit 3
fi
if ! pkg-config --exists glut gl 2>/dev/null; then
  echo "build_legacy_client.sh: freeglut or libGL headers missing (scripts/setup.sh installs freeglut3-dev)" >&2
  exit 3
fi
name=$(basename "$source_file" .c)
mkdir -p "$out_dir"
# -w: the programs are 1990s C, built as they are; their warnings are not ours to fix.
# Built to a temporary name and renamed, so a failed build leaves no program behind.
tmp="$out_dir/.$name.partial.$$"
trap 'rm -f "$tmp"' EXIT
"$cc" -O2 -w -I"$include_dir" -o "$tmp" "$source_file" $(pkg-config --cflags --libs glut gl) -lm
mv -f "$tmp" "$out_dir/$name"
echo "$out_dir/$name"
