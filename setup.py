"""pip's build of the Python package dabench (pyproject.toml): the extension dabench._core is built
by the project's own CMake build, not by setuptools, and its package folder (BUILD/python/dabench:
the extension and the package's Python files, python/CMakeLists.txt) is what the wheel holds.

BUILD is $DABENCH_BUILD_DIR when set (an existing build folder: nothing already compiled there is
compiled again), else build/pip, configured on first use for the module alone (no tests, benchmarks
or MPI module). The version is the project's (CMakeLists.txt), as dabench.__version__ says.
"""
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Distribution, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


def project_version():
    match = re.search(r"project\(dabench VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text())
    if match is None:
        raise RuntimeError("CMakeLists.txt: no `project(dabench VERSION x.y.z ...)`")
    return match.group(1)


class BuildWithCMake(build_ext):
    """Builds the CMake target dabench_python and copies its package folder into the wheel."""

    def run(self):
        build = Path(os.environ.get("DABENCH_BUILD_DIR", ROOT / "build" / "pip")).resolve()
        if not (build / "CMakeCache.txt").is_file():
            subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                            "-DDABENCH_BUILD_TESTS=OFF", "-DDABENCH_BUILD_BENCHMARKS=OFF", "-DDABENCH_WITH_MPI=OFF",
                            f"-DPython3_EXECUTABLE={sys.executable}"], check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "dabench_python", "--parallel",
                        str(os.cpu_count() or 1)], check=True)
        package = build / "python" / "dabench"
        if not any(package.glob("_core*.so")):
            raise RuntimeError(f"{package}: no extension _core after the build (is pybind11-dev installed?)")
        shutil.copytree(package, Path(self.build_lib) / "dabench", dirs_exist_ok=True,
                        ignore=shutil.ignore_patterns("__pycache__"))


class CompiledDistribution(Distribution):
    """A wheel for this platform and Python: it holds a compiled extension."""

    def has_ext_modules(self):
        return True


(ROOT / "build").mkdir(exist_ok=True)  # setuptools' own files go there, beside the CMake build
setup(version=project_version(), packages=[], distclass=CompiledDistribution,
      cmdclass={"build_ext": BuildWithCMake},
      options={"build": {"build_base": str(Path("build") / "pip-wheel")}, "egg_info": {"egg_base": "build"}})
