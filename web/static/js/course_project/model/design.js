/**
 * The design data of a course project, kept in the editor's form (the address's d: masses {links, gravity,
 * forces, moments, point_forces, friction, pair_radius}, inertias {J1, J_rotor, gear_ratio}, motor, flywheel
 * {omega_mean, delta, …}): its values' bounds (the API's), the machine's rows, the loads added and taken away,
 * and the diagram points of a point force written and read as text. SI inside (rad, rad/s); the page's edge
 * writes degrees and rpm. No DOM.
 */
import { parseDecimal } from "../../common/model/decimal_input.js";

export const RPM_PER_RAD_S = 30 / Math.PI;          // n₁ = 30 ω₁ₘ/π
export const DEGREES = 180 / Math.PI;
export const GRAVITY = 9.81;
export const DEFAULT_OMEGA_MEAN = 10;                // rad/s, when the data has no flywheel part
export const DEFAULT_DELTA = 0.05;

/** The bounds of each edited value (inclusive), as the API checks them. */
export const BOUNDS = {
  mass: [0, 1e5], centre: [-1000, 1000], inertia: [0, 1e4], P: [0, 1e7], k: [0, 1], J1: [0, 1e4],
  J_rotor: [0, 1e4], gear_ratio: [1e-6, 1000], omega_mean: [1e-3, 1e4], delta: [1e-4, 0.5], friction: [0, 2],
  pair_radius: [0, 1], point: [-1000, 1000], angle: [-1000, 1000],
};

/** The data with every part the page edits present (the editor's data may lack the flywheel or friction). */
export function completed(dynamics) {
  const d = structuredClone(dynamics);
  d.masses.forces ??= [];
  d.masses.moments ??= [];
  d.masses.point_forces ??= [];
  d.masses.gravity ??= GRAVITY;
  d.masses.friction ??= 0;
  d.masses.pair_radius ??= 0;
  d.inertias ??= {};
  d.inertias.J1 ??= 0;
  d.inertias.J_rotor ??= 0;
  d.inertias.gear_ratio ??= 1;
  d.flywheel ??= {};
  d.flywheel.omega_mean ??= DEFAULT_OMEGA_MEAN;
  d.flywheel.delta ??= DEFAULT_DELTA;
  return d;
}

/**
 * The machine's rows [path, value, text key, bounds, scale] (scale: the value shown is the value kept times it,
 * n₁ in rpm for ω₁ₘ in rad/s).
 */
export function machineRows(d) {
  return [
    ["inertias.J1", d.inertias.J1, "project_J1", BOUNDS.J1, 1],
    ["inertias.J_rotor", d.inertias.J_rotor, "project_J_rotor", BOUNDS.J_rotor, 1],
    ["inertias.gear_ratio", d.inertias.gear_ratio, "project_gear_ratio", BOUNDS.gear_ratio, 1],
    ["flywheel.omega_mean", d.flywheel.omega_mean, "project_n1", BOUNDS.omega_mean, RPM_PER_RAD_S],
    ["flywheel.delta", d.flywheel.delta, "project_delta", BOUNDS.delta, 1],
    ["masses.friction", d.masses.friction, "project_friction", BOUNDS.friction, 1],
    ["masses.pair_radius", d.masses.pair_radius, "project_pair_radius", BOUNDS.pair_radius, 1],
  ];
}

/** A new point force on link (at its origin, 1000 N along −x, on the working stroke only). */
export function newPointForce(link) {
  return { link, point: [0, 0], magnitude: 1000, direction: { kind: "fixed", angle: Math.PI }, acts: "working" };
}

/**
 * A load added to d: kind "force" (on the sliding pair `where`, its first values offered by the estimate's
 * places), "moment" (on link `where`), "point" (a point force on link `where`).
 */
export function addLoad(d, places, kind, where) {
  if (kind === "point") {
    d.masses.point_forces.push(newPointForce(Number(where)));
    return;
  }
  const offered = kind === "force" ? places?.forces.find((f) => f.joint === where)
    : places?.moments.find((m) => String(m.link) === String(where));
  const load = offered ? structuredClone(offered)
    : kind === "force" ? { joint: where, working: 1000, k: 0.1, sense: 1 } : { link: Number(where), working: 100, k: 0.1, sense: 1 };
  d.masses[kind === "force" ? "forces" : "moments"].push(load);
}

/** The load at index of masses[list] ("forces", "moments", "point_forces") taken away. */
export function removeLoad(d, list, index) {
  d.masses[list] = d.masses[list].filter((_, k) => k !== index);
}

/**
 * A diagram's points as the page writes them: "x p; x p; …", x as the stroke's fraction 0…1 or, over the crank
 * angle, φ in degrees; numbers in the page's way (format: value → text).
 */
export function diagramText(diagram, format) {
  if (!diagram) return "";
  const scale = diagram.over === "phi" ? DEGREES : 1;
  return diagram.points.map(([x, p]) => `${format(x * scale)} ${format(p)}`).join("; ");
}

/**
 * The diagram points typed ("x p; x p; …") over "stroke" or "phi" (degrees typed, rad kept): {points} or
 * {error: "empty" | "ambiguous" | "invalid" | "pairs"} (each point two numbers). An empty text is no diagram
 * ({points: null}).
 */
export function readDiagramText(text, over, lang) {
  const pieces = String(text ?? "").split(";").map((piece) => piece.trim()).filter(Boolean);
  if (!pieces.length) return { points: null };
  const scale = over === "phi" ? 1 / DEGREES : 1;
  const points = [];
  for (const piece of pieces) {
    const numbers = piece.split(/\s+/);
    if (numbers.length !== 2) return { error: "pairs" };
    const [x, p] = numbers.map((number) => parseDecimal(number, lang));
    if (x.error || p.error) return { error: x.error ?? p.error };
    points.push([x.value * scale, p.value]);
  }
  return { points };
}
