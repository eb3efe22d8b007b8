// The field editor's latency (issue 22): from the click to the updated field on the screen, in headless Chromium.
//
//   NODE_PATH=build/editor-npm/node_modules PYTHONPATH=build/python \
//     node benchmark/editor/latency.mjs build/trivial_connections-serve MESH [EDITS] [--n N] [--zoom Z] [--json FILE]
//
// Starts the server on MESH (it factors first), opens the page (timed: navigation to the first field drawn), reports
// how much of the mesh shows the field at that view (harness.mjs: fieldCoverage()), then drags one singularity EDITS
// times (default 100) between visible vertices with the mouse; each edit is a solve on the prefactored solver, its
// transfer (binary, one float32 angle per face) and the draw, timed from the pointerup event to the frame read
// back. Prints the median and 95th percentile, and the split: server (request to response, of which the C++
// solve + field), draw (upload: the field, markers and pins handed to the field view; render: the draw calls, the
// field's glyphs into the 2D overlay; finish: until a pixel of it is read back). --zoom Z brings the camera Z times
// closer first (the glyphs follow the screen, one per cell of 16 pixels on the mesh: about as many at any zoom).
// The GPU is Chromium's SwiftShader (software) unless TC_CHROMIUM_GL says otherwise. A drag whose release picks a
// vertex beside the target (the nearest vertex to the point hit) moves the singularity there: an edit all the same.
import { writeFileSync } from "node:fs";
import { fieldCoverage, launchBrowser, startServer } from "../../test/editor/harness.mjs";

const args = process.argv.slice(2);
const nIndex = args.indexOf("--n");
const n = nIndex >= 0 ? args.splice(nIndex, 2)[1] : "4";
const zoomIndex = args.indexOf("--zoom");
const zoom = zoomIndex >= 0 ? Number(args.splice(zoomIndex, 2)[1]) : 1;
const jsonIndex = args.indexOf("--json");
const jsonPath = jsonIndex >= 0 ? args.splice(jsonIndex, 2)[1] : null;
const [serve, mesh, editsArg] = args;
const edits = Number(editsArg || 100);

const startedServer = Date.now();
const { server, address } = await startServer(serve, mesh, ["--n", n]);
const factored = (Date.now() - startedServer) / 1e3;

const quantile = (xs, q) => { const s = [...xs].sort((a, b) => a - b); return s[Math.min(s.length - 1, Math.floor(q * s.length))]; };
const browser = await launchBrowser();
try {
  const page = await browser.newPage({ viewport: { width: 1200, height: 900 } });
  const t0 = Date.now();
  await page.goto(address);
  await page.waitForFunction(() => window.__editor && window.__editor.ready, null, { timeout: 120000 });
  const opened = (Date.now() - t0) / 1e3;
  const faces = await page.evaluate(() => window.__editor.faces);
  if (zoom !== 1) await page.evaluate(z => window.__editor.zoom(z), zoom);
  const shown = await fieldCoverage(page); // the field drawn at this view (glyphs: their number)
  const glyphs = shown.glyphs;
  // visible vertices without a singularity, and one singularity to move among them
  const targets = await page.evaluate(() => {
    const e = window.__editor, nv = e.component.length, found = [];
    for (let i = 1; i < nv && found.length < 24; i += 31) {
      const v = (i * 7919) % nv;
      if (!e.state.singularities.has(v) && e.screenOf(v).picked) found.push(v);
    }
    return found;
  });
  let current = await page.evaluate(() => {
    const e = window.__editor;
    for (const [v] of e.state.singularities) if (e.screenOf(v).picked) return v;
    return -1;
  });
  if (targets.length < 2) throw new Error("no visible vertices to move a singularity to");
  if (current < 0) { // none in view: one moved into it first
    current = targets[0];
    await page.evaluate(v => window.__editor.edit(() => {
      const s = window.__editor.state.singularities, [u, k] = s.entries().next().value;
      s.delete(u);
      s.set(v, k);
    }), current);
  }
  await page.evaluate(() => { window.__editor.measure = true; window.__editor.latencies = []; });
  for (let i = 0, t = 0; i < edits; ++i) {
    // the next target at least 20 pixels away (a shorter move is a click, not a drag) and free
    const p = await page.evaluate(v => window.__editor.screenOf(v), current);
    let next = -1, q = null;
    for (let tries = 0; tries < targets.length && next < 0; ++tries, ++t) {
      const v = targets[t % targets.length];
      const s = await page.evaluate(u => window.__editor.state.singularities.has(u) ? null : window.__editor.screenOf(u), v);
      if (s && s.picked && Math.hypot(s.x - p.x, s.y - p.y) > 20) { next = v; q = s; }
    }
    if (next < 0) throw new Error("no vertex to drag the singularity to");
    const before = await page.evaluate(() => window.__editor.solves);
    const held = await page.evaluate(() => [...window.__editor.state.singularities.keys()]);
    await page.mouse.move(p.x, p.y);
    await page.mouse.down();
    await page.mouse.move(q.x, q.y, { steps: 2 });
    await page.mouse.up();
    await page.waitForFunction(b => window.__editor.solves > b || window.__editor.lastError || window.__editor.unbalanced,
                               before, { timeout: 30000 }).catch(async error => {
      const why = await page.evaluate(([u, v]) => ({ status: document.getElementById("status").textContent,
        from: window.__editor.state.singularities.has(u), to: window.__editor.state.singularities.has(v) }), [current, next]);
      throw new Error(`edit ${i}: no solve after dragging ${current} to ${next} (${JSON.stringify([p, q])}): ${JSON.stringify(why)}`);
    });
    const [error, unbalanced, moved] = await page.evaluate(v => [window.__editor.lastError, window.__editor.unbalanced,
                                                               window.__editor.state.singularities.has(v)], next);
    if (error || unbalanced) throw new Error(`edit ${i}: the drag to ${next} gave no solve (${error})`);
    current = moved ? next : await page.evaluate(held => {
      // the release picked a vertex beside the target (an edit all the same): the singularity is there now
      const added = [...window.__editor.state.singularities.keys()].filter(v => !held.includes(v));
      return added.length === 1 ? added[0] : -1;
    }, held);
    if (current < 0) throw new Error(`edit ${i}: the drag to ${next} moved no singularity`);
  }
  const l = await page.evaluate(() => window.__editor.latencies);
  const col = k => l.map(x => x[k]);
  console.log(`${mesh}: ${faces} faces, n = ${n}, zoom ${zoom} (${glyphs} glyphs; ${(100 * shown.coverage).toFixed(1)} % ` +
              `of the ${shown.blocks} blocks of 24 x 24 pixels wholly on the mesh hold ink, ${(100 * shown.ink).toFixed(1)} % ` +
              `of its pixels); server ` +
              `factored in ${factored.toFixed(2)} s, page opened in ${opened.toFixed(2)} s after that; ${l.length} edits`);
  const stats = {};
  for (const k of ["total", "server", "solve", "draw", "upload", "render", "calls", "finish"]) {
    stats[k] = { median: quantile(col(k), 0.5), p95: quantile(col(k), 0.95) };
    console.log(`  ${k.padEnd(6)} median ${stats[k].median.toFixed(1)} ms, 95th percentile ${stats[k].p95.toFixed(1)} ms`);
  }
  const gl = await page.evaluate(() => {
    const g = window.__editor.internals.renderer.getContext(), i = g.getExtension("WEBGL_debug_renderer_info");
    return i ? g.getParameter(i.UNMASKED_RENDERER_WEBGL) : g.getParameter(g.RENDERER);
  });
  if (jsonPath)
    writeFileSync(jsonPath, JSON.stringify({ mesh, faces, n: Number(n), zoom, glyphs, coverage: shown.coverage,
                                             ink: shown.ink, factored, opened,
                                             edits: l.length, gl, browser: browser.version(), stats,
                                             date: new Date().toISOString() }, null, 1));
} finally {
  await browser.close();
  server.kill();
}
