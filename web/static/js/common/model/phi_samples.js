/**
 * Reading a dynamics answer's arrays between their grid points. phis is the answer's crank angle φ (rad,
 * increasing over one cycle, evenly or not: the angular-acceleration scene's φ(t) under an uneven crank law
 * is not); values hold one entry per angle: a number, a point or vector [x, y], or null where the answer
 * has none (self-locking, P at infinity). Animation frames interpolate here instead of asking the server again.
 */

/** Left index i of phi (rad, wrapped into the grid's cycle) in the grid, and its fraction f towards i + 1. */
export function gridPosition(phis, phi) {
  const last = phis.length - 1;
  const cycle = phis[last] - phis[0];
  const turn = phis[0] + ((((phi - phis[0]) % cycle) + cycle) % cycle);
  let [low, high] = [0, last];
  while (high - low > 1) {
    const middle = (low + high) >> 1;
    if (phis[middle] <= turn) low = middle;
    else high = middle;
  }
  const span = phis[high] - phis[low];
  return { i: low, f: span > 0 ? (turn - phis[low]) / span : 0 };
}

const missing = (value) => value === null || value === undefined
  || (Array.isArray(value) && value.some((v) => v === null));

/** The value at phi, linearly interpolated; null where either neighbouring grid value is null. */
export function sampleAt(phis, values, phi) {
  const { i, f } = gridPosition(phis, phi);
  const [a, b] = [values[i], values[i + 1]];
  if (missing(a) || missing(b)) return null;
  if (Array.isArray(a)) return a.map((v, k) => v + (b[k] - v) * f);
  return a + (b - a) * f;
}
