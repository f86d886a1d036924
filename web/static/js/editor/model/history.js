/**
 * Undo and redo over the mechanism's JSON (the address's document). Every edit is one step: an element added
 * or removed, a value typed, a whole drag (of a joint, or of a length's slider) however many frames it took.
 * The caller records the mechanism as it was before the step (`record(before)`); undo hands back that JSON and
 * keeps the one shown for redo; a new step after an undo forgets what could be redone.
 */
const DEPTH = 100;               // steps kept

export class EditHistory {
  #done = [];                   // the mechanism before each step, oldest first, JSON
  #undone = [];                 // the mechanism after each undone step, latest undone last, JSON

  /** A step begins from the mechanism `before` (JSON); what was undone can no longer be redone. */
  record(before) {
    this.#done.push(before);
    if (this.#done.length > DEPTH) this.#done.shift();
    this.#undone = [];
  }

  get canUndo() {
    return this.#done.length > 0;
  }

  get canRedo() {
    return this.#undone.length > 0;
  }

  /** The mechanism before the last step (JSON), or null; `shown` (JSON, the mechanism now) kept for redo. */
  undo(shown) {
    const before = this.#done.pop();
    if (before === undefined) return null;
    this.#undone.push(shown);
    return before;
  }

  /** The mechanism after the last undone step (JSON), or null; `shown` kept for undo. */
  redo(shown) {
    const after = this.#undone.pop();
    if (after === undefined) return null;
    this.#done.push(shown);
    return after;
  }
}
