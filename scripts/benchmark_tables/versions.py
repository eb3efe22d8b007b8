"""The versions of what the measurements ran with, gathered when the file is written (never hard-coded):
compiler, CGAL, Eigen, Boost, SuiteSparse/CHOLMOD, BLAS, Python/numpy, Google Benchmark, the commit."""

import os
import re
import subprocess

from .common import machine

INCLUDE_DIRS = ["/usr/include", "/usr/local/include"]


def _read(path):
    try:
        with open(path, errors="replace") as f:
            return f.read()
    except OSError:
        return None


def _header(*relative):
    """the text of the first of the headers found under the include directories"""
    for d in INCLUDE_DIRS:
        for r in relative:
            text = _read(os.path.join(d, r))
            if text is not None:
                return text
    return None


def _define(text, name):
    m = re.search(r"^\s*#\s*define\s+" + name + r"\s+(.+?)\s*$", text or "", re.M)
    return m.group(1).strip('"') if m else None


def _run(cmd):
    try:
        out = subprocess.run(cmd, capture_output=True, text=True, timeout=20)
    except (OSError, subprocess.SubprocessError):
        return None
    return out.stdout.strip() if out.returncode == 0 else None


def compiler():
    out = _run([os.environ.get("CXX", "g++"), "--version"])
    return out.splitlines()[0] if out else "unknown"


def cgal():
    text = _header("CGAL/version.h")
    return _define(text, "CGAL_VERSION") or _define(text, "CGAL_STR") or "not found"


def eigen():
    text = _header("eigen3/Eigen/src/Core/util/Macros.h", "Eigen/src/Core/util/Macros.h")
    parts = [_define(text, f"EIGEN_{p}_VERSION") for p in ("WORLD", "MAJOR", "MINOR")]
    return ".".join(parts) if all(parts) else "not found"


def boost():
    v = _define(_header("boost/version.hpp"), "BOOST_VERSION")
    if not v or not v.isdigit():
        return "not found"
    v = int(v)
    return f"{v // 100000}.{v // 100 % 1000}.{v % 100}"


def suitesparse():
    text = _header("suitesparse/cholmod.h", "cholmod.h")
    if text is None:
        return "not installed"
    config = _header("suitesparse/SuiteSparse_config.h", "SuiteSparse_config.h")
    pieces = []
    ss = [_define(config, f"SUITESPARSE_{p}_VERSION") for p in ("MAIN", "SUB", "SUBSUB")]
    if all(ss):
        pieces.append("SuiteSparse " + ".".join(ss))
    core = _header("suitesparse/cholmod_core.h", "cholmod_core.h")  # SuiteSparse 5 defines them there
    ch = [_define(text, f"CHOLMOD_{p}_VERSION") or _define(core, f"CHOLMOD_{p}_VERSION")
          for p in ("MAIN", "SUB", "SUBSUB")]
    if all(ch):
        pieces.append("CHOLMOD " + ".".join(ch))
    return ", ".join(pieces) or "version macros not found"


def python():
    """the interpreter the Python binding's benchmark uses (/usr/bin/python3) and its numpy"""
    exe = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else "python3"
    out = _run([exe, "-c", "import platform, sys\n"
                "try:\n import numpy; n = numpy.__version__\nexcept ImportError:\n n = 'not installed'\n"
                "print(platform.python_version(), n)"])
    if not out:
        return "unknown"
    version, numpy = out.split(maxsplit=1)
    return f"{version} ({exe}), numpy {numpy}"


def google_benchmark():
    out = _run(["dpkg-query", "-W", "-f=${Version}", "libbenchmark-dev"])
    return out or "libbenchmark-dev not installed (dpkg)"


def commit(root):
    sha = _run(["git", "-C", root, "rev-parse", "--short", "HEAD"])
    if not sha:
        return "unknown"
    dirty = _run(["git", "-C", root, "status", "--porcelain", "--untracked-files=no"])
    return sha + (" (with uncommitted changes)" if dirty else "")


def versions(root):
    """[(name, version)] in the order the header shows them"""
    return [("compiler", compiler()), ("CGAL", cgal()), ("Eigen", eigen()), ("Boost", boost()),
            ("SuiteSparse/CHOLMOD", suitesparse()), ("BLAS", f"`{machine()['blas']}`"), ("Python", python()),
            ("Google Benchmark", google_benchmark()), ("commit", commit(root))]


if __name__ == "__main__":
    for name, version in versions(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))):
        print(f"{name}: {version}")
