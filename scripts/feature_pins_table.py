#!/usr/bin/env python3
"""Markdown tables of trivial_connections_feature_pins_benchmark's JSON (benchmark/RESULTS.md, "Feature pins").

    trivial_connections_feature_pins_benchmark --benchmark_out=pins.json --benchmark_out_format=json
    python3 scripts/feature_pins_table.py pins.json
"""
import json
import sys


def size(n):
    return f"{n / 1000:.0f}k" if n >= 1000 else f"{n:.0f}"


def sec(t):
    return f"{t * 1000:.0f} ms" if t < 1 else f"{t:.2f} s"


def mb(b):
    return f"{b / 2**20:.0f} MB" if b >= 0 else "–"


def main(path):
    runs = json.load(open(path))["benchmarks"]
    rows = {"library": [], "program": [], "set_constraints": []}
    for r in runs:
        if r.get("error_occurred"):
            print(f"<!-- {r['name']}: {r.get('error_message')} -->")
            continue
        rows[r["name"].split("/")[0]].append(r)
    print("Whole process: `trivial_connections MESH.off --n 4 --auto --no-refine` without and with "
          "`--constraints PINS` (wall time; the child's own maximum resident size, wait4)\n")
    print("| mesh | faces | pins | pins / faces | time, no pins -> pins | ratio | peak memory, no pins -> pins | ratio "
          "| energy of `--auto --no-refine`, no pins -> pins |")
    print("|---|---:|---|---:|---|---:|---|---:|---|")
    for r in rows["program"]:
        mesh, kind = r["name"].split("/")[1:3]
        print(f"| {mesh} | {size(r['faces'])} | {kind}: {r['pins']:.0f} | {100 * r['pin_fraction']:.1f} % "
              f"| {sec(r['t_program0'])} -> {sec(r['t_program'])} | {r['r_program']:.2f} "
              f"| {mb(r['rss0_bytes'])} -> {mb(r['rss_bytes'])} | {r['r_rss']:.2f} "
              f"| {r['program_energy0']:.4g} -> {r['program_energy']:.4g} |")
    print("\nIn the library: a solver without pins (constructor, `place_singularities()`, `solve()`), then one with the "
          "pins as `constrained_faces` (the same three, `face_directions` given to the placement and the solve); "
          "peak = VmHWM above the resident size before each solver\n")
    print("| mesh | pins | build, no pins -> pins | total (build + place + solve) | ratio | peak | ratio | energy "
          "| placement's field energy | proven optimal | lower bound | max constraint residual | links "
          "| of which decided (faces touch) | across one edge | disagreeing pairs |")
    print("|---|---|---|---|---:|---|---:|---:|---:|---|---:|---:|---:|---:|---:|---|")
    for r in rows["library"]:
        mesh, kind = r["name"].split("/")[1:3]
        t0 = r["t_build0"] + r["t_place0"] + r["t_solve0"]
        t1 = r["t_build"] + r["t_place"] + r["t_solve"]
        print(f"| {mesh} | {kind}: {r['pins']:.0f} ({100 * r['pin_fraction']:.1f} %) "
              f"| {sec(r['t_build0'])} -> {sec(r['t_build'])} | {sec(t0)} -> {sec(t1)} | {r['r_total']:.2f} "
              f"| {mb(r['peak0_bytes'])} -> {mb(r['peak_bytes'])} | {r['r_peak']:.2f} | {r['energy']:.6g} | {r['field_energy']:.6g} "
              f"| {'yes' if r['proven'] else 'no'} | {r['lower_bound']:.4g} | {r['max_constraint_residual']:.2g} | {r['links']:.0f} | {r['decided']:.0f} "
              f"| {r['links_one_edge']:.0f} | {r['disagreeing_pairs']:.0f} of {r['neighbouring_pairs']:.0f} |")
    if rows["set_constraints"]:
        print("\n`set_constraints()` on a solver built without pins, then `place_singularities()` and `solve()` with "
              "the pins' directions\n")
        print("| mesh | pins | constructor (no pins) | set_constraints | placement | solve | (set + solve) / constructor "
              "| peak, constructor -> set_constraints -> all | ratios | energy | proven optimal | lower bound | links | decided |")
        print("|---|---:|---|---|---|---|---:|---|---:|---:|---|---:|---:|---:|")
        for r in rows["set_constraints"]:
            mesh = r["name"].split("/")[1]
            print(f"| {mesh} | {r['pins']:.0f} | {sec(r['t_build0'])} | {sec(r['t_set'])} | {sec(r['t_place'])} "
                  f"| {sec(r['t_solve'])} | {r['r_set_solve']:.2f} "
                  f"| {mb(r['peak0_bytes'])} -> {mb(r.get('peak_set_bytes', -1))} -> {mb(r['peak_bytes'])} "
                  f"| {r.get('r_peak_set', -1):.2f}, {r['r_peak']:.2f} | {r['energy']:.6g} | {'yes' if r['proven'] else 'no'} "
                  f"| {r['lower_bound']:.6g} | {r['links']:.0f} | {r['decided']:.0f} |")


if __name__ == "__main__":
    main(sys.argv[1])
