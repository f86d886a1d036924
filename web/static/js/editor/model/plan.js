/**
 * The velocity and acceleration plans (планы скоростей и ускорений) as drawn: every vector of the API's plan
 * (server/core/structure/plans.py) placed head to tail from the pole p (π), in millimetres of the drawing at
 * the scale μ (m/s per mm, m/s² per mm). The first vector of an equation starts at the pole; each next one
 * starts where the previous ended, so that both equations of a target end at its plan point (b, c, …).
 */
const NICE = [1, 2, 2.5, 5, 10];

/** The smallest "nice" scale (1, 2, 2.5, 5 ·10ᵏ per mm) at which `size` fits into `millimetres`. */
export function niceScale(size, millimetres) {
  if (!(size > 0)) return 1;
  const raw = size / millimetres;
  const power = 10 ** Math.floor(Math.log10(raw));
  return NICE.find((m) => m * power >= raw * (1 - 1e-12)) * power;
}

/**
 * The drawn vectors of one plan (equations: plan.velocity or plan.acceleration): [{name, kind, start, end,
 * value, target}] with start and end in plan units (m/s or m/s², y up), each distinct vector once.
 */
export function planVectors(equations) {
  const out = [];
  const seen = new Set();
  for (const equation of equations) {
    let at = [0, 0];
    for (const v of equation.vectors) {
      const end = [at[0] + v.x, at[1] + v.y];
      const key = `${v.name}|${at.map((c) => c.toPrecision(9))}`;
      if (!seen.has(key) && v.value > 0) {
        seen.add(key);
        out.push({ name: v.name, kind: v.kind, start: at, end, value: v.value, target: equation.target });
      }
      at = end;
    }
  }
  return out;
}

/** The plan's own value of each target (the sum of its first equation's vectors) beside the analytic one. */
export function planTargets(equations) {
  const out = new Map();
  for (const equation of equations) {
    if (out.has(equation.target)) continue;
    const sum = equation.vectors.reduce((s, v) => [s[0] + v.x, s[1] + v.y], [0, 0]);
    out.set(equation.target, { target: equation.target, plan: Math.hypot(...sum), analytic: equation.analytic.value,
      residual: equation.residual });
  }
  return [...out.values()];
}
