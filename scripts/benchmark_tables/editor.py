"""The section "The field editor" (benchmark/editor/latency.mjs)."""

import os

from .common import fmt_faces


EDITOR_TITLE = "### The field editor"


def editor_table(editors, lines, command):
    """the section "The field editor" from the newest JSON file of the editor's latency runs"""
    if not editors:
        return
    data = max(editors, key=lambda d: d.get("date", ""))
    runs = data["editor_latency"]
    lines.append(EDITOR_TITLE)
    lines.append("")
    gl = sorted({r.get("gl", "?") for r in runs})
    browser = sorted({r.get("browser", "?") for r in runs})
    lines.append(f"Measured {data.get('date', '')[:10]}" + (f", commit {data['commit']}" if data.get("commit") else "")
                 + f", by `{command}` (`benchmark/editor/latency.mjs`): the editor in headless Chromium "
                 f"{', '.join(browser)}, GL {', '.join(gl)}, 1200 x 900 pixels, n = 4. Each run drags one singularity "
                 "to another vertex 100 times with the mouse; an edit is timed from the pointer's release to the frame "
                 "read back: the server's solve on the prefactored solver, the transfer (binary, one float32 angle per "
                 "face) and the draw. **server**: request to response, of which **C++** is the library's solve and "
                 "field; **draw**: after the response, until a pixel of the page's field layer is read back. The page "
                 "draws the field in screen space, in a 2D canvas over the WebGL one: a glyph (the n directions) in "
                 "every cell of 16 pixels whose centre is on the mesh, for the face under it, so an edit redraws a few "
                 "hundred to a few thousand glyphs whatever the zoom and the mesh, and the WebGL canvas (the shaded "
                 "mesh, and a buffer of face numbers read back for the glyphs' faces) only when the camera moves. "
                 "**glyphs**: their number at that view; **field shown**: the share of the blocks of 24 x 24 pixels "
                 "wholly on the mesh that hold the glyphs' ink. Zoom 1 shows the whole mesh; zoom 6 brings the camera "
                 "six times closer. `fandisk_large_split` is CGAL's `fandisk_large.off` with every triangle split in "
                 "four at its edge midpoints (`benchmark/editor/split_faces.py`: CGAL's data set has no mesh of 100k "
                 "faces). Target (issue 22, issue 39): median ≤ 50 ms, 95th percentile ≤ 100 ms at 100k faces; the "
                 "page opens in under 3 s after the server has factored. This machine has no GPU: SwiftShader draws "
                 "on the same two cores as the server.")
    lines.append("")
    lines.append("| mesh | faces | zoom | glyphs | field shown | median | 95th percentile | server (median) "
                 "| C++ solve + field | draw (median) | page opens | edits |")
    lines.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    ms = lambda x: f"{x:.0f} ms" if x >= 10 else f"{x:.1f} ms"
    for r in runs:
        st = r["stats"]
        lines.append(f"| {os.path.basename(r['mesh'])} | {fmt_faces(r['faces'])} | {r['zoom']:g} | "
                     f"{r.get('glyphs', '?')} | "
                     + (f"{100 * r['coverage']:.0f} % " if "coverage" in r else "? ")  # runs before the screen-space glyphs
                     + f"| {ms(st['total']['median'])} | {ms(st['total']['p95'])} "
                     f"| {ms(st['server']['median'])} | {ms(st['solve']['median'])} | {ms(st['draw']['median'])} "
                     f"| {r['opened']:.2f} s | {r['edits']} |")
    lines.append("")
