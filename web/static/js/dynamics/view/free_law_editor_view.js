/**
 * Panel view that edits a free law of the driving moment M_P(φ₁) (Chaika–Vasylenko §3.4, step 9): the motor's
 * table of points, φ₁ in degrees and M_P in N·m, one row each (spec.paths.phi and spec.paths.moment, dotted paths
 * into the request such as "motor.table_phi", in rad and N·m). A value typed (a decimal comma or point, a true
 * minus or a hyphen), a row added after the last or removed: the whole table goes to the model as a new request.
 * The server checks the table; a refused one (HTTP 422) is said below it in the page's language, by the
 * server's code and context (content/i18n err_free_law_*: the row and the bound, messages.js errorReason), and
 * the table stays as typed for the student to mend; a refusal the app has no text for is said by the field and
 * the server's words. From 2 to 361 rows (free_law_table.js). The scene's points come back with a button.
 */
import { pathValue } from "../../common/model/dotted_paths.js";
import { errorReason } from "../../common/view/messages.js";
import { TABLE_POINTS } from "../model/free_law_table.js";
import { element } from "../../common/view/dom.js";

const DEGREE = Math.PI / 180;
const DECIMALS = 4;           // of a degree or a N·m as shown (the request keeps the number typed)

/** A number as the reader writes it: at most DECIMALS decimals, a decimal comma but in English, a true minus. */
function written(value, lang) {
  const text = String(Number(value.toFixed(DECIMALS)));
  return (lang === "en" ? text : text.replace(".", ",")).replace("-", "\u2212");
}

/** A typed number: "12,5", "12.5", "−3" or "-3"; NaN for anything else. */
function typed(text) {
  const plain = text.trim().replace(/\u2212/g, "-").replace(",", ".");
  return /^[-+]?(\d+\.?\d*|\.\d+)(e[-+]?\d+)?$/i.test(plain) ? Number(plain) : NaN;
}

export class FreeLawEditorView {
  constructor(body, spec, { t, lang }, model) {
    this.spec = spec;
    this.t = t;
    this.lang = lang;
    this.model = model;
    this.words = Object.fromEntries(Object.entries(spec.words).map(([key, text]) => [key, text[lang]]));
    const request = model.request();
    this.initial = this.#points(model.variant.request);
    this.points = this.#points(request);
    this.rows = element("tbody");
    this.message = element("p", { className: "free-law-refusal", role: "alert", hidden: true });
    const add = element("button", { type: "button", className: "add-point", textContent: this.words.add });
    add.addEventListener("click", () => this.#add());
    this.addButton = add;
    const reset = element("button", { type: "button", className: "reset", textContent: this.words.reset });
    reset.addEventListener("click", () => this.#send(this.initial.map((point) => ({ ...point }))));
    const note = spec.note ? [element("p", { className: "note", rich: spec.note[lang] })] : [];
    body.append(element("table", { className: "free-law-points" },
      element("thead", {}, element("tr", {},
        element("th", { scope: "col", textContent: "№" }),
        element("th", { scope: "col", rich: this.words.phi }),
        element("th", { scope: "col", rich: this.words.moment }),
        element("td", {}))),               // the remove buttons' column: no heading of its own
      this.rows), element("p", { className: "free-law-actions" }, add, reset), this.message, ...note);
    this.#fill();
    model.on("result", (answer) => this.#answered(answer));
  }

  /** The request's points as rows {phi (degrees), moment (N·m)}. */
  #points(request) {
    const phi = pathValue(request, this.spec.paths.phi) ?? [];
    const moment = pathValue(request, this.spec.paths.moment) ?? [];
    return phi.map((angle, i) => ({ phi: angle / DEGREE, moment: moment[i] }));
  }

  #fill() {
    this.rows.replaceChildren(...this.points.map((point, i) => {
      const input = (key, label) => {
        const field = element("input", { type: "text", inputMode: "decimal", className: `point-${key}`,
          value: written(point[key], this.lang), "aria-label": `${label}, № ${i + 1}` });
        field.addEventListener("change", () => this.#typed(i, key, field));
        return element("td", {}, field);
      };
      const remove = element("button", { type: "button", className: "remove-point", textContent: "×",
        title: this.words.remove, "aria-label": `${this.words.remove} № ${i + 1}` });
      remove.disabled = this.points.length <= 2;
      remove.addEventListener("click", () => this.#send(this.points.filter((_, j) => j !== i)));
      return element("tr", {}, element("th", { scope: "row", textContent: String(i + 1) }),
        input("phi", this.words.phi_plain), input("moment", this.words.moment_plain), element("td", {}, remove));
    }));
    this.addButton.disabled = this.points.length >= TABLE_POINTS[1];
  }

  #typed(i, key, field) {
    const value = typed(field.value);
    if (!Number.isFinite(value)) {            // not a number: said here, nothing sent
      field.setAttribute("aria-invalid", "true");
      this.#say(this.words.not_a_number);
      return;
    }
    field.removeAttribute("aria-invalid");
    this.#send(this.points.map((point, j) => (j === i ? { ...point, [key]: value } : point)));
  }

  /** A row after the last: halfway from its angle to the turn's end, with its moment. */
  #add() {
    const last = this.points.at(-1) ?? { phi: 0, moment: 0 };
    this.#send([...this.points, { phi: Number(((last.phi + 360) / 2).toFixed(DECIMALS)), moment: last.moment }]);
  }

  /** The table as the request's two lists; both set before the one change is announced. */
  #send(points) {
    this.points = points;
    this.#fill();
    this.model.edits.set(this.spec.paths.phi, points.map((point) => point.phi * DEGREE));
    this.model.edit(this.spec.paths.moment, points.map((point) => point.moment));
  }

  /** An answer: a refusal said in the page's language (a sentence of its own), else by the field and its words. */
  #answered(answer) {
    const { error } = answer;
    if (answer.ok) this.#say(null);
    else if (error.code && this.t[`err_${error.code}`]) this.#say(errorReason(error, this.t, { lang: this.lang }), ". ");
    else this.#say(error.field ? `${error.field}: ${error.message}` : error.message);
  }

  /** Say text after the words of a refusal (joined by ": ", or ". " before a sentence), or nothing. */
  #say(text, join = ": ") {
    this.message.hidden = !text;
    this.message.textContent = text ? `${this.words.refused}${join}${text}` : "";
  }
}
