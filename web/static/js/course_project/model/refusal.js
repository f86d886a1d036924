/**
 * A refusal of the course project (HTTP 422) as a sentence naming the field in the student's words: the
 * field's dotted path (loc without "body"), the words for it (a link's mass, a load, a setting), and whether
 * it is the mechanism that cannot turn fully (linkage.groups.k: no report then, only the server's sentence).
 * No DOM.
 */
const fill = (text, fields) => text.replace(/\{(\w+)\}/g, (whole, key) => fields[key] ?? whole);

/** The refused field's dotted path ("masses.links.1.mass"), "" for the body as a whole. */
export function refusedPath(error) {
  const loc = (error.loc ?? []).map(String);
  const rest = loc[0] === "body" ? loc.slice(1) : loc;
  return (rest[0] === "params" ? rest.slice(1) : rest).join(".");
}

/** Whether the refusal is about the mechanism itself (it cannot be assembled or turn fully): no report. */
export const refusesMechanism = (error) => refusedPath(error).startsWith("linkage");

const MACHINE = { "inertias.J1": "project_J1", "inertias.J_rotor": "project_J_rotor", "inertias.gear_ratio": "project_gear_ratio",
  omega_mean: "project_n1", delta: "project_delta", "masses.friction": "project_friction",
  "masses.pair_radius": "project_pair_radius", "masses.gravity": "editor_gravity", positions: "project_positions",
  start: "project_phi0", chosen: "project_chosen", drawn: "project_drawn", output: "project_output",
  "title.student": "project_student", "title.group": "project_group", "title.variant": "project_variant" };

const LISTS = { links: "editor_masses_links", forces: "project_stroke_loads", moments: "project_stroke_loads",
  point_forces: "project_point_forces" };

/** The refused field in words, from the request the page sent (to name a link or a slider by its own name). */
export function fieldWords(path, request, t) {
  const keys = path.split(".");
  for (let n = keys.length; n > 0; n -= 1) {
    const head = keys.slice(0, n).join(".");
    if (MACHINE[head]) return t[MACHINE[head]];
  }
  const [top, list, index, ...rest] = keys;
  if (top === "masses" && index === undefined) return t[LISTS[list]] ?? t.project_design_data;
  const item = request?.masses?.[list]?.[Number(index)];
  const tail = rest.length ? ` (${rest.join(".")})` : "";
  if (top === "masses" && list === "links") return `${t.editor_link} ${item?.link ?? Number(index) + 1}${tail}`;
  if (top === "masses" && list === "forces") return `${t.editor_slide} ${item?.joint ?? ""}${tail}`;
  if (top === "masses" && list === "moments") return `M: ${t.editor_link} ${item?.link ?? ""}${tail}`;
  if (top === "masses" && list === "point_forces") {
    return `${fill(t.project_point_force_name, { k: Number(index) + 1, link: item?.link ?? "" })}${tail}`;
  }
  if (top === "linkage" && list === "groups") return fill(t.project_field_group, { group: Number(index) + 1 });
  return path || t.project_field_request;
}

/** The sentence shown for a refusal: the field in words and the reason (reason: the translated server's). */
export function refusalSentence(error, reason, request, t) {
  if (refusesMechanism(error) || error.code === "server" || error.code === "network") return reason;
  return fill(t.project_refused_field, { field: fieldWords(refusedPath(error), request, t), reason });
}
