/**
 * The report's tables as rows of the answer's own values (POST /api/v1/course-project), before any formatting:
 * each table {id, caption, columns: [{header, kind}], rows: [{cells, chosen}]}; the view writes the cells in the
 * page's language (view/report_table.js) and the CSV file takes the same rows (model/csv.js). Headers and
 * captions are interface texts in the notation markup. Nothing is computed here: every number is the server's.
 *
 * Column kinds: "int"; "number" (SI, written with 4 significant digits); "angle" (rad, written in degrees);
 * "text" (words or names in the notation markup: "F_in4", "πa3 = πc + n_A3C + τ_A3C").
 */
import { symbolOf } from "../../forces_friction/model/group_free_body.js";

const fill = (text, fields) => text.replace(/\{(\w+)\}/g, (whole, key) => fields[key] ?? whole);
const column = (header, kind = "number") => ({ header, kind });
const SUB = "₀₁₂₃₄₅₆₇₈₉";

/** "II₃(2,3)": a group by Artobolevsky's kind number and its links. */
export const groupName = (g) => `II${String(g.kind_number).replace(/\d/g, (d) => SUB[d])}(${g.links.join(",")})`;

export function structureGroups(structure, t) {
  return { id: "table-groups", caption: t.project_groups, columns: [column(t.project_col_group, "text"),
    column(t.project_col_kind, "text"), column(t.project_col_links, "text"), column(t.project_col_attached, "text")],
  rows: structure.groups.map((g) => ({ cells: [groupName(g), g.kind, g.links.join(", "), g.attached_to.join(", ")] })) };
}

export function structurePairs(structure, t) {
  return { id: "table-pairs", caption: t.project_pairs, columns: [column(t.project_col_pair, "text"),
    column(t.project_col_pair_kind, "text"), column(t.project_col_links, "text")],
  rows: structure.pairs.map((p) => ({ cells: [p.name, p.kind === "P" ? t.project_pair_prismatic : t.project_pair_revolute,
    p.links.join(", ")] })) };
}

const stroke = (working, t) => (working ? t.project_stroke_working : t.project_stroke_idle);

/** The positions: number, φ, the stroke, ω₁, ε₁ at the real motion. */
export function positionsTable(answer, t) {
  const chosen = answer.positions.chosen;
  return { id: "table-positions", caption: t.project_positions_table, columns: [column("№", "int"),
    column(t.project_col_phi, "angle"), column(t.project_col_stroke, "text"), column(t.project_col_omega1),
    column(t.project_col_epsilon1)],
  rows: answer.kinematics.map((row) => ({ chosen: row.number === chosen,
    cells: [row.number, row.phi, stroke(row.working, t), row.omega1, row.epsilon1] })) };
}

/** One position's points: v and its plan vector pv in mm at μ_v, a and πa in mm at μ_a. */
export function pointsTable(row, t) {
  return { id: `table-points-${row.number}`, caption: fill(t.project_points_caption, { k: row.number }),
    columns: [column(t.project_col_point, "text"), column(t.project_col_v), column(t.project_col_v_mm),
      column(t.project_col_a), column(t.project_col_a_mm)],
    rows: Object.entries(row.points).map(([name, p]) => ({ cells: [name, p.v.value, p.v.mm, p.a.value, p.a.mm] })) };
}

/** The links' ω and ε at every position (one column pair per moving link). */
export function linksTable(answer, t) {
  const links = Object.keys(answer.kinematics[0]?.links ?? {});
  return { id: "table-links", caption: t.project_links_caption, columns: [column("№", "int"), column(t.project_col_phi, "angle"),
    ...links.flatMap((k) => [column(`ω_${k}, ${t.units_rad_s}`), column(`ε_${k}, ${t.units_rad_s2}`)])],
  rows: answer.kinematics.map((row) => ({ chosen: row.number === answer.positions.chosen,
    cells: [row.number, row.phi, ...links.flatMap((k) => [row.links[k].omega, row.links[k].epsilon])] })) };
}

/** A drawn position's plan equations ("velocity" or "acceleration"): each vector's value and length in mm. */
export function planTable(row, kind, t) {
  const unit = kind === "velocity" ? t.project_unit_m_s : t.project_unit_m_s2;
  const rows = [];
  for (const equation of row[kind]) {                   // the equation written once, on its first vector's row
    equation.vectors.forEach((v, k) => rows.push({ cells: [k ? "" : equation.equation, v.name, v.value, v.mm] }));
    rows.push({ cells: ["", `${equation.target} (${t.project_analytic})`, equation.analytic.value, equation.analytic.mm] });
  }
  return { id: `table-${kind}-plan-${row.number}`, caption: fill(t[`project_${kind}_plan_caption`], { k: row.number }),
    columns: [column(t.project_col_equation, "text"), column(t.project_col_vector, "text"),
      column(`${t.project_col_value}, ${unit}`), column(t.project_col_mm)], rows };
}

/** The flywheel by each method: I_I, the flywheel's share, ΔT_I max, the δ it gives. */
export function flywheelTable(flywheel, t) {
  return { id: "table-flywheel", caption: t.project_flywheel_caption, columns: [column(t.project_col_method, "text"),
    column(t.project_col_inertia_I), column(t.project_col_inertia_fly), column(t.project_col_energy_swing),
    column(t.project_col_delta)],
  rows: flywheel.methods.map((m) => ({ chosen: m.method === "exact", cells: [t[`project_method_${m.method}`] ?? m.method,
    m.inertia, m.additional, m.energy_swing, m.delta_achieved] })) };
}

/** The flywheel's dimensions: a solid disk (exact and by the printed constants), a rim. */
export function flywheelDimensions(flywheel, t) {
  const rows = [["project_disk", flywheel.disk], ["project_disk_printed", flywheel.disk_as_printed],
    ["project_rim", flywheel.rim]].filter(([, shape]) => shape)
    .map(([key, shape]) => ({ cells: [t[key], shape.diameter, shape.width ?? shape.section_side ?? null, shape.mass] }));
  return { id: "table-flywheel-size", caption: t.project_flywheel_size, columns: [column(t.project_col_shape, "text"),
    column(t.project_col_diameter), column(t.project_col_width), column(t.project_col_mass)], rows };
}

/**
 * A load's symbol as the textbook and the drawings write it (forces_friction/model/group_free_body.js): G_4, Φ_4,
 * M_Φ4, R_34; a useful force with its place, P_{E/ram}.
 */
export function loadSymbol(name, kind) {
  if (kind === "useful" && name.startsWith("F_")) return `P_{${name.slice(2)}}`;
  return symbolOf(name, kind === "reaction" ? "" : kind ?? "");
}

/** The inertia loads at the chosen position: Φ, its magnitude, M_Φ and the offset h of the resultant. */
export function inertiaTable(kinetostatics, t) {
  const N = t.units_N;
  return { id: "table-inertia", caption: t.project_inertia_caption, columns: [column(t.project_col_link, "int"),
    column(`Φ_x, ${N}`), column(`Φ_y, ${N}`), column(`|Φ|, ${N}`), column(`M_Φ, ${t.units_N_m}`), column(`h, ${t.units_m}`)],
  rows: kinetostatics.inertia.map((row) => ({ cells: [row.link, row.force[0], row.force[1], row.magnitude, row.moment,
    row.offset] })) };
}

/** The magnitudes of one analysis's force-plan vectors by name (the reactions' |R|, as the server gives them). */
function magnitudes(plans) {
  return new Map((plans ?? []).flatMap((plan) => plan.vectors.map((v) => [`${plan.group}:${v.name}`, v.magnitude])));
}

/**
 * One group's free body: its loads (gravity, inertia, useful) and the reactions in its pairs, x, y and the
 * magnitude where the force plan gives it; `friction`: the analysis with friction (its ids differ).
 */
export function groupTable(group, plans, t, friction = false) {
  const sizes = magnitudes(plans);
  const rows = [...group.loads.map((load) => ({ cells: [loadSymbol(load.name, load.kind), t[`project_load_${load.kind}`] ?? load.kind, load.link,
    load.force?.[0] ?? null, load.force?.[1] ?? null, sizes.get(`${group.group}:${load.name}`) ?? null, load.moment ?? null] })),
  ...group.reactions.map((r) => ({ cells: [loadSymbol(r.name, "reaction"), `${t.project_load_reaction} ${r.pair}`, r.link, r.force[0], r.force[1],
    r.magnitude ?? sizes.get(`${group.group}:${r.name}`) ?? null, r.moment ?? null] }))];
  const title = group.kind === "crank" ? t.project_crank_body : `${groupName({ kind_number: KIND_NUMBERS[group.kind], links: group.links })} ${group.kind}`;
  return { id: `table-group-${friction ? "f-" : ""}${group.group}`, caption: fill(t.project_group_caption, { group: title }),
    columns: [column(t.project_col_force, "text"), column(t.project_col_kind, "text"), column(t.project_col_link, "int"),
      column(`x, ${t.units_N}`), column(`y, ${t.units_N}`), column(`|F|, ${t.units_N}`), column(`M, ${t.units_N_m}`)], rows };
}

const KIND_NUMBERS = { RRR: 1, RRP: 2, RPR: 3, PRP: 4, RPP: 5 };

/**
 * Zhukovsky's lever: each force's arm on the turned plan (mm) and its moment about the pole (N·mm), a couple's
 * moment, each row's share of M_b; last the balancing force F_b at the crank pin.
 */
export function leverTable(zhukovsky, t, friction = false) {
  const balancing = zhukovsky.balancing_force;
  return { id: `table-lever${friction ? "-friction" : ""}`, caption: friction ? t.project_lever_friction_caption : t.project_lever_caption,
    columns: [column(t.project_col_force, "text"), column(t.project_col_link, "int"), column(t.project_col_arm),
      column(t.project_col_lever_moment), column(t.project_col_share)],
    rows: [...zhukovsky.lever.map((row) => ({ cells: [loadSymbol(row.name, row.kind), row.link ?? null, row.arm ?? null, row.moment, row.share ?? null] })),
      ...(balancing ? [{ cells: [`${t.project_balancing_force} (${balancing.joint})`, 1, balancing.arm, balancing.moment, null] }] : [])] };
}

/** The balancing moment at every position: by the groups, by the lever, by the reduced equation, with friction. */
export function balancingTable(answer, t) {
  const friction = answer.table.some((row) => row.M_b_friction !== null);
  return { id: "table-balancing", caption: t.project_balancing_caption, columns: [column("№", "int"),
    column(t.project_col_phi, "angle"), column(t.project_col_omega1), column(t.project_col_epsilon1),
    column(t.project_col_Mb_groups), column(t.project_col_Mb_lever), column(t.project_col_Mb_reduced),
    column(t.project_col_difference),
    ...(friction ? [column(t.project_col_Mb_friction), column(t.project_col_Mb_lever_friction)] : []),
    column(t.project_col_useful)],
  rows: answer.table.map((row) => ({ chosen: row.number === answer.kinetostatics.number,
    cells: [row.number, row.phi, row.omega1, row.epsilon1, row.M_b_groups, row.M_b_lever, row.M_b_reduced,
      row.difference_percent, ...(friction ? [row.M_b_friction, row.M_b_lever_friction] : []), row.useful_load] })) };
}
