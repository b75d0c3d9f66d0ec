"""Builds the Python module with CMake for `pip install .` (pyproject.toml).

The extension superdex._superdex is the CMake target superdex_python, configured without the
tests and benchmarks for the interpreter running pip (its headers: python3-dev); the package's
Python files come from python/superdex/. The version is the CMake project's, read from
CMakeLists.txt. SUPERDEX_CMAKE_BUILD_DIR chooses the CMake build folder (default: one below the
setuptools build folder); SUPERDEX_BUILD_JOBS the parallel jobs (default: the CPU count)."""
import os
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def cmake_version():
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as f:
        m = re.search(r"project\(superdex VERSION ([0-9.]+)", f.read())
    if not m:
        sys.exit("setup.py: no 'project(superdex VERSION x.y.z' in CMakeLists.txt")
    return m.group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = os.environ.get("SUPERDEX_CMAKE_BUILD_DIR") or os.path.join(
            os.path.abspath(self.build_temp), "cmake")
        jobs = os.environ.get("SUPERDEX_BUILD_JOBS") or str(os.cpu_count() or 2)
        configure = ["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                     "-DSUPERDEX_BUILD_TESTS=OFF", "-DSUPERDEX_BUILD_BENCH=OFF",
                     "-DPython3_EXECUTABLE=" + sys.executable]
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", build, "--target", "superdex_python", "-j", jobs],
                       check=True)
        package = os.path.join(build, "python", "superdex")
        built = [f for f in os.listdir(package) if f.startswith("_superdex") and f.endswith(".so")]
        if len(built) != 1:
            sys.exit(f"setup.py: expected one _superdex*.so in {package}, found {built}")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(os.path.join(package, built[0]), target)


setup(
    version=cmake_version(),
    packages=["superdex"],
    package_dir={"superdex": "python/superdex"},
    ext_modules=[Extension("superdex._superdex", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own folder, apart from the CMake build/ of the README's commands.
    options={"build": {"build_base": ".pip-build"}},
    zip_safe=False,
)
