#!/usr/bin/env bash
# tests/interpose/piglit_preload.sh LIBRARY — Debian's piglit (surfaceless EGL, -auto -fbo):
# each test below must give the same result with libshadowlab-imaging.so preloaded as
# without, and the library must have put the emulation on the test's context (its verbose
# line), so that the comparison is not vacuous. Exit 77 (skip) when piglit is not installed.
set -uo pipefail
library=$1
bin=/usr/lib/x86_64-linux-gnu/piglit/bin
if [[ ! -x $bin/draw-pixels ]]; then
  echo "SKIP: piglit is not installed (scripts/setup.sh installs it)"
  exit 77
fi
# The pixel paths and texture uploads the emulation wraps (DrawPixels, CopyPixels, ReadPixels,
# Tex(Sub)Image, CopyTex(Sub)Image, PBOs), and fixed-function state it passes on
# (texgen, polygon offset, depth textures).
tests=(
  draw-pixels copy-pixels drawpix-z fbo-readpixels pbo-drawpixels pbo-readpixels-small texgen
  gl-1.0-texgen depth-tex-compare gl-1.4-polygon-offset
  copyteximage-border copyteximage-clipping copytexsubimage copypixels-draw-sync
  draw-copypixels-sync draw-pixel-with-texture fbo-readdrawpix fbo-copyteximage-simple
  getteximage-simple getteximage-luminance pbo-teximage pbo-teximage-tiling
  ext_packed_depth_stencil-readdrawpixels
)
export PIGLIT_PLATFORM=surfaceless_egl
failures=0
for t in "${tests[@]}"; do
  if [[ ! -x $bin/$t ]]; then
    echo "FAIL: $t is not in this piglit"
    failures=$((failures + 1))
    continue
  fi
  plain=$(timeout 120 "$bin/$t" -auto -fbo 2>&1 | grep -o '"result": "[a-z]*"' | tail -1)
  out=$(SHADOWLAB_IMAGING_VERBOSE=1 LD_PRELOAD=$library timeout 120 "$bin/$t" -auto -fbo 2>&1)
  preloaded=$(grep -o '"result": "[a-z]*"' <<<"$out" | tail -1)
  engaged=$(grep -c "imaging emulated" <<<"$out")
  if [[ -z $plain || "$plain" != "$preloaded" || $engaged -eq 0 ]]; then
    echo "FAIL: $t: without [${plain:-no result}] with [${preloaded:-no result}], contexts emulated: $engaged"
    failures=$((failures + 1))
  else
    echo "same: $t: $plain (emulation on $engaged context(s))"
  fi
done
echo "$failures of ${#tests[@]} differ"
[[ $failures -eq 0 ]]
