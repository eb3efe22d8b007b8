#!/usr/bin/env python3
"""Writes benchmark/RESULTS.md from the JSON files of trivial_connections_benchmark (Google Benchmark).

    python3 scripts/benchmark_table.py --out benchmark/RESULTS.md RESULT.json [RESULT.json ...]
    python3 scripts/benchmark_table.py --section placement --out benchmark/RESULTS.md placement-*.json
    python3 scripts/benchmark_table.py --section python --out benchmark/RESULTS.md python-binding.json
    python3 scripts/benchmark_table.py --section editor --out benchmark/RESULTS.md editor-latency.json

Standard library only. A benchmark is named BACKEND/MESH (BACKEND/program/MESH: the main program as a whole
process); with repetitions, every counter is the median of
the repetitions. When a mesh of a backend appears in several files, the newest file wins. One table per
backend (times, ratios to the reference, memory), then the log-log slopes of every phase against the number
of faces (least squares of log t over the meshes), and a header with the machine and the dates.
BACKEND/placement/MESH (trivial_connections_placement_benchmark) makes the section "Automatic placement";
with --section placement, only that section of --out is written (replaced in place, or inserted before the
scaling slopes), the rest of the file kept as it is. A JSON file of benchmark/python/binding_overhead.py (key
"python_binding") makes the section "The Python binding" (--section python: that section only); one with the key
"editor_latency" (benchmark/editor/latency.mjs, gathered by run_benchmarks.sh --editor) the section "The field
editor" (--section editor).
"""

# The tables are in scripts/benchmark_tables/, one module per section; this file is the command line.

import argparse
import os
import sys

from benchmark_tables.editor import EDITOR_TITLE, editor_table
from benchmark_tables.loading import load, load_side_results
from benchmark_tables.pipeline import FLOOR_TITLE, floor_table
from benchmark_tables.placement import PLACEMENT_TITLE, placement_table
from benchmark_tables.python_binding import PYTHON_TITLE, python_table
from benchmark_tables.replace import replace_section
from benchmark_tables.report import results_lines


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("json", nargs="+", help="Google Benchmark JSON outputs")
    ap.add_argument("--out", default="benchmark/RESULTS.md")
    ap.add_argument("--command", default="bash scripts/run_benchmarks.sh", help="how the numbers were made")
    ap.add_argument("--section", choices=["placement", "floor", "python", "editor"],
                    help="write only this section of --out (replaced in place, the rest of the file kept)")
    args = ap.parse_args()

    bindings, editors, benchmark_files = load_side_results([p for p in args.json if os.path.exists(p)])
    sections = {"editor": (editor_table, editors, EDITOR_TITLE, "editor latency"),
                "python": (python_table, bindings, PYTHON_TITLE, "binding_overhead.py")}
    if args.section in sections:
        table, data, title, what = sections[args.section]
        section = []
        table(data, section, f"{args.command} --{args.section}")
        if not section:
            sys.exit(f"benchmark_table: no {what} results in " + " ".join(args.json))
        if not os.path.exists(args.out):
            sys.exit(f"benchmark_table: {args.out} missing (run the suite first)")
        replace_section(args.out, title, section)
        print(f"benchmark_table: wrote the section {title[4:]!r} of {args.out}")
        return
    results, contexts = load(benchmark_files)
    if not any(results.values()):
        sys.exit("benchmark_table: no benchmark results in " + " ".join(args.json))
    if args.section:
        # one section rewritten in place, the rest of the file kept
        section = []
        if args.section == "floor":
            title = FLOOR_TITLE
            floor_table(results, section, contexts, args.command + " --floor")
        else:
            title = PLACEMENT_TITLE
            placement_table(results, section, args.command + " --placement")
        if not section:
            sys.exit(f"benchmark_table: no {args.section} results in " + " ".join(args.json))
        if not os.path.exists(args.out):
            sys.exit(f"benchmark_table: {args.out} missing (run the suite first)")
        replace_section(args.out, title, section)
        print(f"benchmark_table: wrote the section {title[4:]!r} of {args.out}")
        return
    lines = results_lines(results, contexts, bindings, editors, args.command)
    with open(args.out, "w") as f:
        f.write("\n".join(lines))
    print(f"benchmark_table: wrote {args.out}")


if __name__ == "__main__":
    main()
