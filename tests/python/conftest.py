"""tests/python: the Python module against the command line it wraps (ctest label python).

ctest sets PYTHONPATH=build/python, SHADOWLAB_BINARY (the CLI built beside the module) and
SHADOWLAB_TEST_OUTPUT_DIR. Sizes are small (64x48): every test renders in well under a second
on llvmpipe, and the two-worker Dask sweep is a handful of rows.
"""

import json
import os
import subprocess

import numpy as np
import pytest
from PIL import Image as PILImage


def pytest_configure(config):
    """ctest's --basetemp (build/test-output/python/NAME): pytest makes NAME, not its parents."""
    if config.option.basetemp:
        os.makedirs(os.path.dirname(os.path.abspath(config.option.basetemp)), exist_ok=True)


@pytest.fixture(scope="session")
def cli():
    """Runs the shadowlab command: (exit status, stdout, stderr)."""
    binary = os.environ.get("SHADOWLAB_BINARY")
    if not binary:
        pytest.fail("SHADOWLAB_BINARY is not set (ctest sets it)")

    def run(*arguments):
        done = subprocess.run([binary, *arguments], capture_output=True, text=True, timeout=300)
        return done.returncode, done.stdout, done.stderr

    return run


@pytest.fixture
def out_dir(tmp_path):
    return tmp_path


def read_png(path):
    """A PNG's samples as numpy (8-bit RGB: uint8 (h, w, 3); 16-bit grey: uint16 (h, w))."""
    with PILImage.open(path) as image:
        return np.array(image)


def json_line(stdout):
    lines = [line for line in stdout.splitlines() if line.strip()]
    assert len(lines) == 1, stdout
    return json.loads(lines[0])


def quantized_16(mask):
    """The 16-bit samples --mask writes (core/base/image.cpp pngRows): clamp to [0, 1], the product
    with 65535 in float32, rounded half away from zero (lround; the values are >= 0)."""
    scaled = np.clip(mask, 0.0, 1.0).astype(np.float32) * np.float32(65535.0)
    return np.floor(scaled.astype(np.float64) + 0.5).astype(np.uint16)
