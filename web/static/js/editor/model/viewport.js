/**
 * The editor's view of the plane: which metres are shown where on the drawing. A view {x0, y0, k} maps a point
 * (x, y) in metres (y up) to drawing units (X, Y) (Y down) by X = (x − x₀)k, Y = (y₀ − y)k: (x₀, y₀) is the
 * world point at the drawing's top left corner and k the drawing units per metre. Zooming keeps the world point
 * under the pointer (or between two fingers) where it is on the screen; panning moves the world with the
 * pointer. The grid's step is a round length (1, 2 or 5 ·10ⁿ m) at least a given number of drawing units apart
 * (the drawing asks for 10 CSS pixels' worth), and a snapped point is the nearest grid node. No DOM.
 */
export const WIDTH = 800;                // drawing units: the SVG's viewBox
export const HEIGHT = 600;
export const DEFAULT_VIEW = Object.freeze({ x0: -0.5, y0: 0.5, k: 600 });     // 1.33 m × 1 m round the origin
export const K_RANGE = [20, 200000];     // drawing units per metre: 40 m … 4 mm across the drawing
const MANTISSAS = [1, 2, 5];

/** The drawing point [X, Y] of the world point [x, y] (m). */
export function toScreen({ x0, y0, k }, [x, y]) {
  return [(x - x0) * k, (y0 - y) * k];
}

/** The world point [x, y] (m) at the drawing point [X, Y]. */
export function toWorld({ x0, y0, k }, [X, Y]) {
  return [x0 + X / k, y0 - Y / k];
}

const clampK = (k) => Math.min(K_RANGE[1], Math.max(K_RANGE[0], k));

/** The view scaled by `factor` about the drawing point `at`: the world point there stays there. */
export function zoomAbout(view, at, factor) {
  const [x, y] = toWorld(view, at);
  const k = clampK(view.k * factor);
  return { x0: x - at[0] / k, y0: y + at[1] / k, k };
}

/** The view moved with the pointer by [dX, dY] drawing units: the world point under it follows it. */
export function panBy(view, [dX, dY]) {
  return { x0: view.x0 - dX / view.k, y0: view.y0 + dY / view.k, k: view.k };
}

/**
 * Two fingers moved from [a, b] to [c, d] (drawing points): the view zoomed by |c − d| / |a − b| and moved so
 * that the world point that was midway between a and b is midway between c and d.
 */
export function pinch(view, [a, b], [c, d]) {
  const before = Math.hypot(b[0] - a[0], b[1] - a[1]);
  const after = Math.hypot(d[0] - c[0], d[1] - c[1]);
  const mid = (p, q) => [(p[0] + q[0]) / 2, (p[1] + q[1]) / 2];
  const [m, n] = [mid(a, b), mid(c, d)];
  const zoomed = zoomAbout(view, m, before > 0 ? after / before : 1);
  return panBy(zoomed, [n[0] - m[0], n[1] - m[1]]);
}

/** The view that shows the points [x, y] (m) centred, filling `fill` of the drawing (or the view as it was). */
export function fitView(points, view, fill = 0.8) {
  const finite = points.filter((p) => p && Number.isFinite(p[0]) && Number.isFinite(p[1]));
  if (finite.length < 2) return view;
  const xs = finite.map((p) => p[0]);
  const ys = finite.map((p) => p[1]);
  const [xa, xb, ya, yb] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
  const k = clampK(fill * Math.min(WIDTH / Math.max(xb - xa, 0.05), HEIGHT / Math.max(yb - ya, 0.05)));
  return { x0: (xa + xb) / 2 - WIDTH / 2 / k, y0: (ya + yb) / 2 + HEIGHT / 2 / k, k };
}

/** The grid's step (m): the smallest of 1, 2, 5 ·10ⁿ that is at least `units` drawing units long. */
export function gridStep({ k }, units) {
  const least = units / k;
  const power = 10 ** Math.floor(Math.log10(least));
  const mantissa = MANTISSAS.find((m) => m * power >= least * (1 - 1e-12)) ?? 10;
  return Number((mantissa * power).toPrecision(12));
}

/** The grid's major step (m): the next power of ten above the step (0.01, 0.02 and 0.05 m → 0.1 m). */
export function majorStep(step) {
  return Number((10 ** (Math.floor(Math.log10(step) + 1e-9) + 1)).toPrecision(12));
}

/** value (m) at the nearest multiple of step, written without binary noise (0.1 + 0.2 → 0.3). */
export function snapValue(value, step) {
  const decimals = Math.max(0, -Math.floor(Math.log10(step)) + 1);
  return Number((Math.round(value / step) * step).toFixed(decimals)) || 0;      // (no −0)
}

/** The nearest grid node to [x, y] (m). */
export function snapPoint([x, y], step) {
  return [snapValue(x, step), snapValue(y, step)];
}
