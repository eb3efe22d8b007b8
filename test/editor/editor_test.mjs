// The field editor in headless Chromium, driven by playwright-core:
//
//   node editor_test.mjs SERVE MESH BORDERED_MESH OUTDIR     (ctest editor_browser; NODE_PATH: the build's npm packages)
//
// SERVE: the launcher (trivial_connections-serve). First, on CGAL's refined_elephant beside MESH (89k faces), the
// field at the whole-mesh view, by structure: the share of the mesh's 24-pixel blocks that hold the glyphs' ink, and
// a pin's arrow (see largeMesh()). On MESH (closed): load, a click adding +1/n, a shift-click adding
// -1/n elsewhere, two undos, two redos, the legend of the shortcuts (every modifier key the code reads, every tool,
// exactly the keyboard shortcuts of the page's table) and those shortcuts pressed, a drag, a pinned direction, a
// stroke, an undo, an unbalancing click (the page shows the component and by how much, keeps the field drawn, glyphs
// or streamlines, and shows no error) completed by the balancing move (one click: the singularity its button names),
// save and load of singularities and constraints, a save over an existing file (the page asks: declined, the file
// is kept; accepted, replaced), n = 6 (the quad mesh control disabled), streamlines, a PNG. After each step
// the field the page holds is checked against the library's answer for the same request (check_field.py, beside
// this file; PYTHONPATH: the module), not pixels. The screenshot of the last step goes to OUTDIR/editor.png; its
// structure is checked: the mesh at the centre, and each visible singularity's marker, in its colour, at the pixel
// where the camera projects its vertex. On BORDERED_MESH, copied to OUTDIR/held/held.off and served from that folder
// as `cd DIR; trivial_connections-serve held.off` does (issue 36): boundary alignment on, a pin, align with sharp
// features on and off (issue 37), the quad mesh overlay (issue 43: its edges drawn, its counts in the status line,
// half the size about four times the quads, unchecked gone), then saves under the mesh's own name and a hard
// link's, refused with the reason
// shown and the mesh untouched.
import { execFileSync } from "node:child_process";
import { copyFileSync, existsSync, linkSync, mkdirSync, readdirSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import path from "node:path";
import { fileURLToPath } from "node:url";
import { fieldCoverage, launchBrowser, startServer } from "./harness.mjs";

const [serve, mesh, bordered, outdir] = process.argv.slice(2);
const here = path.dirname(fileURLToPath(import.meta.url));
const files = path.join(outdir, "files"); // the server's folder
rmSync(files, { recursive: true, force: true });
mkdirSync(files, { recursive: true });

function fail(message) {
  console.error("editor_test: " + message);
  process.exitCode = 1;
  throw new Error(message);
}

let step = 0;
const t0 = Date.now();
async function checkField(page, meshPath, what) {
  await page.evaluate(() => window.__editor.idle());
  const request = await page.evaluate(() => window.__editor.request());
  const directions = await page.evaluate(() => Array.from(window.__editor.directions));
  const base = path.join(outdir, `step${++step}`);
  writeFileSync(base + ".json", JSON.stringify(request));
  writeFileSync(base + ".f32", Buffer.from(new Float32Array(directions).buffer));
  try {
    const out = execFileSync("/usr/bin/python3", [path.join(here, "check_field.py"), meshPath, base + ".json", base + ".f32"],
                             { encoding: "utf8" });
    console.log(`${((Date.now() - t0) / 1e3).toFixed(1)} s, ${what}: ${out.trim()}`);
  } catch (e) {
    fail(`${what}: the page's field differs from the library's\n${e.stdout || ""}${e.stderr || ""}`);
  }
}

const solves = page => page.evaluate(() => window.__editor.solves);
// the pixels of the view in the quad mesh's green (0x0b7a3e, a colour nothing else of the page uses)
const greenPixels = page => page.evaluate(() => {
  const c = window.__editor.internals.fieldView.composite();
  const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
  let count = 0;
  for (let i = 0; i < d.length; i += 4)
    count += Math.abs(d[i] - 0x0b) < 20 && Math.abs(d[i + 1] - 0x7a) < 20 && Math.abs(d[i + 2] - 0x3e) < 20;
  return count;
});
async function solved(page, before) {
  await page.waitForFunction(n => window.__editor.solves > n || window.__editor.lastError, before, { timeout: 30000 });
  const error = await page.evaluate(() => window.__editor.lastError);
  if (error) fail("the page reports: " + error);
}

// visible vertices (faces) a click there picks, without a singularity (pin), spread over the numbering
const visibleVertices = (page, count, stride) => page.evaluate(([count, stride]) => {
  const e = window.__editor, nv = e.component.length, found = [];
  for (let i = 1; i < nv && found.length < count; i += 97) {
    const v = (i * stride) % nv;
    if (!e.state.singularities.has(v) && e.screenOf(v).picked) found.push(v);
  }
  return found;
}, [count, stride]);
const visibleFaces = (page, count) => page.evaluate(count => {
  const e = window.__editor, found = [];
  for (let i = 1; i < e.faces && found.length < count; i += 37) {
    const f = (i * 7907) % e.faces;
    if (!e.state.constraints.has(f) && e.screenOfFace(f).picked) found.push(f);
  }
  return found;
}, count);

async function drag(page, p, q, steps = 4) {
  await page.mouse.move(p.x, p.y);
  await page.mouse.down();
  await page.mouse.move((p.x + q.x) / 2, (p.y + q.y) / 2, { steps });
  await page.mouse.move(q.x, q.y, { steps });
  await page.mouse.up();
}

async function open(browser, address) {
  const page = await browser.newPage({ viewport: { width: 1000, height: 750 }, acceptDownloads: true });
  // an error in the page closes it: every wait on it fails at once, with this message first
  page.on("pageerror", e => {
    console.error("editor_test: page error: " + e.message);
    process.exitCode = 1;
    page.close();
  });
  await page.goto(address);
  await page.waitForFunction(() => window.__editor && window.__editor.ready, null, { timeout: 60000 });
  return page;
}

// the legend of the shortcuts (#shortcuts): in view without hovering anything, it names every modifier key the
// page's code reads (e.shiftKey, e.altKey, e.ctrlKey, e.metaKey in editor/web/*.js), every tool of the tool menu,
// and exactly the keyboard shortcuts of the page's table (window.__editor.keys), each spelt out in <kbd>s; returns
// the table
async function checkLegend(page) {
  const web = path.join(here, "..", "..", "editor", "web"); // the page's modules, main.js and those it imports
  const source = readdirSync(web).filter(f => f.endsWith(".js")).map(f => readFileSync(path.join(web, f), "utf8"))
    .join("\n");
  const names = { shiftKey: "Shift", altKey: "Alt", ctrlKey: "Ctrl", metaKey: "⌘" };
  const modifiers = [...new Set([...source.matchAll(/\.(shiftKey|altKey|ctrlKey|metaKey)\b/g)].map(m => names[m[1]]))];
  const legend = await page.evaluate(() => {
    const box = document.querySelector("#shortcuts"), r = box.getBoundingClientRect();
    const kbd = e => [...e.querySelectorAll("kbd")].map(k => k.textContent.trim());
    const shown = e => e.checkVisibility() && e.getBoundingClientRect().width > 0;
    return { inView: shown(box) && r.top >= 0 && r.bottom <= innerHeight && r.right <= innerWidth,
             kbd: kbd(box), tools: [...box.querySelectorAll("[data-tool]")].filter(shown).map(e => e.dataset.tool),
             keys: [...box.querySelectorAll("[data-keys]")].filter(shown)
               .map(e => ({ keys: e.dataset.keys, does: e.dataset.does, spelt: kbd(e).join("+") })),
             options: [...document.querySelectorAll("#tool option")].map(o => o.value),
             table: window.__editor.keys.map(({ keys, does }) => ({ keys, does })) };
  });
  if (!legend.inView) fail("the legend of the shortcuts is not in view");
  const missing = modifiers.filter(m => !legend.kbd.includes(m));
  if (modifiers.length < 3 || missing.length) fail(`the legend lacks the modifiers ${missing} (the code reads ${modifiers})`);
  const tools = legend.options.filter(t => !legend.tools.includes(t));
  if (tools.length) fail(`the legend does not say what the tools ${tools} do`);
  const key = k => `${k.keys} ${k.does}`;
  const listed = new Set(legend.keys.map(key)), handled = new Set(legend.table.map(key));
  const unlisted = legend.table.filter(k => !listed.has(key(k))), unhandled = legend.keys.filter(k => !handled.has(key(k)));
  if (!legend.table.length || unlisted.length || unhandled.length)
    fail(`keyboard shortcuts: handled but not in the legend ${JSON.stringify(unlisted)}, in the legend but not ` +
         `handled ${JSON.stringify(unhandled)}`);
  const misspelt = legend.keys.filter(k => k.spelt !== k.keys);
  if (misspelt.length) fail(`the legend's keys are not spelt out: ${JSON.stringify(misspelt)}`);
  console.log(`legend: modifiers ${modifiers.join(", ")}; tools ${legend.tools.join(", ")}; ` +
              legend.keys.map(key).join(", "));
  return legend.table;
}

// the page in an unbalanced state after a click of +1/4 at vertex v: one .unbalanced line, for v's component, of
// `units` units of 1/4, in view; no error shown, nothing that looks like the server's words (a code such as
// poincare_hopf_violated, its "Poincare-Hopf", an HTTP status)
async function unbalancedShown(page, v, units, what) {
  const shown = await page.evaluate(u => ({
    lines: [...document.querySelectorAll("#balance .unbalanced")].map(e => ({
      component: Number(e.dataset.component), units: e.dataset.units, n: Number(e.dataset.n), text: e.textContent,
      visible: e.checkVisibility() })),
    component: window.__editor.component[u], lastError: window.__editor.lastError,
    errors: [...document.querySelectorAll(".error")].filter(e => e.checkVisibility() && e.textContent.trim())
      .map(e => e.textContent),
    text: document.body.innerText }), v);
  const [line] = shown.lines;
  if (shown.lines.length !== 1 || line.component !== shown.component || line.units !== String(units) || line.n !== 4 ||
      !line.visible || !line.text.includes(`+${units} × 1/4`))
    fail(`${what}: the unbalanced component ${shown.component} is shown as ${JSON.stringify(shown.lines)}`);
  const raw = /\b[a-z]+(?:_[a-z]+)+\b|Poincare-Hopf|HTTP \d{3}/.exec(shown.text);
  if (shown.errors.length || shown.lastError || raw)
    fail(`${what}: the page shows an error: ${JSON.stringify(shown.errors)} ${shown.lastError} ${raw}`);
  console.log(`${what}: "${line.text}"; no error shown`);
}

// the keyboard shortcuts, pressed where two clicks are balanced: an undo leaves the unbalanced state between them,
// each redo solves again (the first pair with ⌘, Meta, the others with Ctrl)
async function pressShortcuts(page, table) {
  const undo = table.find(k => k.does === "undo");
  if (!undo) fail("no keyboard shortcut undoes");
  for (const [i, redo] of table.filter(k => k.does === "redo").entries()) {
    // "Ctrl+Shift+Z" -> Playwright's "Meta+Shift+z" or "Control+Shift+z"
    const press = k => page.keyboard.press(k.keys.split("+").map((part, j, all) => j === all.length - 1
      ? part.toLowerCase() : part === "Ctrl" ? (i === 0 ? "Meta" : "Control") : part).join("+"));
    await press(undo);
    await page.waitForFunction(() => window.__editor.unbalanced, null, { timeout: 10000 });
    const before = await solves(page);
    await press(redo);
    await solved(page, before);
    if (await page.evaluate(() => window.__editor.unbalanced)) fail(`${redo.keys} did not redo`);
  }
}

async function closedMesh(browser) {
  const { server, address } = await startServer(serve, mesh, ["--n", "4", "--folder", files]);
  try {
    const page = await open(browser, address);
    await checkField(page, mesh, "load (automatic placement)");
    const at = v => page.evaluate(u => window.__editor.screenOf(u), v);
    const atFace = f => page.evaluate(g => window.__editor.screenOfFace(g), f);

    const [a, b] = await visibleVertices(page, 2, 7919);
    if (b === undefined) fail("no two visible vertices to click");
    let before = await solves(page);
    let p = await at(a);
    await page.mouse.click(p.x, p.y); // +1/4: unbalanced, not solved
    await page.waitForFunction(v => window.__editor.state.singularities.has(v), a);
    p = await at(b);
    await page.keyboard.down("Shift");
    await page.mouse.click(p.x, p.y); // -1/4 elsewhere: balanced again, solved
    await page.keyboard.up("Shift");
    await solved(page, before);
    const added = await page.evaluate(([u, v]) => [window.__editor.singularities().find(s => s[0] === u),
                                                   window.__editor.singularities().find(s => s[0] === v)], [a, b]);
    if (!added[0] || added[0][1] !== "1/4" || !added[1] || added[1][1] !== "-1/4")
      fail(`the clicks gave ${JSON.stringify(added)}, expected +1/4 at ${a} and -1/4 at ${b}`);
    await checkField(page, mesh, "after +1/4 and -1/4");

    // undo twice: the unbalanced state between the clicks (shown, not solved), then the start (solved)
    await page.click("#undo");
    await page.waitForFunction(v => !window.__editor.state.singularities.has(v) && window.__editor.unbalanced, b);
    before = await solves(page);
    await page.click("#undo");
    await solved(page, before);
    if (await page.evaluate(v => window.__editor.state.singularities.has(v), a)) fail("undo kept the +1/4");
    await checkField(page, mesh, "after two undos");

    await page.click("#redo");
    await page.waitForFunction(() => window.__editor.unbalanced);
    before = await solves(page);
    await page.click("#redo");
    await solved(page, before);
    await checkField(page, mesh, "after two redos");
    await pressShortcuts(page, await checkLegend(page));
    await checkField(page, mesh, "undone and redone by the keyboard");

    // drag the +1/4 at a to a visible vertex c: solved, a is free, c has it
    const c = (await visibleVertices(page, 8, 6151)).find(v => v !== a && v !== b);
    if (c === undefined) fail("no vertex to drag to");
    before = await solves(page);
    await drag(page, await at(a), await at(c));
    await solved(page, before);
    const moved = await page.evaluate(([u, w]) => [window.__editor.state.singularities.has(u),
                                                   window.__editor.singularities().find(s => s[0] === w)], [a, c]);
    if (moved[0] || !moved[1] || moved[1][1] !== "1/4") fail(`the drag from ${a} to ${c} gave ${JSON.stringify(moved)}`);
    await checkField(page, mesh, "after a drag");

    // pin: a drag from a visible face, 40 pixels to the right
    const faces = await visibleFaces(page, 6);
    if (faces.length < 3) fail("no visible faces to pin");
    await page.selectOption("#tool", "pin");
    before = await solves(page);
    p = await atFace(faces[0]);
    await drag(page, p, { x: p.x + 40, y: p.y + 10 });
    await solved(page, before);
    if (!(await page.evaluate(f => window.__editor.state.constraints.has(f), faces[0]))) fail("the drag pinned nothing");
    await checkField(page, mesh, "a pinned direction");

    // a stroke from one visible face to another: the faces crossed follow it
    await page.selectOption("#tool", "stroke");
    before = await solves(page);
    await drag(page, await atFace(faces[1]), await atFace(faces[2]), 12);
    await solved(page, before);
    const pinned = await page.evaluate(() => window.__editor.state.constraints.size);
    if (pinned < 2) fail(`the stroke pinned nothing (${pinned} pins)`);
    await checkField(page, mesh, `a stroke (${pinned} pins)`);
    before = await solves(page);
    await page.click("#undo");
    await solved(page, before);
    if (await page.evaluate(() => window.__editor.state.constraints.size) !== 1) fail("undo did not remove the stroke");
    await checkField(page, mesh, "the stroke undone");

    // an unbalancing click: the page says which component is off and by how much (a line of its own), the field
    // drawn before stays (in the streamline view too), no error and no server text is shown; the balancing move,
    // one click, adds the singularity its button names, and the state is solved
    await page.selectOption("#tool", "singularities");
    const [d] = (await visibleVertices(page, 12, 104729)).filter(v => v !== a && v !== b && v !== c);
    const drawn = await page.evaluate(() => Array.from(window.__editor.directions));
    before = await solves(page);
    p = await at(d);
    await page.mouse.click(p.x, p.y);
    await page.waitForFunction(() => window.__editor.unbalanced);
    await page.evaluate(() => window.__editor.idle());
    await unbalancedShown(page, d, 1, "click");
    if (await solves(page) !== before) fail("an unbalanced state was solved");
    const kept = await page.evaluate(() => Array.from(window.__editor.directions));
    if (kept.length !== drawn.length || kept.some((x, i) => x !== drawn[i])) fail("the field drawn before did not stay");
    await page.evaluate(() => { window.__editor.streamlineCount = 0; });
    await page.selectOption("#display", "streamlines"); // the last balanced field's streamlines
    await page.waitForFunction(() => window.__editor.streamlineCount > 0 || window.__editor.lastError, null,
                               { timeout: 30000 });
    await unbalancedShown(page, d, 1, "click, streamlines shown");
    const proposed = await page.evaluate(() => window.__editor.proposal());
    const label = await page.textContent("#balance-move");
    if (!proposed || proposed.length !== 1 || proposed[0][1] !== "-1/4" || !label.includes(`vertex ${proposed[0][0]}`) ||
        !label.includes("−1/4"))
      fail(`the balancing move proposes ${JSON.stringify(proposed)}, its button says "${label}"`);
    before = await solves(page);
    await page.click("#balance-move");
    await solved(page, before);
    const after = await page.evaluate(([v, k]) => ({
      off: window.__editor.balance().filter(x => !x.balanced).length, lines: document.querySelectorAll(".unbalanced").length,
      added: window.__editor.singularities().find(s => s[0] === v)?.[1], unbalanced: window.__editor.unbalanced,
      offered: !document.querySelector("#balance-move").hidden }), proposed[0]);
    if (after.off || after.lines || after.unbalanced || after.offered || after.added !== proposed[0][1])
      fail(`after the balancing move: ${JSON.stringify(after)}`);
    console.log(`the balancing move: "${label}", solved`);
    await page.selectOption("#display", "glyphs");
    await checkField(page, mesh, "the balancing move");

    // save singularities and pins in the server's folder, change things, load them back
    const saved = await page.evaluate(() => window.__editor.request());
    for (const [kind, name] of [["singularities", "design.sing"], ["constraints", "design.dirs"],
                                ["field", "design.field.txt"], ["vtk", "design.vtk"]]) {
      await page.selectOption("#kind", kind);
      await page.fill("#path", name);
      await page.click("#save");
      await page.waitForFunction(x => window.__editor.saved === x || window.__editor.lastError, name);
      if (!existsSync(path.join(files, name))) fail(`save ${kind}: no ${name} in the server's folder`);
    }
    await page.selectOption("#kind", "singularities");
    await page.fill("#path", "../outside.sing");
    await page.click("#save");
    await page.waitForFunction(() => window.__editor.lastError);
    if (existsSync(path.join(outdir, "outside.sing"))) fail("a path outside the folder was written");
    console.log(`refused: ${await page.evaluate(() => window.__editor.lastError)}`);
    await page.evaluate(() => { window.__editor.lastError = null; });

    // a name that exists: the page asks first; declined, the file is kept; accepted, it is replaced
    const taken = path.join(files, "taken.sing"), theirs = "# someone else's file\n";
    writeFileSync(taken, theirs);
    const asked = [];
    let yes = false;
    const answer = dialog => {
      asked.push(dialog.message());
      return yes ? dialog.accept() : dialog.dismiss();
    };
    page.on("dialog", answer);
    await page.selectOption("#kind", "singularities");
    await page.fill("#path", "taken.sing");
    await page.evaluate(() => { window.__editor.saved = window.__editor.declined = null; });
    await page.click("#save");
    await page.waitForFunction(() => window.__editor.declined || window.__editor.saved || window.__editor.lastError);
    if (asked.length !== 1 || !asked[0].includes("taken.sing")) fail(`save over taken.sing: asked ${JSON.stringify(asked)}`);
    if (readFileSync(taken, "utf8") !== theirs) fail("the save over taken.sing, declined, changed it");
    if (!(await page.textContent("#status")).includes("not saved")) fail("the page does not say taken.sing was kept");
    yes = true;
    await page.click("#save");
    await page.waitForFunction(() => window.__editor.saved || window.__editor.lastError);
    const error = await page.evaluate(() => window.__editor.lastError);
    if (error) fail(`the save over taken.sing, accepted: ${error}`);
    const lines = readFileSync(taken, "utf8").split("\n").filter(l => l && !l.startsWith("#"));
    const count = await page.evaluate(() => window.__editor.singularities().length);
    if (asked.length !== 2 || lines.length !== count)
      fail(`the save over taken.sing, accepted: ${lines.length} lines for ${count} singularities, asked ${asked.length}`);
    page.off("dialog", answer);
    console.log(`a save over an existing file: asked "${asked[0]}", declined (kept), then accepted (replaced)`);
    before = await solves(page);
    await page.click("#place"); // another state
    await solved(page, before);
    for (const [kind, name] of [["singularities", "design.sing"], ["constraints", "design.dirs"]]) {
      before = await solves(page);
      await page.selectOption("#kind", kind);
      await page.fill("#path", name);
      await page.click("#load");
      await solved(page, before);
    }
    const loaded = await page.evaluate(() => window.__editor.request());
    const same = (x, y) => JSON.stringify([...x].sort()) === JSON.stringify([...y].sort());
    if (!same(loaded.singularities, saved.singularities) || loaded.constraints.length !== saved.constraints.length)
      fail(`loaded ${JSON.stringify(loaded)}, saved ${JSON.stringify(saved)}`);
    await checkField(page, mesh, "saved and loaded back");

    if (await page.evaluate(() => document.getElementById("quads").disabled)) fail("n = 4: the quad mesh disabled");

    // another n: the automatic placement for it, the pin kept; the quad mesh control disabled
    before = await solves(page);
    await page.selectOption("#n", "6");
    await solved(page, before);
    if (await page.evaluate(() => window.__editor.state.n) !== 6) fail("n did not become 6");
    await checkField(page, mesh, "n = 6 (automatic placement)");
    if (!await page.evaluate(() => document.getElementById("quads").disabled))
      fail("n = 6: the quad mesh control is not disabled");

    await page.selectOption("#display", "streamlines");
    await page.waitForFunction(() => window.__editor.streamlineCount > 0, null, { timeout: 30000 });
    await page.selectOption("#display", "glyphs");

    // a PNG of the view, downloaded
    await page.selectOption("#kind", "png");
    const [download] = await Promise.all([page.waitForEvent("download"), page.click("#save")]);
    const pngPath = path.join(outdir, "download.png");
    await download.saveAs(pngPath);
    const png = readFileSync(pngPath);
    if (png.subarray(1, 4).toString() !== "PNG" || png.readUInt32BE(16) !== 1000 || png.readUInt32BE(20) !== 750)
      fail("the PNG export is not a 1000 x 750 PNG");

    await structure(page);
  } finally {
    server.kill();
  }
}

// the screenshot: the mesh covers the centre (the background is #f4f4f4), and the marker of every singularity a
// click would pick (its vertex in front) is where the camera projects it (every pixel within 3 of it), red for
// positive, blue for negative (drawn over the surface: never cut at the silhouette)
async function structure(page) {
  const shot = path.join(outdir, "editor.png");
  await page.screenshot({ path: shot });
  const found = await page.evaluate(() => {
    const e = window.__editor, rect = document.querySelector("#view canvas").getBoundingClientRect();
    e.internals.draw();
    // the view as shown: the WebGL canvas and the overlay over it
    const g = e.internals.fieldView.composite().getContext("2d");
    // the pixels in the (2 r + 1)-square about (x, y) (CSS pixels of the page), as [r, g, b] lists
    const block = (x, y, r) => {
      const size = 2 * r + 1;
      const p = g.getImageData(Math.round(x - rect.left) - r, Math.round(y - rect.top) - r, size, size).data;
      return Array.from({ length: size * size }, (_, i) => Array.from(p.subarray(4 * i, 4 * i + 3)));
    };
    const markers = [];
    for (const [v, [sign]] of e.state.singularities) {
      const s = e.screenOf(v);
      if (s.picked) markers.push({ v, sign, rgb: block(s.x, s.y, 3) });
    }
    const pixel = (x, y) => block(x, y, 0)[0];
    return { centre: pixel(rect.left + rect.width / 2, rect.top + rect.height / 2), markers };
  });
  const [r, g, b] = found.centre;
  if (r === 244 && g === 244 && b === 244) fail("the centre of the view is background");
  if (!found.markers.length) fail("no singularity is visible");
  // the marker (a 12-pixel square over everything) covers every pixel within 3 of the projection, also at the
  // silhouette (the surface never cuts it); a neighbouring singularity's marker may cover part of it
  const red = ([r, g, b]) => r > 150 && g < 90 && b < 90, blue = ([r, g, b]) => b > 150 && r < 90;
  for (const m of found.markers) {
    const ok = m.rgb.some(m.sign > 0 ? red : blue) && m.rgb.every(p => red(p) || blue(p));
    if (!ok) fail(`the marker of vertex ${m.v} (${m.sign > 0 ? "+" : "-"}) does not cover the pixels within 3 of its ` +
                  `projection: ${JSON.stringify(m.rgb.filter(p => !red(p) && !blue(p)).slice(0, 5))}`);
  }
  console.log(`structure: the mesh at the centre, ${found.markers.length} visible markers where the projection says`);
  console.log(`editor_test: screenshot ${shot}`);
}

async function borderedMesh(browser) {
  // served as `cd DIR; trivial_connections-serve held.off`: the mesh in the server's folder (the working directory)
  const held = path.join(outdir, "held");
  rmSync(held, { recursive: true, force: true });
  mkdirSync(held, { recursive: true });
  const heldMesh = path.join(held, "held.off");
  copyFileSync(bordered, heldMesh);
  linkSync(heldMesh, path.join(held, "other name.off"));
  const original = readFileSync(heldMesh);
  const { server, address } = await startServer(serve, "held.off", ["--n", "4"], held);
  try {
    const page = await open(browser, address);
    await checkField(page, heldMesh, "bordered mesh: load");
    let before = await solves(page);
    await page.check("#align");
    await solved(page, before);
    await checkField(page, heldMesh, "bordered mesh: aligned with the boundary");
    const [f] = await visibleFaces(page, 1);
    await page.selectOption("#tool", "pin");
    before = await solves(page);
    const p = await page.evaluate(g => window.__editor.screenOfFace(g), f);
    await drag(page, p, { x: p.x - 10, y: p.y + 40 });
    await solved(page, before);
    await checkField(page, heldMesh, "bordered mesh: aligned, and a pin");

    // align with sharp features (a low threshold: this mesh is smooth), the field aligned with the boundary: the
    // server's pins added where the user has none (none on the boundary), the library's field follows them all;
    // unchecked, they go and the user's pin stays
    await page.fill("#feature-angle", "5");
    before = await solves(page);
    await page.check("#features");
    await solved(page, before);
    const added = await page.evaluate(() => window.__editor.state.features?.pins.size ?? 0);
    if (!(added > 0)) fail(`align with sharp features pinned nothing: ${await page.textContent("#status")}`);
    await checkField(page, heldMesh, `bordered mesh: aligned, a pin and ${added} feature pins`);
    console.log(`status: ${await page.textContent("#status")}`);
    before = await solves(page);
    await page.uncheck("#features");
    await solved(page, before);
    const [pinsLeft, features] = await page.evaluate(() => [window.__editor.state.constraints.size,
                                                            window.__editor.state.features]);
    if (pinsLeft !== 1 || features !== null) fail(`features unchecked: ${pinsLeft} pins left, features ${features}`);
    await checkField(page, heldMesh, "bordered mesh: the feature pins taken away");

    // the quad mesh overlay (issue 43; n = 4, the field along the boundary and a pin): its edges drawn over the
    // surface (green pixels in the view, none before), the report's counts in the status line; half the default
    // size gives about four times the quads; unchecked, the edges go
    if (await greenPixels(page) !== 0) fail("green pixels before the quad mesh is shown");
    const quadsShown = async (what, size) => {
      await page.waitForFunction(H => (window.__editor.quadReport && (!H || window.__editor.quadReport.quad_size === H)) ||
                                 window.__editor.lastError, size, { timeout: 60000 });
      const [segments, report, error] = await page.evaluate(() => [window.__editor.quadSegments,
        window.__editor.quadReport, window.__editor.lastError]);
      if (error) fail(`${what}: ${error}`);
      const text = await page.textContent("#status"), green = await greenPixels(page);
      const said = /quad mesh \(H = [^)]*\): (\d+) quads, (\d+) folded triangles, (\d+) valence errors/.exec(text);
      if (!said || Number(said[1]) !== report.quads || Number(said[2]) !== report.folded_triangles ||
          Number(said[3]) !== report.valence_errors) fail(`${what}: the status line says "${text}"`);
      // every quad has 4 edges, each in one or two quads
      if (!(report.quads > 0 && segments >= 2 * report.quads && segments <= 4 * report.quads))
        fail(`${what}: ${segments} segments for ${report.quads} quads`);
      if (!(green > 100)) fail(`${what}: ${green} green pixels`);
      console.log(`${what}: ${text} (${segments} segments, ${green} green pixels)`);
      return report;
    };
    await page.check("#quads");
    const first = await quadsShown("quad mesh", null);
    const shownSize = Number(await page.inputValue("#quad-size"));
    if (first.quad_size !== shownSize) fail(`the quad size shown ${shownSize}, used ${first.quad_size}`);
    const half = Number((first.quad_size / 2).toPrecision(6));
    await page.fill("#quad-size", String(half));
    await page.dispatchEvent("#quad-size", "change");
    const finer = await quadsShown("quad mesh, half the size", half);
    if (!(finer.quads > 2.5 * first.quads && finer.quads < 6 * first.quads))
      fail(`half the quad size: ${finer.quads} quads against ${first.quads}`);
    // the field scaled per face first (the scale box): quads of the same size again, made with that scale
    // (a request still running when the box changes is shown first, then the scaled one is made)
    await page.fill("#quad-scale", "0.1");
    await page.dispatchEvent("#quad-scale", "change");
    await page.waitForFunction(() => window.__editor.quadScale === 0.1 || window.__editor.lastError, null,
                               { timeout: 60000 });
    const scaled = await quadsShown("quad mesh, the field scaled", half);
    if (!(scaled.quads > 0.5 * finer.quads && scaled.quads < 2 * finer.quads))
      fail(`the field scaled: ${scaled.quads} quads against ${finer.quads}`);
    await page.fill("#quad-scale", "");
    // with the sharp features aligned, the singularities near them moved off for the quads: the status line says
    // how many (the page's own singularities stay; the server's test checks the moves themselves). At 5 degrees
    // the user's pin above lies across a sharp edge, which no quad mesh can follow: the default angle here.
    const ownSingularities = await page.evaluate(() => JSON.stringify([...window.__editor.state.singularities]));
    await page.fill("#feature-angle", "30");
    before = await solves(page);
    await page.check("#features");
    await solved(page, before);
    await page.check("#quad-off-features");
    await page.waitForFunction(() => typeof window.__editor.quadMoved === "number" || window.__editor.lastError, null,
                               { timeout: 60000 });
    const offFeatures = await quadsShown("quad mesh, singularities off the features", half);
    const movedCount = await page.evaluate(() => window.__editor.quadMoved);
    const movedText = await page.textContent("#status");
    if (!movedText.includes(`${movedCount} singularities moved off the sharp features`))
      fail(`singularities off the features: the status line says "${movedText}"`);
    if (await page.evaluate(() => JSON.stringify([...window.__editor.state.singularities])) !== ownSingularities)
      fail("singularities off the features: the page's own singularities changed");
    console.log(`off the features: ${movedCount} moved, ${offFeatures.quads} quads`);
    await page.uncheck("#quad-off-features");
    before = await solves(page);
    await page.uncheck("#features");
    await solved(page, before);
    await page.uncheck("#quads");
    await page.waitForFunction(() => window.__editor.quadSegments === 0);
    if (await greenPixels(page) !== 0) fail("the quad mesh unchecked: green pixels left");

    // the mesh's own name, and another name of its file: refused with the reason shown, never asked, never written
    const asked = [];
    page.on("dialog", dialog => {
      asked.push(dialog.message());
      return dialog.accept(); // even a yes must not replace the mesh
    });
    for (const name of ["held.off", "other name.off"]) {
      await page.selectOption("#kind", "singularities");
      await page.fill("#path", name);
      await page.evaluate(() => { window.__editor.lastError = window.__editor.saved = null; });
      await page.click("#save");
      await page.waitForFunction(() => window.__editor.lastError || window.__editor.saved);
      const shown = await page.textContent("#status");
      if (!shown.includes("mesh being edited") || !shown.includes(name))
        fail(`save as ${name} (the mesh): the page shows "${shown}"`);
      console.log(`refused: ${shown}`);
    }
    if (asked.length) fail(`the page asked to replace the mesh: ${JSON.stringify(asked)}`);
    if (!readFileSync(heldMesh).equals(original)) fail("the mesh was written");
    const left = readdirSync(held).sort();
    if (JSON.stringify(left) !== JSON.stringify(["held.off", "other name.off"])) fail(`the folder holds ${left}`);
  } finally {
    server.kill();
  }
}

// the field at the whole-mesh view of a large mesh (LARGE_MESH beside MESH, CGAL's refined_elephant: 89k faces,
// most a pixel or two wide): ink in at least COVERAGE of the blocks of 24 x 24 pixels wholly on the mesh, and a
// share of its pixels between INK[0] and INK[1] (the field drawn, the shading still seen); a pinned direction is an
// arrow of at least PIN_PIXELS orange pixels about its face's projection (its size on the screen, not in edges)
const LARGE_MESH = "refined_elephant.off", COVERAGE = 0.95, INK = [0.03, 0.5], PIN_PIXELS = 25;
async function largeMesh(browser) {
  const large = path.join(path.dirname(mesh), LARGE_MESH);
  const { server, address } = await startServer(serve, large, ["--n", "4", "--folder", files]);
  try {
    const page = await open(browser, address);
    const shown = await fieldCoverage(page);
    console.log(`${LARGE_MESH}: ${shown.faces} faces at the whole-mesh view: ${shown.glyphs} glyphs, ink in ` +
                `${(100 * shown.coverage).toFixed(1)} % of the ${shown.blocks} blocks wholly on the mesh, ` +
                `${(100 * shown.ink).toFixed(1)} % of its ${shown.meshPixels} pixels`);
    if (shown.blocks < 20 || shown.coverage < COVERAGE || shown.ink < INK[0] || shown.ink > INK[1])
      fail(`${LARGE_MESH}: the field is not drawn over the mesh at the whole-mesh view: ${JSON.stringify(shown)}`);
    const [f] = await visibleFaces(page, 1);
    if (f === undefined) fail(`${LARGE_MESH}: no visible face to pin`);
    const before = await solves(page);
    await page.evaluate(g => window.__editor.edit(() => {
      const n = window.__editor.internals.fieldView.normals, t = [n[3 * g + 1], -n[3 * g], 0]; // a tangent
      window.__editor.state.constraints.set(g, t[0] || t[1] ? t : [1, 0, 0]);
    }), f);
    await solved(page, before);
    await checkField(page, large, `${LARGE_MESH}: a pin`);
    const orange = await page.evaluate(g => {
      const e = window.__editor, s = e.screenOfFace(g), rect = document.querySelector("#view canvas").getBoundingClientRect();
      e.internals.draw();
      const r = 30, p = e.internals.fieldView.composite().getContext("2d")
        .getImageData(Math.round(s.x - rect.left) - r, Math.round(s.y - rect.top) - r, 2 * r + 1, 2 * r + 1).data;
      let count = 0;
      for (let i = 0; i < p.length; i += 4) if (p[i] > 180 && p[i + 1] > 80 && p[i + 1] < 150 && p[i + 2] < 60) ++count;
      return count;
    }, f);
    if (orange < PIN_PIXELS) fail(`${LARGE_MESH}: the pin of face ${f} shows ${orange} orange pixels`);
    console.log(`${LARGE_MESH}: the pin of face ${f}: ${orange} orange pixels about its projection`);
    await page.screenshot({ path: path.join(outdir, "editor_large.png") });
  } finally {
    server.kill();
  }
}

const browser = await launchBrowser();
try {
  await largeMesh(browser);
  await closedMesh(browser);
  await borderedMesh(browser);
  console.log("editor_test: passed");
} finally {
  await browser.close();
}
