"""The per-backend pipeline tables, the floor (issue 20) and the log-log scaling slopes."""

from .common import (BACKENDS, BUILD_PHASES, PROGRAM_PREFIX, SERIES_PREFIX, SLOPE_PHASES, backend_order,
                     floor_cell, fmt_faces, fmt_num, fmt_time, machine, mesh_order, ordering, pipelines,
                     program_phases, slope, table_head, with_integers)


FLOOR_TITLE = "### Against the fastest factorization of the machine"


def floor_table(results, lines, contexts=(), command=""):
    """every backend against the fastest factorization of the machine (issue 20)"""
    rows = [(b, mesh, e) for b in sorted(results, key=backend_order)
            for mesh, e in sorted(pipelines(results[b]).items(), key=mesh_order)
            if not e["error"] and e["counters"].get("t_floor")]
    if not rows:
        return
    lines.append(FLOOR_TITLE)
    lines.append("")
    if command:
        m = machine()
        dates = sorted({ctx.get("date", "")[:10] for _, ctx in contexts if ctx.get("date")})
        commits = sorted({ctx.get("commit") for _, ctx in contexts if ctx.get("commit")})
        lines.append(f"Measured {', '.join(dates) if dates else 'on an unknown date'} on {m['nproc']} cores "
                     f"({m['cpu']}, BLAS `{m['blas']}`)" + (f", commit {', '.join(commits)}" if commits else "")
                     + f", by `{command}`.")
        lines.append("")
    lines.append("The **floor**: per mesh, the fastest of every sparse Cholesky of the same Laplacian the build has, "
                 "each with its best ordering, timed in the same run as the reference (analysis, ordering included, "
                 "+ factorization): SimplicialLDLT with AMD, SimplicialLDLT with METIS (libmetis-dev), supernodal "
                 "CHOLMOD with its own ordering choice (on the BLAS above). Target of issue 20 (reported, not "
                 "asserted): end to end of the library ≤ 1.2 × the floor at every size ≥ 50k faces; ✗ marks a miss. "
                 "A ratio below 1 means the floor's orderings are not the best ones: the solver's factorization "
                 "(Eigen's AMD order, given to CHOLMOD) can beat CHOLMOD's own choice.")
    lines.append("")
    big = [(b, c["counters"]) for b, _, c in rows if c["counters"].get("faces", 0) >= 5e4]
    for b in sorted({b for b, _ in big}, key=backend_order):
        r = [c.get("r_end_to_end_floor", 0) for bb, c in big if bb == b]
        met = sum(1 for x in r if x <= 1.2)
        lines.append(f"- **{b}**: end to end ≤ 1.2 × floor on {met} of {len(r)} meshes of ≥ 50k faces "
                     f"(ratios {fmt_num(min(r))}–{fmt_num(max(r))}).")
    lines.append("")
    head = ["mesh", "backend", "faces", "floor", "own reference", "build", "end to end", "build / floor",
            "end-to-end / floor"]
    table_head(lines, head)
    for b, mesh, e in rows:
        c = e["counters"]
        end = c.get("r_end_to_end_floor")
        mark = " ✗" if end is not None and c.get("faces", 0) >= 5e4 and end > 1.2 else ""
        lines.append("| " + " | ".join([mesh, b, fmt_faces(c.get("faces", 0)), floor_cell(c),
                                         fmt_time(c.get("t_reference")), fmt_time(c.get("t_build")),
                                         fmt_time(c.get("t_build", 0) + c.get("t_solve", 0) + c.get("t_field", 0)),
                                         fmt_num(c.get("r_build_floor")), fmt_num(end) + mark]) + " |")
    lines.append("")
    programs = [(b, mesh, e) for b in sorted(results, key=backend_order) for mesh, e in sorted(results[b].items())
                if mesh.startswith(PROGRAM_PREFIX) and not e["error"] and e["counters"].get("t_floor")]
    if programs:
        lines.append("The main program as a whole process (as in its section; target of issue 20: program / (CGAL "
                     "read + Laplacian + floor) ≤ 1.0 from 50k to 4.8M faces, and 4.8M faces within 30 s), and its "
                     "own `--progress` phases over the floor:")
        lines.append("")
        head = ["mesh", "backend", "faces", "program", "CGAL read", "Laplacian", "floor",
                "program / (read + Laplacian + floor)", "program / (read + floor)", "program phases / floor"]
        lines.append("| " + " | ".join(head) + " |")
        lines.append("|" + "|".join(["---", "---"] + ["---:"] * (len(head) - 3) + ["---"]) + "|")
        for b, mesh, e in sorted(programs, key=lambda r: r[2]["counters"].get("faces", 0)):
            c = e["counters"]
            r = c.get("r_program_floor")
            mark = " ✗" if r is not None and r > 1.0 else ""
            over_30s = " ✗" if c.get("faces", 0) > 4e6 and c.get("t_program", 0) > 30 else ""
            lines.append("| " + " | ".join([mesh[len(PROGRAM_PREFIX):], b, fmt_faces(c.get("faces", 0)),
                                             fmt_time(c.get("t_program")) + over_30s, fmt_time(c.get("t_read")),
                                             fmt_time(c.get("t_laplacian")), floor_cell(c), fmt_num(r) + mark,
                                             fmt_num(c.get("r_program_floor_without_laplacian")),
                                             program_phases(c)]) + " |")
        lines.append("")


def backend_table(backend, meshes, lines):
    lines.append(f"### {backend}: {BACKENDS.get(backend, backend)}")
    lines.append("")
    head = ["mesh", "faces", "genus", "bnd loops", "sing.", "floor", "reference"] + [t for _, t in BUILD_PHASES] + \
        ["build", "solve", "re-solve", "field", "end-to-end / floor", "re-solve / floor", "end-to-end / ref",
         "peak B/face", "ref peak B/face", "ref factor B/face", "ref GFlop", "faults/face", "floor faults/face",
         "reps"]
    lines.append("| " + " | ".join(head) + " |")
    lines.append("|" + "|".join(["---"] + ["---:"] * (len(head) - 1)) + "|")
    for mesh, e in sorted(pipelines(meshes).items(), key=mesh_order):
        c = e["counters"]
        if e["error"]:
            lines.append(f"| {mesh} | " + " | ".join(["–"] * (len(head) - 2)) + f" | error: {e['error']} |")
            continue
        row = [mesh, fmt_faces(c.get("faces", 0)), f"{c.get('genus', 0):.0f}", f"{c.get('boundary_loops', 0):.0f}",
               f"{c.get('singularities', 0):.0f}", floor_cell(c), fmt_time(c.get("t_reference")) + ordering(c)]
        row += [fmt_time(c.get(k)) for k, _ in BUILD_PHASES]
        floor = c.get("t_floor")
        row += [fmt_time(c.get("t_build")), with_integers(c, "t_solve"), with_integers(c, "t_resolve"),
                fmt_time(c.get("t_field")), fmt_num(c.get("r_end_to_end_floor")),
                fmt_num(c["t_resolve"] / floor) if floor and c.get("t_resolve") is not None else "–",
                fmt_num(c.get("r_end_to_end")),
                fmt_num(c.get("peak_bytes_per_face"), 4), fmt_num(c.get("ref_peak_bytes_per_face"), 4),
                fmt_num(c.get("ref_factor_bytes_per_face"), 4), fmt_num(c.get("ref_factor_gflops"), 3),
                fmt_num(c.get("page_faults_per_face"), 3), fmt_num(c.get("floor_page_faults_per_face"), 3),
                str(e["repetitions"])]
        lines.append("| " + " | ".join(row) + " |")
    lines.append("")


def slope_table(results, lines):
    backends = [b for b in sorted(results, key=backend_order) if results[b]]
    head = ["phase"]
    for b in backends:
        head += [f"{b}: all meshes", f"{b}: {SERIES_PREFIX} series"]
    lines.append("| " + " | ".join(head) + " |")
    lines.append("|" + "|".join(["---"] + ["---:"] * (len(head) - 1)) + "|")
    for key, title in SLOPE_PHASES:
        row = [title]
        any_value = False
        for b in backends:
            ok = [e for e in pipelines(results[b]).values() if not e["error"]]
            for subset in (ok, [e for m, e in results[b].items() if m.startswith(SERIES_PREFIX) and not e["error"]]):
                s, n = slope([(e["counters"].get("faces", 0), e["counters"].get(key)) for e in subset])
                if s is None:
                    row.append("–")
                else:
                    faces = [e["counters"]["faces"] for e in subset if e["counters"].get(key, 0) > 0]
                    row.append(f"{s:.2f} ({n} meshes, {fmt_faces(min(faces))}–{fmt_faces(max(faces))})")
                    any_value = True
        if any_value or key.startswith("t_"):
            lines.append("| " + " | ".join(row) + " |")
    lines.append("")
