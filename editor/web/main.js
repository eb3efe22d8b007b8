// The field editor's page, its entry point (esbuild bundles from here): the mesh loaded, the scene set, a first solve.
// The page: the shaded mesh with its field (glyphs or streamlines), singularities coloured by index, pinned
// directions and boundary loops. Every edit (singularities, pins, strokes, n, boundary alignment, a file loaded) is
// a solve on the server's prefactored solver; undo and redo go through whole states. One concern per module:
// status.js (messages), state.js, mesh.js, scene.js (drawing), picking.js, balance.js, solve.js (requests),
// history.js (edits, undo), server_edits.js (placement, features), files.js, pointer.js, panel.js (controls).
import { balance, proposal, showBalance } from "./balance.js";
import { balancingMove, edit, queue } from "./history.js";
import { F, header, loadMesh } from "./mesh.js";
import { KEYS } from "./panel.js";
import { screenOf, screenOfFace } from "./picking.js";
import "./pointer.js";
import { indexText, parseIndex } from "./protocol.js";
import { buildScene, camera, controls, draw, drawBoundary, fieldView, renderer, scene } from "./scene.js";
import { alignFeatures, placeFor } from "./server_edits.js";
import { solve } from "./solve.js";
import { controlsShow, request, state } from "./state.js";
import { $ } from "./status.js";

async function start() {
  const frame = await loadMesh();
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
  $("quad-size").value = String(header.quad_size); // the quad mesh's default size (the server's: 4 mean edges)
  drawBoundary(frame.arrays.boundary);
  showBalance();
  await solve();
  window.__editor.ready = true;
}
start();
