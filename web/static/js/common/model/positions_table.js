/**
 * Reading a kinematics table between its grid points. The table is one API answer: phi runs evenly from
 * 0 to cycle (rad), every output holds one value per angle (null where undefined), joints hold [x, y]
 * in metres. Animation frames interpolate here instead of asking the server again.
 */

/** Position of phi (rad, taken modulo the cycle) in the grid: left index and fraction towards the next. */
function gridPosition(table, phi) {
  const last = table.phi.length - 1;
  const turn = ((phi % table.cycle) + table.cycle) % table.cycle;
  const x = turn / table.cycle * last;
  const i = Math.min(Math.floor(x), last - 1);
  return { i, f: x - i };
}

function mix(a, b, f) {
  if (a === null) return b;
  if (b === null) return a;
  return a + (b - a) * f;
}

/** Joint coordinates {name: [x, y]} at crank angle phi. */
export function jointsAt(table, phi) {
  const { i, f } = gridPosition(table, phi);
  const joints = {};
  for (const [name, path] of Object.entries(table.outputs.joints)) {
    const [a, b] = [path[i], path[i + 1]];
    joints[name] = [mix(a[0], b[0], f), mix(a[1], b[1], f)];
  }
  return joints;
}

/** Value of an output array at crank angle phi, or null where the table leaves it undefined. */
export function valueAt(table, values, phi) {
  const { i, f } = gridPosition(table, phi);
  if (values[i] === null || values[i + 1] === null) return null;
  return mix(values[i], values[i + 1], f);
}

/** Special positions that are crank angles (the offset crank-slider's stroke ratio is a number, not a place). */
export function specialPositions(table) {
  return (table.outputs.special ?? []).filter((sp) => sp.kind !== "stroke_ratio");
}
