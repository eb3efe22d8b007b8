#!/usr/bin/env python3
"""Writes benchmark/RESULTS.md from the JSON files of trivial_connections_benchmark (Google Benchmark).

    python3 scripts/benchmark_table.py --out benchmark/RESULTS.md RESULT.json [RESULT.json ...]
    python3 scripts/benchmark_table.py --section placement --out benchmark/RESULTS.md placement-*.json
    python3 scripts/benchmark_table.py --section python --out benchmark/RESULTS.md python-binding.json
    python3 scripts/benchmark_table.py --section editor --out benchmark/RESULTS.md editor-latency.json
    python3 scripts/benchmark_table.py --insert SECTION.md [SECTION.md ...] --out benchmark/RESULTS.md
    python3 scripts/benchmark_table.py --header-only [--run-info STEPS.tsv] --out benchmark/RESULTS.md [RESULT.json ...]

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

The file is a header and sections (from a ##, ### or #### heading to the next): the whole-file mode rewrites the
header and the sections it has JSON for and keeps every other section of --out as it is (none dropped; the order
is that of benchmark_tables/sections.py), and names the kept ones in the header. --insert puts Markdown fragments
(files starting with a section heading: the integer choice, the feature pins, the peers, written by
scripts/run_benchmarks.sh and scripts/regenerate_results.sh) in their place. --header-only rewrites the header
alone, with the steps and times of scripts/regenerate_results.sh (--run-info). --out is always written atomically
(FILE.tmp, then renamed).
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
from benchmark_tables.replace import read_fragments, replace_section, replace_sections
from benchmark_tables.report import earlier_runs, header_lines, section_lines
from benchmark_tables.report import section_name
from benchmark_tables.sections import KEYS, join, merge, missing, split, split_file, write_atomically


def log_written(titles):
    """appends the titles of the sections written to $TC_SECTIONS_LOG (scripts/regenerate_results.sh's record)"""
    log = os.environ.get("TC_SECTIONS_LOG")
    if log:
        with open(log, "a") as f:
            f.writelines(t + "\n" for t in titles)


def read_run_info(path):
    """scripts/regenerate_results.sh's record, a tab-separated file: 'command', 'start', 'total' lines, then one
    'step NAME SECONDS STATUS KEYS NOTE' line per step (KEYS: the short names of the sections it writes), 'wrote
    STEP TITLE' lines (the sections a step that succeeded wrote) and 'kept KEY REASON' lines"""
    run = {"command": "bash scripts/regenerate_results.sh", "start": "", "total": 0.0, "steps": [], "kept": {},
           "written": set()}
    with open(path) as f:
        for line in f:
            parts = line.rstrip("\n").split("\t")
            if parts[0] in ("command", "start", "mode") and len(parts) > 1:
                run[parts[0]] = parts[1]
            elif parts[0] == "total" and len(parts) > 1:
                run["total"] = float(parts[1])
            elif parts[0] == "step" and len(parts) >= 5:
                name, seconds, status, keys = parts[1], float(parts[2]), parts[3], parts[4].split()
                run["steps"].append({"name": name, "seconds": seconds, "status": status, "keys": keys,
                                     "note": parts[5] if len(parts) > 5 else ""})
            elif parts[0] == "wrote" and len(parts) >= 3:
                run["written"].add(parts[2])
            elif parts[0] == "kept" and len(parts) >= 3:
                run["kept"][KEYS.get(parts[1], parts[1])] = parts[2]
    return run


def write_header(path, contexts, command, run=None):
    """rewrites the header of `path` (its sections kept); with `run`, the sections its steps wrote are named as
    written, the others as kept"""
    header, sections = split_file(path)
    if run is not None:
        status = [(t, lines, "new" if t in run["written"] else "kept") for t, lines in sections]
    else:
        status = [(t, lines, "kept") for t, lines in sections]
    new_header = header_lines(contexts, command, run=run, status=status, earlier=earlier_runs(header))
    write_atomically(path, join(new_header, status))
    return status


def report_kept(status, path):
    kept = [t for t, _, how in status if how == "kept"]
    print(f"benchmark_table: wrote {path}: {sum(1 for *_, how in status if how == 'new')} sections written, "
          f"{len(kept)} kept as they were" + (": " + "; ".join(section_name(t) for t in kept) if kept else ""))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("json", nargs="*", help="Google Benchmark JSON outputs")
    ap.add_argument("--out", default="benchmark/RESULTS.md")
    ap.add_argument("--command", default="bash scripts/run_benchmarks.sh", help="how the numbers were made")
    ap.add_argument("--section", choices=["placement", "floor", "python", "editor"],
                    help="write only this section of --out (replaced in place, the rest of the file kept)")
    ap.add_argument("--insert", nargs="+", metavar="SECTION.md",
                    help="put these Markdown sections in --out (replaced in place or inserted in their order)")
    ap.add_argument("--header-only", action="store_true", help="rewrite only the header of --out")
    ap.add_argument("--run-info", help="the steps and times of scripts/regenerate_results.sh, for the header")
    args = ap.parse_args()
    if args.insert:
        if not os.path.exists(args.out):
            sys.exit(f"benchmark_table: {args.out} missing")
        try:
            sections = read_fragments(args.insert)
        except (OSError, ValueError) as e:
            sys.exit(f"benchmark_table: {e}")
        replace_sections(args.out, sections)
        log_written(t for t, _ in sections)
        print(f"benchmark_table: wrote the sections {', '.join(repr(t.lstrip('#').strip()) for t, _ in sections)} "
              f"of {args.out}")
        return
    if args.header_only:
        if not os.path.exists(args.out):
            sys.exit(f"benchmark_table: {args.out} missing")
        _, _, files = load_side_results([p for p in args.json if os.path.exists(p)])
        _, contexts = load(files)
        run = read_run_info(args.run_info) if args.run_info else None
        report_kept(write_header(args.out, contexts, args.command, run), args.out)
        return
    if not args.json:
        ap.error("the JSON files are needed (but with --insert or --header-only)")

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
        log_written([title])
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
        log_written([title])
        print(f"benchmark_table: wrote the section {title[4:]!r} of {args.out}")
        return
    # the sections made from the JSON in place of theirs in --out, every other section of --out kept as it is
    _, new = split("\n".join(section_lines(results, bindings, editors, args.command)))
    old_header, old = split_file(args.out) if os.path.exists(args.out) else ([], [])
    status = merge(old, new)
    lost = missing(old, status)
    if lost:
        sys.exit(f"benchmark_table: sections would vanish from {args.out}: {lost}")
    header = header_lines(contexts, args.command, status=status, earlier=earlier_runs(old_header))
    write_atomically(args.out, join(header, status))
    log_written(t for t, _ in new)
    report_kept(status, args.out)


if __name__ == "__main__":
    main()
