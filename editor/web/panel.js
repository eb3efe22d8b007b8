// The panel's controls wired to the edits: n, placement, undo and redo (and their keys), pins, display, files.
import { EXTENSIONS, loadFile, saveFile } from "./files.js";
import { balancingMove, edit, redoStack, travel, undoStack } from "./history.js";
import { alignFeatures, placeFor } from "./server_edits.js";
import { showAs, showQuadMesh } from "./solve.js";
import { controlsShow, state } from "./state.js";
import { $ } from "./status.js";

// another n: the singularities of the old one are not multiples of 1/n in general, so the placement for the new
$("n").onchange = e => placeFor(Number(e.target.value));
$("place").onclick = () => placeFor(state.n);
$("undo").onclick = () => travel(undoStack, redoStack);
$("redo").onclick = () => travel(redoStack, undoStack);
// the keyboard's shortcuts, all with ctrl (cmd on a Mac), not while typing a name or an angle: the legend on the
// page (#shortcuts, one [data-keys] element each) lists them, and the browser test checks it against this table
export const KEYS = [{ keys: "Ctrl+Z", key: "z", shift: false, does: "undo" },
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
$("features").onchange = e => alignFeatures(e.target.checked);
$("feature-angle").onchange = () => { if (state.features) alignFeatures(true); };
$("display").onchange = e => showAs(e.target.value);
$("quads").onchange = e => showQuadMesh(e.target.checked);
$("quad-size").onchange = () => { if ($("quads").checked) showQuadMesh(true); };
$("quad-scale").onchange = () => { if ($("quads").checked) showQuadMesh(true); };
$("quad-off-features").onchange = () => { if ($("quads").checked) showQuadMesh(true); };
// the name's extension follows the kind of file
$("kind").onchange = e => {
  const path = $("path").value, old = Object.values(EXTENSIONS).sort((a, b) => b.length - a.length)
    .find(x => path.endsWith(x));
  $("path").value = (old ? path.slice(0, -old.length) : path) + EXTENSIONS[e.target.value];
};
$("save").onclick = saveFile;
$("load").onclick = loadFile;
