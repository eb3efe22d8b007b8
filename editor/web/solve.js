// Solve requests: the state's field and streamlines from the server; a state shown, solved or unbalanced.
import { balance, proposal, showBalance } from "./balance.js";
import { post } from "./protocol.js";
import { draw, drawMarkers, drawPins, drawQuads, drawStreamlines, fieldView, renderer } from "./scene.js";
import { request, state } from "./state.js";
import { $, explain, say } from "./status.js";

let display = "glyphs";
let solvedText = "";
// the quad mesh is shown while its box is checked (state.js unchecks and disables it for n other than 4)
const quadsOn = () => $("quads").checked && !$("quads").disabled;
// the request of the field on the screen (the last solve that succeeded: an unbalanced state keeps it)
let solvedRequest = null;

export async function solve() {
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
  solvedText = `energy ${h.energy.toPrecision(6)}, residual ${h.max_residual.toExponential(1)}, ` +
               `${(performance.now() - started).toFixed(1)} ms (solve ${(1e3 * h.timings.solve).toFixed(1)} ms)`;
  say(solvedText);
  if (display === "streamlines") traceStreamlines();
  if (quadsOn()) quadMesh(); else if (window.__editor.quadSegments) showQuadMesh(false);
  return true;
}

// the quad mesh of the field on the screen (n = 4 only: the control is disabled otherwise), its edges drawn and its
// report's counts added to the status line; a refusal (e.g. a quad size too small, a boundary the field does not
// follow) said in words, the overlay taken away. One request at a time (a quad mesh can take seconds with many
// singularities): edits meanwhile ask for one more, of the latest field, when it is done
let quadRequests = 0, quadBusy = false, quadAgain = false;
async function quadMesh() {
  if (quadBusy) { quadAgain = true; return; }
  if (!solvedRequest || solvedRequest.n !== 4) { drawQuads(null); draw(); return; }
  const body = { ...solvedRequest }, size = Number($("quad-size").value), asked = ++quadRequests;
  if ($("quad-size").value.trim() !== "" && Number.isFinite(size)) body.quad_size = size;
  const scale = Number($("quad-scale").value); // the field scaled per face first (empty: not scaled)
  if ($("quad-scale").value.trim() !== "" && Number.isFinite(scale)) body.scale_smoothness = scale;
  if (state.features) body.feature_threshold = state.features.threshold; // the sharp edges on iso-lines too
  // the singularities near the sharp edges moved off them for these quads (the user's own are not changed)
  if (state.features && $("quad-off-features").checked) body.move_off_features = true;
  const e = window.__editor;
  quadBusy = true;
  try {
    const { header: h, arrays } = await post("/api/quads", body);
    if (quadsOn() && asked === quadRequests) { // not taken away meanwhile
      const r = h.report;
      e.quadSegments = drawQuads(arrays.points, arrays.quads);
      e.quadReport = r;
      e.quadScale = body.scale_smoothness ?? 0; // the scale these quads were made with
      e.quadMoved = h.moved_off_features ? h.moved_off_features.moves.length : null; // null: not asked
      draw();
      const moved = e.quadMoved === null ? "" : `, ${e.quadMoved} singularities moved off the sharp features`;
      say(`${solvedText} · quad mesh (H = ${r.quad_size.toPrecision(3)}): ${r.quads} quads, ` +
          `${r.folded_triangles} folded triangles, ${r.valence_errors} valence errors${moved}`);
    }
  } catch (error) {
    if (asked === quadRequests) {
      drawQuads(null);
      draw();
      e.quadSegments = 0;
      say(explain(error, "quads"), true);
    }
  } finally {
    quadBusy = false;
  }
  if (quadAgain) {
    quadAgain = false;
    if (quadsOn()) quadMesh();
  }
}

// the quad mesh overlay on or off
export function showQuadMesh(on) {
  if (on && quadsOn()) quadMesh();
  else { ++quadRequests; drawQuads(null); draw(); window.__editor.quadSegments = 0; }
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
export async function show() {
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

// glyphs or streamlines
export function showAs(style) {
  display = style;
  fieldView.style = display;
  if (display === "streamlines") traceStreamlines(); else { drawStreamlines(null); draw(); }
}
