// What the page and the server (editor/serve.py) exchange: binary frames, and singularity indices as exact
// fractions p/q.

// ---- the server's binary frames (editor_server/wire.py: frame()) -------------------------------------------------
const TYPES = { "<f4": Float32Array, "<u4": Uint32Array, "<i4": Int32Array };

export function parseFrame(buffer) {
  const bytes = new Uint8Array(buffer);
  if (String.fromCharCode(...bytes.subarray(0, 4)) !== "TCB1") throw new Error("not a TCB1 frame");
  const length = new DataView(buffer).getUint32(4, true);
  const header = JSON.parse(new TextDecoder().decode(bytes.subarray(8, 8 + length)));
  const start = 8 + length;
  const arrays = {};
  for (const a of header.arrays) {
    const Type = TYPES[a.dtype];
    const count = a.shape.reduce((p, q) => p * q, 1);
    arrays[a.name] = new Type(buffer, start + a.offset, count);
  }
  return { header, arrays };
}

// POSTs a JSON body; the frame of the answer, or an Error with the server's one-line reason (for the console: the
// page words it itself), the HTTP status (error.status: e.g. 409 when a save would replace an existing file) and,
// for the library's refusals (422 "code: message"), the code (error.code: e.g. "poincare_hopf_violated"); no
// status when the server does not answer
export async function post(path, body) {
  const response = await fetch(path, { method: "POST", body: JSON.stringify(body) });
  if (!response.ok) {
    const error = new Error((await response.text()).trim() || `${path}: HTTP ${response.status}`);
    error.status = response.status;
    const code = /^([a-z]+(?:_[a-z]+)*): /.exec(error.message);
    if (response.status === 422 && code) error.code = code[1];
    throw error;
  }
  return parseFrame(await response.arrayBuffer());
}

// ---- indices as exact fractions [p, q], q > 0 -----------------------------------------------------------------
function gcd(a, b) { return b === 0 ? Math.abs(a) : gcd(b, a % b); }
export function fraction(p, q) { const g = gcd(p, q) || 1; return [p / g * Math.sign(q), Math.abs(q) / g]; }
export function parseIndex(s) { const [p, q] = String(s).split("/").map(Number); return fraction(p, q || 1); }
export function indexText([p, q]) { return q === 1 ? String(p) : `${p}/${q}`; }
export function add([a, b], [c, d]) { return fraction(a * d + c * b, b * d); }
