"""setup.py: setuptools driving the project's CMake build for `pip install --no-build-isolation .`.

The package is python/shadowlab/ (pure Python) plus its compiled half, _shadowlab*.so, which
the CMake target `shadowlab_python` builds (pybind11, linked against the system's OSMesa). This
file configures the release build in build/ when it is not configured yet, builds that one
target, and puts the .so and the assets the program reads at run time (scenes, meshes, lessons,
the course) into the package; shadowlab/__init__.py points the library at those assets.
SHADOWLAB_BUILD_DIR names another CMake build directory.
"""
import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

ROOT = Path(__file__).resolve().parent
BUILD = Path(os.environ.get("SHADOWLAB_BUILD_DIR", ROOT / "build"))


class BuildWithCMake(build_py):
    """build_py, then the CMake target shadowlab_python, its .so and the assets copied in."""

    def run(self):
        super().run()
        if not (BUILD / "CMakeCache.txt").exists():
            subprocess.check_call(["cmake", "--preset", "release"], cwd=ROOT)
        jobs = str(os.cpu_count() or 1)
        subprocess.check_call(
            ["cmake", "--build", str(BUILD), "--target", "shadowlab_python", "-j", jobs], cwd=ROOT)
        package = Path(self.build_lib) / "shadowlab"
        modules = list((BUILD / "python" / "shadowlab").glob("_shadowlab*.so"))
        if len(modules) != 1:
            sys.exit(f"setup.py: expected one _shadowlab*.so in {BUILD}/python/shadowlab, "
                     f"found {len(modules)}")
        shutil.copy2(modules[0], package / modules[0].name)
        shutil.copytree(ROOT / "assets", package / "assets", dirs_exist_ok=True)


class BinaryDistribution(Distribution):
    """The wheel holds a compiled module: tagged for this platform and Python, not 'any'."""

    def has_ext_modules(self):
        return True


setup(cmdclass={"build_py": BuildWithCMake}, distclass=BinaryDistribution,
      options={"build": {"build_base": str(BUILD / "setuptools")}})
