"""Reads the JSON files of the benchmarks: Google Benchmark runs, and the Python binding's and the editor's."""

import json
import statistics
import sys

from .common import PLACEMENT_PREFIX


def load(paths):
    """{backend: {mesh: {"counters": {...}, "date": str, "context": {...}, "error": str|None}}}"""
    results = {}
    contexts = []
    for path in paths:
        with open(path) as f:
            try:
                data = json.load(f)
            except json.JSONDecodeError as e:
                print(f"benchmark_table: skipping {path}: {e}", file=sys.stderr)
                continue
        ctx = data.get("context", {})
        date = ctx.get("date", "")
        runs = {}
        for b in data.get("benchmarks", []):
            if b.get("run_type", "iteration") != "iteration":
                continue
            name = b.get("run_name", b["name"]).split("/iterations")[0].split("/manual_time")[0]
            if "/" not in name:
                continue
            runs.setdefault(name, []).append(b)
        if any(not n.split("/", 1)[1].startswith(PLACEMENT_PREFIX) for n in runs if "/" in n):
            contexts.append((path, ctx))
        for name, reps in runs.items():
            backend, mesh = name.split("/", 1)
            errors = [r.get("error_message", "error") for r in reps if r.get("error_occurred")]
            good = [r for r in reps if not r.get("error_occurred")]
            counters = {}
            if good:
                keys = set().union(*(r.keys() for r in good))
                for k in keys:
                    vals = [r[k] for r in good if isinstance(r.get(k), (int, float)) and not isinstance(r.get(k), bool)]
                    if len(vals) == len(good):
                        counters[k] = statistics.median(vals)
            entry = {"counters": counters, "date": date, "context": ctx, "repetitions": len(good),
                     "error": errors[0] if errors and not good else None}
            old = results.setdefault(backend, {}).get(mesh)
            if old is None or old["date"] <= date:
                results[backend][mesh] = entry
    return results, contexts


def load_side_results(paths):
    """the contents of the JSON files of benchmark/python/binding_overhead.py and of the editor's latency among
    `paths`, and the other paths"""
    bindings, editors, others = [], [], []
    for path in paths:
        try:
            with open(path) as f:
                data = json.load(f)
        except (OSError, json.JSONDecodeError):
            others.append(path)  # load() reports it
            continue
        if isinstance(data, dict) and "python_binding" in data:
            bindings.append(data)
        elif isinstance(data, dict) and "editor_latency" in data:
            editors.append(data)
        else:
            others.append(path)
    return bindings, editors, others
