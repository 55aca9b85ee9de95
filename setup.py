"""Builds the Python module `stickslip` with CMake for pip, `python3 -m build` and setuptools
(docs/python.md, "Installing"). The metadata is in pyproject.toml; the version is the VERSION of
CMakeLists.txt's project().

build_ext configures the project in Release with only the module (the compiled mode; no tests,
examples, benchmarks nor install rules), builds the target `stickslip_python` and puts the module
into the package. Environment:

- STICKSLIP_CMAKE_BUILD_DIR=<dir>: an existing, configured build tree of this source tree for the
  same Python; its `stickslip_python` target is brought up to date (nothing to do when it is
  built) and its module is packaged, instead of a build of its own (the test suite installs the
  module it has just built this way).
- CMAKE_ARGS: extra arguments of the configure step (e.g. "-DCMAKE_CXX_COMPILER=clang++").
- CMAKE_BUILD_PARALLEL_LEVEL: parallel jobs of the build (default: the number of CPUs).
"""
import os
import re
import shlex
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = os.path.dirname(os.path.abspath(__file__))


def cmake_project_version():
    """The VERSION of the project() call in CMakeLists.txt (the single source of the version)."""
    with open(os.path.join(HERE, "CMakeLists.txt"), encoding="utf-8") as fh:
        match = re.search(r"project\(\s*stickslip\s+VERSION\s+([0-9][0-9.]*)", fh.read())
    if not match:
        raise RuntimeError("setup.py: no 'project(stickslip VERSION x.y.z' in CMakeLists.txt")
    return match.group(1)


def module_file(build_dir):
    """The module `stickslip` built in build_dir (<build>/python/stickslip<EXT_SUFFIX>)."""
    suffix = sysconfig.get_config_var("EXT_SUFFIX")
    path = os.path.join(build_dir, "python", "stickslip" + suffix)
    if not os.path.exists(path):
        found = [f for f in os.listdir(os.path.join(build_dir, "python"))
                 if f.startswith("stickslip.")] if os.path.isdir(os.path.join(build_dir, "python")) else []
        raise RuntimeError(
            "setup.py: %s was not built%s; this Python (%s) needs the suffix %s: configure the build tree "
            "with -DPython_EXECUTABLE=%s" % (path, " (found: " + ", ".join(found) + ")" if found else "",
                                             sys.executable, suffix, sys.executable))
    return path


class CMakeBuild(build_ext):
    """build_ext for the one extension `stickslip`, built by CMake."""

    def run(self):
        if shutil.which("cmake") is None:
            raise RuntimeError("setup.py: cmake is needed to build stickslip (Debian: apt-get install cmake)")
        super().run()

    def build_extension(self, ext):
        given = os.environ.get("STICKSLIP_CMAKE_BUILD_DIR")
        if given:
            build_dir = os.path.abspath(given)
            if not os.path.exists(os.path.join(build_dir, "CMakeCache.txt")):
                raise RuntimeError("setup.py: STICKSLIP_CMAKE_BUILD_DIR=%s is not a configured CMake build tree"
                                   % given)
        else:
            build_dir = os.path.join(os.path.abspath(self.build_temp), "cmake")
            self.configure(build_dir)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        self.spawn(["cmake", "--build", build_dir, "--target", "stickslip_python", "-j", jobs])
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(module_file(build_dir), target)

    def configure(self, build_dir):
        args = ["cmake", "-S", HERE, "-B", build_dir,
                "-DCMAKE_BUILD_TYPE=Release",
                "-DPython_EXECUTABLE=" + sys.executable,
                "-DSTICKSLIP_PYTHON=ON", "-DSTICKSLIP_COMPILED=ON",
                "-DSTICKSLIP_BUILD_TESTS=OFF", "-DSTICKSLIP_BUILD_EXAMPLES=OFF",
                "-DSTICKSLIP_BUILD_BENCHMARKS=OFF", "-DSTICKSLIP_INSTALL=OFF", "-DSTICKSLIP_MPI=OFF",
                "-DCMAKE_DISABLE_FIND_PACKAGE_Doxygen=ON", "-DCMAKE_DISABLE_FIND_PACKAGE_MPI=ON"]
        if not os.path.exists(os.path.join(build_dir, "CMakeCache.txt")) and shutil.which("ninja"):
            args += ["-G", "Ninja"]
        try:  # pybind11 from pip (an isolated build) brings its CMake package with it
            import pybind11
            args.append("-Dpybind11_DIR=" + pybind11.get_cmake_dir())
        except (ImportError, AttributeError):
            pass  # CMake finds a system pybind11 (Debian: pybind11-dev)
        args += shlex.split(os.environ.get("CMAKE_ARGS", ""))
        self.spawn(args)


def setuptools_options():
    """With STICKSLIP_CMAKE_BUILD_DIR, setuptools' own build directory goes into that build tree
    too, so that installing from it leaves the source tree as it was."""
    given = os.environ.get("STICKSLIP_CMAKE_BUILD_DIR")
    if not given:
        return {}
    base = os.path.join(os.path.abspath(given), "python-package")
    os.makedirs(base, exist_ok=True)
    return {"build": {"build_base": base}, "egg_info": {"egg_base": base}}


setup(
    version=cmake_project_version(),
    options=setuptools_options(),
    packages=[],  # the package is the one extension module (no package discovery: src/ holds C++)
    ext_modules=[Extension("stickslip", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)
