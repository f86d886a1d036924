/**
 * The drawing's view controls: zoom in and out about the drawing's centre, the grid and its snapping switched
 * on and off, and the readout of the pointer's coordinates in metres (the point a click there places: on the
 * grid while snapping is on, written to the grid's step; else to the millimetre).
 */
import { formatNumber } from "../../common/view/notation.js";

const ZOOM = 1.5;

/** Wire the controls (ids editor-zoom-in, editor-zoom-out, editor-grid, editor-snap, editor-pointer). */
export function viewControls(drawing, { t, lang, onView }) {
  const $ = (id) => document.getElementById(id);
  const zoom = (factor) => {
    drawing.zoom(factor);
    onView();
  };
  $("editor-zoom-in").addEventListener("click", () => zoom(ZOOM));
  $("editor-zoom-out").addEventListener("click", () => zoom(1 / ZOOM));
  const grid = $("editor-grid");
  const snap = $("editor-snap");
  drawing.grid = grid.checked;
  drawing.snap = snap.checked;
  grid.addEventListener("change", () => {
    drawing.grid = grid.checked;
    onView();
  });
  snap.addEventListener("change", () => {
    drawing.snap = snap.checked;
  });
  const readout = $("editor-pointer");
  return {
    /** Show the pointer's world point p (m). */
    pointer(p) {
      const decimals = drawing.snap ? Math.max(0, Math.ceil(-Math.log10(drawing.step) - 1e-9)) : 3;
      const write = (value) => formatNumber(value, lang, decimals);
      readout.textContent = `x = ${write(p[0])} ${t.units_m}; y = ${write(p[1])} ${t.units_m}`;
      readout.dataset.x = String(p[0]);
      readout.dataset.y = String(p[1]);
    },
  };
}
