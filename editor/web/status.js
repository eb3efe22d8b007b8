// What the page says: the status line, and the server's refusals put in words.

export const $ = id => document.getElementById(id);
const status = $("status");

export function say(text, error = false) {
  status.textContent = text;
  status.className = error ? "error" : "";
  if (error) window.__editor.lastError = text;
}

// ---- the server's refusals in words: its one-line reason ("code: message" for the library's) goes to the console,
// the page says in a sentence of its own what was not done and why --------------------------------------------------
const REASONS = {
  poincare_hopf_violated: "the singularities do not balance: on a closed surface their indices must add up to its " +
                          "Euler characteristic",
  index_not_multiple: "an index is not a multiple of 1/n for this n",
  invalid_index: "an index cannot be read (a zero denominator, or a number too large)",
  invalid_vertex: "a singularity is on a vertex this mesh does not have (or one of no face)",
  duplicate_singularity: "a vertex has two singularities",
  singularity_on_boundary: "a singularity is on the boundary, where the field can have none",
  invalid_constraint: "a pinned direction cannot be followed (zero, along its face's normal, on the boundary the " +
                      "field follows, or a face pinned twice)",
  invalid_symmetry_order: "n must be a whole number from 1 up",
  invalid_loop_periods: "the turns prescribed along the boundary do not fit the singularities",
  invalid_argument: "a setting is out of range",
  io_error: "the file could not be read or written (the folder's permissions, or the disk)",
  parse_error: "the file is not one of the package's files of that kind",
  solver_failure: "the solver failed on this mesh and these pins",
};
const NOT_DONE = { solve: "Not solved", place: "No automatic placement", features: "No sharp features",
                   streamlines: "No streamlines", save: "Not saved", load: "Not loaded", quads: "No quad mesh" };
export function explain(error, doing, path = "") {
  console.warn(`editor: ${doing}${path ? " " + path : ""}: ${error.status ? "HTTP " + error.status + ": " : ""}` +
               error.message);
  const file = `“${path}”`, raw = error.message, files = doing === "save" || doing === "load";
  let why;
  if (error.status === undefined) why = "the server does not answer (is it still running?)";
  else if (error.status === 422 && doing === "features" && error.code === "invalid_argument")
    why = "the angle of the sharp features must be from 0° to 180°";
  else if (error.status === 422 && doing === "quads" && /border/.test(raw))
    why = "on a mesh with boundary the field must follow it (check “align with the boundary”)";
  else if (error.status === 422 && doing === "quads" && /feature edge/.test(raw))
    why = "the field does not follow a sharp edge (a pin of yours across it?): the quads cannot follow it";
  else if (error.status === 422 && doing === "quads" && error.code === "invalid_argument")
    why = "the quad size must be a positive number, and not so small that the quads would be too many";
  else if (error.status === 422 && doing === "quads" && error.code === "invalid_symmetry_order")
    why = "a quad mesh needs a cross field (n = 4)";
  else if (error.status === 422) why = REASONS[error.code] ?? "the library refused it (the browser's console says why)";
  else if (error.status === 403 && files)
    why = /mesh being edited/.test(raw) ? `${file} is the mesh being edited, which the editor never replaces`
                                        : `${file} is outside the server's folder, the only one it reads and writes`;
  else if (error.status === 404 && files)
    why = doing === "load" ? `there is no file ${file} in the server's folder` : `the folder of ${file} does not exist`;
  else if (error.status === 413 && doing === "load") why = `${file} is too large to load`;
  else if (error.status === 400 && files) {
    const ending = /must end in (\.[a-z]+)/.exec(raw);
    why = ending ? `the name of such a file must end in ${ending[1]}`
          : /directory/.test(raw) ? `${file} is a folder`
          : `${file} is not the name of a file in the server's folder (a relative path to a regular file)`;
  } else if (error.status >= 500) why = "the server failed on it (its terminal says why)";
  else why = "the server could not take the request (the browser's console says why)";
  return `${NOT_DONE[doing] ?? "Not done"}: ${why}.`;
}
