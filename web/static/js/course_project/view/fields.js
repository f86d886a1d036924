/**
 * The inputs of the course-project page: a decimal cell (comma or point, decimal_input.js), a choice, a
 * check box and a text field, each calling back with the value it takes. A decimal cell takes its text on
 * "change" and on leaving it, once per text (data-taken); a text that is no number, or outside the cell's
 * bounds, is refused beside the cell (its validity message and title) and not taken. Every input carries the
 * dotted path of the value it edits (data-path), which a refusal of the server may name.
 */
import { element } from "../../common/view/dom.js";
import { formatQuantity, plainText } from "../../common/view/notation.js";
import { decimalMessage, parseDecimal } from "../../common/model/decimal_input.js";

/** A number as a cell shows it to be edited: 6 significant digits in the page's language. */
export const editable = (value, lang) => (Number.isFinite(value) ? formatQuantity(value, lang, 6) : "");

/**
 * <input> of a decimal value. options: lang, t, label (plain text), path, min, max (inclusive bounds, the
 * API's), scale (the value shown is the value kept times scale: degrees, rpm), onTake(value).
 */
export function decimalInput(value, { lang, t, label, path, min = -Infinity, max = Infinity, scale = 1, onTake, size = 7 }) {
  const shown = editable(value * scale, lang);
  const input = element("input", { type: "text", inputMode: "decimal", size, value: shown,
    "aria-label": label, "data-path": path, "data-taken": shown });
  const take = () => {
    if (input.value === input.dataset.taken) return;
    input.dataset.taken = input.value;
    const read = parseDecimal(input.value, lang);
    const outside = !read.error && (read.value < min * scale || read.value > max * scale);
    const message = read.error ? decimalMessage(read.error, input.value, t)
      : outside ? t.project_out_of_range.replace("{min}", formatQuantity(min * scale, lang, 6))
        .replace("{max}", formatQuantity(max * scale, lang, 6)) : "";
    input.setCustomValidity(message);
    input.title = message;
    input.toggleAttribute("aria-invalid", Boolean(message));
    if (!message) onTake(read.value / scale);
  };
  input.addEventListener("change", take);
  input.addEventListener("blur", take);
  return input;
}

/** <select> of [value, text] choices (values kept as strings; onTake gets the chosen one's value back). */
export function choiceInput(value, choices, { label, path, onTake }) {
  const select = element("select", { "aria-label": label, "data-path": path },
    ...choices.map(([key, text]) => new Option(plainText(text), String(key))));
  select.value = String(value);
  select.addEventListener("change", () => onTake(choices.find(([key]) => String(key) === select.value)[0]));
  return select;
}

/** A check box with its label (rich text). */
export function checkInput(checked, { text, path, id, onTake }) {
  const box = element("input", { type: "checkbox", checked, "data-path": path, ...(id ? { id } : {}) });
  box.addEventListener("change", () => onTake(box.checked));
  return element("label", { className: "check" }, box, " ", element("span", { rich: text }));
}

/** A free-text field of at most maxLength characters, taken on every change. */
export function textInput(value, { label, path, id, maxLength, onTake }) {
  const input = element("input", { type: "text", value, maxLength, id, "data-path": path });
  input.addEventListener("change", () => onTake(input.value));
  return element("label", { className: "text-field" }, element("span", { textContent: label }), input);
}

/** A cell of a table holding one input. */
export const inputCell = (input) => element("td", {}, input);
