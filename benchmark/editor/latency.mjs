// The field editor's latency (issue 22): from the click to the updated field on the screen, in headless Chromium.
//
//   NODE_PATH=build/editor-npm/node_modules PYTHONPATH=build/python \
//     node benchmark/editor/latency.mjs build/trivial_connections-serve MESH [EDITS] [--n N]
//
// Starts the server on MESH (it factors first), opens the page (timed: navigation to the first field drawn), then
// drags one singularity EDITS times (default 100) between visible vertices with the mouse; each edit is a solve on
// the prefactored solver, its transfer (binary), the glyphs' upload and the draw, timed from the pointerup event
// to the frame read back from the GPU. Prints the median and 95th percentile, and the split: server (request to
// response, of which the C++ solve + field), draw (parse, glyphs, upload, draw). The GPU is Chromium's
// SwiftShader (software) unless TC_CHROMIUM_GL says otherwise.
import { launchBrowser, startServer } from "../../test/editor/harness.mjs";

const args = process.argv.slice(2);
const nIndex = args.indexOf("--n");
const n = nIndex >= 0 ? args.splice(nIndex, 2)[1] : "4";
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
  const faces = await page.evaluate(() => window.__editor.directions.length / 3 / window.__editor.state.n);
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
  if (current < 0 || targets.length < 2) throw new Error("no visible singularity or vertices to move it to");
  await page.evaluate(() => { window.__editor.measure = true; window.__editor.latencies = []; });
  for (let i = 0; i < edits; ++i) {
    const next = targets[i % targets.length] === current ? targets[(i + 1) % targets.length] : targets[i % targets.length];
    const p = await page.evaluate(v => window.__editor.screenOf(v), current);
    const q = await page.evaluate(v => window.__editor.screenOf(v), next);
    const before = await page.evaluate(() => window.__editor.solves);
    await page.mouse.move(p.x, p.y);
    await page.mouse.down();
    await page.mouse.move(q.x, q.y, { steps: 2 });
    await page.mouse.up();
    await page.waitForFunction(b => window.__editor.solves > b || window.__editor.lastError, before);
    current = next;
  }
  const l = await page.evaluate(() => window.__editor.latencies);
  const col = k => l.map(x => x[k]);
  console.log(`${mesh}: ${faces} faces, n = ${n}; server factored in ${factored.toFixed(2)} s, page opened in ` +
              `${opened.toFixed(2)} s after that; ${l.length} edits`);
  for (const k of ["total", "server", "solve", "draw", "glyphs", "render"])
    console.log(`  ${k.padEnd(6)} median ${quantile(col(k), 0.5).toFixed(1)} ms, 95th percentile ${quantile(col(k), 0.95).toFixed(1)} ms`);
} finally {
  await browser.close();
  server.kill();
}
