// The mesh from the server (/api/mesh): its arrays, and the positions and neighbours of its elements.
import * as THREE from "three";
import { parseFrame } from "./protocol.js";

export let V = null, F = null, header = null, angleDefect = null;
// V, F, the header and the angle defects set from the server's mesh frame, which is returned
export async function loadMesh() {
  const frame = parseFrame(await (await fetch("/api/mesh")).arrayBuffer());
  header = frame.header;
  V = frame.arrays.V;
  F = frame.arrays.F;
  angleDefect = frame.arrays.angle_defect;
  return frame;
}

export const point = v => new THREE.Vector3(V[3 * v], V[3 * v + 1], V[3 * v + 2]);
export function centroid(f) {
  return point(F[3 * f]).add(point(F[3 * f + 1])).add(point(F[3 * f + 2])).divideScalar(3);
}

let neighbourLists = null;
export function adjacency() {
  if (neighbourLists) return neighbourLists;
  neighbourLists = Array.from({ length: V.length / 3 }, () => []);
  for (let f = 0; f < F.length / 3; ++f)
    for (let k = 0; k < 3; ++k) neighbourLists[F[3 * f + k]].push(F[3 * f + (k + 1) % 3]);
  return neighbourLists;
}
