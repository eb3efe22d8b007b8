// Edits, one after the other, each a solve; undo and redo through whole states; the balancing move.
import { proposeBalance, showBalance } from "./balance.js";
import { draw, drawMarkers, drawPins } from "./scene.js";
import { show } from "./solve.js";
import { restore, snapshot, state } from "./state.js";

export const undoStack = [], redoStack = [];

// edits run one after the other, each on the state the previous one left
export let queue = Promise.resolve();
export function edit(change) {
  queue = queue.then(async () => {
    const before = snapshot();
    if (change() === false) return;
    if (await show()) {
      undoStack.push(before);
      redoStack.length = 0;
    } else {
      restore(before); // refused by the server: the reason stays shown
      showBalance();
      drawMarkers();
      drawPins();
      draw();
    }
  });
  return queue;
}

export function travel(from, to) {
  queue = queue.then(async () => {
    if (!from.length) return;
    to.push(snapshot());
    restore(from.pop());
    await show();
  });
}

// the balancing move: one edit that adds what proposeBalance() proposes
export function balancingMove() {
  return edit(() => {
    const more = proposeBalance();
    if (!more) return false;
    for (const [v, k] of more) state.singularities.set(v, k);
  });
}
