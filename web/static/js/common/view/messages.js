/**
 * The app's messages in the reader's language with their values filled, on every page (editor and scenes):
 * a text of content/i18n with Python's format fields ({group}, {mu:.2f}, {budget:g}, {ranges}) said with the
 * values of the API's error context or of the page; and the boxes that say why there is nothing to draw.
 */
import { element } from "./dom.js";
import { formatNumber, formatQuantity } from "./notation.js";

/** A format field of a text: {name}, {name:.2f}, {name:g}; not a subscript's braces (l_{AB}, x^{2}). */
const FIELD = /(?<![_^\\])\{(\w+)(?::([^{}]*))?\}/g;
const MINUS = "\u2212";
const SUPERSCRIPTS = { "-": "⁻", 0: "⁰", 1: "¹", 2: "²", 3: "³", 4: "⁴", 5: "⁵", 6: "⁶", 7: "⁷", 8: "⁸", 9: "⁹" };

/** A number as a format field asks for it: ".2f" fixed decimals, ".4g"/"g" significant digits (6 by default). */
function numberText(value, spec, lang) {
  const fixed = /^\.(\d+)f$/.exec(spec ?? "");
  if (fixed) return formatNumber(value, lang, Number(fixed[1]));
  const general = /^(?:\.(\d+))?g$/.exec(spec ?? "");
  if (general) return formatQuantity(value, lang, Number(general[1] ?? 6));
  const [mantissa, power] = String(value).split("e");          // no format: every digit, as Python's str()
  const digits = lang === "en" ? mantissa : mantissa.replace(".", ",");
  const exponent = power === undefined ? "" : `·10${[...String(Number(power))].map((c) => SUPERSCRIPTS[c]).join("")}`;
  return `${digits}${exponent}`.replace("-", MINUS);
}

/**
 * One value of a message: crank-angle ranges [[from, to], …] in degrees as "57,0°–133,0°"; a group's number
 * (as in linkage.groups) by its name in the structural formula where the page knows them (`groups`:
 * ["II₁(2,3)", …]), else counted from 1; a number as its field's format asks; a list joined by commas; text as it is.
 */
function valueText(name, value, spec, { lang, groups }) {
  if (name === "ranges" && Array.isArray(value)) {
    return value.map(([a, b]) => `${formatNumber(a, lang, 1)}°–${formatNumber(b, lang, 1)}°`).join(", ");
  }
  if (name === "group" && Number.isInteger(value)) return groups?.[value] ?? String(value + 1);
  if (typeof value === "number") return numberText(value, spec, lang);
  if (Array.isArray(value)) return value.join(", ");
  return String(value);
}

const pageLanguage = () => globalThis.document?.documentElement.lang || "en";

/**
 * `template` with every format field filled from `values` (a value missing: "…", never the field itself);
 * lang: the reader's language (numbers with its decimal separator and a true minus); groups: the names of the
 * linkage's groups in the structural formula, where the page has a linkage.
 */
export function messageText(template, values = {}, { lang = pageLanguage(), groups = null } = {}) {
  return template.replace(FIELD, (whole, name, spec) => (values[name] === undefined || values[name] === null
    ? "…" : valueText(name, values[name], spec, { lang, groups })));
}

/**
 * The reason of an API error ({code, message, ctx}) in the reader's language: err_<code> of content/i18n with
 * the error's context filled (messageText), or the server's own words where the app has no text for the code.
 */
export function errorReason(error, t, options = {}) {
  const template = error.code && t[`err_${error.code}`];
  return template ? messageText(template, error.ctx ?? {}, options) : error.message;
}

/** A box saying that the request was refused (heading) and why. */
export function refusalMessage(heading, error, t) {
  return element("div", { className: "refusal", role: "alert" },
    element("strong", { textContent: heading }),
    element("p", { rich: errorReason(error, t) }));
}

/** A box saying the mechanism cannot be assembled, and why. */
export function geometryMessage(error, t) {
  const box = refusalMessage(t.invalid_geometry, error, t);
  box.classList.add("geometry-error");
  return box;
}
