#!/usr/bin/python3
"""Checks scripts/render_field.py on the example sphere, against what the geometry says the picture
must show, so that a renderer drawing something plausible but wrong fails:
  * n = 1 with examples/data/sphere.sing (two +1 singularities at antipodal vertices) and streamlines:
    a valid PNG of the requested size, not uniform; 40-60% of the faces visible (orthographic view of a
    sphere); exactly the singularity on the camera's side visible, drawn red where the documented camera
    projects it and nothing red where the hidden one projects; all streamline segments counted (from the
    file) and only part of them drawn, and drawn where the sphere is (compared with a render without
    field);
  * n = 4 with eight +1/4 singularities at vertices 0..7 (four antipodal pairs of the icosahedron):
    8 singularities, exactly the 4 on the camera's side visible, glyphs drawn;
  * --quads with a quad mesh of the sphere written by the test (a latitude-longitude grid of 6 x 16 quads,
    208 edges): every edge counted, about half drawn, the lines on the sphere and darker than without;
    an OBJ face with an index out of range: exit status 1, no picture;
  * a truncated VTK file and a missing file: exit status 1, a 'render_field.py: FILE: reason' message,
    no picture written (not even a temporary file).
Usage: check_render.py PROGRAM OUTDIR   (PROGRAM: the trivial_connections executable)
Exit status: 0 success, 1 failure, 77 numpy or matplotlib missing (skip).
"""
import importlib, json, math, subprocess, sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
RENDER = ROOT / "scripts" / "render_field.py"
MESH, SING = ROOT / "examples" / "data" / "sphere.off", ROOT / "examples" / "data" / "sphere.sing"
W, H = 900, 700                  # not the default size, to check that --size is honoured
VIEW = (190.0, 35.0)             # azimuth, elevation: no singular vertex near the silhouette


def fail(msg):
    print(f"check_render.py: FAIL: {msg}")
    sys.exit(1)


def run(cmd, cwd):
    try:
        r = subprocess.run([str(c) for c in cmd], cwd=cwd, capture_output=True, text=True)
    except OSError as e:
        fail(f"cannot run {cmd[0]}: {e.strerror or e}")
    return r.returncode, r.stdout, r.stderr


def must_run(cmd, cwd):
    rc, out, err = run(cmd, cwd)
    if rc != 0:
        fail(f"{' '.join(map(str, cmd))} exited with {rc}:\n{out}{err}")
    return out


def read_vertices(path):
    import numpy as np
    words = [w for line in open(path) for w in line.split("#", 1)[0].split()]
    nv = int(words[1])
    return np.array(words[4:4 + 3 * nv], dtype=float).reshape(nv, 3)


def count_segments(path):
    """Segments of the polylines of a streamline file, from its LINES section."""
    tok = open(path).read().split()
    i = tok.index("LINES")
    nlines, p, total = int(tok[i + 1]), i + 3, 0
    for _ in range(nlines):
        m = int(tok[p])
        total, p = total + max(m - 1, 0), p + 1 + m
    return total


def camera(az, el):
    """The camera documented in render_field.py for --up y: frame (a, b, up) = (z, x, y)."""
    import numpy as np
    a, b, u = np.eye(3)[2], np.eye(3)[0], np.eye(3)[1]
    az, el = math.radians(az), math.radians(el)
    d = math.cos(el) * (math.cos(az) * a + math.sin(az) * b) + math.sin(el) * u
    r = -math.sin(az) * a + math.cos(az) * b
    return d, r, np.cross(d, r)


def read_png(path):
    import matplotlib.image as mpimg
    with open(path, "rb") as f:
        if f.read(8) != b"\x89PNG\r\n\x1a\n":
            fail(f"{path}: not a PNG file")
    img = mpimg.imread(path)
    if img.shape[:2] != (H, W):
        fail(f"{path}: {img.shape[1]}x{img.shape[0]} pixels, {W}x{H} requested")
    return img[:, :, :3]


def render(field, png, out, extra=()):
    stats = png.with_suffix(".json")
    must_run([sys.executable, RENDER, field, "-o", png, "--size", W, H, "--view", *VIEW,
              "--stats", stats, *extra], out)
    return json.loads(stats.read_text()), read_png(png)


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    try:
        import numpy as np
        importlib.import_module("matplotlib.image")    # used by read_png
    except ImportError as e:
        print(f"check_render.py: SKIP: {e} (run with a python that has numpy and matplotlib)")
        return 77
    program, out = Path(sys.argv[1]).resolve(), Path(sys.argv[2]).resolve()
    out.mkdir(parents=True, exist_ok=True)
    V = read_vertices(MESH)
    d, r, c = camera(*VIEW)

    # ---- n = 1, streamlines
    field, stream = out / "sphere.vtk", out / "sphere_stream.vtk"
    must_run([program, MESH, "--singularities", SING, "--vtk", field, "--streamlines", stream,
              "--connection", out / "sphere.connection.txt", "--field", out / "sphere.field.txt"], out)
    st, img = render(field, out / "sphere.png", out, ["--streamlines", stream])
    if img.std() < 0.05:
        fail("sphere.png is (nearly) uniform")
    if (st["width"], st["height"], st["faces"]) != (W, H, 1280):
        fail(f"stats: size {st['width']}x{st['height']}, {st['faces']} faces; expected {W}x{H}, 1280")
    if not 0.4 <= st["visible_faces"] / st["faces"] <= 0.6:
        fail(f"{st['visible_faces']} of {st['faces']} faces visible: not about half of a sphere")
    sing = [int(line.split()[0]) for line in open(SING) if line.split("#", 1)[0].strip()]
    if len(sing) != 2 or not np.allclose(V[sing[0]], -V[sing[1]]):
        fail(f"{SING}: expected two antipodal singular vertices")
    facing = [v for v in sing if V[v] @ d > 0]
    if min(abs(V[v] @ d) for v in sing) < 0.2 or len(facing) != 1:
        fail("the test's view is not generic: pick another VIEW")
    if (st["singularities"], st["visible_singularities"]) != (2, 1):
        fail(f"singularities {st['singularities']} ({st['visible_singularities']} visible), expected 2 (1)")
    total = count_segments(stream)
    if st["streamline_segments"] != total:
        fail(f"{st['streamline_segments']} streamline segments counted, the file has {total}")
    if not 0 < st["visible_streamline_segments"] < total:
        fail(f"{st['visible_streamline_segments']} of {total} streamline segments drawn")

    # Where the sphere is: the non-white extent on the middle row and column (the legend is in a corner).
    covered = (img < 0.97).any(axis=2)
    cols, rows = np.flatnonzero(covered[H // 2]), np.flatnonzero(covered[:, W // 2])
    cx, cy = (cols[0] + cols[-1] + 1) / 2, (rows[0] + rows[-1] + 1) / 2
    radius = (cols[-1] + 1 - cols[0]) / 2
    round_disc = abs((rows[-1] + 1 - rows[0]) / 2 - radius) < 0.05 * radius
    if abs(cx - W / 2) > 0.05 * W or abs(cy - H / 2) > 0.05 * H or not round_disc:
        fail(f"the sphere is not a centred disc: columns {cols[[0, -1]]}, rows {rows[[0, -1]]}")
    red = (img[:, :, 0] > 0.55) & (img[:, :, 1] < 0.35) & (img[:, :, 2] < 0.35)
    yy, xx = np.mgrid[0:H, 0:W] + 0.5

    def red_near(p):
        # image y points down, camera up is c
        px, py = cx + radius * (p @ r), cy - radius * (p @ c)
        return int((red & ((xx - px) ** 2 + (yy - py) ** 2 < (0.06 * radius) ** 2)).sum()), (px, py)

    front, back = facing[0], [v for v in sing if v != facing[0]][0]
    n_front, at_front = red_near(V[front])
    n_back, at_back = red_near(V[back])
    if n_front < 20:
        fail(f"no red (+1) singularity drawn near ({at_front[0]:.0f}, {at_front[1]:.0f}), where vertex "
             f"{front} facing the camera projects ({n_front} red pixels); flipped or wrong camera?")
    if n_back:
        fail(f"{n_back} red pixels near ({at_back[0]:.0f}, {at_back[1]:.0f}), where the hidden vertex "
             f"{back} projects: occlusion is wrong")

    # The lines are drawn on the sphere: compare with the same picture without field.
    _, bare = render(field, out / "sphere_bare.png", out, ["--glyphs", "0"])
    inner = (xx - cx) ** 2 + (yy - cy) ** 2 < (0.8 * radius) ** 2
    darker = (bare - img).max(axis=2) > 0.15
    if (darker & inner).sum() < 0.005 * inner.sum():
        fail(f"streamlines: only {(darker & inner).sum()} pixels darkened inside the sphere")
    if (darker & ((xx - cx) ** 2 + (yy - cy) ** 2 > (radius + 3) ** 2)).any():
        fail("streamlines drawn outside the sphere")

    # ---- n = 4, glyphs, eight +1/4 singularities
    quarters = out / "sphere_quarters.sing"
    quarters.write_text("# written by check_render.py\n" + "".join(f"{v} 1/4\n" for v in range(8)))
    field4 = out / "sphere4.vtk"
    must_run([program, MESH, "--n", "4", "--singularities", quarters, "--vtk", field4,
              "--connection", out / "sphere4.connection.txt", "--field", out / "sphere4.field.txt"], out)
    st4, img4 = render(field4, out / "sphere4.png", out)
    expect = int((V[:8] @ d > 0).sum())
    if min(abs(V[:8] @ d)) < 0.2:
        fail("the test's view is not generic for vertices 0..7: pick another VIEW")
    if st4["singularities"] != 8 or st4["visible_singularities"] != expect:
        fail(f"n = 4: singularities {st4['singularities']} ({st4['visible_singularities']} visible), "
             f"expected 8 ({expect})")
    if st4.get("glyphs", 0) <= 0 or st4["streamline_segments"] != 0 or img4.std() < 0.05:
        fail(f"n = 4: no glyphs drawn ({st4})")

    # ---- a quad mesh over the mesh: a latitude-longitude grid of the sphere, rings 1..7 of 8, 16 meridians
    radius3 = float(np.linalg.norm(V, axis=1).max())
    rings, meridians = 7, 16
    grid = out / "sphere_grid.obj"
    with open(grid, "w") as g:
        for i in range(1, rings + 1):
            t = math.pi * i / (rings + 1)
            for j in range(meridians):
                p = 2 * math.pi * j / meridians
                g.write(f"v {radius3 * math.sin(t) * math.cos(p)} {radius3 * math.sin(t) * math.sin(p)} "
                        f"{radius3 * math.cos(t)}\n")
        for i in range(rings - 1):
            for j in range(meridians):
                a, b = i * meridians + j + 1, i * meridians + (j + 1) % meridians + 1
                g.write(f"f {a} {b} {b + meridians} {a + meridians}\n")
    edges = rings * meridians + (rings - 1) * meridians
    stq, imgq = render(field4, out / "sphere_quads.png", out, ["--quads", grid])
    if stq["quad_edges"] != edges or stq["glyphs"] != 0:
        fail(f"--quads: {stq.get('quad_edges')} quad edges counted (the file has {edges}), "
             f"{stq['glyphs']} glyphs (none expected without --glyphs)")
    if not 0.3 * edges <= stq["visible_quad_edges"] <= 0.7 * edges:
        fail(f"--quads: {stq['visible_quad_edges']} of {edges} edges drawn: not about half of a sphere's")
    _, bare4 = render(field4, out / "sphere4_bare.png", out, ["--glyphs", "0"])
    darker = (bare4 - imgq).max(axis=2) > 0.15
    if (darker & inner).sum() < 0.005 * inner.sum():
        fail(f"--quads: only {(darker & inner).sum()} pixels darkened inside the sphere")
    if (darker & ((xx - cx) ** 2 + (yy - cy) ** 2 > (radius + 3) ** 2)).any():
        fail("--quads: lines drawn outside the sphere")
    broken = out / "broken_grid.obj"
    broken.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n")
    png = out / "broken_grid.png"
    png.unlink(missing_ok=True)
    rc, _, err = run([sys.executable, RENDER, field4, "--quads", broken, "-o", png], out)
    if rc != 1 or not err.startswith(f"render_field.py: {broken}: line 4:") or png.exists():
        fail(f"--quads with an index out of range: exit status {rc}, stderr {err!r}, picture written: {png.exists()}")

    # ---- errors: truncated file, missing file
    lines = field.read_text().splitlines(keepends=True)
    bad = out / "truncated.vtk"
    bad.write_text("".join(lines[:len(lines) // 2]))
    for src in (bad, out / "no_such_file.vtk"):
        png = out / f"{src.stem}.png"
        png.unlink(missing_ok=True)
        rc, _, err = run([sys.executable, RENDER, src, "-o", png], out)
        if rc != 1 or not err.startswith(f"render_field.py: {src}: "):
            fail(f"{src.name}: exit status {rc}, stderr {err!r}; "
                 f"expected 1 and 'render_field.py: {src}: ...'")
        if png.exists() or list(out.glob(".render_field.*")):
            fail(f"{src.name}: a picture was written despite the error")

    print(f"check_render.py: OK (sphere: {st['visible_faces']}/{st['faces']} faces, "
          f"{st['visible_streamline_segments']}/{total} segments; n = 4: {st4['visible_singularities']}/8 "
          f"singularities, {st4['glyphs']} glyphs; quads: {stq['visible_quad_edges']}/{edges} edges)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
