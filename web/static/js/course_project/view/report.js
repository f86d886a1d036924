/**
 * The report of the course project, section by section, from the answer of POST /api/v1/course-project: the
 * title block; 1 the structural analysis; 2 the kinematics (positions, plans, the points' velocities and
 * accelerations at every position, the output's diagrams); 3 the dynamics (the reduced inertia and moments, the
 * works, the energy–mass diagram, the flywheel by each method and its dimensions, ω₁, ε₁, δ, η); 4 the
 * kinetostatics at the chosen position (inertia loads, the groups' reactions, the force plans, the balancing
 * moment, Zhukovsky's lever, with friction the same and η) and the balancing moment at every position; the
 * equations used; the sheets to download. Every number is the answer's, written in the page's language.
 */
import { element } from "../../common/view/dom.js";
import { balancingTable, flywheelDimensions, flywheelTable, groupTable, inertiaTable, leverTable, linksTable, planTable,
  pointsTable, positionsTable, structureGroups, structurePairs } from "../model/report_tables.js";
import { RPM_PER_RAD_S } from "../model/design.js";
import { cellText, renderTable } from "./report_table.js";
import { figure, sheetTools } from "./figures.js";
import { equationsList } from "./equations.js";

const fill = (text, fields) => text.replace(/\{(\w+)\}/g, (whole, key) => fields[key] ?? whole);

/**
 * A list of facts: [label (rich), value (rich: "μ_l = …"), data-q, plain]: the quantities a section states in
 * words; `plain` for free text the student typed (no notation read in it).
 */
function facts(rows) {
  return element("dl", { className: "report-facts" }, ...rows.filter(Boolean).flatMap(([label, value, q, plain]) => [
    element("dt", { rich: label }),
    element("dd", { ...(plain ? { textContent: value } : { rich: value }), ...(q ? { "data-q": q } : {}) })]));
}

const heading = (text) => element("h3", { rich: text });

function numberWithUnit(value, unit, lang) {
  const text = cellText(value, "number", lang);
  return unit && text !== "—" ? `${text} ${unit}` : text;
}

const degrees = (rad, lang) => `${cellText(rad, "angle", lang)}°`;

function titleBlock(answer, { t, lang, request }) {
  const title = answer.title ?? request?.title ?? {};
  return [facts([
    [t.project_student, title.student || "—", "student", true],
    [t.project_group, title.group || "—", "group", true],
    [t.project_variant, title.variant || "—", "variant", true],
    [t.project_mechanism, answer.structure.formula, "formula"],
    [t.project_n1, cellText(request.omega_mean * RPM_PER_RAD_S, "number", lang), "n1"],
    [t.project_delta, cellText(request.delta, "number", lang), "delta"],
    [t.project_positions, String(answer.positions.count), "positions"],
  ])];
}

function structure(answer, options) {
  const { t } = options;
  const s = answer.structure;
  return [facts([
    [t.editor_n, String(s.n)], [t.editor_p5, String(s.p5)], [t.editor_p4, String(s.p4)],
    [t.editor_mobility, `W = 3·${s.n} − 2·${s.p5} − ${s.p4} = ${s.W}`, "W"],
    [t.editor_formula, s.formula, "structural-formula"],
    [t.editor_class, s.class === 2 ? "II" : "I", "class"],
  ]), renderTable(structureGroups(s, t), options), renderTable(structurePairs(s, t), options)];
}

function kinematics(answer, options) {
  const { t, lang } = options;
  const p = answer.positions;
  const { scales } = answer;
  const output = p.output.kind === "slide" ? fill(t.project_output_slide, { name: p.output.name })
    : fill(t.project_output_link, { name: p.output.name.replace(/^link /, "") });
  const stroke = p.extremes?.stroke;
  const parts = [facts([
    [t.project_output, output, "output"],
    [t.project_phi0_found, `${degrees(p.phi0, lang)} (${p.start === "extreme" ? t.project_start_extreme_short : t.project_start_typed_short})`, "phi0"],
    stroke !== undefined ? [t.project_stroke_H, numberWithUnit(stroke, p.extremes.unit === "rad" ? t.units_rad : t.units_m, lang), "stroke"] : null,
    [t.project_spans, `${degrees(p.spans.working, lang)} / ${degrees(p.spans.idle, lang)}`, "spans"],
    [t.project_time_ratio, cellText(p.time_ratio, "number", lang), "time-ratio"],
    [t.project_scales, [`μ_l = ${cellText(scales.mu_l, "number", lang)} ${t.project_unit_mu_l}`,
      `μ_v = ${cellText(scales.mu_v, "number", lang)} ${t.project_unit_mu_v}`,
      `μ_a = ${cellText(scales.mu_a, "number", lang)} ${t.project_unit_mu_a}`].join("; "), "scales"],
  ]),
  renderTable(positionsTable(answer, t), options),
  figure("plan_of_positions", answer, options),
  figure("output_diagrams", answer, options)];
  for (const number of p.drawn) {
    const row = answer.kinematics[number - 1];
    parts.push(heading(fill(t.project_plans_at, { k: number })),
      figure("velocity_plan", answer, { ...options, position: number }),
      renderTable(planTable(row, "velocity", t), options),
      figure("acceleration_plan", answer, { ...options, position: number }),
      renderTable(planTable(row, "acceleration", t), options));
  }
  parts.push(heading(t.project_points_heading),
    ...answer.kinematics.map((row) => renderTable(pointsTable(row, t), options)),
    renderTable(linksTable(answer, t), options));
  return parts;
}

function dynamics(answer, options) {
  const { t, lang } = options;
  const d = answer.dynamics;
  const fly = d.flywheel;
  return [
    figure("inertia_diagram", answer, options),
    figure("moment_diagram", answer, options),
    figure("work_diagrams", answer, options),
    figure("wittenbauer", answer, options),
    renderTable(flywheelTable(fly, t), options),
    facts([
      [t.project_driving_moment, numberWithUnit(d.driving_moment, t.units_N_m, lang), "driving-moment"],
      [t.project_group_i, numberWithUnit(fly.group_i_existing, t.units_kg_m2, lang), "group-i"],
      [t.project_flywheel_inertia, numberWithUnit(fly.flywheel_inertia, t.units_kg_m2, lang), "flywheel-inertia"],
      [t.project_omega_range, `${numberWithUnit(d.omega_min.omega, "", lang)} … ${numberWithUnit(d.omega_max.omega, t.units_rad_s, lang)}`, "omega-range"],
      [t.project_delta_achieved, cellText(d.delta_achieved, "number", lang), "delta-achieved"],
      [t.project_efficiency, cellText(d.efficiency, "number", lang), "efficiency"],
    ]),
    renderTable(flywheelDimensions(fly, t), options),
    figure("flywheel", answer, options),
    figure("speed_diagrams", answer, options),
    numericsNote(fly.numerics, t), numericsNote(d.numerics, t),
  ];
}

function numericsNote(numerics, t) {
  if (!numerics) return null;
  const said = [numerics.method, numerics.message].filter(Boolean).join("; ");
  return element("p", { className: "hint", textContent: `${t.project_numerics}: ${said}` });
}

function friction(kin, options) {
  const { t, lang } = options;
  const f = kin.friction;
  if (!f) return [element("p", { className: "hint", textContent: t.project_no_friction })];
  return [heading(t.project_with_friction),
    ...f.groups.map((group) => renderTable(groupTable(group, f.force_plans, t, true), options)),
    facts([
      [t.project_Mb_friction, numberWithUnit(f.balancing_moment, t.units_N_m, lang), "Mb-friction"],
      [t.project_Mb_lever_friction, numberWithUnit(f.zhukovsky.moment, t.units_N_m, lang), "Mb-lever-friction"],
      [t.project_efficiency_kinetostatics, cellText(f.efficiency, "number", lang), "efficiency-friction"],
    ]),
    renderTable(leverTable(f.zhukovsky, t, true), options)];
}

function kinetostatics(answer, options) {
  const { t, lang } = options;
  const kin = answer.kinetostatics;
  return [facts([
    [t.project_chosen, String(kin.number), "chosen"],
    [t.project_col_phi, cellText(kin.phi, "angle", lang), "chosen-phi"],
    [t.project_col_omega1, cellText(kin.omega1, "number", lang), "chosen-omega1"],
    [t.project_col_epsilon1, cellText(kin.epsilon1, "number", lang), "chosen-epsilon1"],
  ]),
  renderTable(inertiaTable(kin, t), options),
  figure("groups_with_forces", answer, options),
  ...kin.groups.flatMap((group) => [renderTable(groupTable(group, kin.force_plans, t), options)]),
  figure("force_plans", answer, options),
  facts([
    [t.project_Mb_groups, numberWithUnit(kin.balancing_moment, t.units_N_m, lang), "Mb"],
    [t.project_Mb_lever, numberWithUnit(kin.zhukovsky.moment, t.units_N_m, lang), "Mb-lever"],
    [t.project_difference, `${cellText(kin.zhukovsky.difference_percent, "number", lang)} %`, "difference"],
    [t.project_Mb_reduced, numberWithUnit(kin.reduced_moment, t.units_N_m, lang), "Mb-reduced"],
  ]),
  figure("zhukovsky", answer, options),
  renderTable(leverTable(kin.zhukovsky, t), options),
  ...friction(kin, options),
  heading(t.project_balancing_heading),
  renderTable(balancingTable(answer, t), options),
  numericsNote(kin.numerics, t)];
}

function notices(answer, t) {
  const said = [...(answer.warnings ?? []), ...(answer.notices ?? [])].map((n) => (typeof n === "string" ? n : n.text));
  if (!said.length) return [];
  return [element("div", { className: "report-notices", role: "note" }, element("strong", { textContent: t.warnings }),
    element("ul", {}, ...said.map((text) => element("li", { rich: text }))))];
}

const SECTIONS = { "report-title": titleBlock, "report-structure": structure, "report-kinematics": kinematics,
  "report-dynamics": dynamics, "report-kinetostatics": kinetostatics };

/** Fill the report's sections (their headings are the page's) from answer. options: t, lang, request. */
export function renderReport(report, answer, options) {
  for (const [id, build] of Object.entries(SECTIONS)) {
    const parts = build(answer, options).filter(Boolean);
    if (id === "report-title") parts.push(...notices(answer, options.t));
    report.querySelector(`#${id} .report-body`).replaceChildren(...parts);
  }
  report.querySelector("#report-equations .report-body").replaceChildren(equationsList(answer, options));
  report.querySelector("#report-sheets .report-body").replaceChildren(sheetTools(answer, options));
}

