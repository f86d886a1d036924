/**
 * Zhukovsky's lever at the position of the force analysis: the velocity plan turned by 90° counter-clockwise
 * about its pole p at μ_v (the answer's images, mm), each load applied at its point's image in its own direction
 * (drawn at this drawing's force scale μ_F), its arm h from the pole drawn and numbered; the answer's balancing
 * force P_b = M_b/l₁ at the crank pin's image, perpendicular to pa, whose moment about p balances the lever.
 * Beside it each load's arm and moment about the pole (N·mm, as the answer gives them), the couples' moments,
 * and the balancing moment from the lever and from the groups with their difference in % (Chaika–Vasylenko
 * (3.2): the crank's equilibrium checked against a moment found otherwise).
 */
import { formatNumber, formatQuantity } from "../../../common/view/notation.js";
import { symbolOf } from "../../../forces_friction/model/group_free_body.js";
import { standardScale, unionBox, FONT } from "../../model/drawing_layout.js";
import { heading, imageLabels, scaleText, textLines } from "./captions.js";
import { Figure } from "./figure.js";

const ARROW = 22;              // mm: the largest force's arrow at most
const SHORTEST = 4;            // mm: a shorter force is drawn this long and dashed (its direction shown)
const MARGIN = 10;             // mm around the lever
const HEAD = 22;               // mm of the heading
const LIST_GAP = 10;           // mm from the lever to its list
const SHORTEST_ARM = 0.5;      // mm: a shorter arm is not drawn (the force passes through the pole)

/** Zhukovsky's lever of answer.kinetostatics (fields: number, balancing_moment, zhukovsky), as an SVG. */
export function zhukovskyLever(answer, t, lang, options = {}) {
  const figure = zhukovskyLeverFigure(answer, t, lang);
  return options.figure ? figure : figure.toSvg(figure.title, "cp-zhukovsky");
}

export function zhukovskyLeverFigure(answer, t, lang) {
  const { kinetostatics: kinetic } = answer;
  const lever = kinetic.zhukovsky;
  const balancing = lever.balancing_force;
  const forces = lever.lever.filter((row) => row.force && Math.hypot(...row.force) > 0);
  forces.push({ name: "balancing", kind: "balancing", ...balancing });
  const largest = Math.max(1e-9, ...forces.map((row) => Math.hypot(...row.force)));
  const muF = standardScale(largest, ARROW);
  const stretch = (row) => Math.max(1, SHORTEST / (Math.hypot(...row.force) / muF));
  const local = ([x, y]) => [x, -y];
  const extent = unionBox([[0, 0], ...Object.values(lever.images).map(local), ...forces.flatMap((row) => {
    const p = local(row.image);
    return [p, [p[0] + stretch(row) * row.force[0] / muF, p[1] - stretch(row) * row.force[1] / muF]];
  })], MARGIN);
  const at = (p) => {
    const [x, y] = local(p);
    return [x - extent.x, y - extent.y + HEAD];
  };
  const figure = new Figure();
  figure.title = t.project_dwg_zhukovsky.replace("{n}", kinetic.number);
  heading(figure, [0, 0], figure.title, [scaleText("μ_v", lever.mu_v, t.editor_unit_velocity, t, lang),
    scaleText("μ_F", muF, t.units_N, t, lang)]);
  const pole = at(lever.pole ?? [0, 0]);
  for (const [name, image] of Object.entries(lever.images)) {
    figure.line(pole, at(image), "thin", { "data-image": name });
  }
  figure.dot(pole, 0.7, { "data-role": "pole" });
  const balancingSymbol = t.symbol_balancing_moment.replace(/^M/, "P");
  const list = [];
  let arms = 0;
  for (const row of forces) {
    const tail = at(row.image);
    const size = Math.hypot(...row.force);
    const k = stretch(row) / muF;
    const tip = [tail[0] + row.force[0] * k, tail[1] - row.force[1] * k];
    const symbol = row.kind === "balancing" ? balancingSymbol : symbolOf(row.name, row.kind);
    figure.arrow(tail, tip, row.kind === "balancing" ? "bold" : size / muF < SHORTEST ? "dashed" : "main",
      { "data-force": row.name });
    const length = Math.hypot(tip[0] - tail[0], tip[1] - tail[1]) || 1;
    figure.label(symbol, [tip[0] + 2.5 * (tip[0] - tail[0]) / length, tip[1] + 2.5 * (tip[1] - tail[1]) / length + 1.2],
      { target: tip, attrs: { "data-role": "force-name" } });
    const foot = armFoot(row.image, row.force);
    if (Math.hypot(...foot) < SHORTEST_ARM) {           // too short to draw: listed with its value
      list.push(`${symbol}: h = ${formatNumber(row.arm, lang, 2)} ${t.editor_mm}; ${formatQuantity(row.moment, lang, 4)} ${t.units_N}·${t.editor_mm}`);
      continue;
    }
    arms += 1;
    const end = at(foot);
    figure.line(pole, end, "dashed", { "data-arm": row.name });
    figure.label(`h_${arms}`, [(pole[0] + end[0]) / 2 + 1.5, (pole[1] + end[1]) / 2 - 1],
      { size: FONT.small, target: [(pole[0] + end[0]) / 2, (pole[1] + end[1]) / 2], attrs: { "data-role": "arm-name" } });
    list.push(`${symbol}: h_${arms} = ${formatNumber(row.arm, lang, 2)} ${t.editor_mm}; ${formatQuantity(row.moment, lang, 4)} ${t.units_N}·${t.editor_mm}`);
  }
  const couples = lever.lever.filter((row) => Number.isFinite(row.couple) && row.couple !== 0)
    .map((row) => `${symbolOf(row.name, row.kind)}: ${formatQuantity(row.moment, lang, 4)} ${t.units_N}·${t.editor_mm}`);
  const moment = t.symbol_balancing_moment;
  const unit = t.units_N_m;
  imageLabels(figure, "p", pole, Object.entries(lever.images).map(([name, image]) => ({ name, p: at(image) })), "end");
  let y = textLines(figure, [extent.width + LIST_GAP, HEAD], list, FONT.small);
  if (couples.length) y = textLines(figure, [extent.width + LIST_GAP, y], [`${t.project_dwg_couples}:`, ...couples], FONT.small);
  textLines(figure, [extent.width + LIST_GAP, y], [
    `${balancingSymbol} = ${formatQuantity(Math.hypot(...balancing.force), lang, 4)} ${t.units_N}`,
    `${moment} ${t.project_dwg_from_lever} = ${formatQuantity(lever.moment, lang, 5)} ${unit}`,
    `${moment} ${t.project_dwg_from_groups} = ${formatQuantity(kinetic.balancing_moment, lang, 5)} ${unit}`,
    `${t.project_dwg_difference}: ${formatQuantity(lever.difference_percent, lang, 2)} %`], FONT.label);
  return figure;
}

/** The foot of the perpendicular from the pole (the origin) to the line through image along force (mm, y up). */
function armFoot(image, force) {
  const size = Math.hypot(force[0], force[1]);
  const u = [force[0] / size, force[1] / size];
  const along = image[0] * u[0] + image[1] * u[1];
  return [image[0] - along * u[0], image[1] - along * u[1]];
}
