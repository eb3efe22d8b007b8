#!/usr/bin/python3
"""A cross field on one of CGAL's meshes, from Python: automatic placement, the trivial connection, a picture.

    PYTHONPATH=build/python python3 examples/python/cross_field.py MESH.off OUT_DIR

Reads the mesh with the package's reader, places the singularities of the smoothest cross field (n = 4)
automatically, solves the trivial connection with exactly those singularities, checks the holonomy report,
writes the field as a VTK file and draws it with the package's renderer (scripts/render_field.py, numpy +
matplotlib) into OUT_DIR/cross_field.png.
"""
import os
import subprocess
import sys

import trivial_connections as tc


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    mesh, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)

    solver = tc.Solver.from_file(mesh)                        # validated, factored once
    singularities, placement = solver.place_singularities(n=4)
    result = solver.solve(singularities, n=4)                 # back-substitutions on the same factor
    print(f"{os.path.basename(mesh)}: {solver.number_of_faces} faces, "
          f"{len(singularities)} singularities {dict(placement['singularities_per_index'])}, "
          f"energy {result.energy:.6g} (smoothest field's connection: {placement['field_energy']:.6g}), "
          f"max residual {result.max_residual:.1e}")
    if not result.max_residual < 1e-8:
        sys.exit("the holonomy residual is too large")

    field = os.path.join(out, "cross_field.vtk")
    solver.write_field(field, result, singularities)
    tc.write_singularities(os.path.join(out, "cross_field.sing"), singularities)
    renderer = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "render_field.py")
    picture = os.path.join(out, "cross_field.png")
    subprocess.run([sys.executable, renderer, field, "-o", picture, "--title",
                    f"{os.path.basename(mesh)}: automatic cross field"], check=True)
    print("wrote", picture)


if __name__ == "__main__":
    main()
