"""Builds and installs the Python package mocapdb: mocapdb/*.py and the compiled module
mocapdb._core, built by CMake from the repository around this folder (its target mocapdb_python, with
the library; no tests, tools or benchmarks) for the interpreter running pip.

    pip install --no-build-isolation ./python

Environment: MOCAPDB_CMAKE_BUILD_DIR=DIR builds the target in an existing configured build folder
instead of a fresh one (e.g. build/release); CMAKE_BUILD_PARALLEL_LEVEL=N jobs (default 2); CMake's own
variables (CMAKE_CXX_COMPILER_LAUNCHER=ccache, ...) apply.
"""
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent


def version():
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(mocapdb VERSION ([0-9.]+)", text).group(1)


class CMakeBuild(build_ext):
    """The extension is not compiled by setuptools: CMake builds it, and it is copied where setuptools
    expects it."""

    def build_extension(self, ext):
        build = os.environ.get("MOCAPDB_CMAKE_BUILD_DIR")
        if build:
            build = Path(build).resolve()
        else:
            build = Path(self.build_temp).resolve() / "cmake"
            generator = ["-G", "Ninja"] if shutil.which("ninja") else []
            subprocess.check_call(["cmake", "-S", str(ROOT), "-B", str(build), *generator, "-DCMAKE_BUILD_TYPE=Release",
                                   f"-DMOCAPDB_PYTHON_EXECUTABLE={sys.executable}", "-DMOCAPDB_BUILD_TESTS=OFF",
                                   "-DMOCAPDB_BUILD_TOOLS=OFF", "-DMOCAPDB_BUILD_BENCHMARKS=OFF",
                                   "-DMOCAPDB_BUILD_EXAMPLES=OFF", "-DMOCAPDB_NATIVE=OFF"])
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", "2")
        subprocess.check_call(["cmake", "--build", str(build), "--target", "mocapdb_python", "-j", jobs])
        built = sorted((build / "python" / "mocapdb").glob("_core*"))
        if not built:
            sys.exit(f"mocapdb: CMake built no module in {build / 'python' / 'mocapdb'} (is pybind11-dev installed? "
                     "scripts/setup.sh installs what the build needs)")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


setup(
    name="mocapdb",
    version=version(),
    description="Motion capture databases: clips as numpy arrays, synthesis and training windows",
    packages=["mocapdb"],
    package_dir={"mocapdb": str(Path("mocapdb"))},
    ext_modules=[Extension("mocapdb._core", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    python_requires=">=3.8",
    install_requires=["numpy"],
    zip_safe=False,
)
