/**
 * The editor's "Masses and loads" table: per moving link its mass, centre S (along, across its line) and J_S;
 * the useful loads on pairs (P, k) and links (M, k); the crank's J₁, the rotor's J, the gear ratio i and the
 * linear motor M₀, b at the motor shaft. Every cell is a decimal input (comma or point); a value typed that is
 * no number is refused beside the cell and not taken. onEdit(path, value) puts a value at its dotted path of
 * the dynamics; the links open the dynamics scenes with the mechanism (hrefs given by the page).
 */
import { element } from "../../common/view/dom.js";
import { formatQuantity } from "../../common/view/notation.js";
import { decimalMessage, parseDecimal } from "../../common/model/decimal_input.js";

function cell(value, path, label, { lang, t, onEdit }) {
  const input = element("input", { type: "text", inputMode: "decimal", size: 7, value: formatQuantity(value, lang, 6),
    "aria-label": label, "data-path": path });
  input.addEventListener("change", () => {
    const read = parseDecimal(input.value, lang);
    input.setCustomValidity(read.error ? decimalMessage(read.error, input.value, t) : "");
    input.title = read.error ? decimalMessage(read.error, input.value, t) : "";
    if (read.error || read.value < 0) return;
    onEdit(path, read.value);
  });
  return element("td", {}, input);
}

const header = (...cells) => element("thead", {}, element("tr", {}, ...cells.map((text) => element("th", { rich: text }))));

/** Render the table of dynamics (null: none yet) into container. */
export function renderMasses(container, dynamics, options) {
  const { t } = options;
  if (!dynamics) {
    container.replaceChildren(element("p", { className: "hint", textContent: t.editor_masses_none }));
    return;
  }
  const { masses, inertias, motor } = dynamics;
  const links = masses.links.map((row, k) => element("tr", {},
    element("th", { scope: "row", textContent: `${t.editor_link} ${row.link}` }),
    cell(row.mass ?? 0, `masses.links.${k}.mass`, `${t.editor_link} ${row.link}: m`, options),
    cell(row.centre?.[0] ?? 0, `masses.links.${k}.centre.0`, `${t.editor_link} ${row.link}: ${t.editor_along}`, options),
    cell(row.centre?.[1] ?? 0, `masses.links.${k}.centre.1`, `${t.editor_link} ${row.link}: ${t.editor_across}`, options),
    cell(row.inertia ?? 0, `masses.links.${k}.inertia`, `${t.editor_link} ${row.link}: J_S`, options)));
  const loads = [
    ...(masses.forces ?? []).map((f, k) => element("tr", {},
      element("th", { scope: "row", textContent: `${t.editor_slide} ${f.joint}` }),
      cell(f.working, `masses.forces.${k}.working`, `${f.joint}: P`, options),
      cell(f.k ?? 1, `masses.forces.${k}.k`, `${f.joint}: k`, options))),
    ...(masses.moments ?? []).map((m, k) => element("tr", {},
      element("th", { scope: "row", textContent: `${t.editor_link} ${m.link}` }),
      cell(m.working, `masses.moments.${k}.working`, `${t.editor_link} ${m.link}: M`, options),
      cell(m.k ?? 1, `masses.moments.${k}.k`, `${t.editor_link} ${m.link}: k`, options))),
  ];
  const machine = [
    ["J1", "inertias.J1", inertias.J1 ?? 0, t.editor_masses_J1],
    ["J_rotor", "inertias.J_rotor", inertias.J_rotor ?? 0, t.editor_masses_rotor],
    ["i", "inertias.gear_ratio", inertias.gear_ratio ?? 1, t.editor_masses_ratio],
    ["M0", "motor.M0", motor.M0 ?? 0, t.editor_masses_M0],
    ["b", "motor.b", motor.b ?? 0, t.editor_masses_b],
  ].map(([, path, value, label]) => element("tr", {}, element("th", { scope: "row", rich: label }),
    cell(value, path, label.replace(/_/g, ""), options)));
  container.replaceChildren(
    element("div", { className: "table-scroll" }, element("table", { className: "editor-masses", id: "editor-masses-links" },
      element("caption", { textContent: t.editor_masses_links }),
      header("", t.editor_masses_m, t.editor_masses_along, t.editor_masses_across, t.editor_masses_JS),
      element("tbody", {}, ...links))),
    loads.length ? element("div", { className: "table-scroll" }, element("table", { className: "editor-masses" },
      element("caption", { textContent: t.editor_masses_loads }),
      header("", t.editor_masses_P, "k"), element("tbody", {}, ...loads))) : "",
    element("div", { className: "table-scroll" }, element("table", { className: "editor-masses" },
      element("caption", { textContent: t.editor_masses_machine }), element("tbody", {}, ...machine))));
}

/** The links to the dynamics scenes (hrefs: scene id → address, or null while there is nothing to open). */
export function renderOpenLinks(container, hrefs, scenes) {
  container.replaceChildren(...scenes.map(({ scene, title }) => hrefs
    ? element("a", { className: "button secondary", href: hrefs[scene], "data-scene": scene, textContent: title })
    : element("span", { className: "button secondary disabled", "aria-disabled": "true", textContent: title })));
}
