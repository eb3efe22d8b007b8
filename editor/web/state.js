// The editor's state: n, singularities, pins, alignment, features; its snapshots, requests and panel controls.
import { indexText } from "./protocol.js";
import { $ } from "./status.js";

// ---- the state: n, singularities {vertex: [p, q]}, pinned directions {face: [x, y, z]}, boundary alignment, the
// sharp features' pins (null, or {threshold, pins: Map face -> the direction added to constraints}) -----------------
export const state = { n: 4, singularities: new Map(), constraints: new Map(), alignBoundary: false, features: null };

export function snapshot() {
  return { n: state.n, singularities: new Map(state.singularities), constraints: new Map(state.constraints),
           alignBoundary: state.alignBoundary, features: state.features };
}
export function restore(s) {
  state.n = s.n;
  state.singularities = new Map(s.singularities);
  state.constraints = new Map(s.constraints);
  state.alignBoundary = s.alignBoundary;
  state.features = s.features;
  controlsShow();
}
// what every solve-like request carries
export function request() {
  return { n: state.n, singularities: [...state.singularities].map(([v, k]) => [v, indexText(k)]),
           constraints: [...state.constraints], align_boundary: state.alignBoundary };
}

// the panel's controls set from the state
export function controlsShow() {
  const select = $("n");
  if (![...select.options].some(o => o.value === String(state.n))) select.add(new Option(String(state.n)));
  select.value = String(state.n);
  $("align").checked = state.alignBoundary;
  $("features").checked = state.features !== null;
  if (state.features) $("feature-angle").value = String(state.features.threshold);
  // the quad mesh needs a cross field: off (and its overlay taken away by the next solve) for another n
  $("quads").disabled = state.n !== 4;
  if (state.n !== 4) $("quads").checked = false;
}
