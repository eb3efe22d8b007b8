// The field editor's page (issue 22, work in progress): the shaded mesh, n directions per face as glyphs,
// singularities coloured by index; a click edits the singularities and the server solves on its prefactored solver.
import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";

// ---- the server's binary frames (editor/serve.py: frame()) ------------------------------------------------
const TYPES = { "<f4": Float32Array, "<u4": Uint32Array, "<i4": Int32Array };

export function parseFrame(buffer) {
  const bytes = new Uint8Array(buffer);
  if (String.fromCharCode(...bytes.subarray(0, 4)) !== "TCB1") throw new Error("not a TCB1 frame");
  const length = new DataView(buffer).getUint32(4, true);
  const header = JSON.parse(new TextDecoder().decode(bytes.subarray(8, 8 + length)));
  const start = 8 + length;
  const arrays = {};
  for (const a of header.arrays) {
    const Type = TYPES[a.dtype];
    const count = a.shape.reduce((p, q) => p * q, 1);
    arrays[a.name] = new Type(buffer, start + a.offset, count);
  }
  return { header, arrays };
}

// ---- indices as exact fractions p/q --------------------------------------------------------------------------
function gcd(a, b) { return b === 0 ? Math.abs(a) : gcd(b, a % b); }
function fraction(p, q) { const g = gcd(p, q) || 1; return [p / g * Math.sign(q), Math.abs(q) / g]; }
function parseIndex(s) { const [p, q] = String(s).split("/").map(Number); return fraction(p, q || 1); }
function indexText([p, q]) { return q === 1 ? String(p) : `${p}/${q}`; }
function add([a, b], [c, d]) { return fraction(a * d + c * b, b * d); }

// ---- the state: singularities {vertex: [p, q]}, n; undo/redo of whole states ---------------------------------
const state = { n: 4, singularities: new Map() };
const undoStack = [], redoStack = [];
function snapshot() { return { n: state.n, singularities: new Map(state.singularities) }; }
function restore(s) {
  state.n = s.n;
  state.singularities = new Map(s.singularities);
  document.getElementById("n").value = String(state.n);
}

// ---- the scene ------------------------------------------------------------------------------------------------
const view = document.getElementById("view");
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
renderer.setSize(view.clientWidth, view.clientHeight);
view.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xf4f4f4);
const camera = new THREE.PerspectiveCamera(40, view.clientWidth / view.clientHeight, 1e-3, 1e3);
const controls = new OrbitControls(camera, renderer.domElement);
scene.add(new THREE.HemisphereLight(0xffffff, 0x666666, 2.2));
const light = new THREE.DirectionalLight(0xffffff, 1.2);
scene.add(light);

let mesh = null, glyphs = null, markers = null, V = null, F = null, header = null, glyphLength = 1;
const status = document.getElementById("status");

function draw() {
  light.position.copy(camera.position);
  renderer.render(scene, camera);
}
controls.addEventListener("change", draw);
window.addEventListener("resize", () => {
  camera.aspect = view.clientWidth / view.clientHeight;
  camera.updateProjectionMatrix();
  renderer.setSize(view.clientWidth, view.clientHeight);
  draw();
});

function buildMesh() {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(V, 3));
  geometry.setIndex(new THREE.BufferAttribute(F, 1));
  geometry.computeVertexNormals();
  geometry.computeBoundingSphere();
  mesh = new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({
    color: 0xb8c4d6, roughness: 0.8, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 }));
  scene.add(mesh);
  const { center, radius } = geometry.boundingSphere;
  controls.target.copy(center);
  camera.position.copy(center).add(new THREE.Vector3(0, 0, 2.8 * radius));
  camera.near = radius * 1e-3;
  camera.far = radius * 20;
  camera.updateProjectionMatrix();
  controls.update();
  let total = 0;
  for (let f = 0; f < F.length / 3; ++f) {
    const a = F[3 * f], b = F[3 * f + 1];
    total += Math.hypot(V[3 * a] - V[3 * b], V[3 * a + 1] - V[3 * b + 1], V[3 * a + 2] - V[3 * b + 2]);
  }
  glyphLength = 0.35 * total / (F.length / 3);
}

// the n directions of every face (n per face, 3 numbers each): the field's, turned by 2 pi k / n about the face's
// unit normal (the field is tangent to the face)
function nDirections(field, n) {
  const nf = F.length / 3;
  const out = new Float32Array(nf * n * 3);
  for (let f = 0; f < nf; ++f) {
    const a = 3 * F[3 * f], b = 3 * F[3 * f + 1], c = 3 * F[3 * f + 2];
    const ux = V[b] - V[a], uy = V[b + 1] - V[a + 1], uz = V[b + 2] - V[a + 2];
    const wx = V[c] - V[a], wy = V[c + 1] - V[a + 1], wz = V[c + 2] - V[a + 2];
    let nx = uy * wz - uz * wy, ny = uz * wx - ux * wz, nz = ux * wy - uy * wx;
    const length = Math.hypot(nx, ny, nz);
    nx /= length; ny /= length; nz /= length;
    const x = field[3 * f], y = field[3 * f + 1], z = field[3 * f + 2];
    const px = ny * z - nz * y, py = nz * x - nx * z, pz = nx * y - ny * x; // normal x field
    for (let k = 0; k < n; ++k) {
      const t = 2 * Math.PI * k / n, cos = Math.cos(t), sin = Math.sin(t), o = 3 * (f * n + k);
      out[o] = cos * x + sin * px;
      out[o + 1] = cos * y + sin * py;
      out[o + 2] = cos * z + sin * pz;
    }
  }
  return out;
}

// n segments per face from its centroid, along the directions of the solve
function drawGlyphs(directions, n) {
  const nf = F.length / 3;
  const positions = new Float32Array(nf * n * 6);
  for (let f = 0; f < nf; ++f) {
    const a = 3 * F[3 * f], b = 3 * F[3 * f + 1], c = 3 * F[3 * f + 2];
    const cx = (V[a] + V[b] + V[c]) / 3, cy = (V[a + 1] + V[b + 1] + V[c + 1]) / 3, cz = (V[a + 2] + V[b + 2] + V[c + 2]) / 3;
    for (let k = 0; k < n; ++k) {
      const d = 3 * (f * n + k), o = 6 * (f * n + k);
      positions[o] = cx; positions[o + 1] = cy; positions[o + 2] = cz;
      positions[o + 3] = cx + glyphLength * directions[d];
      positions[o + 4] = cy + glyphLength * directions[d + 1];
      positions[o + 5] = cz + glyphLength * directions[d + 2];
    }
  }
  if (!glyphs) {
    glyphs = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x1f3a93 }));
    scene.add(glyphs);
  }
  glyphs.geometry.setAttribute("position", new THREE.BufferAttribute(positions, 3));
  glyphs.geometry.computeBoundingSphere();
}

function drawMarkers() {
  const positions = [], colors = [];
  for (const [v, [p]] of state.singularities) {
    positions.push(V[3 * v], V[3 * v + 1], V[3 * v + 2]);
    colors.push(...(p > 0 ? [0.85, 0.1, 0.1] : [0.1, 0.45, 0.9]));
  }
  if (markers) scene.remove(markers);
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.Float32BufferAttribute(positions, 3));
  geometry.setAttribute("color", new THREE.Float32BufferAttribute(colors, 3));
  markers = new THREE.Points(geometry, new THREE.PointsMaterial({ size: 12, sizeAttenuation: false, vertexColors: true }));
  scene.add(markers);
}

// the boundary loops, as the border edges the server found
function drawBoundary(edges) {
  const positions = new Float32Array(edges.length * 3);
  for (let i = 0; i < edges.length; ++i)
    for (let j = 0; j < 3; ++j) positions[3 * i + j] = V[3 * edges[i] + j];
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(positions, 3));
  scene.add(new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color: 0xd4740a })));
}

// the automatic placement for n, as one edit
async function placeFor(n) {
  const response = await fetch("/api/place", { method: "POST", body: JSON.stringify({ n }) });
  if (!response.ok) {
    status.textContent = await response.text();
    status.className = "error";
    return;
  }
  const { header: h } = parseFrame(await response.arrayBuffer());
  await edit(() => {
    state.n = h.n;
    state.singularities = new Map(h.singularities.map(([v, k]) => [v, parseIndex(k)]));
  });
  document.getElementById("n").value = String(state.n);
}

// per component: the sum of the indices against its Euler characteristic (closed components must balance)
function balance() {
  const sums = header.chi.map(() => [0, 1]);
  for (const [v, k] of state.singularities) {
    const c = window.__editor.component[v];
    if (c >= 0) sums[c] = add(sums[c], k);
  }
  return header.chi.map((chi, c) => ({ component: c, sum: sums[c], chi, closed: header.closed[c],
                                       balanced: !header.closed[c] || (sums[c][0] === chi && sums[c][1] === 1) }));
}

function showBalance() {
  const rows = balance().map(b => `component ${b.component}: ${indexText(b.sum)}` +
    (b.closed ? ` of χ = ${b.chi}${b.balanced ? "" : " (unbalanced)"}` : " (bordered)"));
  document.getElementById("balance").textContent = rows.join("\n");
}

async function solve() {
  const started = performance.now();
  const body = JSON.stringify({ n: state.n,
    singularities: [...state.singularities].map(([v, k]) => [v, indexText(k)]) });
  const response = await fetch("/api/solve", { method: "POST", body });
  if (!response.ok) {
    status.textContent = await response.text();
    status.className = "error";
    window.__editor.lastError = status.textContent;
    return false;
  }
  const buffer = await response.arrayBuffer();
  const received = performance.now();
  const { header: h, arrays } = parseFrame(buffer);
  const directions = nDirections(arrays.field, h.n);
  drawGlyphs(directions, h.n);
  drawMarkers();
  const built = performance.now();
  draw();
  const e = window.__editor;
  if (e.measure) {
    // the frame on the screen: reading a pixel waits for the GPU to finish drawing it
    const gl = renderer.getContext();
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
    const now = performance.now();
    e.latencies.push({ total: now - (e.clickTime ?? started), server: received - started,
                       solve: 1e3 * (h.timings.solve + h.timings.field), draw: now - received,
                       glyphs: built - received, render: now - built });
  }
  window.__editor.directions = directions;
  window.__editor.solves += 1;
  window.__editor.lastError = null;
  status.className = "";
  status.textContent = `energy ${h.energy.toPrecision(6)}, residual ${h.max_residual.toExponential(1)}, ` +
    `${(performance.now() - started).toFixed(1)} ms (solve ${(1e3 * h.timings.solve).toFixed(1)} ms)`;
  return true;
}

// shows the current state: solved when every closed component balances, else the markers and the reason
async function show() {
  showBalance();
  if (!balance().every(b => b.balanced)) {
    status.textContent = "unbalanced: the indices of a closed component must sum to its Euler characteristic";
    status.className = "error";
    window.__editor.unbalanced = true;
    drawMarkers();
    draw();
    return true;
  }
  window.__editor.unbalanced = false;
  return solve();
}

async function edit(change) {
  const before = snapshot();
  change();
  if (await show()) {
    undoStack.push(before);
    redoStack.length = 0;
  } else {
    restore(before); // refused by the server: the reason stays shown
    showBalance();
  }
}

// the vertex of the clicked face nearest to the click
const raycaster = new THREE.Raycaster();
function pickVertex(clientX, clientY) {
  const r = renderer.domElement.getBoundingClientRect();
  const p = new THREE.Vector2(((clientX - r.left) / r.width) * 2 - 1, -((clientY - r.top) / r.height) * 2 + 1);
  raycaster.setFromCamera(p, camera);
  const hit = raycaster.intersectObject(mesh)[0];
  if (!hit) return -1;
  let best = -1, distance = Infinity;
  for (const v of [hit.face.a, hit.face.b, hit.face.c]) {
    const d = hit.point.distanceTo(new THREE.Vector3(V[3 * v], V[3 * v + 1], V[3 * v + 2]));
    if (d < distance) { distance = d; best = v; }
  }
  return best;
}

// where vertex v is on the screen, and whether a click there picks it (for tests: window.__editor.screenOf)
function screenOf(v) {
  const p = new THREE.Vector3(V[3 * v], V[3 * v + 1], V[3 * v + 2]).project(camera);
  const r = renderer.domElement.getBoundingClientRect();
  const x = r.left + (p.x + 1) / 2 * r.width, y = r.top + (1 - p.y) / 2 * r.height;
  const inside = Math.abs(p.x) < 0.95 && Math.abs(p.y) < 0.95;
  return { x, y, picked: inside && pickVertex(x, y) === v };
}

// a click edits the vertex under it; a press on a singularity drags it to the vertex where it is released (the
// view does not orbit meanwhile); any other drag orbits
let pressed = null, dragged = -1;
renderer.domElement.addEventListener("pointerdown", e => {
  pressed = [e.clientX, e.clientY];
  const v = pickVertex(e.clientX, e.clientY);
  dragged = v >= 0 && state.singularities.has(v) && !e.shiftKey && !e.altKey ? v : -1;
  controls.enabled = dragged < 0;
});
renderer.domElement.addEventListener("pointerup", e => {
  window.__editor.clickTime = e.timeStamp; // the latency of an edit is measured from here
  controls.enabled = true;
  const moved = pressed && Math.hypot(e.clientX - pressed[0], e.clientY - pressed[1]) > 4;
  const from = dragged;
  pressed = null;
  dragged = -1;
  const v = pickVertex(e.clientX, e.clientY);
  if (v < 0) return;
  if (moved) {
    if (from < 0 || v === from) return; // an orbit, or back where it started
    edit(() => {
      const k = state.singularities.get(from);
      state.singularities.delete(from);
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
// another n: the singularities of the old one are not multiples of 1/n in general, so the placement for the new
document.getElementById("n").onchange = e => placeFor(Number(e.target.value));
document.getElementById("place").onclick = () => placeFor(state.n);
document.getElementById("undo").onclick = () => {
  if (!undoStack.length) return;
  redoStack.push(snapshot());
  restore(undoStack.pop());
  show();
};
document.getElementById("redo").onclick = () => {
  if (!redoStack.length) return;
  undoStack.push(snapshot());
  restore(redoStack.pop());
  show();
};

async function start() {
  const frame = parseFrame(await (await fetch("/api/mesh")).arrayBuffer());
  header = frame.header;
  V = frame.arrays.V;
  F = frame.arrays.F;
  window.__editor = { component: frame.arrays.component, solves: 0, state, edit, solve, balance, screenOf, placeFor,
                      measure: false, latencies: [],
                      singularities: () => [...state.singularities].map(([v, k]) => [v, indexText(k)]) };
  state.n = header.n;
  document.getElementById("n").value = String(header.n);
  for (const [v, k] of header.singularities) state.singularities.set(v, parseIndex(k));
  buildMesh();
  drawBoundary(frame.arrays.boundary);
  showBalance();
  await solve();
  window.__editor.ready = true;
}
start();
