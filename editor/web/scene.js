// Rendering glue: renderer, camera, orbit controls, the field view; markers, pins, boundary loops, streamlines.
import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";
import { MeshBVH } from "three-mesh-bvh";
import { proposal } from "./balance.js";
import { FieldView } from "./field_view.js";
import { F, V, point } from "./mesh.js";
import { state } from "./state.js";
import { $ } from "./status.js";

const view = $("view");
// no multisampling: a software GL pays for every sample; the drawing buffer is preserved: it is drawn again only
// when the camera moves (the field, pins and markers are in the field view's 2D overlay over it)
export const renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
renderer.setSize(view.clientWidth, view.clientHeight);
view.appendChild(renderer.domElement);
const BACKGROUND = new THREE.Color(0xf4f4f4);
// the 3D lines drawn over the mesh (boundary loops, streamlines), depth-tested against it, writing no depth
export const scene = new THREE.Scene();
export const camera = new THREE.PerspectiveCamera(40, view.clientWidth / view.clientHeight, 1e-3, 1e3);
export const controls = new OrbitControls(camera, renderer.domElement);

export let fieldView = null, bvh = null;
let streamlines = null, quadLines = null;

export function draw() {
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

export function buildScene() {
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
export function drawMarkers() {
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
export function drawPins() {
  const features = state.features?.pins;
  fieldView.setPins([...state.constraints].map(([f, d]) => ({ face: f, direction: d,
                                                              feature: features?.get(f) === d })));
}

export function drawBoundary(edges) {
  const positions = new Float32Array(edges.length * 3);
  for (let i = 0; i < edges.length; ++i)
    for (let j = 0; j < 3; ++j) positions[3 * i + j] = V[3 * edges[i] + j];
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(positions, 3));
  scene.add(new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color: 0xd4740a, depthWrite: false })));
}

// indexed line segments over `points` ((k, 3) flat) in `color`, added to the 3D lines of the view frame
function addLines(points, segments, color) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(points, 3));
  geometry.setIndex(segments);
  const lines = new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color, depthWrite: false }));
  scene.add(lines);
  fieldView.stale = true; // the 3D lines are in the view frame
  return lines;
}

// takes lines of addLines() away (null: nothing); returns null
function removeLines(lines) {
  if (!lines) return null;
  scene.remove(lines);
  lines.geometry.dispose();
  fieldView.stale = true;
  return null;
}

export function drawStreamlines(points, offsets) {
  streamlines = removeLines(streamlines);
  if (!points) return;
  const segments = [];
  for (let i = 0; i + 1 < offsets.length; ++i)
    for (let k = offsets[i]; k + 1 < offsets[i + 1]; ++k) segments.push(k, k + 1);
  streamlines = addLines(points, segments, 0x1f3a93);
}

// the quad mesh's edges (points (k, 3), quads (q, 4) into them), green lines over the mesh; null: none. Returns
// the number of segments drawn
export function drawQuads(points, quads) {
  quadLines = removeLines(quadLines);
  if (!points) return 0;
  // each edge once: the quads of a closed mesh share every edge
  const segments = [], taken = new Set(), k = points.length / 3;
  for (let q = 0; q < quads.length; q += 4)
    for (let j = 0; j < 4; ++j) {
      const a = quads[q + j], b = quads[q + (j + 1) % 4], key = Math.min(a, b) * k + Math.max(a, b);
      if (taken.has(key)) continue;
      taken.add(key);
      segments.push(a, b);
    }
  quadLines = addLines(points, segments, 0x0b7a3e);
  return segments.length / 2;
}

// whether the camera sees vertex v: nothing of the mesh is hit before it (within a fifth of an edge)
export function seen(v) {
  const p = point(v), origin = camera.position, distance = p.distanceTo(origin);
  const hit = bvh.raycastFirst(new THREE.Ray(origin.clone(), p.sub(origin).normalize()), THREE.DoubleSide);
  return !hit || hit.distance >= distance - 0.2 * fieldView.meanEdge;
}
