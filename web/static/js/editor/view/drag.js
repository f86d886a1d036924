/**
 * A drag of a handle (model/handles.js) with the server in the loop. Each pointer move writes the handle's
 * data from the mechanism as it stood when the drag began, and the drawing is redrawn at the next frame from
 * that dragged geometry (the joint at the pointer, the rest where the last table put it). The changed
 * mechanism's table is asked for at once, one question in flight: while it is out, newer moves only replace
 * the question to ask next (the newest wins, none is starved by the next move). An answer that assembles at
 * the shown input position is drawn whole (and the fields show the new lengths); one that does not (the
 * group cannot close there, or never) stops the drag: the drawing stays at the last assembling geometry,
 * marked, until the pointer comes back to where it assembles. On release the last assembling mechanism is
 * kept with its table, the answer to it (the exact one: the rest of the page's answers follow; one undo step);
 * Escape or a cancelled touch puts back the mechanism as it was.
 * Performance marks: "editor-drag-preview-drawn" (a frame drawn from the dragged geometry) and
 * "editor-drag-answer-drawn" (an answer drawn), for bench/editor_redraw.py.
 */
import { assemblesAt, moveHandle } from "../model/handles.js";

const ANGLE_SNAP = Math.PI / 36;          // rad: a guide's angle on 5° steps while snapping is on

export class DirectEdit {
  /**
   * page: {read() → {linkage, table, k, s, shown}: the mechanism, its table, the row shown, the state there and
   * the input's value there (φ, rad, or s, m); ask(linkage, onAnswer): the table's question (answers {ok, data}
   * or {ok: false, error}); show(linkage, table, preview, answered): draw this (preview: {joints: {name: [x, y]}}
   * or {stop: {at, pointer}}, or null; answered: the fields are to show it); commit(linkage, table): the drag is
   * over with this mechanism (table: its exact table, the answer to it, or null: to be asked); snapping(): whether
   * the grid snaps}.
   */
  constructor(page) {
    this.page = page;
    this.session = null;
  }

  /** Begin dragging `handle` (true: the drag has begun). */
  start(handle) {
    const { linkage, table, k, s, shown } = this.page.read();
    const json = JSON.stringify(linkage);
    const assembled = Boolean(table) && assemblesAt(table, k);
    this.session = { handle, json, table, k, s, shown, good: assembled ? { linkage, table } : null,
      latest: null, inFlight: null, stopped: false, frame: 0, ending: false };
    return true;
  }

  /** The pointer is at p (m): the handle's data written from there, drawn at the next frame and asked. */
  move(p) {
    const session = this.session;
    if (!session) return;
    const linkage = JSON.parse(session.json);
    const at = moveHandle(linkage, session.handle, p, session.s, session.shown, this.page.snapping() ? ANGLE_SNAP : 0);
    session.latest = { linkage, at, p };
    session.frame ||= requestAnimationFrame(() => this.#preview());
    if (!session.inFlight) this.#ask();
  }

  /** The drag is over: the last assembling mechanism kept, once the answer on its way has come. */
  end() {
    const session = this.session;
    if (!session) return;
    session.ending = true;
    if (!session.inFlight) this.#finish();
  }

  /**
   * A step from the keyboard: the handle moved from where it is (or where the last step left it, while that
   * step's answer is on its way) to step(at), as a drag there and a release.
   */
  nudge(handle, step) {
    if (this.session?.handle.id !== handle.id) this.start(handle);
    const session = this.session;
    session.target = step(session.target ?? handle.at);
    session.ending = false;
    this.move(session.target);
    this.end();
  }

  /** Put the mechanism back as it was before the drag. */
  cancel() {
    const session = this.session;
    if (!session) return;
    this.session = null;
    cancelAnimationFrame(session.frame);
    this.page.commit(JSON.parse(session.json), null);
  }

  #preview() {
    const session = this.session;
    if (!session) return;
    session.frame = 0;
    if (session.stopped || !session.latest) return;
    const start = performance.now();
    const { linkage, at } = session.latest;
    const table = session.good?.table ?? session.table;
    this.page.show(linkage, table, at ? { joints: { [session.handle.name]: at } } : null, false);
    performance.measure("editor-drag-preview-drawn", { start, end: performance.now() });
  }

  #ask() {
    const session = this.session;
    const question = session.latest;
    session.inFlight = question;
    this.page.ask(question.linkage, (answer) => {
      if (this.session !== session) return;
      session.inFlight = null;
      this.#answered(question, answer);
      if (session.latest !== question) this.#ask();
      else if (session.ending) this.#finish();
    });
  }

  #answered(question, answer) {
    const session = this.session;
    const start = performance.now();
    if (answer.ok && assemblesAt(answer.data, session.k)) {
      session.good = { linkage: question.linkage, table: answer.data };
      session.stopped = false;
      const { linkage, at } = session.latest;        // the pointer may have moved on: drawn there on this table
      this.page.show(linkage, answer.data, at && linkage !== question.linkage ? { joints: { [session.handle.name]: at } }
        : null, true);
    } else if (session.good) {
      session.stopped = true;
      const { linkage, table } = session.good;
      const at = table.outputs.joints[session.handle.name]?.[session.k] ?? session.handle.at;
      this.page.show(linkage, table, { stop: { at, pointer: session.latest.p } }, true);
    } else {                                       // nothing assembled when the drag began: no stop, it follows
      this.page.show(question.linkage, answer.ok ? answer.data : session.table,
        question.at ? { joints: { [session.handle.name]: question.at } } : null, true);
    }
    performance.measure("editor-drag-answer-drawn", { start, end: performance.now() });
  }

  #finish() {
    const session = this.session;
    this.session = null;
    cancelAnimationFrame(session.frame);
    const kept = session.good?.linkage ?? session.latest?.linkage ?? JSON.parse(session.json);
    this.page.commit(kept, session.good?.table ?? null);
  }
}
