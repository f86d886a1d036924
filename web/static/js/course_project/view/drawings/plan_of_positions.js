/**
 * The plan of positions (Chaika–Vasylenko §3.4, step 5): the mechanism at all N positions of the answer drawn
 * over each other at μ_l, each position's links in thin lines and the position of the force analysis in main
 * lines with its pairs, slider blocks and letters; the frame's supports and guides hatched; the crank pin's
 * circle and the trajectories of the centres of mass and of the loads' points dash-dotted; the positions
 * numbered 1 … N at the crank pin and at the output's point, and the working stroke's other extreme k′ marked
 * where the answer places it. Every length is the answer's metres over μ_l: L/μ_l mm.
 */
import { paperPlacement, FONT } from "../../model/drawing_layout.js";
import { heading, pointSymbol, scaleText } from "./captions.js";
import { Figure } from "./figure.js";

const MARGIN = 14;             // mm around the mechanism: room for the supports and numbers
const NUMBER_OFFSET = 3.2;     // mm from a point to its position's number
const LETTER_OFFSET = [2.2, -2.2];
const GUIDE_BEYOND = 6;        // mm the guide reaches beyond the slider's travel
const BLOCK_HALF = 2.25;       // mm: the guide's hatched line lies under the slider block's face
const HEAD = 16;               // mm of the heading above the mechanism
const SAME = 1e-9;             // m: a joint that stays within this at every position is fixed

/**
 * The plan of positions of answer (fields read: scales.mu_l, positions {count, chosen, phi, output, extremes,
 * other_extreme}, plan_of_positions {joints, marked, links, guides, trajectories}, structure.pairs), as an SVG
 * in mm; options.figure: return the Figure (no DOM) instead.
 */
export function planOfPositions(answer, t, lang, options = {}) {
  const figure = planOfPositionsFigure(answer, t, lang);
  return options.figure ? figure : figure.toSvg(t.project_dwg_plan_of_positions, "cp-plan-of-positions");
}

export function planOfPositionsFigure(answer, t, lang) {
  const { plan_of_positions: plan, positions, scales } = answer;
  const mu = scales.mu_l;
  const count = positions.count;
  const chosen = (positions.chosen ?? 1) - 1;
  const joints = plan.joints;
  const everything = [...Object.values(joints).flat(), ...Object.values(plan.marked ?? {}).flat(),
    ...Object.values(plan.trajectories ?? {}).flat()];
  const place = paperPlacement(everything, mu, MARGIN);
  const at = (p) => {
    const [x, y] = place.at(p);
    return [x, y + HEAD];
  };
  const figure = new Figure();
  heading(figure, [0, 0], t.project_dwg_plan_of_positions, [scaleText("μ_l", mu, t.units_m, t, lang)]);

  const fixed = Object.keys(joints).filter((name) => joints[name].every((p) => Math.hypot(p[0] - joints[name][0][0],
    p[1] - joints[name][0][1]) <= SAME));
  const framePins = (answer.structure?.pairs ?? []).filter((pair) => pair.kind === "R" && pair.links.includes(0))
    .map((pair) => pair.name).filter((name) => fixed.includes(name));

  for (const [name, path] of Object.entries(plan.trajectories ?? {})) {
    figure.polyline(path.map(at), "dashdot", { "data-role": "trajectory", "data-point": name });
  }
  crankCircle(figure, answer, at);
  for (const [name, guide] of Object.entries(plan.guides ?? {})) {
    if (guide.link === 0) frameGuide(figure, name, guide, answer, at);
  }
  for (let i = 0; i < count; i += 1) {
    if (i !== chosen) drawPosition(figure, answer, i, at, "thin");
  }
  drawPosition(figure, answer, chosen, at, "main");
  const centre = centroid(Object.values(joints).map((path) => at(path[chosen])));
  for (const name of framePins) {
    const p = at(joints[name][0]);
    figure.support(p, supportAngle(p, centre), { "data-joint": name });
  }
  letters(figure, answer, chosen, at);
  numbers(figure, answer, at);
  return figure;
}

/** The crank pin's circle: about the crank's pivot through its pin (the first link of the answer's links). */
function crankCircle(figure, answer, at) {
  const crank = answer.plan_of_positions.links.find((link) => link.link === 1) ?? answer.plan_of_positions.links[0];
  const [pivot, pin] = crank.joints.map((name) => answer.plan_of_positions.joints[name][0]);
  figure.circle(at(pivot), Math.hypot(pin[0] - pivot[0], pin[1] - pivot[1]) / answer.scales.mu_l, "dashdot",
    { "data-role": "crank-circle" });
}

/** A frame guide: hatched under the slider blocks over their travel along it, its axis dash-dotted. */
function frameGuide(figure, name, guide, answer, at) {
  const { joints, links } = answer.plan_of_positions;
  const slider = links.find((link) => link.slides.some((slide) => slide.split("/")[1] === name));
  const joint = slider?.slides.find((slide) => slide.split("/")[1] === name)?.split("/")[0];
  if (!joint || !joints[joint]) return;
  const point = at(guide.point[0]);
  const angle = -guide.angle[0];                                  // on paper y points down
  const u = [Math.cos(angle), Math.sin(angle)];
  const along = joints[joint].map((p) => {
    const q = at(p);
    return (q[0] - point[0]) * u[0] + (q[1] - point[1]) * u[1];
  });
  const [from, to] = [Math.min(...along) - GUIDE_BEYOND, Math.max(...along) + GUIDE_BEYOND];
  const on = (s, offset = 0) => [point[0] + u[0] * s - u[1] * offset, point[1] + u[1] * s + u[0] * offset];
  figure.line(on(from), on(to), "dashdot", { "data-role": "guide-axis" });
  figure.guide(on(from, BLOCK_HALF), on(to, BLOCK_HALF), -1, { "data-guide": name });
}

/** One position's links: bars between their joints, blocks on their slides; pins where main. */
function drawPosition(figure, answer, i, at, kind) {
  drawLinks(figure, answer, i, at, { kind });
  if (kind !== "main") return;
  for (const path of Object.values(answer.plan_of_positions.marked ?? {})) figure.dot(at(path[i]), 0.6);
}

/**
 * The links of position index i (plan_of_positions.links; only those numbered in `only` if given): bars between
 * their joints, a block on each slide (main) or a dot (thin), with kind "main" the pairs' pins; at maps metres
 * to paper. Shared with the groups' drawing of the force analysis.
 */
export function drawLinks(figure, answer, i, at, { kind = "main", only = null } = {}) {
  const { joints, links, guides } = answer.plan_of_positions;
  const number = i + 1;
  const shown = links.filter((link) => !only || only.includes(link.link));
  for (const link of shown) {
    const points = link.joints.filter((name) => joints[name]).map((name) => at(joints[name][i]));
    for (let k = 1; k < points.length; k += 1) {
      figure.line(points[k - 1], points[k], kind, { "data-link": link.link, "data-position": number,
        ...(link.link === 1 && k === 1 ? { "data-role": "crank" } : {}) });
    }
    for (const slide of link.slides) {
      const [joint, guideName] = slide.includes("/") ? slide.split("/") : [link.joints[0], null];
      if (!joints[joint]) continue;
      const direction = guideName ? -guides[guideName].angle[i] : slideDirection(answer, slide, i, at);
      if (direction === null) continue;
      if (kind === "main") figure.block(at(joints[joint][i]), direction, "main", { "data-position": number });
      else figure.dot(at(joints[joint][i]), 0.45, { "data-position": number });
    }
  }
  for (const [name, guide] of Object.entries(guides ?? {})) {     // a guide on a moving link reaches its slider
    if (guide.link === 0 || !shown.some((link) => link.link === guide.link)) continue;
    const joint = links.flatMap((link) => link.slides).find((slide) => slide.split("/")[1] === name)?.split("/")[0];
    if (!joint || !joints[joint]) continue;
    const from = at(guide.point[i]);
    const to = at(joints[joint][i]);
    const length = Math.hypot(to[0] - from[0], to[1] - from[1]);
    if (!(length > 0)) continue;
    const beyond = 1 + GUIDE_BEYOND / length;
    figure.line(from, [from[0] + (to[0] - from[0]) * beyond, from[1] + (to[1] - from[1]) * beyond], kind,
      { "data-link": guide.link, "data-guide": name, "data-position": number });
  }
  if (kind !== "main") return;
  const pinned = new Set(shown.flatMap((link) => link.joints).filter((name) => joints[name] && isPair(answer, name)));
  for (const name of pinned) figure.pin(at(joints[name][i]));
}

/** Whether a joint of the plan is a pair of the structure (not a point fixed on a link, such as S₃ or K). */
function isPair(answer, name) {
  return (answer.structure?.pairs ?? []).some((pair) => pair.name === name);
}

/**
 * The direction (rad on paper) of a slide on a moving link: along the link of the pair that carries the slot,
 * from its first joint to the joint farthest from it; null where the structure does not name the pair.
 */
function slideDirection(answer, slide, i, at) {
  const pair = (answer.structure?.pairs ?? []).find((p) => p.name === slide);
  if (!pair) return null;
  const { joints, links } = answer.plan_of_positions;
  for (const number of pair.links) {
    const link = links.find((l) => l.link === number);
    const names = (link?.joints ?? []).filter((name) => joints[name]);
    if (names.length < 2) continue;
    const first = at(joints[names[0]][i]);
    const far = names.slice(1).map((name) => at(joints[name][i]))
      .reduce((a, b) => (Math.hypot(b[0] - first[0], b[1] - first[1]) > Math.hypot(a[0] - first[0], a[1] - first[1]) ? b : a));
    return Math.atan2(far[1] - first[1], far[0] - first[0]);
  }
  return null;
}

/** The joints' and marked points' letters at the position of the force analysis. */
function letters(figure, answer, i, at) {
  const { joints, marked } = answer.plan_of_positions;
  const named = new Map();
  for (const [name, path] of [...Object.entries(joints), ...Object.entries(marked ?? {})]) {
    const p = at(path[i]);
    const key = `${p[0].toFixed(2)},${p[1].toFixed(2)}`;          // coinciding points share one label
    named.set(key, { p, names: [...(named.get(key)?.names ?? []), pointSymbol(name)] });
  }
  for (const { p, names } of named.values()) {
    const unique = [...new Set(names)];
    figure.label(unique.join(", "), [p[0] + LETTER_OFFSET[0], p[1] + LETTER_OFFSET[1]],
      { anchor: "start", target: p, attrs: { "data-role": "letter" } });
  }
}

/**
 * The positions' numbers: at the crank pin (outward from the pivot) and at the output's point where it is a
 * slider; the other extreme k′ at the output's point on its guide (its travel s from the guide's point).
 */
function numbers(figure, answer, at) {
  const { plan_of_positions: plan, positions } = answer;
  const crank = plan.links.find((link) => link.link === 1) ?? plan.links[0];
  const [pivotName, pinName] = crank.joints;
  const pivot = at(plan.joints[pivotName][0]);
  const outputJoint = positions.output?.kind === "slide" ? positions.output.name.split("/")[0] : null;
  for (let i = 0; i < positions.count; i += 1) {
    const pin = at(plan.joints[pinName][i]);
    const length = Math.hypot(pin[0] - pivot[0], pin[1] - pivot[1]) || 1;
    const out = [(pin[0] - pivot[0]) / length, (pin[1] - pivot[1]) / length];
    figure.label(String(i + 1), [pin[0] + out[0] * NUMBER_OFFSET, pin[1] + out[1] * NUMBER_OFFSET + FONT.small / 2],
      { size: FONT.small, target: pin, attrs: { "data-role": "position-number", "data-position": i + 1 } });
  }
  if (outputJoint && plan.joints[outputJoint]) {
    for (let i = 0; i < positions.count; i += 1) {
      const p = at(plan.joints[outputJoint][i]);
      figure.label(String(i + 1), [p[0], p[1] - NUMBER_OFFSET - 1.5],
        { size: FONT.small, target: p, attrs: { "data-role": "position-number", "data-position": i + 1 } });
    }
    const guideName = positions.output.name.split("/")[1];
    const guide = plan.guides?.[guideName];
    const extreme = positions.other_extreme;
    if (guide && extreme && positions.extremes) {
      const s = positions.extremes.end;
      const [gx, gy] = guide.point[0];
      const p = at([gx + s * Math.cos(guide.angle[0]), gy + s * Math.sin(guide.angle[0])]);
      figure.dot(p, 0.6, { "data-role": "other-extreme" });
      figure.label(extreme.label, [p[0], p[1] + NUMBER_OFFSET + FONT.small],
        { size: FONT.small, target: p, attrs: { "data-role": "position-number", "data-position": extreme.label } });
    }
  }
}

function centroid(points) {
  const n = points.length || 1;
  return [points.reduce((s, p) => s + p[0], 0) / n, points.reduce((s, p) => s + p[1], 0) / n];
}

/** The angle (rad, 0 = down on paper) that turns a support at p away from the mechanism's centre. */
function supportAngle(p, centre) {
  const away = Math.atan2(p[1] - centre[1], p[0] - centre[0]);      // direction from the centre to p
  const quarter = Math.round((away - Math.PI / 2) / (Math.PI / 2)) * (Math.PI / 2);
  return quarter;
}
