/**
 * The energy–mass diagram (Wittenbauer, Lecture 10 §10.8 (L28)–(L29)) and the flywheel it gives, drawn from
 * answer.dynamics: the curve ΔT(I_II) over the cycle at μ_I and μ_T, its two tangents of slopes ω_max²/2 and
 * ω_min²/2 (the answer's intercepts b_up, b_low on the ordinate I_II = 0, the points k and l), the angles ψ_max,
 * ψ_min they make on paper (tg ψ = slope·μ_I/μ_T), the segment kl = ΔT_I max and the group-I inertia
 * I_I = kl/(δ ω_m²) the answer found; and the flywheel's solid disk (diameter D, width b) drawn to an ESKD scale.
 */
import { degrees, formatNumber, formatQuantity } from "../../../common/view/notation.js";
import { eskdScale, roundTicks, standardScale, FONT } from "../../model/drawing_layout.js";
import { heading, scaleText, textLines } from "./captions.js";
import { Figure } from "./figure.js";

const SIZE = 120;              // mm: the diagram's width and height at most
const LEFT = 22;               // mm left of the ordinate for its values
const HEAD = 26;               // mm of the heading
const TICK = 1.5;              // mm
const DISK = 100;              // mm: the flywheel's diameter on paper at most

/** The energy–mass diagram of answer.dynamics.wittenbauer with the flywheel's inertia, as an SVG in mm. */
export function wittenbauerDiagram(answer, t, lang, options = {}) {
  const figure = wittenbauerFigure(answer, t, lang);
  return options.figure ? figure : figure.toSvg(t.project_dwg_wittenbauer, "cp-wittenbauer");
}

export function wittenbauerFigure(answer, t, lang) {
  const d = answer.dynamics;
  const w = d.wittenbauer;
  const x1 = Math.max(0, ...w.inertia_ii);
  const ys = [0, ...w.work, w.b_up, w.b_low, w.b_up + w.slope_up * x1, w.b_low + w.slope_low * x1];
  const [y0, y1] = [Math.min(...ys), Math.max(...ys)];
  const muI = standardScale(x1, SIZE);
  const muT = standardScale(y1 - y0, SIZE);
  const origin = [LEFT, HEAD + y1 / muT];
  const at = ([x, y]) => [origin[0] + x / muI, origin[1] - y / muT];
  const right = at([x1, 0])[0] + 8;
  const figure = new Figure();
  heading(figure, [0, 0], t.project_dwg_wittenbauer, [scaleText("μ_I", muI, t.units_kg_m2, t, lang),
    scaleText("μ_T", muT, t.units_J, t, lang)]);
  figure.arrow([origin[0], at([0, y0])[1] + 3], [origin[0], HEAD - 4], "thin", { "data-role": "axis-energy" });
  figure.arrow(origin, [right + 4, origin[1]], "thin", { "data-role": "axis-inertia" });
  figure.text(`ΔT, ${t.units_J}`, [origin[0] + 2, HEAD - 3], { size: FONT.label });
  figure.text(`${t.symbol_inertia_group_II}, ${t.units_kg_m2}`, [right + 5, origin[1] + 4.5], { size: FONT.label });
  for (const value of roundTicks(y0, y1, muT, 10).ticks) {
    const y = at([0, value])[1];
    figure.line([origin[0] - TICK, y], [origin[0], y], "thin");
    figure.text(formatQuantity(value, lang, 3), [origin[0] - TICK - 0.8, y + 0.9], { size: FONT.small, anchor: "end" });
  }
  for (const value of roundTicks(0, x1, muI, 15).ticks.filter((v) => v > 0)) {
    const x = at([value, 0])[0];
    figure.line([x, origin[1]], [x, origin[1] + TICK], "thin");
    figure.text(formatQuantity(value, lang, 3), [x, origin[1] + TICK + FONT.small + 0.5], { size: FONT.small, anchor: "middle" });
  }
  figure.polyline(w.inertia_ii.map((x, i) => at([x, w.work[i]])), "main", { "data-curve": "energy-mass" });
  const tangent = (b, slope, phi, name) => {
    figure.line(at([0, b]), at([x1, b + slope * x1]), "dashed", { "data-tangent": name });
    const k = nearest(d.phi, phi);
    figure.dot(at([w.inertia_ii[k], w.work[k]]), 0.6, { "data-touch": name });
    const psi = degrees(Math.atan(slope * muI / muT));
    const end = at([x1, b + slope * x1]);
    figure.label(`ψ_${name} = ${formatNumber(psi, lang, 1)}°`, [end[0] + 1.5, end[1] + 1.2],
      { anchor: "start", target: end, attrs: { "data-role": "tangent-name" } });
  };
  tangent(w.b_up, w.slope_up, w.phi_up, "max");
  tangent(w.b_low, w.slope_low, w.phi_low, "min");
  for (const [b, letter] of [[w.b_up, "k"], [w.b_low, "l"]]) {
    const p = at([0, b]);
    figure.dot(p, 0.7, { "data-intercept": letter });
    figure.label(letter, [p[0] - 2, p[1] - 1.2], { anchor: "end", target: p, attrs: { "data-role": "intercept" } });
  }
  const method = d.flywheel.methods.find((m) => m.method === "wittenbauer");
  textLines(figure, [origin[0], at([0, y0])[1] + 8], [
    `kl = ΔT_{I max} = ${formatQuantity(method.energy_swing, lang, 5)} ${t.units_J}`,
    `${t.symbol_inertia_group_I} = kl/(δ ${t.symbol_mean_speed}²) = ${formatQuantity(method.inertia, lang, 5)} ${t.units_kg_m2}`,
    `${t.project_dwg_symbol_flywheel} = ${formatQuantity(method.additional, lang, 5)} ${t.units_kg_m2}`], FONT.label);
  return figure;
}

/** The index of the angle of phi nearest to angle (the turn's period taken into account). */
function nearest(phi, angle) {
  let best = 0;
  let distance = Infinity;
  phi.forEach((p, i) => {
    const gap = Math.abs(Math.atan2(Math.sin(p - angle), Math.cos(p - angle)));
    if (gap < distance) [best, distance] = [i, gap];
  });
  return best;
}

/**
 * The flywheel: a solid disk of the answer's diameter D and width b (dynamics.flywheel.disk, m), front view and
 * section side by side at a standard μ_l (the ESKD scale written too), its dimensions in mm of the machine
 * (with their unit, which an ESKD drawing leaves out).
 */
export function flywheelDrawing(answer, t, lang, options = {}) {
  const figure = flywheelFigure(answer, t, lang);
  return options.figure ? figure : figure.toSvg(t.project_dwg_flywheel, "cp-flywheel");
}

export function flywheelFigure(answer, t, lang) {
  const { flywheel } = answer.dynamics;
  const { diameter, width, mass } = flywheel.disk;
  const mu = standardScale(diameter, DISK);
  const figure = new Figure();
  heading(figure, [0, 0], t.project_dwg_flywheel, [
    `${scaleText("μ_l", mu, t.units_m, t, lang)} (${eskdScale(mu, (x) => formatNumber(x, lang))})`]);
  const radius = diameter / 2 / mu;
  const centre = [radius + 8, HEAD + radius + 6];
  figure.circle(centre, radius, "main", { "data-role": "disk" });
  figure.line([centre[0] - radius - 4, centre[1]], [centre[0] + radius + 4, centre[1]], "dashdot");
  figure.line([centre[0], centre[1] - radius - 4], [centre[0], centre[1] + radius + 4], "dashdot");
  const side = [centre[0] + radius + 20, centre[1] - radius];
  const b = width / mu;
  figure.polygon([side, [side[0] + b, side[1]], [side[0] + b, side[1] + 2 * radius], [side[0], side[1] + 2 * radius]], "main",
    { "data-role": "disk-section" });
  figure.line([side[0] - 4, centre[1]], [side[0] + b + 4, centre[1]], "dashdot");
  const mm = (metres) => `${formatNumber(metres * 1000, lang, 0)} ${t.editor_mm}`;
  dimension(figure, [centre[0] - radius, centre[1] + radius + 6], [centre[0] + radius, centre[1] + radius + 6],
    centre[1], `⌀${mm(diameter)}`);
  dimension(figure, [side[0], side[1] - 5], [side[0] + b, side[1] - 5], side[1], mm(width));
  textLines(figure, [side[0] + b + 10, side[1]], [
    `D = ${formatQuantity(diameter, lang, 4)} ${t.units_m}`, `b = ${formatQuantity(width, lang, 4)} ${t.units_m}`,
    `m = ${formatQuantity(mass, lang, 4)} ${t.units_kg}`,
    `${t.project_dwg_symbol_flywheel} = ${formatQuantity(flywheel.flywheel_inertia, lang, 5)} ${t.units_kg_m2}`], FONT.label);
  return figure;
}

/**
 * A horizontal dimension line from a to b with arrows at both ends, its text above the middle, and extension
 * lines from the drawn edge at height edge to a little beyond it.
 */
function dimension(figure, a, b, edge, text) {
  const beyond = Math.sign(a[1] - edge) * 1.5;
  figure.line([a[0], edge], [a[0], a[1] + beyond], "thin");
  figure.line([b[0], edge], [b[0], b[1] + beyond], "thin");
  const middle = [(a[0] + b[0]) / 2, a[1]];
  figure.arrow(middle, a, "thin");
  figure.arrow(middle, b, "thin");
  figure.text(text, [middle[0], a[1] - 1], { size: FONT.label, anchor: "middle" });
}
