"""The section "The Python binding" (benchmark/python/binding_overhead.py)."""

from .common import fmt_faces, fmt_time


PYTHON_TITLE = "### The Python binding"


def python_table(bindings, lines, command):
    """the section "The Python binding" from the newest JSON file of benchmark/python/binding_overhead.py"""
    if not bindings:
        return
    data = max(bindings, key=lambda d: d.get("date", ""))
    lines.append(PYTHON_TITLE)
    lines.append("")
    lines.append(f"Measured {data.get('date', '')[:10]}"
                 + (f", commit {data['commit']}" if data.get("commit") else "")
                 + f", backend `{data.get('backend', 'auto')}`, by `{command}` (`benchmark/python/binding_overhead.py`, "
                 "everything in one Python process; medians over the repetitions). Build: `Solver(V, F)` timed in "
                 "Python against what a C++ program holding the same arrays does, `triangle_soup_to_mesh()` into a "
                 "`Surface_mesh` then the solver's constructor, both timed in C++ by "
                 "`trivial_connections._reference_build`; the two alternate and each starts with the freed heap given "
                 "back to the system. **arrays** = Python / (soup to mesh + constructor), the target (≤ 1: from arrays "
                 "no dearer than from a Surface_mesh made of them); **mesh** = Python / constructor alone, for a "
                 "program that holds a Surface_mesh already: the arrays carry no adjacency, and finding it (the soup's "
                 "validation) costs more than reading it out of a halfedge structure, which the constructor does. "
                 "The module builds its solver from the soup's validated connectivity rather than from the "
                 "Surface_mesh it also makes, and makes that mesh on a second thread at the lowest priority while the "
                 "constructor runs: on a mesh whose constructor keeps both cores busy (cheese, genus 133, mostly the "
                 "loop metric) it finds no idle time, and the two paths are even (0.99–1.06 over the runs of "
                 "2026-12-03). Solve: `Solver.solve()` timed in Python against the C++ `solve()` + "
                 "`compute_field()` inside it (target ≤ 1.05 at 75k faces).")
    lines.append("")
    lines.append("| mesh | faces | Solver(V, F) | C++: soup to mesh | C++: constructor | arrays | mesh "
                 "| solve, Python | C++ solve + field | solve ratio | reps |")
    lines.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in data["python_binding"]:
        cpp_build = r["soup_to_mesh"] + r["constructor"]
        lines.append(f"| {r['mesh']} | {fmt_faces(r['faces'])} | {fmt_time(r['python_build'])} "
                     f"| {fmt_time(r['soup_to_mesh'])} | {fmt_time(r['constructor'])} "
                     f"| {r['python_build'] / cpp_build:.2f} | {r['python_build'] / r['constructor']:.2f} "
                     f"| {fmt_time(r['python_solve'])} | {fmt_time(r['cpp_solve'])} "
                     f"| {r['python_solve'] / r['cpp_solve']:.3f} | {r['repetitions']} |")
    lines.append("")
