// The edits that ask the server first: the automatic placement and the sharp features' pins.
import { edit } from "./history.js";
import { parseIndex, post } from "./protocol.js";
import { controlsShow, state } from "./state.js";
import { $, explain, say } from "./status.js";

// the automatic placement for n, as one edit (constraints and alignment kept)
export async function placeFor(n) {
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

// the sharp features' pins (the server's feature_aligned_faces()), added where the user has no pin of their own, or
// taken away (those still as the features set them); with the boundary alignment as `alignBoundary`: one edit
export async function alignFeatures(on, alignBoundary = state.alignBoundary) {
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
