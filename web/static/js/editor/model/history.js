/**
 * Undo over the mechanism's JSON (the address's document): each change keeps the mechanism shown before it;
 * edits closer together than DRAG_MS (a slider drag) are one step, an added or removed element always one.
 */
const UNDO_DEPTH = 100;
const DRAG_MS = 800;

export class UndoHistory {
  #steps = [];
  #shown = null;          // the mechanism as last shown, JSON
  #at = -Infinity;        // when it last changed, ms

  /** The mechanism is now `json` (at time `now`, ms); `structural`: an element was added or removed. */
  remember(json, structural, now) {
    if (this.#shown !== null && this.#shown !== json && (structural || now - this.#at > DRAG_MS)) {
      this.#steps.push(this.#shown);
      if (this.#steps.length > UNDO_DEPTH) this.#steps.shift();
    }
    if (this.#shown !== json) this.#at = now;
    this.#shown = json;
  }

  get empty() {
    return this.#steps.length === 0;
  }

  /** The mechanism before the last step (JSON), or null; it becomes the one shown. */
  undo() {
    const before = this.#steps.pop();
    if (before === undefined) return null;
    this.#shown = before;
    this.#at = -Infinity;
    return before;
  }
}
