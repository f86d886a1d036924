/**
 * The design data of the project, as tables to edit: the mechanism's dimensions read-only (changed in the
 * editor: the link goes there with the same m and d), every link's m, centre S (along, across) and J_S; g on
 * or off; the useful loads (forces on sliders: P, k, the working stroke's sense; forces at points of links: the
 * link, the point along and across, P, the direction at a fixed angle or along the link, on the working stroke
 * or always, a diagram's points; moments on links: M, k, sense), added on the places the mechanism has and
 * taken away; the machine: J₁, J_rot, i, n₁ (rpm), [δ], f and the journals' r.
 *
 * options: t, lang, places (the estimate's load_places or null), editorHref, onEdit(path, value),
 * onChange() (a load added or taken away: the data's shape changed, the tables are drawn again by the page).
 */
import { element } from "../../common/view/dom.js";
import { formatQuantity, plainText } from "../../common/view/notation.js";
import { decimalMessage } from "../../common/model/decimal_input.js";
import { dimensionRows } from "../model/dimensions.js";
import { guideLabel } from "../../editor/model/linkage.js";
import { BOUNDS, DEGREES, GRAVITY, addLoad, diagramText, machineRows, readDiagramText, removeLoad } from "../model/design.js";
import { checkInput, choiceInput, decimalInput, inputCell } from "./fields.js";

const fill = (text, fields) => text.replace(/\{(\w+)\}/g, (whole, key) => fields[key] ?? whole);

/** A table: caption, column headers (rich text), rows (<tr>); each cell labelled by its column on a phone. */
function table(id, caption, headers, rows) {
  for (const row of rows) {
    [...row.children].forEach((cell, column) => {
      if (cell.tagName === "TD" && headers[column] && cell.colSpan === 1) {
        cell.prepend(element("span", { className: "cell-label", "aria-hidden": "true", rich: headers[column] }));
      }
    });
  }
  return element("div", { className: "table-scroll" }, element("table", { className: "design-table", id },
    element("caption", { rich: caption }),
    element("thead", {}, element("tr", {}, ...headers.map((text) => element("th", { scope: "col", rich: text })))),
    element("tbody", {}, ...rows)));
}

const rowHead = (text) => element("th", { scope: "row", rich: text });

function dimensionValue(row, lang, t) {
  const written = ({ value, unit }) => (unit === "rad" ? `${formatQuantity(value * DEGREES, lang, 4)}°`
    : `${formatQuantity(value, lang, 4)} ${t.units_m}`);
  const names = { xy: ["x", "y"], guide: ["x", "y", "α"], point: [t.editor_along, t.editor_across],
    link_guide: [t.editor_along, t.editor_across, "α"] }[row.kind];
  if (!names) return `${row.symbol} = ${written(row.values[0])}`;
  return row.values.map((value, k) => `${names[k]} = ${written(value)}`).join(", ");
}

function dimensions(linkage, { t, lang, editorHref }) {
  const rows = dimensionRows(linkage).map((row) => element("tr", {},
    rowHead(fill(t[row.element[0]], row.kind.endsWith("guide")          // a preset's guide by its textbook label
      ? { ...row.element[1], name: guideLabel(row.element[1].name, t) } : row.element[1])),
    element("td", { textContent: row.link ? String(row.link) : "0" }),
    element("td", { className: "dimension", rich: dimensionValue(row, lang, t) })));
  return [table("project-dimensions", t.project_dimensions, ["", t.project_link_number, t.project_value], rows),
    element("p", { className: "hint" }, `${t.project_dimensions_note} `,
      element("a", { href: editorHref, id: "project-dimensions-editor", textContent: t.project_edit_in_editor }))];
}

function linkRows(d, options) {
  const { t } = options;
  return d.masses.links.map((row, k) => {
    const name = `${t.editor_link} ${row.link}`;
    const cell = (value, path, symbol, bounds) => inputCell(decimalInput(value, { ...options, label: `${name}: ${symbol}`,
      path, min: bounds[0], max: bounds[1], onTake: (v) => options.onEdit(path, v) }));
    return element("tr", {}, rowHead(name),
      cell(row.mass ?? 0, `masses.links.${k}.mass`, "m", BOUNDS.mass),
      cell(row.centre?.[0] ?? 0, `masses.links.${k}.centre.0`, t.editor_along, BOUNDS.centre),
      cell(row.centre?.[1] ?? 0, `masses.links.${k}.centre.1`, t.editor_across, BOUNDS.centre),
      cell(row.inertia ?? 0, `masses.links.${k}.inertia`, "J_S", BOUNDS.inertia));
  });
}

function removeButton(list, index, name, { t, d, onChange }) {
  const button = element("button", { type: "button", className: "secondary", textContent: t.editor_load_remove,
    "aria-label": `${t.editor_load_remove}: ${name}`, "data-remove": `${list}.${index}` });
  button.addEventListener("click", () => {
    removeLoad(d, list, index);
    onChange();
  });
  return element("td", {}, button);
}

function numberCell(value, path, label, bounds, options, scale = 1) {
  return inputCell(decimalInput(value, { ...options, label, path, min: bounds[0], max: bounds[1], scale,
    onTake: (v) => options.onEdit(path, v) }));
}

function senseCell(value, path, label, words, options) {
  return inputCell(choiceInput(value === -1 ? -1 : 1, [[1, words[0]], [-1, words[1]]],
    { label, path, onTake: (v) => options.onEdit(path, v) }));
}

/** Forces on sliders and moments on links: place, P (M), k, the working stroke's sense, remove. */
function strokeLoadRows(d, options) {
  const { t } = options;
  const rows = [];
  d.masses.forces.forEach((f, k) => {
    const name = `${t.editor_slide} ${f.joint}`;
    const path = `masses.forces.${k}`;
    rows.push(element("tr", {}, rowHead(name),
      numberCell(f.working, `${path}.working`, `${name}: P`, BOUNDS.P, options),
      numberCell(f.k ?? 1, `${path}.k`, `${name}: k`, BOUNDS.k, options),
      senseCell(f.sense, `${path}.sense`, `${name}: ${t.editor_masses_sense}`,
        [t.editor_sense_slide_plus, t.editor_sense_slide_minus], options),
      removeButton("forces", k, name, options)));
  });
  d.masses.moments.forEach((m, k) => {
    const name = `${t.editor_link} ${m.link}`;
    const path = `masses.moments.${k}`;
    rows.push(element("tr", {}, rowHead(`M: ${name}`),
      numberCell(m.working, `${path}.working`, `${name}: M`, BOUNDS.P, options),
      numberCell(m.k ?? 1, `${path}.k`, `${name}: k`, BOUNDS.k, options),
      senseCell(m.sense, `${path}.sense`, `${name}: ${t.editor_masses_sense}`,
        [t.editor_sense_link_plus, t.editor_sense_link_minus], options),
      removeButton("moments", k, name, options)));
  });
  return rows;
}

/** A point force's diagram: over the stroke or the crank angle (or none), and its points as text. */
function diagramCell(force, path, name, options) {
  const { t, lang } = options;
  const over = force.diagram?.over ?? "none";
  const format = (value) => formatQuantity(value, lang, 4);
  const choices = [["none", t.project_diagram_none], ["stroke", t.project_diagram_stroke], ["phi", t.project_diagram_phi]];
  const text = element("input", { type: "text", size: 16, value: diagramText(force.diagram, format),
    "aria-label": `${name}: ${t.project_diagram_points}`, "data-path": `${path}.diagram.points`,
    placeholder: over === "phi" ? t.project_diagram_placeholder_phi : t.project_diagram_placeholder, hidden: over === "none" });
  const select = choiceInput(over, choices, { label: `${name}: ${t.project_diagram}`, path: `${path}.diagram.over`,
    onTake: (value) => {
      if (value === "none") options.onEdit(`${path}.diagram`, null);
      else options.onEdit(`${path}.diagram`, { over: value, points: value === "phi" ? [[0, 1], [Math.PI, 1]] : [[0, 1], [1, 1]] });
      options.onChange();
    } });
  text.addEventListener("change", () => {
    const read = readDiagramText(text.value, force.diagram?.over, lang);
    const message = read.error === "pairs" ? t.project_diagram_pairs : read.error ? decimalMessage(read.error, text.value, t) : "";
    text.setCustomValidity(message);
    text.title = message;
    text.toggleAttribute("aria-invalid", Boolean(message));
    if (!message && read.points) options.onEdit(`${path}.diagram.points`, read.points);
  });
  return element("td", { className: "diagram-cell" }, select, " ", text);
}

function pointForceRows(d, options) {
  const { t } = options;
  return d.masses.point_forces.map((f, k) => {
    const path = `masses.point_forces.${k}`;
    const name = `${f.name ?? `P${k + 1}`} (${t.editor_link} ${f.link})`;
    const direction = choiceInput(f.direction?.kind ?? "fixed", [["fixed", t.project_direction_fixed], ["link", t.project_direction_link]],
      { label: `${name}: ${t.project_direction}`, path: `${path}.direction.kind`, onTake: (v) => options.onEdit(`${path}.direction.kind`, v) });
    const acts = choiceInput(f.acts ?? "working", [["working", t.project_acts_working], ["always", t.project_acts_always]],
      { label: `${name}: ${t.project_acts}`, path: `${path}.acts`, onTake: (v) => options.onEdit(`${path}.acts`, v) });
    return element("tr", {}, rowHead(name),
      numberCell(f.point?.[0] ?? 0, `${path}.point.0`, `${name}: ${t.editor_along}`, BOUNDS.point, options),
      numberCell(f.point?.[1] ?? 0, `${path}.point.1`, `${name}: ${t.editor_across}`, BOUNDS.point, options),
      numberCell(f.magnitude, `${path}.magnitude`, `${name}: P`, BOUNDS.P, options),
      element("td", { className: "direction-cell" }, direction, " ",
        decimalInput(f.direction?.angle ?? 0, { ...options, label: `${name}: α, °`, path: `${path}.direction.angle`,
          min: BOUNDS.angle[0], max: BOUNDS.angle[1], scale: DEGREES, size: 5,
          onTake: (v) => options.onEdit(`${path}.direction.angle`, v) })),
      inputCell(acts),
      diagramCell(f, path, name, options),
      removeButton("point_forces", k, name, options));
  });
}

/** "Add a load": the free places (sliding pairs, links) and a point force on any moving link. */
function addLoadTools(d, options) {
  const { t, places, linkage, onChange } = options;
  const taken = new Set([...d.masses.forces.map((f) => `force:${f.joint}`), ...d.masses.moments.map((m) => `moment:${m.link}`)]);
  const choices = [
    ...(places?.forces ?? []).map((f) => [`force:${f.joint}`, fill(t.editor_load_on_slide, { pair: f.joint })]),
    ...(places?.moments ?? []).map((m) => [`moment:${m.link}`, fill(t.editor_load_on_link, { link: m.link })]),
  ].filter(([key]) => !taken.has(key));
  const moving = [linkage.input?.link, ...(linkage.groups ?? []).flatMap((g) => g.links)].filter(Boolean);
  choices.push(...moving.map((link) => [`point:${link}`, fill(t.project_load_point_on, { link })]));
  const select = element("select", { id: "project-load-place", "aria-label": t.editor_load_place },
    ...choices.map(([key, text]) => new Option(plainText(text), key)));
  const button = element("button", { type: "button", id: "project-load-add", textContent: t.editor_load_add });
  button.addEventListener("click", () => {
    if (!select.value) return;
    const [kind, where] = [select.value.slice(0, select.value.indexOf(":")), select.value.slice(select.value.indexOf(":") + 1)];
    addLoad(d, places, kind, where);
    onChange();
  });
  return element("p", { className: "load-tools" }, element("label", {}, `${t.editor_load_place} `, select), " ", button);
}

function machine(d, options) {
  const { t } = options;
  const rows = machineRows(d).map(([path, value, key, bounds, scale]) => element("tr", {}, rowHead(t[key]),
    numberCell(value, path, plainText(t[key]), bounds, options, scale)));
  return table("project-machine", t.project_machine, ["", t.project_value], rows);
}

/** Draw the design-data tables of linkage and d (completed, design.js) into container. */
export function renderDesign(container, linkage, d, options) {
  const { t } = options;
  const all = { ...options, d, linkage };
  const gravity = checkInput(d.masses.gravity > 0, { text: t.editor_gravity, path: "masses.gravity", id: "project-gravity",
    onTake: (on) => options.onEdit("masses.gravity", on ? GRAVITY : 0) });
  const strokeLoads = strokeLoadRows(d, all);
  const points = pointForceRows(d, all);
  container.replaceChildren(
    ...dimensions(linkage, all),
    table("project-links", t.editor_masses_links,
      ["", t.editor_masses_m, t.editor_masses_along, t.editor_masses_across, t.editor_masses_JS], linkRows(d, all)),
    element("p", {}, gravity),
    table("project-stroke-loads", t.project_stroke_loads, ["", t.editor_masses_P, "k", t.editor_masses_sense, ""],
      strokeLoads.length ? strokeLoads : [element("tr", {}, element("td", { colSpan: 5, className: "hint", textContent: t.project_loads_none }))]),
    ...(points.length ? [table("project-point-forces", t.project_point_forces,
      ["", t.editor_masses_along, t.editor_masses_across, `P, ${t.units_N}`, t.project_direction_header, t.project_acts, t.project_diagram, ""], points)] : []),
    element("p", { className: "hint", rich: t.project_loads_note }),
    addLoadTools(d, all),
    machine(d, all));
}
