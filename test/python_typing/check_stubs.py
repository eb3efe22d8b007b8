# Copyright (c) 2026 CGAL Trivial Connections contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
# ctest python_typing: the type stubs of the module (build/python/trivial_connections.pyi, from
# python/trivial_connections.pyi) checked by Debian's mypy:
#   1. the typed example of the README (examples/python/readme_example.py) passes mypy --strict, then runs;
#   2. wrong uses of the module are errors (so the stubs are read, not Any);
#   3. stubtest: the stubs against the module itself (every name of one in the other, and the same kinds);
#   4. the batch module (python/trivial_connections_batch.py) passes mypy.
# Usage: python3 check_stubs.py MYPY MODULE_DIR SOURCE_DIR   (PYTHONPATH=MODULE_DIR)

import os
import subprocess
import sys
import tempfile

mypy, module_dir, source = sys.argv[1:4]
env = dict(os.environ, MYPYPATH=module_dir, PYTHONPATH=module_dir)
failures = []


def run(args, **kwargs):
    print("$", " ".join(args), flush=True)
    out = subprocess.run(args, env=env, capture_output=True, text=True, **kwargs)
    print(out.stdout + out.stderr, flush=True)
    return out


with tempfile.TemporaryDirectory() as d:
    common = [mypy, "--strict", "--no-incremental", "--cache-dir", os.path.join(d, "cache")]
    example = os.path.join(source, "examples", "python", "readme_example.py")
    if run(common + [example]).returncode != 0:
        failures.append("mypy --strict on the README's example")
    if run([sys.executable, example, os.path.join(source, "examples", "data", "sphere.off"), d]).returncode != 0:
        failures.append("the README's example")
    wrong = os.path.join(d, "wrong.py")
    with open(wrong, "w") as f:
        f.write("import trivial_connections as tc\n"
                "V, F = tc.read_mesh(3)\n"                         # not a path
                "s = tc.Solver(V, F, weights=1)\n"                 # not a str
                "r = s.solve({0: 1}, n='4')\n"                     # n not an int
                "x: str = r.energy\n"                              # a float
                "t: int = s.topology\n")                           # a list
    out = run(common + [wrong])
    errors = [line for line in out.stdout.splitlines() if ": error:" in line]
    if len(errors) != 5:
        failures.append(f"mypy found {len(errors)} errors in 5 wrong uses")
    # the stubs against the module (pybind11's functions have no inspectable signatures: names and kinds)
    allowlist = os.path.join(os.path.dirname(os.path.abspath(__file__)), "stubtest_allowlist.txt")
    out = run([sys.executable, "-m", "mypy.stubtest", "trivial_connections", "--mypy-config-file", os.devnull,
               "--allowlist", allowlist])
    if out.returncode != 0:
        failures.append("stubtest")
    batch = os.path.join(source, "python", "trivial_connections_batch.py")
    if run([mypy, "--no-incremental", "--cache-dir", os.path.join(d, "cache"), batch]).returncode != 0:
        failures.append("mypy on trivial_connections_batch.py")

if failures:
    print("FAILED:", "; ".join(failures))
    sys.exit(1)
print("the stubs pass")
