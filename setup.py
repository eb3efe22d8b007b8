# Copyright (c) 2026 CGAL Trivial Connections contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
# The build of pip install . (pyproject.toml): the project's CMake configures the sources and builds the one target
# trivial_connections_python (the same flags, CHOLMOD and METIS when found, as the top-level build), whose module
# and type stubs (python/trivial_connections.pyi) are then put where pip installs them. The version is the
# project's (CMakeLists.txt). Environment: TC_CMAKE_ARGS, extra arguments of the CMake configure (e.g.
# "-DCMAKE_BUILD_TYPE=Debug"); CMAKE_BUILD_PARALLEL_LEVEL, the build's jobs (CMake's own variable).

import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent
VERSION = re.search(r"project\(TrivialConnections VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text()).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = pathlib.Path(self.build_temp).resolve() / "cmake"
        configure = ["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release", "-DBUILD_TESTING=OFF",
                     "-DTRIVIAL_CONNECTIONS_WITH_PYTHON=ON", "-DTRIVIAL_CONNECTIONS_WITH_EDITOR=OFF",
                     f"-DTC_PYTHON={sys.executable}"] + shlex.split(os.environ.get("TC_CMAKE_ARGS", ""))
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "trivial_connections_python"], check=True)
        built = sorted((build / "python").glob("trivial_connections*.so"))
        if len(built) != 1:
            sys.exit(f"setup.py: CMake built no Python module (found {built}): is pybind11-dev, python3-pybind11 "
                     "and python3-dev installed? (scripts/install_dependencies.sh)")
        target = pathlib.Path(self.get_ext_fullpath(ext.name)).resolve()
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built[0], target)
        shutil.copy2(ROOT / "python" / "trivial_connections.pyi", target.parent / "trivial_connections.pyi")


setup(
    version=VERSION,
    ext_modules=[Extension("trivial_connections", sources=[])],
    packages=[],  # the module alone: no automatic discovery of the folders of the source tree
    py_modules=[],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own build folder: not build/, the README's CMake build folder
    options={"build": {"build_base": "build-python"}},
    zip_safe=False,
)
