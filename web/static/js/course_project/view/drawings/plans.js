/**
 * The velocity and the acceleration plan of one position (Chaika–Vasylenko §3.4, step 6) at the sheet's μ_v
 * and μ_a: every vector of the answer's plan equations laid head to tail from the pole p (π) as the editor lays
 * them (editor/model/plan.js), each point's image lettered as its joint (a, d, s₃ …; images at one place share
 * a label), the absolute vectors in main lines from the pole, on the acceleration plan the normal and Coriolis
 * components in thin lines and the tangential and relative ones dashed (their directions known, their lengths
 * found by the plan), the components named as the editor names them (n_BA, τ_BA, k_B3B2 …); beside the plan
 * each vector's length on paper and its value. A vector of V m/s is V/μ_v mm long.
 */
import { formatNumber, formatQuantity } from "../../../common/view/notation.js";
import { planVectors } from "../../../editor/model/plan.js";
import { vectorLabel } from "../../../editor/view/plans.js";
import { paperPlacement, FONT } from "../../model/drawing_layout.js";
import { heading, imageLabels, imageSymbol, scaleText, textLines } from "./captions.js";
import { Figure } from "./figure.js";

const MARGIN = 8;              // mm around the plan
const HEAD = 18;               // mm of the heading above the plan
const LIST_GAP = 8;            // mm from the plan to its list of vectors
const SAME_PLACE = 0.4;        // mm: an absolute vector ending this near a drawn one is not drawn again
const LINE_OF = { absolute: "main", normal: "thin", coriolis: "thin", rotation: "thin", sliding: "thin",
  tangential: "dashed", relative: "dashed" };

/** The velocity plan of position options.number (default: the first drawn, else the chosen position). */
export function velocityPlan(answer, t, lang, options = {}) {
  const figure = velocityPlanFigure(answer, t, lang, options);
  return options.figure ? figure : figure.toSvg(figure.title, "cp-velocity-plan");
}

/** The acceleration plan of position options.number. */
export function accelerationPlan(answer, t, lang, options = {}) {
  const figure = accelerationPlanFigure(answer, t, lang, options);
  return options.figure ? figure : figure.toSvg(figure.title, "cp-acceleration-plan");
}

/** The position a plan is drawn at: options.number, else the first drawn one, else the chosen one. */
function planPosition(answer, options = {}) {
  return options.number ?? answer.positions.drawn?.[0] ?? answer.positions.chosen ?? 1;
}

export function velocityPlanFigure(answer, t, lang, options = {}) {
  const number = planPosition(answer, options);
  return planFigure(answer.kinematics[number - 1], {
    which: "velocity", field: "v", pole: "p", mu: answer.scales.mu_v, muSymbol: "μ_v", unit: t.editor_unit_velocity,
    title: t.project_dwg_velocity_plan.replace("{n}", number) }, t, lang);
}

export function accelerationPlanFigure(answer, t, lang, options = {}) {
  const number = planPosition(answer, options);
  return planFigure(answer.kinematics[number - 1], {
    which: "acceleration", field: "a", pole: "π", mu: answer.scales.mu_a, muSymbol: "μ_a",
    unit: t.editor_unit_acceleration, title: t.project_dwg_acceleration_plan.replace("{n}", number) }, t, lang);
}

function planFigure(row, spec, t, lang) {
  const { mu } = spec;
  const vectors = planVectors(row[spec.which]);
  const images = Object.entries(row.points).map(([name, point]) => ({ name, at: [point[spec.field].x, point[spec.field].y] }));
  for (const equation of row[spec.which]) {         // a target's image: where its first equation's vectors end
    if (images.some((image) => image.name === equation.target)) continue;
    const end = equation.vectors.reduce((s, v) => [s[0] + v.x, s[1] + v.y], [0, 0]);
    images.push({ name: equation.target, at: end });
  }
  const ends = [[0, 0], ...vectors.flatMap((v) => [v.start, v.end]), ...images.map((image) => image.at)];
  const place = paperPlacement(ends, mu, MARGIN);
  const at = (p) => {
    const [x, y] = place.at(p);
    return [x, y + HEAD];
  };
  const figure = new Figure();
  figure.title = spec.title;
  heading(figure, [0, 0], spec.title, [scaleText(spec.muSymbol, mu, spec.unit, t, lang)]);
  const pole = at([0, 0]);

  const drawnEnds = [];
  for (const v of vectors) {
    const attrs = { "data-vector": v.name, "data-kind": v.kind };
    figure.arrow(at(v.start), at(v.end), LINE_OF[v.kind] ?? "thin", attrs);
    if (v.kind === "absolute") drawnEnds.push(at(v.end));
    else {
      const [a, b] = [at(v.start), at(v.end)];
      if (Math.hypot(b[0] - a[0], b[1] - a[1]) > 2) {
        figure.label(vectorLabel(v.name), [(a[0] + b[0]) / 2 + 1.5, (a[1] + b[1]) / 2 - 1],
          { size: FONT.small, target: [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2], attrs: { "data-role": "vector-name" } });
      }
    }
  }
  for (const image of images) {        // the points' absolute vectors the equations do not draw (centres, points on links)
    const end = at(image.at);
    if (!drawnEnds.some((p) => Math.hypot(p[0] - end[0], p[1] - end[1]) < SAME_PLACE)) {
      figure.arrow(pole, end, "thin", { "data-vector": `${spec.pole}${imageSymbol(image.name)}`, "data-kind": "point" });
      drawnEnds.push(end);
    }
  }
  figure.dot(pole, 0.7, { "data-role": "pole" });
  imageLabels(figure, spec.pole, pole, images.map((image) => ({ name: image.name, p: at(image.at) })));
  textLines(figure, [place.width + LIST_GAP, HEAD], vectorList(vectors, spec, lang, t), FONT.small);
  return figure;
}

/** "pa = 24,9 мм; 0,996 м/с": each vector's length on paper and its value. */
function vectorList(vectors, spec, lang, t) {
  const seen = new Set();
  const lines = [];
  for (const v of vectors) {
    if (seen.has(v.name)) continue;
    seen.add(v.name);
    const length = Math.hypot(v.end[0] - v.start[0], v.end[1] - v.start[1]) / spec.mu;
    lines.push(`${vectorLabel(v.name)} = ${formatNumber(length, lang, 1)} ${t.editor_mm}; ${formatQuantity(v.value, lang, 3)} ${spec.unit}`);
  }
  return lines;
}
