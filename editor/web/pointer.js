// The pointer on the mesh: singularities clicked and dragged, directions pinned by drags and strokes.
import * as THREE from "three";
import { edit } from "./history.js";
import { add } from "./protocol.js";
import { grabbed, pick, pickVertex, rayAt, tangent } from "./picking.js";
import { controls, fieldView, renderer } from "./scene.js";
import { state } from "./state.js";
import { $ } from "./status.js";

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
