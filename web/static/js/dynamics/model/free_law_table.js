/**
 * A free law M_P(φ₁) of the driving moment as a table of points (Chaika–Vasylenko §3.4, step 9), by the
 * server's own rules (MotorInput in server/api/schemas_dynamics.py): the angles φ_j in rad, increasing within one
 * turn [0, 2π), at least TABLE_GAP apart; the moments M_j in N·m within ±TABLE_MOMENT, one per angle; from
 * TABLE_POINTS[0] to TABLE_POINTS[1] points. A table the page takes from its address must be one the server
 * accepts. No DOM.
 */
export const TABLE_POINTS = [2, 361];     // at least 2 points, at most one a degree
const TURN = 2 * Math.PI;
const TABLE_GAP = 1e-6;                   // rad
const TABLE_MOMENT = 1e7;                 // N·m

const numbers = (list) => Array.isArray(list) && list.every(Number.isFinite);

/** Whether phi (rad) and moment (N·m) are a free law's table the server accepts. */
export function isFreeLaw(phi, moment) {
  return numbers(phi) && numbers(moment) && phi.length === moment.length
    && phi.length >= TABLE_POINTS[0] && phi.length <= TABLE_POINTS[1]
    && phi.every((angle, j) => angle >= 0 && angle < TURN && (j === 0 || angle - phi[j - 1] >= TABLE_GAP))
    && moment.every((value) => Math.abs(value) <= TABLE_MOMENT);
}
