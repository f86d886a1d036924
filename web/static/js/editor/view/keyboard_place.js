/**
 * The editor without a mouse. The form "place at x, y" (metres; the page's decimal comma in ru and uk) does
 * what a click at that point does: on a joint (or a guide) within half a millimetre it picks that one, else it
 * places there (a frame joint, a guide, a crank's pin, a group's inner joint, a point, as the tool wants). In
 * the drawing, Tab goes from joint to guide to angle handle; Enter or Space picks the focused joint or guide as
 * a click would; the arrow keys move the focused handle by the grid's step (a guide's angle handle turns by
 * 5°, 1° without snapping).
 */
import { decimalMessage, parseDecimal } from "../../common/model/decimal_input.js";

const NEAR = 5e-4;                       // m: a typed point this close to a joint or guide is on it
const ARROWS = { ArrowRight: [1, 0], ArrowLeft: [-1, 0], ArrowUp: [0, 1], ArrowDown: [0, -1] };
const TURN = { snapped: Math.PI / 36, free: Math.PI / 180 };

/** The joint or guide of the drawn scene at p (within NEAR), as {joint} or {guide}, else null. */
function hitAt(scene, p) {
  for (const [name, q] of Object.entries(scene.joints)) {
    if (q && Math.hypot(q[0] - p[0], q[1] - p[1]) <= NEAR) return { joint: name };
  }
  for (const g of scene.guides) {
    const off = (p[0] - g.point[0]) * Math.sin(g.angle) - (p[1] - g.point[1]) * Math.cos(g.angle);
    if (Math.abs(off) <= NEAR) return { guide: g.name };
  }
  return null;
}

/** Where a focused joint or guide is (m), from the drawn scene. */
function placeOf(scene, target) {
  if (target.dataset.joint) return scene.joints[target.dataset.joint];
  return scene.guides.find((g) => g.name === target.dataset.guide)?.point;
}

/**
 * Wire the form (ids: editor-place-form, editor-place-x, editor-place-y, editor-place-error) and the drawing's
 * keys. on: {joint(name, at), guide(name, at), place(at), handle(id) → the handle (model/handles.js) or
 * undefined, nudge(handle, step)}.
 */
export function keyboardEditing(drawing, { t, lang, on }) {
  const $ = (id) => document.getElementById(id);
  const form = $("editor-place-form");
  form.addEventListener("submit", (event) => {
    event.preventDefault();
    const read = ["editor-place-x", "editor-place-y"].map((id) => [id, parseDecimal($(id).value, lang)]);
    const wrong = read.find(([, value]) => value.error);
    $("editor-place-error").textContent = wrong ? decimalMessage(wrong[1].error, $(wrong[0]).value, t) : "";
    if (wrong) return;
    const p = read.map(([, value]) => value.value);
    const hit = drawing.scene ? hitAt(drawing.scene, p) : null;
    if (hit?.joint) on.joint(hit.joint, p);
    else if (hit?.guide) on.guide(hit.guide, p);
    else on.place(p);
  });
  drawing.svg.addEventListener("keydown", (event) => {
    const target = event.target;
    if ((event.key === "Enter" || event.key === " ") && (target.dataset.joint || target.dataset.guide)) {
      event.preventDefault();
      const at = placeOf(drawing.scene, target);
      if (target.dataset.joint) on.joint(target.dataset.joint, at);
      else on.guide(target.dataset.guide, at);
      return;
    }
    const arrow = ARROWS[event.key];
    const handle = arrow && target.dataset.drag ? on.handle(target.dataset.drag) : undefined;
    if (!handle || event.ctrlKey || event.metaKey || event.altKey) return;
    event.preventDefault();
    if (handle.kind === "guide_angle") {
      const turn = (arrow[0] + arrow[1]) * (drawing.snap ? TURN.snapped : TURN.free);
      const [c, s] = [Math.cos(turn), Math.sin(turn)];
      const o = handle.from;
      on.nudge(handle, ([x, y]) => [o[0] + (x - o[0]) * c - (y - o[1]) * s, o[1] + (x - o[0]) * s + (y - o[1]) * c]);
    } else {
      const step = drawing.step;
      on.nudge(handle, ([x, y]) => drawing.snapped([x + arrow[0] * step, y + arrow[1] * step]));
    }
  });
}
