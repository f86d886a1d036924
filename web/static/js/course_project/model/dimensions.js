/**
 * The mechanism's dimensions as rows of a read-only table (they are edited in the editor): the frame's joints
 * and guides, the crank's length, each group's lengths (RRR l_BC, l_DC; RRP l_BC; RPR the slot's offset e; RPP
 * the slot's angle α) and the points and guides fixed on the links (along, across their link). Lengths in m,
 * angles in rad (the view writes degrees). No DOM.
 *
 * A row: {element, link, symbol, values: [{value, unit: "m"|"rad"}]}; `symbol` in the notation markup
 * ("l_{OA}"), `element` a key of the interface texts with its fields ({name}, {kind}).
 */

const length = (value) => ({ value, unit: "m" });
const angle = (value) => ({ value, unit: "rad" });

function attachedRows(element) {
  const rows = [];
  for (const [name, p] of Object.entries(element.points ?? {})) {
    rows.push({ element: ["project_dim_point", { name }], link: p.link, kind: "point", values: [length(p.along ?? 0), length(p.across ?? 0)] });
  }
  for (const [name, g] of Object.entries(element.new_guides ?? {})) {
    rows.push({ element: ["project_dim_guide", { name }], link: g.link, kind: "link_guide",
      values: [length(g.along ?? 0), length(g.across ?? 0), angle(g.angle ?? 0)] });
  }
  return rows;
}

/** The rows of linkage's dimensions, in the order the mechanism is built. */
export function dimensionRows(linkage) {
  const rows = [];
  for (const [name, xy] of Object.entries(linkage.frame?.joints ?? {})) {
    rows.push({ element: ["project_dim_frame_joint", { name }], link: 0, kind: "xy", values: [length(xy[0]), length(xy[1])] });
  }
  for (const [name, g] of Object.entries(linkage.frame?.guides ?? {})) {
    const through = typeof g.through === "string" ? linkage.frame.joints[g.through] : g.through ?? [0, 0];
    rows.push({ element: ["project_dim_frame_guide", { name }], link: 0, kind: "guide",
      values: [length(through[0]), length(through[1]), angle(g.angle ?? 0)] });
  }
  const crank = linkage.input;
  if (crank) {
    rows.push({ element: ["project_dim_crank", {}], link: crank.link, kind: "length", symbol: `l_{${crank.pivot}${crank.joint}}`,
      values: [length(crank.length)] });
    rows.push(...attachedRows(crank));
  }
  for (const group of linkage.groups ?? []) {
    const [i, j] = group.links;
    const [b, d] = group.outer ?? [];
    const at = { kind: group.kind };
    if (group.kind === "RRR") {
      rows.push({ element: ["project_dim_group", at], link: i, kind: "length", symbol: `l_{${b}${group.inner}}`, values: [length(group.lengths[0])] });
      rows.push({ element: ["project_dim_group", at], link: j, kind: "length", symbol: `l_{${d}${group.inner}}`, values: [length(group.lengths[1])] });
    } else if (group.kind === "RRP") {
      rows.push({ element: ["project_dim_group", at], link: i, kind: "length", symbol: `l_{${b}${group.inner}}`, values: [length(group.length)] });
    } else if (group.kind === "RPR") {
      rows.push({ element: ["project_dim_group", at], link: j, kind: "length", symbol: "e", values: [length(group.offset ?? 0)] });
    } else if (group.kind === "RPP") {
      rows.push({ element: ["project_dim_group", at], link: j, kind: "angle", symbol: "α", values: [angle(group.angle ?? Math.PI / 2)] });
    }
    rows.push(...attachedRows(group));
  }
  return rows;
}
