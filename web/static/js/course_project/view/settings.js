/**
 * The project's settings and its title block, as inputs: the student, the group, the variant; the number of
 * positions (8, 12, 24); the start (the working stroke's extreme position found by the app, or φ₀ typed in
 * degrees); the position of the force analysis (the one with the largest useful load, or 1…N); the positions
 * whose plans are drawn (none ticked: the chosen one). onSettings(change) gets a function that changes the
 * settings (the page then writes the address and asks the server again).
 */
import { element } from "../../common/view/dom.js";
import { POSITION_CHOICES, TITLE_FIELDS, TITLE_LENGTH, withPositions } from "../model/address.js";
import { DEGREES } from "../model/design.js";
import { choiceInput, decimalInput, textInput } from "./fields.js";

/** The title block's inputs. */
export function renderTitleInputs(container, settings, { t, onSettings }) {
  container.replaceChildren(element("div", { className: "title-inputs" }, ...TITLE_FIELDS.map((field) => textInput(
    settings.title[field], { label: t[`project_${field}`], path: `title.${field}`, id: `project-${field}`,
      maxLength: TITLE_LENGTH, onTake: (text) => onSettings((s) => { s.title[field] = text; }) }))));
}

/**
 * The settings' inputs; found: what the app found where the student left it to the app (the answer's phi0, chosen,
 * output {kind, name}); outputs: the outputs to choose from (model/address.js outputChoices).
 */
export function renderSettings(container, settings, found, outputs, { t, lang, onSettings }) {
  const n = settings.positions;
  const positions = choiceInput(n, POSITION_CHOICES.map((k) => [k, String(k)]), { label: t.project_positions,
    path: "positions", onTake: (k) => onSettings((s) => Object.assign(s, withPositions(s, k))) });
  positions.id = "project-positions";
  const start = choiceInput(settings.start === null ? "extreme" : "typed",
    [["extreme", t.project_start_extreme], ["typed", t.project_start_typed]], { label: t.project_start, path: "start",
      onTake: (kind) => onSettings((s) => { s.start = kind === "extreme" ? null : found?.phi0 ?? 0; }) });
  start.id = "project-start";
  const phi0 = decimalInput(settings.start ?? found?.phi0 ?? 0, { t, lang, label: t.project_phi0, path: "start",
    min: -2 * Math.PI, max: 2 * Math.PI, scale: DEGREES, size: 6, onTake: (rad) => onSettings((s) => { s.start = rad; }) });
  phi0.id = "project-phi0";
  phi0.disabled = settings.start === null;
  const autoChosen = found?.chosen ? `${t.project_chosen_auto} (${found.chosen})` : t.project_chosen_auto;
  const chosen = choiceInput(settings.chosen ?? "auto", [["auto", autoChosen],
    ...Array.from({ length: n }, (_, k) => [k + 1, String(k + 1)])], { label: t.project_chosen, path: "chosen",
    onTake: (k) => onSettings((s) => { s.chosen = k === "auto" ? null : k; }) });
  chosen.id = "project-chosen";
  const words = (o) => (o.kind === "slide" ? t.project_output_slide : t.project_output_link).replace("{name}", o.name);
  const autoOutput = found?.output ? `${t.project_output_auto} (${words(found.output)})` : t.project_output_auto;
  const output = choiceInput(settings.output ?? "auto", [["auto", autoOutput], ...outputs.map((o) => [o.value, words(o)])],
    { label: t.project_output, path: "output", onTake: (value) => onSettings((s) => { s.output = value === "auto" ? null : value; }) });
  output.id = "project-output";
  const drawn = element("fieldset", { className: "drawn", id: "project-drawn" },
    element("legend", { textContent: t.project_drawn }),
    ...Array.from({ length: n }, (_, k) => {
      const box = element("input", { type: "checkbox", value: String(k + 1), checked: settings.drawn?.includes(k + 1) ?? false,
        "aria-label": `${t.project_drawn}: ${k + 1}` });
      box.addEventListener("change", () => onSettings((s) => {
        const set = new Set(s.drawn ?? []);
        if (box.checked) set.add(k + 1);
        else set.delete(k + 1);
        s.drawn = set.size ? [...set].sort((a, b) => a - b) : null;
      }));
      return element("label", { className: "drawn-position" }, box, String(k + 1));
    }));
  container.replaceChildren(element("div", { className: "settings-grid" },
    element("label", {}, element("span", { textContent: t.project_positions }), positions),
    element("label", {}, element("span", { textContent: t.project_start }), start),
    element("label", {}, element("span", { rich: t.project_phi0 }), phi0),
    element("label", {}, element("span", { textContent: t.project_chosen }), chosen),
    element("label", {}, element("span", { textContent: t.project_output }), output)),
  drawn, element("p", { className: "hint", textContent: t.project_drawn_note }));
}
