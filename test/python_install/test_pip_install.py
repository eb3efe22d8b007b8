# Copyright (c) 2026 CGAL Trivial Connections contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
# ctest python_pip_install: pip install . --no-build-isolation, offline (--no-index), into a fresh virtual
# environment (--system-site-packages, for Debian's numpy), from a copy of the source tree's files as git lists them
# (a fresh clone of the working tree); then the module imports from the environment, outside the sources, with its
# version and its type stubs beside it, and solves. Skipped, saying which Debian package is missing, without
# python3-venv, python3-pip, python3-setuptools (>= 61), python3-wheel or cmake (scripts/install_dependencies.sh
# installs them). The module is built unoptimised here (-O0), to save time: what is tested is the installation.

import importlib.metadata
import importlib.util
import os
import pathlib
import shutil
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def missing_prerequisites():
    missing = []
    if importlib.util.find_spec("ensurepip") is None:
        missing.append("python3-venv (python3 -m venv)")
    if importlib.util.find_spec("pip") is None:
        missing.append("python3-pip")
    try:  # not imported here: its distutils hack would clash with pytest's distutils
        version = importlib.metadata.version("setuptools")
        if int(version.split(".")[0]) < 61:
            missing.append(f"python3-setuptools >= 61 (found {version})")
    except importlib.metadata.PackageNotFoundError:
        missing.append("python3-setuptools")
    if importlib.util.find_spec("wheel") is None:
        missing.append("python3-wheel")
    if shutil.which("cmake") is None:
        missing.append("cmake")
    return missing


def copy_of_the_sources(target):
    """the files git lists (tracked, and new ones not ignored), as a fresh clone of the working tree has them"""
    listed = subprocess.run(["git", "-C", str(ROOT), "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                            capture_output=True, check=False)
    if listed.returncode != 0:
        pytest.skip("the sources are not a git working tree: nothing says which files a clone has")
    for name in listed.stdout.decode().split("\0"):
        source = ROOT / name
        if name and source.is_file():
            (target / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, target / name)


def test_pip_install_into_a_virtual_environment(tmp_path):
    missing = missing_prerequisites()
    if missing:
        pytest.skip("pip install . needs the Debian packages " + ", ".join(missing) +
                    " (bash scripts/install_dependencies.sh installs them)")
    source, venv, elsewhere = tmp_path / "source", tmp_path / "venv", tmp_path / "elsewhere"
    source.mkdir()
    elsewhere.mkdir()
    copy_of_the_sources(source)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], check=True, env=env)
    python = venv / "bin" / "python"
    env["TC_CMAKE_ARGS"] = "'-DCMAKE_CXX_FLAGS_RELEASE=-O0 -DNDEBUG'"  # one argument (setup.py splits as a shell)
    install = subprocess.run([str(python), "-m", "pip", "install", "--no-build-isolation", "--no-index", "-v", "."],
                             cwd=source, env=env, capture_output=True, text=True)
    assert install.returncode == 0, install.stdout[-20000:] + install.stderr[-5000:]
    version = [line for line in (ROOT / "CMakeLists.txt").read_text().splitlines()
               if line.startswith("project(TrivialConnections VERSION ")][0].split()[2]
    check = f"""
import os, pathlib, sys, trivial_connections as tc
module = pathlib.Path(tc.__file__)
assert str(module).startswith({str(venv)!r}), module
assert (module.parent / "trivial_connections.pyi").is_file(), "no stubs beside the module"
assert tc.__version__ == {version!r}, tc.__version__
V, F = tc.read_mesh(pathlib.Path({str(ROOT / "examples" / "data" / "sphere.off")!r}))
solver = tc.Solver(V, F)
chi = solver.topology[0]["euler_characteristic"]
result = solver.solve({{0: chi}})
assert result.max_residual < 1e-9, result.max_residual
print("installed", tc.__version__, module)
"""
    run = subprocess.run([str(python), "-c", check], cwd=elsewhere, env=env, capture_output=True, text=True)
    assert run.returncode == 0, run.stdout + run.stderr
    print(run.stdout)
