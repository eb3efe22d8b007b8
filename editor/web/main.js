// The field editor's page: the shaded mesh with its field (glyphs or streamlines), singularities
// coloured by index, pinned directions and boundary loops. Every edit (singularities, pins, strokes, n, boundary
// alignment, a file loaded) is a solve on the server's prefactored solver; undo and redo go through whole states.
import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";
import { MeshBVH } from "three-mesh-bvh";
import { FieldView } from "./field_view.js";
import { add, fraction, indexText, parseFrame, parseIndex, post } from "./protocol.js";

// ---- the state: n, singularities {vertex: [p, q]}, pinned directions {face: [x, y, z]}, boundary alignment, the
// sharp features' pins (null, or {threshold, pins: Map face -> the direction added to constraints}) -----------------
const state = { n: 4, singularities: new Map(), constraints: new Map(), alignBoundary: false, features: null };
const undoStack = [], redoStack = [];
function snapshot() {
  return { n: state.n, singularities: new Map(state.singularities), constraints: new Map(state.constraints),
           alignBoundary: state.alignBoundary, features: state.features };
}
function restore(s) {
  state.n = s.n;
  state.singularities = new Map(s.singularities);
  state.constraints = new Map(s.constraints);
  state.alignBoundary = s.alignBoundary;
  state.features = s.features;
  controlsShow();
}
// what every solve-like request carries
function request() {
  return { n: state.n, singularities: [...state.singularities].map(([v, k]) => [v, indexText(k)]),
           constraints: [...state.constraints], align_boundary: state.alignBoundary };
}

// ---- the scene ------------------------------------------------------------------------------------------------
const $ = id => document.getElementById(id);
const view = $("view");
// no multisampling: a software GL pays for every sample; the drawing buffer is preserved: it is drawn again only
// when the camera moves (the field, pins and markers are in the field view's 2D overlay over it)
const renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
renderer.setSize(view.clientWidth, view.clientHeight);
view.appendChild(renderer.domElement);
const BACKGROUND = new THREE.Color(0xf4f4f4);
// the 3D lines drawn over the mesh (boundary loops, streamlines), depth-tested against it, writing no depth
const scene = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(40, view.clientWidth / view.clientHeight, 1e-3, 1e3);
const controls = new OrbitControls(camera, renderer.domElement);

let fieldView = null, streamlines = null, V = null, F = null, header = null;
let bvh = null, angleDefect = null, display = "glyphs";
// the request of the field on the screen (the last solve that succeeded: an unbalanced state keeps it), and the
// singularities the balancing move would add ([[vertex, [p, q]]], drawn pale; null: none to offer)
let solvedRequest = null, proposal = null;
const status = $("status");

function draw() {
  if (fieldView.stale) drawMarkers(); // the camera moved: other vertices are in sight
  fieldView.render(camera, BACKGROUND, scene);
}
controls.addEventListener("change", () => {
  fieldView.stale = true;
  draw();
});
window.addEventListener("resize", () => {
  camera.aspect = view.clientWidth / view.clientHeight;
  camera.updateProjectionMatrix();
  renderer.setSize(view.clientWidth, view.clientHeight);
  if (fieldView) {
    fieldView.stale = true;
    draw();
  }
});

function say(text, error = false) {
  status.textContent = text;
  status.className = error ? "error" : "";
  if (error) window.__editor.lastError = text;
}

// ---- the server's refusals in words: its one-line reason ("code: message" for the library's) goes to the console,
// the page says in a sentence of its own what was not done and why --------------------------------------------------
const REASONS = {
  poincare_hopf_violated: "the singularities do not balance: on a closed surface their indices must add up to its " +
                          "Euler characteristic",
  index_not_multiple: "an index is not a multiple of 1/n for this n",
  invalid_index: "an index cannot be read (a zero denominator, or a number too large)",
  invalid_vertex: "a singularity is on a vertex this mesh does not have (or one of no face)",
  duplicate_singularity: "a vertex has two singularities",
  singularity_on_boundary: "a singularity is on the boundary, where the field can have none",
  invalid_constraint: "a pinned direction cannot be followed (zero, along its face's normal, on the boundary the " +
                      "field follows, or a face pinned twice)",
  invalid_symmetry_order: "n must be a whole number from 1 up",
  invalid_loop_periods: "the turns prescribed along the boundary do not fit the singularities",
  invalid_argument: "a setting is out of range",
  io_error: "the file could not be read or written (the folder's permissions, or the disk)",
  parse_error: "the file is not one of the package's files of that kind",
  solver_failure: "the solver failed on this mesh and these pins",
};
const NOT_DONE = { solve: "Not solved", place: "No automatic placement", features: "No sharp features",
                   streamlines: "No streamlines", save: "Not saved", load: "Not loaded" };
function explain(error, doing, path = "") {
  console.warn(`editor: ${doing}${path ? " " + path : ""}: ${error.status ? "HTTP " + error.status + ": " : ""}` +
               error.message);
  const file = `“${path}”`, raw = error.message, files = doing === "save" || doing === "load";
  let why;
  if (error.status === undefined) why = "the server does not answer (is it still running?)";
  else if (error.status === 422 && doing === "features" && error.code === "invalid_argument")
    why = "the angle of the sharp features must be from 0° to 180°";
  else if (error.status === 422) why = REASONS[error.code] ?? "the library refused it (the browser's console says why)";
  else if (error.status === 403 && files)
    why = /mesh being edited/.test(raw) ? `${file} is the mesh being edited, which the editor never replaces`
                                        : `${file} is outside the server's folder, the only one it reads and writes`;
  else if (error.status === 404 && files)
    why = doing === "load" ? `there is no file ${file} in the server's folder` : `the folder of ${file} does not exist`;
  else if (error.status === 413 && doing === "load") why = `${file} is too large to load`;
  else if (error.status === 400 && files) {
    const ending = /must end in (\.[a-z]+)/.exec(raw);
    why = ending ? `the name of such a file must end in ${ending[1]}`
          : /directory/.test(raw) ? `${file} is a folder`
          : `${file} is not the name of a file in the server's folder (a relative path to a regular file)`;
  } else if (error.status >= 500) why = "the server failed on it (its terminal says why)";
  else why = "the server could not take the request (the browser's console says why)";
  return `${NOT_DONE[doing] ?? "Not done"}: ${why}.`;
}

function buildScene() {
  // picking: a bounding volume hierarchy over the triangles in input order ("indirect": faces keep their numbers)
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(V, 3));
  geometry.setIndex(new THREE.BufferAttribute(F, 1));
  bvh = new MeshBVH(geometry, { indirect: true });
  fieldView = new FieldView(renderer, V, F);
  view.appendChild(fieldView.overlay);
  const { center, radius } = fieldView.boundingSphere;
  controls.target.copy(center);
  camera.position.copy(center).add(new THREE.Vector3(0, 0, 2.8 * radius));
  camera.near = radius * 1e-3;
  camera.far = radius * 20;
  camera.updateProjectionMatrix();
  controls.update();
}

// the singularities whose vertex the camera sees (a marker is a square of 12 pixels over everything: one behind the
// surface would show through it), red for positive indices, blue for negative ones; pale: what the balancing move
// would add
function drawMarkers() {
  const markers = [];
  camera.updateMatrixWorld();
  const at = v => [V[3 * v], V[3 * v + 1], V[3 * v + 2]];
  for (const [v, [p]] of state.singularities)
    if (seen(v)) markers.push({ position: at(v), color: p > 0 ? "#d91a1a" : "#1a73e6" });
  for (const [v, [p]] of proposal ?? [])
    if (seen(v)) markers.push({ position: at(v), color: p > 0 ? "#ffb8b8" : "#b3d6ff" });
  fieldView.setMarkers(markers);
}

// the pinned directions (arrows of a fixed size on the screen, drawn by the field view where their face is seen);
// the sharp features' pins shorter
function drawPins() {
  const features = state.features?.pins;
  fieldView.setPins([...state.constraints].map(([f, d]) => ({ face: f, direction: d,
                                                              feature: features?.get(f) === d })));
}

function drawBoundary(edges) {
  const positions = new Float32Array(edges.length * 3);
  for (let i = 0; i < edges.length; ++i)
    for (let j = 0; j < 3; ++j) positions[3 * i + j] = V[3 * edges[i] + j];
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(positions, 3));
  scene.add(new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color: 0xd4740a, depthWrite: false })));
}

function drawStreamlines(points, offsets) {
  if (streamlines) { scene.remove(streamlines); streamlines = null; fieldView.stale = true; }
  if (!points) return;
  const segments = [];
  for (let i = 0; i + 1 < offsets.length; ++i)
    for (let k = offsets[i]; k + 1 < offsets[i + 1]; ++k) segments.push(k, k + 1);
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(points, 3));
  geometry.setIndex(segments);
  streamlines = new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color: 0x1f3a93, depthWrite: false }));
  scene.add(streamlines);
  fieldView.stale = true; // the 3D lines are in the view frame
}

// ---- geometry of faces ------------------------------------------------------------------------------------------
const point = v => new THREE.Vector3(V[3 * v], V[3 * v + 1], V[3 * v + 2]);
function centroid(f) { return point(F[3 * f]).add(point(F[3 * f + 1])).add(point(F[3 * f + 2])).divideScalar(3); }
// d projected on face f's plane, unit (the solver projects constraints the same way)
function tangent(f, d) {
  const n = new THREE.Vector3().fromArray(fieldView.normals, 3 * f), t = new THREE.Vector3().fromArray(d);
  return t.addScaledVector(n, -t.dot(n)).normalize();
}

// ---- solving and showing ----------------------------------------------------------------------------------------
// per component: the sum of the indices against its Euler characteristic (closed components must balance), and
// the difference in units of 1/n (units: [p, q], whole when q = 1)
function balance() {
  const sums = header.chi.map(() => [0, 1]);
  for (const [v, k] of state.singularities) {
    const c = window.__editor.component[v];
    if (c >= 0) sums[c] = add(sums[c], k);
  }
  return header.chi.map((chi, c) => {
    const excess = add(sums[c], [-chi, 1]);
    return { component: c, sum: sums[c], chi, closed: header.closed[c], units: fraction(excess[0] * state.n, excess[1]),
             balanced: !header.closed[c] || excess[0] === 0 };
  });
}

// the balance of every component: a line (.unbalanced, with data-component, data-units, data-n) for each closed one
// that is off and by how much, then the others (each, or counted when there are many); the balancing move's button
// names what it would add, and those vertices get pale markers
function showBalance() {
  const rows = balance(), off = rows.filter(b => !b.balanced), box = $("balance");
  box.replaceChildren();
  for (const b of off) {
    const line = document.createElement("div"), [p, q] = b.units;
    line.className = "unbalanced";
    Object.assign(line.dataset, { component: b.component, units: indexText(b.units), n: state.n });
    line.textContent = `component ${b.component} is unbalanced by ${p > 0 ? "+" : "−"}` +
      (q === 1 ? `${Math.abs(p)} × 1/${state.n}`
               : `${indexText([Math.abs(p), q])} × 1/${state.n} (not a whole number)`) +
      `: its indices sum to ${minus(indexText(b.sum))}, its Euler characteristic χ is ${minus(String(b.chi))}`;
    box.append(line);
  }
  const others = rows.filter(b => b.balanced);
  const text = others.length <= 6
    ? others.map(b => `component ${b.component}: ${minus(indexText(b.sum))}` +
                      (b.closed ? ` of χ = ${minus(String(b.chi))}` : " (bordered)"))
    : [`${others.filter(b => b.closed).length} closed components balanced, ${others.filter(b => !b.closed).length} ` +
       "bordered (no sum required)"];
  if (text.length) {
    const rest = document.createElement("div");
    rest.textContent = text.join("\n");
    box.append(rest);
  }
  proposal = off.length ? proposeBalance() : null;
  const button = $("balance-move");
  button.hidden = !proposal;
  if (proposal)
    button.textContent = "balance: add " + (proposal.length <= 2
      ? proposal.map(([v, k]) => `${signed(k)} at vertex ${v}`).join(" and ")
      : `${proposal.length} singularities of ±1/${state.n} (the pale markers)`);
}
const signed = k => (k[0] > 0 ? "+" : "−") + indexText([Math.abs(k[0]), k[1]]);
const minus = text => text.replace("-", "−");

async function solve() {
  const e = window.__editor, started = performance.now();
  let frame;
  const body = request();
  try {
    frame = await post("/api/solve", body);
  } catch (error) {
    say(explain(error, "solve"), true);
    return false;
  }
  solvedRequest = body;
  const received = performance.now();
  const { header: h, arrays } = frame;
  fieldView.setField(arrays.angle, h.n);
  drawMarkers();
  drawPins();
  const built = performance.now();
  draw();
  if (e.measure) {
    // the frame drawn: reading a pixel of the overlay waits for its drawing (and a pixel of the WebGL canvas for the
    // GPU, when the camera had moved)
    const called = performance.now();
    fieldView.context.getImageData(0, 0, 1, 1);
    const gl = renderer.getContext();
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
    const now = performance.now();
    e.latencies.push({ total: now - (e.clickTime ?? started), server: received - started,
                       solve: 1e3 * (h.timings.solve + h.timings.field), draw: now - received,
                       upload: built - received, render: now - built, calls: called - built, finish: now - called });
  }
  e.solves += 1;
  e.lastError = null;
  say(`energy ${h.energy.toPrecision(6)}, residual ${h.max_residual.toExponential(1)}, ` +
      `${(performance.now() - started).toFixed(1)} ms (solve ${(1e3 * h.timings.solve).toFixed(1)} ms)`);
  if (display === "streamlines") traceStreamlines();
  return true;
}

// the streamlines of the field on the screen (the last solved, also while the state is unbalanced)
async function traceStreamlines() {
  if (!solvedRequest) return;
  try {
    const { arrays } = await post("/api/streamlines", solvedRequest);
    if (display !== "streamlines") return; // glyphs again meanwhile
    drawStreamlines(arrays.points, arrays.offsets);
    window.__editor.streamlineCount = arrays.offsets.length - 1;
    draw();
  } catch (error) {
    say(explain(error, "streamlines"), true);
  }
}

// shows the current state: solved when every closed component balances; else a state the editor shows, not a
// refusal: the markers, the balance's lines, and the last field solved stays drawn
async function show() {
  showBalance();
  drawPins();
  if (!balance().every(b => b.balanced)) {
    say("Unbalanced (see above): the field drawn is the last balanced one. Edit on, or " +
        (!proposal ? "make every index a multiple of 1/n."
         : "press “balance” to add " +
           (proposal.length === 1 ? "the pale marker's singularity." : "the pale markers' singularities.")));
    window.__editor.lastError = null;
    window.__editor.unbalanced = true;
    drawMarkers();
    draw();
    return true;
  }
  window.__editor.unbalanced = false;
  return solve();
}

// edits run one after the other, each on the state the previous one left
let queue = Promise.resolve();
function edit(change) {
  queue = queue.then(async () => {
    const before = snapshot();
    if (change() === false) return;
    if (await show()) {
      undoStack.push(before);
      redoStack.length = 0;
    } else {
      restore(before); // refused by the server: the reason stays shown
      showBalance();
      drawMarkers();
      drawPins();
      draw();
    }
  });
  return queue;
}

function travel(from, to) {
  queue = queue.then(async () => {
    if (!from.length) return;
    to.push(snapshot());
    restore(from.pop());
    await show();
  });
}

// the automatic placement for n, as one edit (constraints and alignment kept)
async function placeFor(n) {
  let h;
  try {
    ({ header: h } = await post("/api/place", { n, align_boundary: state.alignBoundary,
                                                constraints: [...state.constraints] }));
  } catch (error) {
    say(explain(error, "place"), true);
    controlsShow();
    return;
  }
  await edit(() => {
    state.n = h.n;
    state.singularities = new Map(h.singularities.map(([v, k]) => [v, parseIndex(k)]));
  });
  controlsShow();
}

// what completes every unbalanced closed component: singularities of +-1/n ([[vertex, [p, q]]]) at its vertices
// whose angle defect is most like them (largest K_v for positive ones, most negative for negative ones: where the
// Levi-Civita holonomy already turns the most that way), two rings from each other and, where the component has
// room, from its singularities; null when an excess is not a whole number of 1/n (no such completion)
function proposeBalance() {
  const neighbours = adjacency(), added = [];
  const near = (blocked, v) => { // v's two rings into `blocked`
    for (const u of neighbours[v]) { blocked.add(u); for (const w of neighbours[u]) blocked.add(w); }
  };
  for (const b of balance()) {
    if (b.balanced) continue;
    const [p, q] = b.units;
    if (q !== 1) return null;
    const sign = -Math.sign(p), count = Math.abs(p);
    const candidates = [];
    for (let v = 0; v < V.length / 3; ++v)
      if (window.__editor.component[v] === b.component && !state.singularities.has(v)) candidates.push(v);
    candidates.sort((u, w) => sign * (angleDefect[w] - angleDefect[u]) || u - w);
    const apart = new Set(), taken = new Set();
    for (const v of state.singularities.keys()) if (window.__editor.component[v] === b.component) near(apart, v);
    // two rings from the singularities and from each other; then from each other only; then anywhere
    for (const rule of [v => !apart.has(v), () => true]) {
      const blocked = new Set();
      for (const v of taken) near(blocked, v);
      for (const v of candidates) {
        if (taken.size === count) break;
        if (taken.has(v) || blocked.has(v) || !rule(v)) continue;
        taken.add(v);
        near(blocked, v);
      }
    }
    for (const v of candidates) { // a small component: the rest anywhere
      if (taken.size === count) break;
      taken.add(v);
    }
    for (const v of taken) added.push([v, [sign, state.n]]);
  }
  return added.length ? added : null;
}

// the balancing move: one edit that adds what proposeBalance() proposes
function balancingMove() {
  return edit(() => {
    const more = proposeBalance();
    if (!more) return false;
    for (const [v, k] of more) state.singularities.set(v, k);
  });
}

let neighbourLists = null;
function adjacency() {
  if (neighbourLists) return neighbourLists;
  neighbourLists = Array.from({ length: V.length / 3 }, () => []);
  for (let f = 0; f < F.length / 3; ++f)
    for (let k = 0; k < 3; ++k) neighbourLists[F[3 * f + k]].push(F[3 * f + (k + 1) % 3]);
  return neighbourLists;
}

// ---- picking ------------------------------------------------------------------------------------------------------
const raycaster = new THREE.Raycaster();
function rayAt(clientX, clientY) {
  const r = renderer.domElement.getBoundingClientRect();
  raycaster.setFromCamera(new THREE.Vector2(((clientX - r.left) / r.width) * 2 - 1,
                                            -((clientY - r.top) / r.height) * 2 + 1), camera);
  return raycaster.ray;
}
// the face under the pointer, the point hit and the face's vertex nearest to it
function pick(clientX, clientY) {
  // a ray through a vertex or along an edge can pass between the triangles' tests: a third of a pixel aside then
  let hit = null;
  for (const [dx, dy] of [[0, 0], [0.3, 0.3], [-0.3, -0.3], [0.3, -0.3], [-0.3, 0.3]])
    if ((hit = bvh.raycastFirst(rayAt(clientX + dx, clientY + dy), THREE.DoubleSide))) break;
  if (!hit) return null;
  const f = hit.faceIndex;
  let vertex = -1, distance = Infinity;
  for (let k = 0; k < 3; ++k) {
    const v = F[3 * f + k], d = hit.point.distanceTo(point(v));
    if (d < distance) { distance = d; vertex = v; }
  }
  return { face: f, point: hit.point.clone(), vertex };
}
const pickVertex = (x, y) => pick(x, y)?.vertex ?? -1;

// whether the camera sees vertex v: nothing of the mesh is hit before it (within a fifth of an edge)
function seen(v) {
  const p = point(v), origin = camera.position, distance = p.distanceTo(origin);
  const hit = bvh.raycastFirst(new THREE.Ray(origin.clone(), p.sub(origin).normalize()), THREE.DoubleSide);
  return !hit || hit.distance >= distance - 0.2 * fieldView.meanEdge;
}

// the singularity whose marker is under the pointer (within 8 pixels of its vertex, the nearest, seen by the
// camera), or -1: a drag starts on the marker, not only on the vertex's own faces
function grabbed(clientX, clientY) {
  let best = -1, distance = 8;
  for (const v of state.singularities.keys()) {
    const s = screenOfPoint(point(v)), d = Math.hypot(s.x - clientX, s.y - clientY);
    if (d <= distance && seen(v)) { best = v; distance = d; }
  }
  return best;
}

// where a point is on the screen, and whether it is in the view
function screenOfPoint(p) {
  const q = p.clone().project(camera), r = renderer.domElement.getBoundingClientRect();
  return { x: r.left + (q.x + 1) / 2 * r.width, y: r.top + (1 - q.y) / 2 * r.height,
           inside: Math.abs(q.x) < 0.95 && Math.abs(q.y) < 0.95 && q.z < 1 };
}
// where vertex v is on the screen, and whether a click there picks it (for tests: window.__editor.screenOf)
function screenOf(v) {
  const s = screenOfPoint(point(v));
  return { x: s.x, y: s.y, picked: s.inside && pickVertex(s.x, s.y) === v };
}
// where face f's centroid is, and whether a press there picks f
function screenOfFace(f) {
  const s = screenOfPoint(centroid(f));
  return { x: s.x, y: s.y, picked: s.inside && pick(s.x, s.y)?.face === f };
}

// ---- the pointer ----------------------------------------------------------------------------------------------
// tool "singularities": a click edits the vertex under it (+1/n, shift -1/n, alt removes); a press on a
// singularity drags it to the vertex where it is released. Tool "pin": a drag from a face pins the direction of
// the drag there (alt-click removes a pin). Tool "stroke": the faces a stroke crosses get its direction. A press
// off the mesh, or any other drag, orbits.
let press = null;
renderer.domElement.addEventListener("pointerdown", e => {
  const hit = pick(e.clientX, e.clientY);
  const tool = $("tool").value;
  press = { x: e.clientX, y: e.clientY, hit, tool, dragged: -1, stroke: hit ? [hit] : [] };
  if (tool === "singularities" && hit && !e.shiftKey && !e.altKey)
    press.dragged = grabbed(e.clientX, e.clientY);
  controls.enabled = tool === "singularities" ? press.dragged < 0 : !hit;
});
renderer.domElement.addEventListener("pointermove", e => {
  if (!press || press.tool !== "stroke" || !press.hit) return;
  const last = press.stroke[press.stroke.length - 1];
  const hit = pick(e.clientX, e.clientY);
  if (hit && hit.face !== last.face) press.stroke.push(hit);
});
renderer.domElement.addEventListener("pointerup", e => {
  window.__editor.clickTime = e.timeStamp; // the latency of an edit is measured from here
  controls.enabled = true;
  const p = press;
  press = null;
  if (!p || !p.hit) return;
  const moved = Math.hypot(e.clientX - p.x, e.clientY - p.y) > 4;
  if (p.tool === "pin") return pinDrag(p, e, moved);
  if (p.tool === "stroke") return moved ? pinStroke(p.stroke) : undefined;
  const v = pickVertex(e.clientX, e.clientY);
  if (v < 0) return;
  if (moved) {
    if (p.dragged < 0 || v === p.dragged) return; // an orbit, or back where it started
    edit(() => {
      const k = state.singularities.get(p.dragged);
      state.singularities.delete(p.dragged);
      const sum = add(state.singularities.get(v) || [0, 1], k);
      if (sum[0] === 0) state.singularities.delete(v); else state.singularities.set(v, sum);
    });
    return;
  }
  edit(() => {
    if (e.altKey) state.singularities.delete(v);
    else {
      const k = add(state.singularities.get(v) || [0, 1], [e.shiftKey ? -1 : 1, state.n]);
      if (k[0] === 0) state.singularities.delete(v); else state.singularities.set(v, k);
    }
  });
});

// the drag's end on the plane of the face where it started: the direction from the press to there
function pinDrag(p, e, moved) {
  const f = p.hit.face;
  if (!moved) return e.altKey && state.constraints.has(f) ? edit(() => { state.constraints.delete(f); }) : undefined;
  const normal = new THREE.Vector3().fromArray(fieldView.normals, 3 * f);
  const plane = new THREE.Plane().setFromNormalAndCoplanarPoint(normal, p.hit.point);
  const end = rayAt(e.clientX, e.clientY).intersectPlane(plane, new THREE.Vector3());
  if (!end) return;
  const d = end.sub(p.hit.point);
  if (d.lengthSq() === 0) return;
  edit(() => { state.constraints.set(f, tangent(f, d.toArray()).toArray()); });
}

// each face the stroke crossed gets the direction from its hit to the next one
function pinStroke(stroke) {
  const pinned = [];
  for (let i = 0; i + 1 < stroke.length; ++i) {
    const f = stroke[i].face, d = stroke[i + 1].point.clone().sub(stroke[i].point);
    const t = tangent(f, d.toArray());
    if (Number.isFinite(t.x) && t.lengthSq() > 0.5) pinned.push([f, t.toArray()]);
  }
  if (pinned.length) edit(() => { for (const [f, d] of pinned) state.constraints.set(f, d); });
}

// ---- the panel ------------------------------------------------------------------------------------------------
function controlsShow() {
  const select = $("n");
  if (![...select.options].some(o => o.value === String(state.n))) select.add(new Option(String(state.n)));
  select.value = String(state.n);
  $("align").checked = state.alignBoundary;
  $("features").checked = state.features !== null;
  if (state.features) $("feature-angle").value = String(state.features.threshold);
}
// another n: the singularities of the old one are not multiples of 1/n in general, so the placement for the new
$("n").onchange = e => placeFor(Number(e.target.value));
$("place").onclick = () => placeFor(state.n);
$("undo").onclick = () => travel(undoStack, redoStack);
$("redo").onclick = () => travel(redoStack, undoStack);
// the keyboard's shortcuts, all with ctrl (cmd on a Mac), not while typing a name or an angle: the legend on the
// page (#shortcuts, one [data-keys] element each) lists them, and the browser test checks it against this table
const KEYS = [{ keys: "Ctrl+Z", key: "z", shift: false, does: "undo" },
              { keys: "Ctrl+Shift+Z", key: "z", shift: true, does: "redo" },
              { keys: "Ctrl+Y", key: "y", shift: false, does: "redo" }];
window.addEventListener("keydown", e => {
  const typing = e.target instanceof HTMLInputElement && e.target.type !== "checkbox";
  if (!(e.ctrlKey || e.metaKey) || e.altKey || typing) return;
  const k = KEYS.find(k => k.key === e.key.toLowerCase() && k.shift === e.shiftKey);
  if (!k) return;
  if (k.does === "undo") travel(undoStack, redoStack); else travel(redoStack, undoStack);
  e.preventDefault();
});
$("balance-move").onclick = () => balancingMove();
$("clear-pins").onclick = () => edit(() => {
  if (!state.constraints.size) return false;
  state.constraints.clear();
  state.features = null;
}).then(controlsShow);
// with the features' pins shown, they are asked for again: none on the boundary while the field follows it
$("align").onchange = e => state.features ? alignFeatures(true, e.target.checked)
                                          : edit(() => { state.alignBoundary = e.target.checked; });

// the sharp features' pins (the server's feature_aligned_faces()), added where the user has no pin of their own, or
// taken away (those still as the features set them); with the boundary alignment as `alignBoundary`: one edit
async function alignFeatures(on, alignBoundary = state.alignBoundary) {
  let h = null;
  if (on) {
    const threshold = Number($("feature-angle").value);
    try {
      ({ header: h } = await post("/api/features", { threshold: Number.isFinite(threshold) ? threshold : null,
                                                     n: state.n, align_boundary: alignBoundary }));
    } catch (error) {
      say(explain(error, "features"), true);
      controlsShow();
      return;
    }
  }
  let kept = 0;
  window.__editor.lastError = null;
  await edit(() => {
    if (state.features)
      for (const [f, d] of state.features.pins) if (state.constraints.get(f) === d) state.constraints.delete(f);
    state.features = null;
    state.alignBoundary = alignBoundary;
    if (h) {
      const pins = new Map();
      for (const [f, d] of h.constraints)
        if (state.constraints.has(f)) ++kept; else { state.constraints.set(f, d); pins.set(f, d); }
      state.features = { threshold: h.threshold, pins };
    }
  });
  controlsShow();
  window.__editor.features = h && h.report;
  if (h && !window.__editor.lastError) {
    const r = h.report;
    say(r.number_of_sharp_edges === 0
      ? `no edge is sharper than ${h.threshold}°: no face pinned`
      : `features: ${r.number_of_sharp_edges} sharp edges, ${r.number_of_curves} curves, ` +
        `${state.features.pins.size} faces pinned` + (kept ? `, ${kept} left to your pins` : "") +
        (h.on_aligned_boundary ? `, ${h.on_aligned_boundary} left to the boundary alignment` : "") +
        `; ${r.disagreeing_pairs} of ${r.neighbouring_pairs} neighbouring pins disagree by over 5°`);
  }
}
$("features").onchange = e => alignFeatures(e.target.checked);
$("feature-angle").onchange = () => { if (state.features) alignFeatures(true); };
$("display").onchange = e => {
  display = e.target.value;
  fieldView.style = display;
  if (display === "streamlines") traceStreamlines(); else { drawStreamlines(null); draw(); }
};
// the name's extension follows the kind of file
const EXTENSIONS = { singularities: ".sing", constraints: ".dirs", field: ".field.txt", vtk: ".vtk", ply: ".ply",
                     streamlines: ".streamlines.vtk", png: ".png" };
$("kind").onchange = e => {
  const path = $("path").value, old = Object.values(EXTENSIONS).sort((a, b) => b.length - a.length)
    .find(x => path.endsWith(x));
  $("path").value = (old ? path.slice(0, -old.length) : path) + EXTENSIONS[e.target.value];
};
// a file that exists is replaced only once the user says so: the server refuses it (409) without "overwrite": true;
// the mesh being edited it never replaces (403, its reason shown)
$("save").onclick = async () => {
  const kind = $("kind").value, path = $("path").value;
  if (kind === "png") return savePng(path);
  if (!balance().every(b => b.balanced)) // the server solves before it writes, and solves balanced states only
    return say("Not saved: the singularities are unbalanced (see above); balance them first.", true);
  const body = { ...request(), kind, path };
  let h;
  try {
    try {
      ({ header: h } = await post("/api/save", body));
    } catch (error) {
      if (error.status !== 409) throw error;
      if (!window.confirm(`${path} already exists in the server's folder. Replace it?`)) {
        window.__editor.declined = path;
        return say(`not saved: ${path} exists and was kept`);
      }
      ({ header: h } = await post("/api/save", { ...body, overwrite: true }));
    }
  } catch (error) {
    return say(explain(error, "save", path), true);
  }
  say(`saved ${h.saved} (${h.bytes} bytes)`);
  window.__editor.saved = h.saved;
};
$("load").onclick = async () => {
  const kind = $("kind").value, path = $("path").value;
  if (kind !== "singularities" && kind !== "constraints")
    return say(`Not loaded: only singularities and constraints are loaded, not ${$("kind").selectedOptions[0].text}.`,
               true);
  let h;
  try {
    ({ header: h } = await post("/api/load", { kind, path }));
  } catch (error) {
    return say(explain(error, "load", path), true);
  }
  if (kind === "singularities")
    edit(() => { state.singularities = new Map(h.singularities.map(([v, k]) => [v, parseIndex(k)])); });
  else edit(() => { state.constraints = new Map(h.constraints.map(([f, d]) => [f, d])); });
};

// a PNG of the view, downloaded by the browser under the name given
function savePng(path) {
  draw();
  fieldView.composite().toBlob(blob => {
    const a = document.createElement("a");
    a.href = URL.createObjectURL(blob);
    a.download = (path.split("/").pop() || "field").replace(/\.png$/i, "") + ".png";
    a.click();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
    say(`PNG of the view: ${a.download}`);
  }, "image/png");
}

async function start() {
  const frame = parseFrame(await (await fetch("/api/mesh")).arrayBuffer());
  header = frame.header;
  V = frame.arrays.V;
  F = frame.arrays.F;
  angleDefect = frame.arrays.angle_defect;
  window.__editor = {
    component: frame.arrays.component, solves: 0, state, edit, solve, balance, balancingMove, screenOf, screenOfFace,
    placeFor, alignFeatures, keys: KEYS, measure: false, latencies: [], faces: F.length / 3, idle: () => queue,
    proposal: () => proposal && proposal.map(([v, k]) => [v, indexText(k)]), // what the balancing move would add
    get directions() { return fieldView.directions(); },
    singularities: () => [...state.singularities].map(([v, k]) => [v, indexText(k)]),
    constraints: () => [...state.constraints],
    request,
    // the camera brought `factor` times closer to the target (factor < 1: farther)
    zoom: factor => {
      camera.position.sub(controls.target).divideScalar(factor).add(controls.target);
      controls.update();
    },
    internals: { renderer, scene, camera, draw, get fieldView() { return fieldView; } }, // for measurements and tests
  };
  state.n = header.n;
  for (const [v, k] of header.singularities) state.singularities.set(v, parseIndex(k));
  controlsShow();
  $("align").disabled = header.closed.every(c => c);
  buildScene();
  drawBoundary(frame.arrays.boundary);
  showBalance();
  await solve();
  window.__editor.ready = true;
}
start();
