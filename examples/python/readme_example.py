#!/usr/bin/env python3
# Copyright (c) 2026 CGAL Trivial Connections contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
# The README's Python snippet as a program, typed: a mesh read into numpy arrays, its topology, singularities
# whose indices sum to each closed component's Euler characteristic, a solve with progress, a cross field placed
# automatically, and the files. ctest python_typing checks it with mypy --strict against the module's stubs
# (python/trivial_connections.pyi) and runs it.
#   PYTHONPATH=build/python python3 examples/python/readme_example.py [MESH] [OUTPUT_FOLDER]

import logging
import pathlib
import sys
from fractions import Fraction
from typing import Dict

import numpy as np
import numpy.typing as npt

import trivial_connections as tc


def main() -> None:
    here = pathlib.Path(__file__).resolve().parent
    mesh = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else here.parent / "data" / "sphere.off"
    out = pathlib.Path(sys.argv[2]) if len(sys.argv) > 2 else pathlib.Path(".")
    logging.basicConfig(level=logging.INFO, format="%(name)s: %(message)s")  # the phases of the long calls

    V, F = tc.read_mesh(mesh)  # (n, 3) float64 and (m, 3) int64, no solver yet
    solver = tc.Solver(V, F)  # factored once
    print(repr(solver), f"trivial_connections {tc.__version__}")
    # one singularity per closed component with chi != 0, of index chi: Poincare-Hopf holds
    singularities: Dict[int, int] = {}
    for component in solver.topology:
        print(f"component: {component['number_of_faces']} faces, chi {component['euler_characteristic']}, "
              f"genus {component['genus']}, {component['number_of_boundary_loops']} boundary loops")
        if component["closed"] and component["euler_characteristic"] != 0:
            first_face = int(component["faces"][0])
            singularities[int(F[first_face, 0])] = int(component["euler_characteristic"])

    def progress(phase: str, fraction: float) -> None:
        if fraction == 1:
            print(f"  {phase} done")

    result = solver.solve(singularities, progress=progress)
    connection: npt.NDArray[np.float64] = result.connection
    print(f"{len(connection)} interior edges, energy {result.energy:.6g}, max residual {result.max_residual:.2g}")

    placed, report = solver.place_singularities(n=4)  # a cross field, its singularities placed automatically
    cross = solver.solve(placed, n=4)
    total: Fraction = sum(placed.values(), Fraction(0))
    print(f"n = 4: {len(placed)} singularities (index sum {total}), energy {cross.energy:.6g}, "
          f"field energy {report['field_energy']:.6g}")
    solver.write_field(out / "cross_field.vtk", cross, placed)
    tc.write_singularities(out / "cross_field.sing", placed)
    assert tc.read_singularities(out / "cross_field.sing") == placed


if __name__ == "__main__":
    main()
