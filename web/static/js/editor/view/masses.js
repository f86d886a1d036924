/**
 * The editor's "Masses and loads" table: per moving link its mass, centre S (along, across its line) and J_S;
 * the useful loads on sliding pairs (P, k, the working stroke's sense) and links (M, k, sense), and forces at
 * points of links (the point along and across the link, P, its angle α in degrees from +x or from the link, on the
 * working stroke or always), added on the places the mechanism has and removed; gravity on or off; the crank's J₁,
 * the rotor's J, the gear ratio i and the linear motor M₀, b at the motor shaft. Every number cell is a decimal
 * input (comma or point); a value typed that is no number is refused beside the cell and not taken.
 * onEdit(path, value) puts a value (SI: an angle in rad) at its dotted path of the dynamics; the links open the
 * dynamics scenes with the mechanism (hrefs given by the page).
 */
import { element } from "../../common/view/dom.js";
import { slideLabel } from "../model/linkage.js";
import { formatQuantity, plainText } from "../../common/view/notation.js";
import { decimalMessage, parseDecimal } from "../../common/model/decimal_input.js";
import { GRAVITY, freePlaces, pointPlaces } from "../model/dynamics.js";

const DEG = Math.PI / 180;
const NAME_LENGTH = 8;                   // a point force's label, characters at most (the API's)

/**
 * A decimal input. Its text is taken on "change" and again on leaving it (an input redrawn while typed into gets
 * the typed text back, and the browser's "change" would not see it as changed): the text taken last is kept
 * in data-taken, so each text is taken once. A negative number is refused unless the input is ``signed``; it
 * shows and takes the value in ``unit`` (DEG: degrees shown, radians put).
 */
function decimalInput(value, path, label, { lang, t, onEdit }, { signed = false, unit = 1 } = {}) {
  const shown = formatQuantity(value / unit, lang, 6);
  const input = element("input", { type: "text", inputMode: "decimal", size: 7, value: shown,
    "aria-label": label, "data-path": path, "data-taken": shown });
  const take = () => {
    if (input.value === input.dataset.taken) return;
    input.dataset.taken = input.value;
    const read = parseDecimal(input.value, lang);
    input.setCustomValidity(read.error ? decimalMessage(read.error, input.value, t) : "");
    input.title = read.error ? decimalMessage(read.error, input.value, t) : "";
    if (read.error || (read.value < 0 && !signed)) return;
    onEdit(path, read.value * unit);
  };
  input.addEventListener("change", take);
  input.addEventListener("blur", take);
  return input;
}

/** A decimal cell of a table (``decimalInput`` in a td). */
const cell = (...args) => element("td", {}, decimalInput(...args));

/** The working stroke's sense (+1, −1) of a load as a choice said in words. */
function senseCell(sense, path, label, words, { onEdit }) {
  const select = element("select", { "aria-label": label, "data-path": path },
    ...[[1, words[0]], [-1, words[1]]].map(([value, text]) => new Option(plainText(text), String(value))));
  select.value = String(sense === -1 ? -1 : 1);
  select.addEventListener("change", () => onEdit(path, Number(select.value)));
  return element("td", {}, select);
}

function removeButton(list, index, label, { t, onRemoveLoad }) {
  const button = element("button", { type: "button", className: "secondary", textContent: t.editor_load_remove,
    "aria-label": `${t.editor_load_remove}: ${label}`, "data-remove": `${list}.${index}` });
  button.addEventListener("click", () => onRemoveLoad(list, index));
  return button;
}

const removeCell = (...args) => element("td", {}, removeButton(...args));

/**
 * A table of rows under column headers. Each data cell also carries its column's header as a label of its own
 * (hidden from assistive technology: the inputs are labelled), which a phone shows when the rows are laid out
 * as cards instead of columns (editor.css): five columns of inputs do not fit 390 px.
 */
function columnTable(id, caption, headers, rows) {
  for (const row of rows) {
    [...row.children].forEach((child, column) => {
      if (child.tagName === "TD" && headers[column] && child.colSpan === 1) {
        child.prepend(element("span", { className: "cell-label", "aria-hidden": "true", rich: headers[column] }));
      }
    });
  }
  return element("div", { className: "table-scroll" }, element("table", { className: "editor-masses by-column", id },
    element("caption", { textContent: caption }),
    element("thead", {}, element("tr", {}, ...headers.map((text) => element("th", { rich: text })))),
    element("tbody", {}, ...rows)));
}

/** One load's row: its place, P or M (symbol), k, the working stroke's sense (words: + and −) and "remove". */
function loadRow(list, load, k, place, symbol, words, options) {
  const path = `masses.${list}.${k}`;
  return element("tr", {}, element("th", { scope: "row", textContent: place }),
    cell(load.working, `${path}.working`, `${place}: ${symbol}`, options),
    cell(load.k ?? 1, `${path}.k`, `${place}: k`, options),
    senseCell(load.sense, `${path}.sense`, `${place}: ${options.t.editor_masses_sense}`, words, options),
    removeCell(list, k, place, options));
}

/** The loads' rows: the forces on sliding pairs, then the moments on links. */
function loadRows(masses, options) {
  const { t } = options;
  const slideWords = [t.editor_sense_slide_plus, t.editor_sense_slide_minus];
  const linkWords = [t.editor_sense_link_plus, t.editor_sense_link_minus];
  return [
    ...(masses.forces ?? []).map((f, k) => loadRow("forces", f, k, `${t.editor_slide} ${slideLabel(f.joint, t)}`, "P",
      slideWords, options)),
    ...(masses.moments ?? []).map((m, k) => loadRow("moments", m, k, `${t.editor_link} ${m.link}`, "M", linkWords, options)),
  ];
}

/** A choice among (value, words) pairs, put at path on "change". */
function choice(value, path, label, choices, { onEdit }) {
  const select = element("select", { "aria-label": label, "data-path": path },
    ...choices.map(([key, text]) => new Option(plainText(text), key)));
  select.value = value;
  select.addEventListener("change", () => onEdit(path, select.value));
  return select;
}

/** A point force's name (a label for drawings, up to NAME_LENGTH characters; empty: none). */
function nameInput(name, path, label, { onEdit }) {
  const input = element("input", { type: "text", size: 4, maxLength: NAME_LENGTH, value: name ?? "",
    "aria-label": label, "data-path": path, "data-taken": name ?? "" });
  input.addEventListener("change", () => {
    input.dataset.taken = input.value;
    onEdit(path, input.value.trim() || undefined);
  });
  return input;
}

/**
 * A control with its words before it: an input as one whole (editor.css .field), a choice beside its words (a
 * .field would put its select under them); the fields wrap between one another.
 */
const field = (words, control) => control.tagName === "SELECT" ? element("label", {}, `${words} `, control)
  : element("label", { className: "field" }, words, control);

/**
 * Each force at a point as a group of fields that wrap in the panel's width (nine columns would not fit it): the
 * name, the point along and across the link (m), P (N), whether α is from +x or from the link, α in degrees, on
 * the working stroke or always, and "remove".
 */
function pointForces(masses, options) {
  const { t } = options;
  return (masses.point_forces ?? []).map((f, k) => {
    const path = `masses.point_forces.${k}`;
    const place = `${t.editor_point_force} ${k + 1}, ${t.editor_link} ${f.link}`;
    const direction = f.direction ?? { kind: "fixed", angle: 0 };
    const fields = [
      field(t.editor_point_name, nameInput(f.name, `${path}.name`, `${place}: ${t.editor_point_name}`, options)),
      field(t.editor_point_along, decimalInput(f.point?.[0] ?? 0, `${path}.point.0`, `${place}: ${t.editor_along}`,
        options, { signed: true })),
      field(t.editor_point_across, decimalInput(f.point?.[1] ?? 0, `${path}.point.1`,
        `${place}: ${t.editor_across}`, options, { signed: true })),
      field(t.editor_point_P, decimalInput(f.magnitude ?? 0, `${path}.magnitude`, `${place}: P`, options)),
      field(t.editor_point_angle, decimalInput(direction.angle ?? 0, `${path}.direction.angle`, `${place}: α`,
        options, { signed: true, unit: DEG })),
      field(t.editor_point_direction, choice(direction.kind, `${path}.direction.kind`,
        `${place}: ${t.editor_point_direction}`, [["fixed", t.editor_direction_fixed], ["link", t.editor_direction_link]],
        options)),
      field(t.editor_point_acts, choice(f.acts ?? "working", `${path}.acts`, `${place}: ${t.editor_point_acts}`,
        [["working", t.editor_acts_working], ["always", t.editor_acts_always]], options)),
      removeButton("point_forces", k, place, options),
    ];
    return element("fieldset", { className: "editor-masses editor-point-force", "data-point-force": String(k) },
      element("legend", { textContent: place }), ...fields.flatMap((item) => [item, " "]));
  });
}

/**
 * "Add a load": a choice of the places without one (a slider's pair, a link) and of the links a force at a point
 * may go on, and its button.
 */
function addLoadTools(dynamics, { t, places, onAddLoad }) {
  const free = [...freePlaces(dynamics, places), ...pointPlaces(places)];
  const words = (place) => ({ force: () => t.editor_load_on_slide.replace("{pair}", slideLabel(place.joint, t)),
    moment: () => t.editor_load_on_link.replace("{link}", String(place.link)),
    point: () => t.editor_load_at_point.replace("{link}", String(place.link)) })[place.kind]();
  const select = element("select", { id: "editor-load-place", "aria-label": t.editor_load_place },
    ...free.map((place) => new Option(words(place), place.key)));
  const button = element("button", { type: "button", id: "editor-load-add", textContent: t.editor_load_add,
    disabled: !free.length });
  button.addEventListener("click", () => select.value && onAddLoad(select.value));
  return element("p", { className: "editor-load-tools" },
    element("label", {}, `${t.editor_load_place} `, select), " ", button);
}

function gravityTool(masses, { t, onEdit }) {
  const box = element("input", { type: "checkbox", id: "editor-gravity", checked: (masses.gravity ?? GRAVITY) > 0 });
  box.addEventListener("change", () => onEdit("masses.gravity", box.checked ? GRAVITY : 0));
  return element("p", { className: "editor-gravity" }, element("label", {}, box, " ", element("span", { rich: t.editor_gravity })));
}

/**
 * The input being typed into (its label, text, caret) if it is in container, to be given back after a redraw;
 * null otherwise.
 */
function typing(container) {
  const active = document.activeElement;
  if (!(active instanceof HTMLInputElement) || active.type !== "text" || !container.contains(active)) return null;
  return { label: active.getAttribute("aria-label"), text: active.value, typed: active.value !== active.dataset.taken,
    start: active.selectionStart, end: active.selectionEnd };
}

function giveBack(container, was) {
  if (!was) return;
  const input = [...container.querySelectorAll("input[type=text]")].find((i) => i.getAttribute("aria-label") === was.label);
  if (!input) return;
  if (was.typed) input.value = was.text;
  input.focus();
  input.setSelectionRange(Math.min(was.start, input.value.length), Math.min(was.end, input.value.length));
}

/**
 * Render the table of dynamics (null: none yet) into container; a cell being typed into keeps its text, caret
 * and focus. Options: t, lang; places (the estimate's load_places, or null); onEdit(path, value);
 * onAddLoad(placeKey); onRemoveLoad(list, index).
 */
export function renderMasses(container, dynamics, options) {
  const { t } = options;
  const was = typing(container);
  if (!dynamics) {
    container.replaceChildren(element("p", { className: "hint", textContent: t.editor_masses_none }));
    return;
  }
  const { masses, inertias, motor } = dynamics;
  const links = masses.links.map((row, k) => element("tr", {},
    element("th", { scope: "row", textContent: `${t.editor_link} ${row.link}` }),
    cell(row.mass ?? 0, `masses.links.${k}.mass`, `${t.editor_link} ${row.link}: ${t.editor_say_mass}`, options),
    cell(row.centre?.[0] ?? 0, `masses.links.${k}.centre.0`, `${t.editor_link} ${row.link}: ${t.editor_along}`, options),
    cell(row.centre?.[1] ?? 0, `masses.links.${k}.centre.1`, `${t.editor_link} ${row.link}: ${t.editor_across}`, options),
    cell(row.inertia ?? 0, `masses.links.${k}.inertia`, `${t.editor_link} ${row.link}: ${t.editor_say_inertia}`, options)));
  const loads = loadRows(masses, options);
  const points = pointForces(masses, options);
  const machine = [
    ["inertias.J1", inertias.J1 ?? 0, t.editor_masses_J1],
    ["inertias.J_rotor", inertias.J_rotor ?? 0, t.editor_masses_rotor],
    ["inertias.gear_ratio", inertias.gear_ratio ?? 1, t.editor_masses_ratio],
    ["motor.M0", motor.M0 ?? 0, t.editor_masses_M0],
    ["motor.b", motor.b ?? 0, t.editor_masses_b],
  ].map(([path, value, label]) => element("tr", {}, element("th", { scope: "row", rich: label }),
    cell(value, path, label.replace(/_/g, ""), options)));
  container.replaceChildren(
    columnTable("editor-masses-links", t.editor_masses_links,
      ["", t.editor_masses_m, t.editor_masses_along, t.editor_masses_across, t.editor_masses_JS], links),
    gravityTool(masses, options),
    columnTable("editor-masses-loads", t.editor_masses_loads, ["", t.editor_masses_P, "k", t.editor_masses_sense, ""],
      loads.length ? loads
        : [element("tr", {}, element("td", { colSpan: 5, className: "hint", textContent: t.editor_loads_none }))]),
    element("p", { className: "hint", rich: t.editor_loads_note }),
    ...(points.length ? [element("div", { id: "editor-masses-points" },
      element("p", { className: "editor-points-caption" }, element("strong", { textContent: t.editor_points_caption })),
      ...points, element("p", { className: "hint", rich: t.editor_points_note }))] : []),
    addLoadTools(dynamics, options),
    element("div", { className: "table-scroll" }, element("table", { className: "editor-masses" },
      element("caption", { textContent: t.editor_masses_machine }), element("tbody", {}, ...machine))));
  giveBack(container, was);
}

/**
 * The links to the dynamics scenes (hrefs: scene id → address, or null while there is nothing to open). Links
 * already there get their new addresses in place: every edit and answer rewrites them, and a link replaced under
 * the pointer between its press and release is never clicked, one replaced under the keyboard loses the focus.
 */
export function renderOpenLinks(container, hrefs, scenes) {
  const links = [...container.children];
  const kept = hrefs && links.length === scenes.length
    && links.every((link, k) => link.tagName === "A" && link.dataset.scene === scenes[k].scene);
  if (kept) {
    for (const link of links) link.href = hrefs[link.dataset.scene];
    return;
  }
  container.replaceChildren(...scenes.map(({ scene, title }) => hrefs
    ? element("a", { className: "button secondary", href: hrefs[scene], "data-scene": scene, textContent: title })
    : element("span", { className: "button secondary disabled", "aria-disabled": "true", textContent: title })));
}
