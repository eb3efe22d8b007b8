"""The tables of the main program as a whole process and of the design controls."""

from .common import (CONTROLS_PREFIX, PROGRAM_PREFIX, backend_order, error_row, floor_cell, fmt_faces, fmt_num,
                     fmt_time, program_phases, table_head)


def program_table(results, lines):
    rows = [(b, m[len(PROGRAM_PREFIX):], e) for b in sorted(results, key=backend_order)
            for m, e in results[b].items() if m.startswith(PROGRAM_PREFIX)]
    if not rows:
        return
    lines.append("### The main program as a whole process")
    lines.append("")
    lines.append("`trivial_connections MESH.off --singularities S --n 1 --connection C --field F` (read, solve, field, "
                 "both files written), timed as a child process, against reading the same OFF file with CGAL "
                 "(`read_polygon_mesh` into a `Surface_mesh`) plus one analysis + factorization of the mesh's "
                 "Laplacian with the program's backend (the choice by predicted cost whenever CHOLMOD is installed). "
                 "Laplacian: building it from the mesh read (cotan weights, then the sparse matrix). "
                 "Targets: ratio ≤ 2; program / (read + Laplacian + floor) ≤ 1.0 (issue 20; the floor as in the "
                 "section above; without the Laplacian in the next column). The program's phases are its own "
                 "`--progress` times (10 ms resolution) over the floor.")
    lines.append("")
    head = ["mesh", "backend", "faces", "program", "program peak", "CGAL read", "reference factorization",
            "program / (read + reference)", "Laplacian", "floor", "program / (read + Laplacian + floor)",
            "program / (read + floor)", "program phases / floor"]
    table_head(lines, head)
    for b, mesh, e in rows:
        c = e["counters"]
        if e["error"]:
            lines.append(error_row(mesh, b, head, e['error']))
            continue
        peak = c.get("program_peak_bytes")
        lines.append("| " + " | ".join([mesh, b, fmt_faces(c.get("faces", 0)), fmt_time(c.get("t_program")),
                                         f"{peak / 2**30:.2f} GiB" if peak and peak > 0 else "–",
                                         fmt_time(c.get("t_read")), fmt_time(c.get("t_reference")),
                                         fmt_num(c.get("r_program")), fmt_time(c.get("t_laplacian")), floor_cell(c),
                                         fmt_num(c.get("r_program_floor")),
                                         fmt_num(c.get("r_program_floor_without_laplacian")),
                                         program_phases(c)]) + " |")
    lines.append("")


def controls_table(results, lines):
    rows = [(b, m[len(CONTROLS_PREFIX):], e) for b in sorted(results, key=backend_order)
            for m, e in results[b].items() if m.startswith(CONTROLS_PREFIX)]
    if not rows:
        return
    rows.sort(key=lambda r: (backend_order(r[0]), r[2]["counters"].get("faces", 0)))
    lines.append("### Design controls: constrained and guided faces")
    lines.append("")
    lines.append("A solver with 20 constrained and 10 guided faces (n = 4), one solve, a re-solve with new directions "
                 "on the same faces, `set_constraints()` with 5 constrained faces dropped and 10 added (links kept "
                 "in the factor, links dropped from the dense block, new links bordered: one forward substitution "
                 "each), and a solve after it; against the same reference factorization as above. Expected: "
                 "re-solve and set_constraints far below the reference.")
    lines.append("")
    head = ["mesh", "backend", "faces", "reference", "build", "solve", "re-solve", "set_constraints",
            "solve after", "links (bordered, new)", "build / ref", "re-solve / ref", "set_constraints / ref"]
    table_head(lines, head)
    for b, mesh, e in rows:
        c = e["counters"]
        if e["error"]:
            lines.append(error_row(mesh, b, head, e['error']))
            continue
        lines.append("| " + " | ".join([
            mesh, b, fmt_faces(c.get("faces", 0)), fmt_time(c.get("t_reference")), fmt_time(c.get("t_build")),
            fmt_time(c.get("t_solve")), fmt_time(c.get("t_resolve")), fmt_time(c.get("t_set_constraints")),
            fmt_time(c.get("t_solve_after_set")),
            f"{int(c.get('links_after_set', 0))} ({int(c.get('links_outside_the_factor', 0))}, "
            f"{int(c.get('new_forward_substitutions', 0))})",
            fmt_num(c.get("r_build")), fmt_num(c.get("r_resolve")), fmt_num(c.get("r_set_constraints"))]) + " |")
    lines.append("")
