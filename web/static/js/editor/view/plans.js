/**
 * The velocity and acceleration plans at the cursor angle, drawn to scale from the pole p (π): one SVG per
 * plan in millimetres (viewBox units), the scale μ written under it, every vector an arrow labelled as the
 * textbook labels it (pa, ab, n_BA, τ_BA, k_B3B2 …); beside it the table of the vectors' values and of each
 * point's value from the plan and from the analytic transfer functions (v = z′ω₁, a = z″ω₁² + z′ε₁).
 */
import { element } from "../../common/view/dom.js";
import { svgElement } from "../../common/view/svg.js";
import { formatNumber, formatQuantity, setRichText } from "../../common/view/notation.js";
import { niceScale, planTargets, planVectors } from "../model/plan.js";

const PLAN_MM = 70;                     // the largest extent of a plan, mm
const MARGIN = 9;                       // mm around the plan
const SUB = "₀₁₂₃₄₅₆₇₈₉";
const COLORS = { absolute: "#1f4e79", rotation: "#2e7d4f", sliding: "#c07400", normal: "#6a4c93",
  tangential: "#2e7d4f", coriolis: "#b5442f", relative: "#c07400" };

/** A plan label as notation: "n_A3C" keeps its subscript run; "a2a3" → "a₂a₃". */
export function vectorLabel(name) {
  return name.includes("_") ? name : name.replace(/\d/g, (d) => SUB[d]);
}

let markers = 0;

function drawPlan(vectors, scale, pole, label) {
  const ends = vectors.flatMap((v) => [v.start, v.end]).concat([[0, 0]]);
  const xs = ends.map((p) => p[0] / scale);
  const ys = ends.map((p) => -p[1] / scale);
  const [x0, y0] = [Math.min(...xs) - MARGIN, Math.min(...ys) - MARGIN];
  const [w, h] = [Math.max(...xs) - x0 + MARGIN, Math.max(...ys) - y0 + MARGIN];
  const svg = svgElement("svg", { viewBox: `${x0} ${y0} ${w} ${h}`, class: "plan-svg", role: "img", "aria-label": label,
    "data-scale": scale });
  const id = `plan-arrow-${(markers += 1)}`;
  const marker = svgElement("marker", { id, viewBox: "0 0 10 10", refX: 10, refY: 5, markerWidth: 5, markerHeight: 5,
    orient: "auto-start-reverse" }, svgElement("defs", {}, svg));
  svgElement("path", { d: "M0,0 L10,5 L0,10 z", fill: "context-stroke" }, marker);
  for (const v of vectors) {
    const [a, b] = [[v.start[0] / scale, -v.start[1] / scale], [v.end[0] / scale, -v.end[1] / scale]];
    svgElement("line", { x1: a[0], y1: a[1], x2: b[0], y2: b[1], class: `plan-vector ${v.kind}`, stroke: COLORS[v.kind],
      "marker-end": `url(#${id})`, "data-name": v.name }, svg);
    const [mx, my] = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
    const length = Math.hypot(b[0] - a[0], b[1] - a[1]) || 1;
    const [nx, ny] = [-(b[1] - a[1]) / length, (b[0] - a[0]) / length];
    setRichText(svgElement("text", { x: mx + 2.6 * nx, y: my + 2.6 * ny, class: "plan-label", fill: COLORS[v.kind] }, svg),
      vectorLabel(v.name));
  }
  svgElement("circle", { cx: 0, cy: 0, r: 0.9, class: "pole" }, svg);
  svgElement("text", { x: -3.5, y: -1.5, class: "plan-label pole-label" }, svg).textContent = pole;
  return svg;
}

function table(vectors, targets, scale, unit, t, lang, kind) {
  const cell = (text, attrs = {}) => element("td", { textContent: text, ...attrs });
  const vectorRows = vectors.map((v) => element("tr", {},
    element("th", { scope: "row", rich: vectorLabel(v.name), translate: false }),
    cell(formatQuantity(v.value, lang, 4), { "data-vector": v.name }),
    cell(formatQuantity(Math.hypot(v.end[0] - v.start[0], v.end[1] - v.start[1]) / scale, lang, 3))));
  const targetRows = targets.map((p) => element("tr", {},
    element("th", { scope: "row", rich: `${kind}_{${p.target}}`, translate: false }),
    cell(formatQuantity(p.plan, lang, 6), { "data-plan": p.target }),
    cell(formatQuantity(p.analytic, lang, 6), { "data-analytic": p.target }),
    cell(formatQuantity(p.residual, lang, 2))));
  return [
    element("table", { className: "plan-table" },
      element("caption", { textContent: `${t.editor_plan_vectors}, ${unit}` }),
      element("thead", {}, element("tr", {}, element("th", { textContent: t.editor_vector, scope: "col" }),
        element("th", { textContent: t.editor_value, scope: "col" }), element("th", { textContent: t.editor_length_mm, scope: "col" }))),
      element("tbody", {}, ...vectorRows)),
    element("table", { className: "plan-table" },
      element("caption", { textContent: `${t.editor_plan_check}, ${unit}` }),
      element("thead", {}, element("tr", {}, element("th", { textContent: t.editor_point_col, scope: "col" }),
        element("th", { textContent: t.editor_from_plan, scope: "col" }),
        element("th", { textContent: t.editor_analytic, scope: "col" }),
        element("th", { textContent: t.editor_difference, scope: "col" }))),
      element("tbody", {}, ...targetRows)),
  ];
}

/**
 * Both plans of the API's `plan` answer into host; scales {velocity, acceleration}: the student's μ (m/s per
 * mm, m/s² per mm), or null for the smallest nice scale at which the plan fits 70 mm.
 */
export function renderPlans(host, plan, t, lang, scales = {}, slider = false) {
  if (!plan) {
    host.replaceChildren(element("p", { className: "hint", textContent: t.editor_plans_none }));
    return;
  }
  const parts = [];
  for (const [which, pole, unit, kind, muName] of [
    ["velocity", "p", t.editor_unit_velocity, "v", "μ_v"], ["acceleration", "π", t.editor_unit_acceleration, "a", "μ_a"]]) {
    const vectors = planVectors(plan[which]);
    const ends = vectors.flatMap((v) => [v.start, v.end]).concat([[0, 0]]);
    const extent = (axis) => Math.max(...ends.map((p) => p[axis])) - Math.min(...ends.map((p) => p[axis]));
    const scale = scales[which] > 0 ? scales[which] : niceScale(Math.max(extent(0), extent(1), 1e-12), PLAN_MM);
    const figure = element("figure", { className: "plan", "data-plan-kind": which },
      drawPlan(vectors, scale, pole, t[`editor_plan_${which}`]),
      element("figcaption", {}, element("span", { textContent: `${t[`editor_plan_${which}`]}: ` }),
        element("span", { rich: `${muName} = ` }),
        element("span", { className: "plan-scale", textContent: formatQuantity(scale, lang, 3) }),
        ` ${unit}/${t.editor_mm}`));
    parts.push(element("div", { className: "plan-block" }, figure, ...table(vectors, planTargets(plan[which]), scale,
      unit, t, lang, kind)));
  }
  const links = element("p", { className: "plan-links" }, ...Object.entries(plan.links).flatMap(([link, w]) => [
    element("span", { rich: `ω_${link} = ${formatQuantity(w.omega, lang, 4)} ${t.units_rad_s}, ε_${link} = ${formatQuantity(w.epsilon, lang, 4)} ${t.units_rad_s2}` }),
    "; "]).slice(0, -1));
  const input = slider      // an input slider: its position s, velocity v₁ and acceleration a₁
    ? `s = ${formatNumber(plan.phi, lang, 3)} ${t.units_m}, v₁ = ${formatQuantity(plan.omega1, lang, 4)} ${t.editor_unit_velocity}, a₁ = ${formatQuantity(plan.epsilon1, lang, 4)} ${t.editor_unit_acceleration}`
    : `φ = ${formatNumber(plan.phi * 180 / Math.PI, lang, 1)}°, ω₁ = ${formatQuantity(plan.omega1, lang, 4)} ${t.units_rad_s}, ε₁ = ${formatQuantity(plan.epsilon1, lang, 4)} ${t.units_rad_s2}`;
  host.replaceChildren(element("p", { className: "hint", textContent: input }),
  ...parts, links);
}
