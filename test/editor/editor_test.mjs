// The field editor in headless Chromium (issue 22, work in progress), driven by playwright-core:
//
//   node editor_test.mjs SERVE MESH OUTDIR        (ctest editor_browser; NODE_PATH: the build's npm packages)
//
// SERVE: the launcher (trivial_connections-serve). Starts it on MESH, opens the page, and after each step (load,
// a click adding +1/n, a shift-click adding -1/n elsewhere, two undos, two redos, a drag, n = 6) checks the field the page holds against the
// library's answer for the same singularities (check_field.py, beside this file; PYTHONPATH: the module), not
// pixels; the screenshot of
// the last step goes to OUTDIR/editor.png, where the page must show the mesh (not the background) at the centre.
import { execFileSync } from "node:child_process";
import { mkdirSync, writeFileSync } from "node:fs";
import path from "node:path";
import { fileURLToPath } from "node:url";
import { launchBrowser, startServer } from "./harness.mjs";

const [serve, mesh, outdir] = process.argv.slice(2);
const here = path.dirname(fileURLToPath(import.meta.url));
mkdirSync(outdir, { recursive: true });

function fail(message) {
  console.error("editor_test: " + message);
  process.exitCode = 1;
  throw new Error(message);
}

// the server, on a free port: it prints its address once the solver is factored
const { server, address } = await startServer(serve, mesh, ["--n", "4"]);

let step = 0;
const t0 = Date.now();
async function checkField(page, what) {
  const state = await page.evaluate(() => ({ n: window.__editor.state.n, singularities: window.__editor.singularities() }));
  const directions = await page.evaluate(() => Array.from(window.__editor.directions));
  const base = path.join(outdir, `step${++step}`);
  writeFileSync(base + ".json", JSON.stringify(state));
  writeFileSync(base + ".f32", Buffer.from(new Float32Array(directions).buffer));
  try {
    const out = execFileSync("/usr/bin/python3", [path.join(here, "check_field.py"), mesh, base + ".json", base + ".f32"],
                             { encoding: "utf8" });
    console.log(`${((Date.now() - t0) / 1e3).toFixed(1)} s, ${what}: ${out.trim()}`);
  } catch (e) {
    fail(`${what}: the page's field differs from the library's\n${e.stdout || ""}${e.stderr || ""}`);
  }
}

async function solved(page, before) {
  await page.waitForFunction(n => window.__editor.solves > n || window.__editor.lastError, before, { timeout: 30000 });
  const error = await page.evaluate(() => window.__editor.lastError);
  if (error) fail("the page reports: " + error);
}

const browser = await launchBrowser();
try {
  const page = await browser.newPage({ viewport: { width: 1000, height: 750 } });
  page.on("pageerror", e => fail("page error: " + e.message));
  await page.goto(address);
  await page.waitForFunction(() => window.__editor && window.__editor.ready, null, { timeout: 60000 });
  await checkField(page, "load (automatic placement)");

  // two visible vertices without a singularity, far apart in index
  const [a, b] = await page.evaluate(() => {
    const e = window.__editor, found = [];
    const nv = e.component.length;
    for (let i = 0; i < nv && found.length < 2; i += 97) {
      const v = (i * 7919) % nv;
      if (!e.state.singularities.has(v) && e.screenOf(v).picked) found.push(v);
    }
    return found;
  });
  if (b === undefined) fail("no two visible vertices to click");
  const at = v => page.evaluate(u => window.__editor.screenOf(u), v);

  let solves = await page.evaluate(() => window.__editor.solves);
  let p = await at(a);
  await page.mouse.click(p.x, p.y); // +1/4: unbalanced, not solved
  await page.waitForFunction(v => window.__editor.state.singularities.has(v), a);
  p = await at(b);
  await page.keyboard.down("Shift");
  await page.mouse.click(p.x, p.y); // -1/4 elsewhere: balanced again, solved
  await page.keyboard.up("Shift");
  await solved(page, solves);
  const added = await page.evaluate(([u, v]) => [window.__editor.singularities().find(s => s[0] === u),
                                                 window.__editor.singularities().find(s => s[0] === v)], [a, b]);
  if (!added[0] || added[0][1] !== "1/4" || !added[1] || added[1][1] !== "-1/4")
    fail(`the clicks gave ${JSON.stringify(added)}, expected +1/4 at ${a} and -1/4 at ${b}`);
  await checkField(page, "after +1/4 and -1/4");

  // undo twice: the unbalanced state between the clicks (shown, not solved), then the start (solved)
  await page.click("#undo");
  await page.waitForFunction(v => !window.__editor.state.singularities.has(v) && window.__editor.unbalanced, b);
  solves = await page.evaluate(() => window.__editor.solves);
  await page.click("#undo");
  await solved(page, solves);
  if (await page.evaluate(v => window.__editor.state.singularities.has(v), a)) fail("undo kept the +1/4");
  await checkField(page, "after two undos");

  await page.click("#redo");
  await page.waitForFunction(() => window.__editor.unbalanced);
  solves = await page.evaluate(() => window.__editor.solves);
  await page.click("#redo");
  await solved(page, solves);
  await checkField(page, "after two redos");

  // drag the +1/4 at a to a visible vertex c: solved, a is free, c has it
  const c = await page.evaluate(([u, w]) => {
    const e = window.__editor, nv = e.component.length;
    for (let i = 1; i < nv; i += 89) {
      const v = (i * 6151) % nv;
      if (v !== u && v !== w && !e.state.singularities.has(v) && e.screenOf(v).picked) return v;
    }
    return -1;
  }, [a, b]);
  if (c < 0) fail("no vertex to drag to");
  solves = await page.evaluate(() => window.__editor.solves);
  p = await at(a);
  const q = await at(c);
  await page.mouse.move(p.x, p.y);
  await page.mouse.down();
  await page.mouse.move((p.x + q.x) / 2, (p.y + q.y) / 2, { steps: 4 });
  await page.mouse.move(q.x, q.y, { steps: 4 });
  await page.mouse.up();
  await solved(page, solves);
  const moved = await page.evaluate(([u, w]) => [window.__editor.state.singularities.has(u),
                                                 window.__editor.singularities().find(s => s[0] === w)], [a, c]);
  if (moved[0] || !moved[1] || moved[1][1] !== "1/4") fail(`the drag from ${a} to ${c} gave ${JSON.stringify(moved)}`);
  await checkField(page, "after a drag");

  // another n: the automatic placement for it, solved
  solves = await page.evaluate(() => window.__editor.solves);
  await page.selectOption("#n", "6");
  await solved(page, solves);
  if (await page.evaluate(() => window.__editor.state.n) !== 6) fail("n did not become 6");
  await checkField(page, "n = 6 (automatic placement)");

  // structure: the mesh covers the centre of the view (the background is #f4f4f4)
  const png = path.join(outdir, "editor.png");
  await page.screenshot({ path: png });
  const centre = await page.evaluate(() => {
    const c = document.querySelector("#view canvas");
    const gl = c.getContext("webgl2") || c.getContext("webgl");
    const pixel = new Uint8Array(4);
    gl.readPixels(c.width >> 1, c.height >> 1, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
    return Array.from(pixel);
  });
  if (centre[0] === 244 && centre[1] === 244 && centre[2] === 244) fail("the centre of the view is background");
  console.log(`editor_test: passed (screenshot ${png})`);
} finally {
  await browser.close();
  server.kill();
}
