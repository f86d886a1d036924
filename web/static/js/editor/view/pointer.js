/**
 * The drawing's pointer gestures, one code path for mouse, pen and touch (Pointer Events):
 * - pressed and let go without moving (within SLOP pixels): a click on a joint, a guide or the plane, at the
 *   pointer's world point (on the grid when snapping is on);
 * - pressed on a draggable handle (data-drag) and moved: the handle dragged, while dragging is allowed;
 * - pressed anywhere else and moved: the view panned, the plane following the pointer;
 * - two fingers: pinched (zoom by their distance, pan by their midpoint), a drag in progress ended first;
 * - the wheel: zoom about the pointer;
 * - every move over the drawing: its world point reported (the coordinates readout).
 */
import { panBy, pinch, zoomAbout } from "../model/viewport.js";

const SLOP = { mouse: 4, pen: 6, touch: 10 };          // CSS px a press may wander and still be a click
const WHEEL = { pixel: 0.0015, line: 0.05, page: 1 };    // zoom = e^(−Δ·this) per wheel delta unit

export class PointerGestures {
  /**
   * drawing: the Drawing; on: {canDrag(), dragStart(id) → whether it started, drag(at), dragEnd(), dragCancel(),
   * joint(name, at), guide(name, at), place(at), hover(at), view()}; `at` in metres.
   */
  constructor(drawing, on) {
    this.drawing = drawing;
    this.on = on;
    this.pointers = new Map();       // pointerId → the drawing point [X, Y] where it is
    this.gesture = null;
    const svg = drawing.svg;
    svg.addEventListener("pointerdown", (event) => this.#down(event));
    svg.addEventListener("pointermove", (event) => this.#move(event));
    svg.addEventListener("pointerup", (event) => this.#up(event, false));
    svg.addEventListener("pointercancel", (event) => this.#up(event, true));
    svg.addEventListener("wheel", (event) => this.#wheel(event), { passive: false });
  }

  #point(event) {
    return this.drawing.toDrawing(event.clientX, event.clientY);
  }

  #world(event) {
    return this.drawing.toWorld(event.clientX, event.clientY);
  }

  #down(event) {
    if (event.pointerType === "mouse" && event.button !== 0) return;
    // no focus moved by a press (a focused joint redrawn every frame costs a layout of the page): the keyboard's
    // focus is the keyboard's
    event.preventDefault();
    this.drawing.svg.setPointerCapture?.(event.pointerId);
    this.pointers.set(event.pointerId, this.#point(event));
    if (this.pointers.size === 1) {
      const target = event.target.closest?.("[data-joint], [data-guide], [data-drag]") ?? null;
      this.gesture = { kind: "press", client: [event.clientX, event.clientY], target, slop: SLOP[event.pointerType] ?? 4,
        last: this.#point(event) };
      return;
    }
    if (this.gesture?.kind === "drag") this.on.dragEnd();
    this.gesture = { kind: "pinch", last: [...this.pointers.values()].slice(0, 2) };
  }

  #move(event) {
    this.on.hover(this.drawing.snapped(this.#world(event)));
    if (!this.pointers.has(event.pointerId)) return;
    const point = this.#point(event);
    this.pointers.set(event.pointerId, point);
    const gesture = this.gesture;
    if (gesture?.kind === "press") {
      const moved = Math.hypot(event.clientX - gesture.client[0], event.clientY - gesture.client[1]);
      if (moved <= gesture.slop) return;
      const id = gesture.target?.dataset.drag;
      if (id && this.on.canDrag() && this.on.dragStart(id)) this.gesture = { kind: "drag" };
      else this.gesture = { kind: "pan", last: gesture.last };
      this.drawing.svg.classList.add(this.gesture.kind === "drag" ? "dragging" : "panning");
    }
    if (this.gesture.kind === "drag") this.on.drag(this.drawing.snapped(this.#world(event)));
    else if (this.gesture.kind === "pan") {
      const { last } = this.gesture;
      this.gesture.last = point;
      this.#show(panBy(this.drawing.view, [point[0] - last[0], point[1] - last[1]]));
    } else if (this.gesture.kind === "pinch" && this.pointers.size >= 2) {
      const now = [...this.pointers.values()].slice(0, 2);
      const { last } = this.gesture;
      this.gesture.last = now;
      this.#show(pinch(this.drawing.view, last, now));
    }
  }

  #up(event, cancelled) {
    if (!this.pointers.delete(event.pointerId)) return;
    const gesture = this.gesture;
    if (gesture?.kind === "pinch") {
      this.gesture = this.pointers.size ? { kind: "pinch-ending" } : null;      // the last finger up clicks nothing
      return;
    }
    if (this.pointers.size) return;
    this.gesture = null;
    this.drawing.svg.classList.remove("dragging", "panning");
    if (gesture?.kind === "drag") {
      if (cancelled) this.on.dragCancel();
      else this.on.dragEnd();
    } else if (gesture?.kind === "press" && !cancelled) {
      const at = this.drawing.snapped(this.#world(event));
      const { target } = gesture;
      if (target?.dataset.joint) this.on.joint(target.dataset.joint, at);
      else if (target?.dataset.guide) this.on.guide(target.dataset.guide, at);
      else this.on.place(at);
    }
  }

  #wheel(event) {
    event.preventDefault();
    const factor = Math.exp(-event.deltaY * WHEEL[["pixel", "line", "page"][event.deltaMode] ?? "pixel"]);
    this.#show(zoomAbout(this.drawing.view, this.#point(event), factor));
  }

  #show(view) {
    this.drawing.setView(view);
    this.on.view();
  }
}
