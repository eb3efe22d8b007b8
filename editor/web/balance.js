// The balance of the singularities per component (Poincaré–Hopf) and what the balancing move would add.
import { V, adjacency, angleDefect, header } from "./mesh.js";
import { add, fraction, indexText } from "./protocol.js";
import { state } from "./state.js";
import { $ } from "./status.js";

// the singularities the balancing move would add ([[vertex, [p, q]]], drawn pale; null: none to offer)
export let proposal = null;

// per component: the sum of the indices against its Euler characteristic (closed components must balance), and
// the difference in units of 1/n (units: [p, q], whole when q = 1)
export function balance() {
  const sums = header.chi.map(() => [0, 1]);
  for (const [v, k] of state.singularities) {
    const c = window.__editor.component[v];
    if (c >= 0) sums[c] = add(sums[c], k);
  }
  return header.chi.map((chi, c) => {
    const excess = add(sums[c], [-chi, 1]);
    return { component: c, sum: sums[c], chi, closed: header.closed[c], units: fraction(excess[0] * state.n, excess[1]),
             balanced: !header.closed[c] || excess[0] === 0 };
  });
}

// the balance of every component: a line (.unbalanced, with data-component, data-units, data-n) for each closed one
// that is off and by how much, then the others (each, or counted when there are many); the balancing move's button
// names what it would add, and those vertices get pale markers
export function showBalance() {
  const rows = balance(), off = rows.filter(b => !b.balanced), box = $("balance");
  box.replaceChildren();
  for (const b of off) {
    const line = document.createElement("div"), [p, q] = b.units;
    line.className = "unbalanced";
    Object.assign(line.dataset, { component: b.component, units: indexText(b.units), n: state.n });
    line.textContent = `component ${b.component} is unbalanced by ${p > 0 ? "+" : "−"}` +
      (q === 1 ? `${Math.abs(p)} × 1/${state.n}`
               : `${indexText([Math.abs(p), q])} × 1/${state.n} (not a whole number)`) +
      `: its indices sum to ${minus(indexText(b.sum))}, its Euler characteristic χ is ${minus(String(b.chi))}`;
    box.append(line);
  }
  const others = rows.filter(b => b.balanced);
  const text = others.length <= 6
    ? others.map(b => `component ${b.component}: ${minus(indexText(b.sum))}` +
                      (b.closed ? ` of χ = ${minus(String(b.chi))}` : " (bordered)"))
    : [`${others.filter(b => b.closed).length} closed components balanced, ${others.filter(b => !b.closed).length} ` +
       "bordered (no sum required)"];
  if (text.length) {
    const rest = document.createElement("div");
    rest.textContent = text.join("\n");
    box.append(rest);
  }
  proposal = off.length ? proposeBalance() : null;
  const button = $("balance-move");
  button.hidden = !proposal;
  if (proposal)
    button.textContent = "balance: add " + (proposal.length <= 2
      ? proposal.map(([v, k]) => `${signed(k)} at vertex ${v}`).join(" and ")
      : `${proposal.length} singularities of ±1/${state.n} (the pale markers)`);
}
const signed = k => (k[0] > 0 ? "+" : "−") + indexText([Math.abs(k[0]), k[1]]);
const minus = text => text.replace("-", "−");

// what completes every unbalanced closed component: singularities of +-1/n ([[vertex, [p, q]]]) at its vertices
// whose angle defect is most like them (largest K_v for positive ones, most negative for negative ones: where the
// Levi-Civita holonomy already turns the most that way), two rings from each other and, where the component has
// room, from its singularities; null when an excess is not a whole number of 1/n (no such completion)
export function proposeBalance() {
  const neighbours = adjacency(), added = [];
  const near = (blocked, v) => { // v's two rings into `blocked`
    for (const u of neighbours[v]) { blocked.add(u); for (const w of neighbours[u]) blocked.add(w); }
  };
  for (const b of balance()) {
    if (b.balanced) continue;
    const [p, q] = b.units;
    if (q !== 1) return null;
    const sign = -Math.sign(p), count = Math.abs(p);
    const candidates = [];
    for (let v = 0; v < V.length / 3; ++v)
      if (window.__editor.component[v] === b.component && !state.singularities.has(v)) candidates.push(v);
    candidates.sort((u, w) => sign * (angleDefect[w] - angleDefect[u]) || u - w);
    const apart = new Set(), taken = new Set();
    for (const v of state.singularities.keys()) if (window.__editor.component[v] === b.component) near(apart, v);
    // two rings from the singularities and from each other; then from each other only; then anywhere
    for (const rule of [v => !apart.has(v), () => true]) {
      const blocked = new Set();
      for (const v of taken) near(blocked, v);
      for (const v of candidates) {
        if (taken.size === count) break;
        if (taken.has(v) || blocked.has(v) || !rule(v)) continue;
        taken.add(v);
        near(blocked, v);
      }
    }
    for (const v of candidates) { // a small component: the rest anywhere
      if (taken.size === count) break;
      taken.add(v);
    }
    for (const v of taken) added.push([v, [sign, state.n]]);
  }
  return added.length ? added : null;
}
