#!/usr/bin/env bash
# scripts/setup.sh — installs the Debian 12 packages shadowlab builds and runs with.
# As root it runs apt-get; otherwise it prints the exact command and stops.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config
  clang-format        # the sources' format, checked by ctest (style.clang_format)
  libosmesa6-dev      # Mesa OSMesa (llvmpipe): the embedded GL, no GPU or display needed
  libegl-dev libegl1-mesa-dev libgl1-mesa-dri  # EGL back end (Mesa llvmpipe here, NVIDIA on GPU machines)
  libglm-dev          # vector and matrix math
  libpng-dev zlib1g-dev  # PNG images, gzip-compressed meshes
  libssl-dev          # SHA-256 of scene files in render's provenance (OpenSSL libcrypto)
  nlohmann-json3-dev  # scene files and machine-readable output
  libcli11-dev        # command-line parsing (shadowlab COMMAND --help)
  libassimp-dev       # OBJ and PLY meshes
  libembree-dev       # ray-traced reference visibility
  libgtest-dev googletest  # tests
  gnuplot-nox         # plots in the report
  imagemagick fonts-dejavu-core  # figure.png's labels: text drawn by convert in DejaVu Sans
  chromium            # tests/figures: report.html checked in headless Chromium (skips without)
  libcpp-httplib-dev  # `shadowlab serve`: the live lab's HTTP server (lab/)
  nodejs              # tests/browser: the lab's page driven by puppeteer-core (npm ci below)
  python3-dev pybind11-dev  # the Python module `shadowlab` (build/python; docs/python.md)
  python3-numpy python3-pandas  # its arrays and DataFrames
  python3-distributed  # sweeps on Dask workers (shadowlab.sweep(spec, client=...))
  python3-matplotlib python3-pil  # examples/ plots; tests/python reads PNGs with Pillow
  python3-pytest      # tests/python (ctest label python)
  python3-venv python3-pip python3-setuptools python3-wheel  # pip install --no-build-isolation . (pyproject.toml)
  python3-nbclient python3-nbformat python3-ipykernel  # examples/*.ipynb executed in tests/python
  freeglut3-dev xvfb  # run-legacy: unchanged GLUT programs on GLX (Xvfb when there is no display)
  xauth               # xvfb-run (GlutShapes.SameCallsAsFreeglut runs freeglut under it)
  piglit              # tests/interpose: piglit's pixel tests with and without the drop-in library
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# npm: Debian's package, unless the installed nodejs brings its own.
command -v npm >/dev/null 2>&1 || missing+=(npm)
if [[ ${#missing[@]} -gt 0 ]]; then
  if [[ $(id -u) -ne 0 ]]; then
    echo "shadowlab needs these Debian packages; run as root:" >&2
    echo "  apt-get update && apt-get install -y ${missing[*]}" >&2
    exit 1
  fi
  echo "installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq "${missing[@]}" >/dev/null
fi

# tests/browser: puppeteer-core from npm at the versions of package-lock.json (it drives
# /usr/bin/chromium and downloads no browser). Installed here, never when a test or the tool
# runs; skipped when it is there already for this lock file.
browser_dir="$(cd "$(dirname "$0")/.." && pwd)/tests/browser"
if [[ ! -f "$browser_dir/node_modules/.package-lock.json" ||
      "$browser_dir/package-lock.json" -nt "$browser_dir/node_modules/.package-lock.json" ]]; then
  (cd "$browser_dir" && PUPPETEER_SKIP_DOWNLOAD=1 npm ci --no-audit --no-fund --loglevel=error)
fi
