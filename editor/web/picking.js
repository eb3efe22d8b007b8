// Picking: the face and vertex under the pointer, the marker grabbed, where vertices and faces are on the screen.
import * as THREE from "three";
import { F, centroid, point } from "./mesh.js";
import { bvh, camera, fieldView, renderer, seen } from "./scene.js";
import { state } from "./state.js";

// d projected on face f's plane, unit (the solver projects constraints the same way)
export function tangent(f, d) {
  const n = new THREE.Vector3().fromArray(fieldView.normals, 3 * f), t = new THREE.Vector3().fromArray(d);
  return t.addScaledVector(n, -t.dot(n)).normalize();
}

const raycaster = new THREE.Raycaster();
export function rayAt(clientX, clientY) {
  const r = renderer.domElement.getBoundingClientRect();
  raycaster.setFromCamera(new THREE.Vector2(((clientX - r.left) / r.width) * 2 - 1,
                                            -((clientY - r.top) / r.height) * 2 + 1), camera);
  return raycaster.ray;
}
// the face under the pointer, the point hit and the face's vertex nearest to it
export function pick(clientX, clientY) {
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
export const pickVertex = (x, y) => pick(x, y)?.vertex ?? -1;

// the singularity whose marker is under the pointer (within 8 pixels of its vertex, the nearest, seen by the
// camera), or -1: a drag starts on the marker, not only on the vertex's own faces
export function grabbed(clientX, clientY) {
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
export function screenOf(v) {
  const s = screenOfPoint(point(v));
  return { x: s.x, y: s.y, picked: s.inside && pickVertex(s.x, s.y) === v };
}
// where face f's centroid is, and whether a press there picks f
export function screenOfFace(f) {
  const s = screenOfPoint(centroid(f));
  return { x: s.x, y: s.y, picked: s.inside && pick(s.x, s.y)?.face === f };
}
