/**
 * The velocity and acceleration plans at the cursor angle, drawn to scale from the pole p (π): one SVG per
 * plan in millimetres (viewBox units), the scale μ written under it; every point's image lettered at its place
 * as the textbook letters it (p, a, b, s₂ … on the velocity plan, π, a, b … on the acceleration plan; images at
 * one place share a label: "p, o, o₁"), the components named (n_BA, τ_BA, k_B3B2 …), the vectors between
 * lettered points read by their letters (pa, ab); all labels placed so that no two meet (the course project's
 * label placement, drawing_layout.js). Beside each plan the table of the vectors' values and of each point's
 * value from the plan and from the analytic transfer functions (v = z′ω₁, a = z″ω₁² + z′ε₁), every column with
 * its unit.
 */
import { element } from "../../common/view/dom.js";
import { svgElement } from "../../common/view/svg.js";
import { formatNumber, formatQuantity, setRichText } from "../../common/view/notation.js";
import { niceScale, planTargets, planVectors } from "../model/plan.js";
import { placeLabels, unionBox } from "../../course_project/model/drawing_layout.js";
import { imageSymbol } from "../../course_project/view/drawings/captions.js";

const PLAN_MM = 70;                     // the largest extent of a plan, mm
const MARGIN = 4;                       // mm around the plan and its labels
const SAME_PLACE = 0.3;                 // mm: images this close share a label
const VERTEX_SIZE = 3.4;                // mm: a point's letter
const VECTOR_SIZE = 2.6;                // mm: a component's name
const DOT = 0.9;                        // mm: the radius kept clear round a lettered point
const NAMED = new Set(["normal", "tangential", "coriolis", "relative", "sliding"]);   // the rest run between letters
const SUB = "₀₁₂₃₄₅₆₇₈₉";
const COLORS = { absolute: "#1f4e79", rotation: "#2e7d4f", sliding: "#c07400", normal: "#6a4c93",
  tangential: "#2e7d4f", coriolis: "#b5442f", relative: "#c07400" };

/** A plan label as notation: "n_A3C" keeps its subscript run; "a2a3" → "a₂a₃". */
export function vectorLabel(name) {
  return name.includes("_") ? name : name.replace(/\d/g, (d) => SUB[d]);
}

let markers = 0;

/**
 * The plan's lettered places: every point's image (equations: the plan's; points: {name: {x, y}} of the
 * answer's points, each at its absolute velocity or acceleration) and each target's (where its first
 * equation ends), in plan units; images within SAME_PLACE mm of another at `scale` join its label.
 */
function images(equations, points, scale, pole) {
  const places = [{ at: [0, 0], names: [pole] }];
  const add = (name, at) => {
    const symbol = imageSymbol(name);
    const near = places.find((p) => Math.hypot(p.at[0] - at[0], p.at[1] - at[1]) / scale < SAME_PLACE);
    if (!near) places.push({ at, names: [symbol] });
    else if (!near.names.includes(symbol)) near.names.push(symbol);
  };
  for (const [name, v] of Object.entries(points ?? {})) add(name, [v.x, v.y]);
  for (const equation of equations) {
    add(equation.target, equation.vectors.reduce((s, v) => [s[0] + v.x, s[1] + v.y], [0, 0]));
  }
  return places;
}

function drawPlan(equations, points, scale, pole, label) {
  const vectors = planVectors(equations);
  const mm = (p) => [p[0] / scale, -p[1] / scale];
  const places = images(equations, points, scale, pole);
  const segments = vectors.map((v) => [mm(v.start), mm(v.end)]);
  const labels = [
    ...places.map((place) => ({ text: place.names.join(", "), at: [mm(place.at)[0] + 1.2, mm(place.at)[1] - 1.2],
      fontSize: VERTEX_SIZE, anchor: "start", vertex: place.names[0] })),
    ...vectors.filter((v) => NAMED.has(v.kind)).map((v) => {
      const [a, b] = [mm(v.start), mm(v.end)];
      return { text: vectorLabel(v.name), at: [(a[0] + b[0]) / 2 + 1, (a[1] + b[1]) / 2 - 0.8], fontSize: VECTOR_SIZE,
        anchor: "middle", vector: v };
    }),
  ];
  const marks = places.map((place) => {
    const [x, y] = mm(place.at);
    return { x: x - DOT, y: y - DOT, width: 2 * DOT, height: 2 * DOT };
  });
  const placed = placeLabels(labels, { marks, segments });
  const box = unionBox([...segments.flat(), [0, 0], ...placed.map((l) => l.box)], MARGIN);
  const svg = svgElement("svg", { viewBox: `${box.x} ${box.y} ${box.width} ${box.height}`, class: "plan-svg", role: "img",
    "aria-label": label, "data-scale": scale });
  const id = `plan-arrow-${(markers += 1)}`;
  const marker = svgElement("marker", { id, viewBox: "0 0 10 10", refX: 10, refY: 5, markerWidth: 5, markerHeight: 5,
    orient: "auto-start-reverse" }, svgElement("defs", {}, svg));
  svgElement("path", { d: "M0,0 L10,5 L0,10 z", fill: "context-stroke" }, marker);
  for (const v of vectors) {
    const [a, b] = [mm(v.start), mm(v.end)];
    svgElement("line", { x1: a[0], y1: a[1], x2: b[0], y2: b[1], class: `plan-vector ${v.kind}`, stroke: COLORS[v.kind],
      "marker-end": `url(#${id})`, "data-name": v.name }, svg);
  }
  for (const place of places) {
    const [x, y] = mm(place.at);
    svgElement("circle", { cx: x, cy: y, r: 0.6, class: place.names[0] === pole ? "pole" : "plan-point" }, svg);
  }
  for (const l of placed) {
    const text = svgElement("text", { x: l.x, y: l.y, "font-size": l.fontSize, "text-anchor": l.anchor,
      class: l.vertex ? "plan-label plan-vertex" : "plan-label", fill: l.vector ? COLORS[l.vector.kind] : "#1d2733",
      ...(l.vertex ? { "data-vertex": l.vertex } : { "data-label": l.vector.name }) }, svg);
    setRichText(text, l.text);
  }
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
  const column = (text) => element("th", { textContent: text, scope: "col" });
  return [
    element("table", { className: "plan-table" },
      element("caption", { textContent: t.editor_plan_vectors }),
      element("thead", {}, element("tr", {}, column(t.editor_vector), column(`${t.editor_value}, ${unit}`),
        column(t.editor_length_mm))),
      element("tbody", {}, ...vectorRows)),
    element("table", { className: "plan-table" },
      element("caption", { textContent: t.editor_plan_check }),
      element("thead", {}, element("tr", {}, column(t.editor_point_col), column(`${t.editor_from_plan}, ${unit}`),
        column(`${t.editor_analytic}, ${unit}`), column(`${t.editor_difference}, ${unit}`))),
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
    const points = Object.fromEntries(Object.entries(plan.points ?? {}).map(([name, p]) => [name, p[kind]]));
    const ends = vectors.flatMap((v) => [v.start, v.end]).concat([[0, 0]], Object.values(points).map((p) => [p.x, p.y]));
    const extent = (axis) => Math.max(...ends.map((p) => p[axis])) - Math.min(...ends.map((p) => p[axis]));
    const scale = scales[which] > 0 ? scales[which] : niceScale(Math.max(extent(0), extent(1), 1e-12), PLAN_MM);
    const figure = element("figure", { className: "plan", "data-plan-kind": which },
      drawPlan(plan[which], points, scale, pole, t[`editor_plan_${which}`]),
      element("figcaption", {}, element("span", { textContent: `${t[`editor_plan_${which}`]}: ` }),
        element("span", { rich: `${muName} = ` }),
        element("span", { className: "plan-scale", textContent: formatQuantity(scale, lang, 3) }),
        ` (${unit})/${t.editor_mm}`));
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
