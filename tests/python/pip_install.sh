#!/usr/bin/env bash
# tests/python/pip_install.sh SOURCE_DIR BUILD_DIR OUT — the ctest `python.pip_install`: makes a
# fresh venv (--system-site-packages: Debian's numpy and pandas), runs
# `pip install --no-build-isolation SOURCE_DIR` as docs/python.md says (setup.py builds the
# module with BUILD_DIR's CMake build), then, with no PYTHONPATH and from another directory,
# imports shadowlab from the venv and renders with the assets installed beside it.
set -euo pipefail
src=$(realpath "$1")
build=$(realpath "$2")
out=$(realpath -m "$3")
rm -rf "$out"
mkdir -p "$out"
/usr/bin/python3 -m venv --system-site-packages "$out/venv"
SHADOWLAB_BUILD_DIR="$build" "$out/venv/bin/pip" install --no-build-isolation --no-input \
  --quiet --disable-pip-version-check "$src"
cd "$out"
env -u PYTHONPATH -u SHADOWLAB_ASSETS "$out/venv/bin/python" - "$out/venv" <<'PY'
import os
import sys

import shadowlab

venv = sys.argv[1]
assert shadowlab.__file__.startswith(venv), shadowlab.__file__
assets = os.environ["SHADOWLAB_ASSETS"]
assert assets.startswith(venv) and os.path.isfile(os.path.join(assets, "scenes", "bunny.json")), assets
r = shadowlab.render(scene="bunny", technique="modern.hw", size=(64, 48))
assert r["image"].shape == (48, 64, 3) and 0.0 < float(r["mask"].mean()) < 1.0
print("ok: shadowlab", shadowlab.commit(), "from", shadowlab.__file__)
PY
