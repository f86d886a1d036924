/**
 * One table per change of the mechanism: the kinematics answer over one turn of the crank (n angles), from
 * which the page animates, traces paths and plots without asking the server again. Positions in metres,
 * first analogs x′ = dx/dφ (velocity v = x′ω₁), second x″ (acceleration a = x″ω₁² + x′ε₁); link angles θ (rad)
 * with θ′, θ″; slides s along their guides with s′, s″ (Eremyants §2.1).
 */
export const TURN_POINTS = 361;                   // 1° steps, both ends of the turn included
export const TABLE_OUTPUTS = ["structure", "joints", "joints_d1", "joints_d2", "angles", "angles_d1", "angles_d2",
  "slides", "slides_d1", "slides_d2"];

/** The request of the table for a linkage. */
export function tableRequest(linkage) {
  return { mechanism: "general", linkage, n: TURN_POINTS, outputs: TABLE_OUTPUTS };
}

/**
 * The request of the special positions over the turn, asked apart from the table: the server finds them on
 * its own 0.5° grid and refines the reversals (25 times the table's work), so that a drag redraws from the
 * table alone and the list follows when it comes.
 */
export function specialRequest(linkage) {
  return { mechanism: "general", linkage, n: 2, outputs: ["special"] };
}

/** The request of the plans at crank angle phi (rad) with ω₁ (rad/s) and ε₁ (rad/s²). */
export function planRequest(linkage, phi, omega1, epsilon1) {
  return { mechanism: "general", linkage, n: 2, outputs: ["plan"], plan: { phi, omega1, epsilon1 } };
}

/** Position [x, y] of every joint at frame k (null where the group does not close). */
export function positionsAt(table, k) {
  const out = {};
  for (const [name, rows] of Object.entries(table.outputs.joints)) {
    const [x, y] = rows[k];
    out[name] = x === null || y === null ? null : [x, y];
  }
  return out;
}

/** Angle θ of every link at frame k. */
export function anglesAt(table, k) {
  return Object.fromEntries(Object.entries(table.outputs.angles).map(([link, rows]) => [link, rows[k]]));
}

const DIGITS = "₀₁₂₃₄₅₆₇₈₉";
const subscriptDigits = (text) => String(text).replace(/\d/g, (d) => DIGITS[d]);

/**
 * Every quantity the student may plot against φ: {id, label (notation markup), unit, values}.
 * Joints: x, y, x′, y′, x″, y″; links: θ, θ′, θ″; slides: s, s′, s″, each slide labelled by slideName(pair).
 */
export function quantities(table, slideName = (pair) => pair) {
  const out = [];
  const o = table.outputs;
  const primes = ["", "′", "″"];
  for (const name of Object.keys(o.joints)) {
    ["joints", "joints_d1", "joints_d2"].forEach((key, order) => {
      for (const [axis, column] of [["x", 0], ["y", 1]]) {
        out.push({ id: `${key}:${name}:${axis}`, label: `${axis}${primes[order]}_{${name}}`, unit: "m",
          values: o[key][name].map((row) => row[column]) });
      }
    });
  }
  for (const link of Object.keys(o.angles)) {
    ["angles", "angles_d1", "angles_d2"].forEach((key, order) => {
      out.push({ id: `${key}:${link}`, label: `θ${primes[order]}${subscriptDigits(link)}`, unit: order ? "1" : "rad",
        values: o[key][link] });
    });
  }
  for (const slide of Object.keys(o.slides)) {
    ["slides", "slides_d1", "slides_d2"].forEach((key, order) => {
      out.push({ id: `${key}:${slide}`, label: `s${primes[order]}_{${slideName(slide)}}`, unit: "m", values: o[key][slide] });
    });
  }
  return out;
}

/** The frame whose crank angle (or input slider's s) is nearest to phi (rad or m). */
export function frameOf(table, phi) {
  const step = table.phi[1] - table.phi[0];
  return Math.max(0, Math.min(table.phi.length - 1, Math.round((phi - table.phi[0]) / step)));
}
