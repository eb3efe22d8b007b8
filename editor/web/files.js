// Files in the server's folder: the state's files saved, singularities and pins loaded; a PNG of the view.
import { balance } from "./balance.js";
import { edit } from "./history.js";
import { parseIndex, post } from "./protocol.js";
import { draw, fieldView } from "./scene.js";
import { request, state } from "./state.js";
import { $, explain, say } from "./status.js";

// the file name's extension of each kind (the panel's kind renames the file)
export const EXTENSIONS = { singularities: ".sing", constraints: ".dirs", field: ".field.txt", vtk: ".vtk",
                            ply: ".ply", streamlines: ".streamlines.vtk", png: ".png" };

// a file that exists is replaced only once the user says so: the server refuses it (409) without "overwrite": true;
// the mesh being edited it never replaces (403, its reason shown)
export async function saveFile() {
  const kind = $("kind").value, path = $("path").value;
  if (kind === "png") return savePng(path);
  if (!balance().every(b => b.balanced)) // the server solves before it writes, and solves balanced states only
    return say("Not saved: the singularities are unbalanced (see above); balance them first.", true);
  const body = { ...request(), kind, path };
  let h;
  try {
    try {
      ({ header: h } = await post("/api/save", body));
    } catch (error) {
      if (error.status !== 409) throw error;
      if (!window.confirm(`${path} already exists in the server's folder. Replace it?`)) {
        window.__editor.declined = path;
        return say(`not saved: ${path} exists and was kept`);
      }
      ({ header: h } = await post("/api/save", { ...body, overwrite: true }));
    }
  } catch (error) {
    return say(explain(error, "save", path), true);
  }
  say(`saved ${h.saved} (${h.bytes} bytes)`);
  window.__editor.saved = h.saved;
}
export async function loadFile() {
  const kind = $("kind").value, path = $("path").value;
  if (kind !== "singularities" && kind !== "constraints")
    return say(`Not loaded: only singularities and constraints are loaded, not ${$("kind").selectedOptions[0].text}.`,
               true);
  let h;
  try {
    ({ header: h } = await post("/api/load", { kind, path }));
  } catch (error) {
    return say(explain(error, "load", path), true);
  }
  if (kind === "singularities")
    edit(() => { state.singularities = new Map(h.singularities.map(([v, k]) => [v, parseIndex(k)])); });
  else edit(() => { state.constraints = new Map(h.constraints.map(([f, d]) => [f, d])); });
}

// a PNG of the view, downloaded by the browser under the name given
function savePng(path) {
  draw();
  fieldView.composite().toBlob(blob => {
    const a = document.createElement("a");
    a.href = URL.createObjectURL(blob);
    a.download = (path.split("/").pop() || "field").replace(/\.png$/i, "") + ".png";
    a.click();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
    say(`PNG of the view: ${a.download}`);
  }, "image/png");
}
