/**
 * Textbook notation (Eremyants, ch. 2) of the outputs, their units for each mechanism, and numbers
 * written the way the reader's language writes them (decimal comma in Russian and Ukrainian, a true
 * minus sign U+2212 in every language, never "−0").
 *
 * Subscripts and superscripts in interface texts (content/i18n, the scenes' texts and labels, the server's
 * sentences) are written as markup, the one convention of the app:
 *   X_y     → X with subscript y, where y is the run of letters and decimal digits after "_" ("M_c0", "l_BS2",
 *             "ω_ср"; "ω_ср²" lowers "ср" only);
 *   X_{y z} → X with subscript "y z" (anything up to the closing brace: "A_{P,k}", "ω_{1ср}");
 *   X^y, X^{y} → the same as superscripts ("(f tg ψ)^i", "R^{1/3}").
 * A "_" or "^" with nothing after it to lower or raise stays as it is; "\_" is a plain "_" ("solve\_ivp",
 * written "solve\\_ivp" inside JSON). Digits that Unicode has as subscripts (u₃₁) may be written as glyphs;
 * letters never (there are no Cyrillic subscript glyphs).
 * notationParts() reads the markup; richText() turns it into DOM nodes (<sub>/<sup> in HTML, a shifted
 * <tspan> in SVG; text nodes only, never innerHTML), plotText() into the pseudo-HTML Plotly draws, with the
 * text escaped. The server's pages use the same rule (the Jinja filter "notation", server/api/routers/pages.py).
 */

/** Unit of the position functions s (link 3) and s₂ (link 2), from GET /api/v1/mechanisms "conventions". */
const POSITION_UNITS = {
  sine: { s: "m", s2: "m" },               // yoke travel x, block travel y in the slot
  slider_crank: { s: "m", s2: "rad" },     // slider travel, rod angle ψ
  slotted_link: { s: "rad", s2: "m" },     // lever angle ψ, block travel along the lever
  four_bar: { s: "rad", s2: "rad" },       // rocker angle φ₃, coupler angle φ₂
};

/** Which position function each output differentiates. */
const POSITION_OF = { s: "s", u31: "s", du31: "s", s2: "s2", u21: "s2", du21: "s2" };

const SYMBOLS = { s: "s", s2: "s₂", u31: "u₃₁", du31: "u′₃₁", u21: "u₂₁", du21: "u′₂₁" };

const SUBSCRIPT_DIGITS = "₀₁₂₃₄₅₆₇₈₉";

/** "u31_approx" → "u31": the exact output an approximation stands for. */
export function exactName(output) {
  return output.replace(/_approx$/, "");
}

export function symbol(output) {
  return SYMBOLS[exactName(output)];
}

/** "m", "rad" or "1": s in m gives u = ds/dφ and u′ in m; s in rad gives them dimensionless. */
export function unitOf(mechanism, output) {
  const name = exactName(output);
  const position = POSITION_UNITS[mechanism][POSITION_OF[name]];
  if (name === POSITION_OF[name]) return position;
  return position === "m" ? "m" : "1";
}

/** Interface texts (content/i18n) of the units that have a name in the reader's language. */
const UNIT_KEYS = {
  m: "units_m", rad: "units_rad", 1: "units_1", s: "units_s", ms: "units_ms", kg: "units_kg",
  "kg·m²": "units_kg_m2", "rad/s": "units_rad_s", "rad/s²": "units_rad_s2", J: "units_J", N: "units_N",
  "N·m": "units_N_m", "µm": "units_um", Pa: "units_Pa",
};

/** The unit in the reader's language ("m" → "м"); a unit without a translation ("%") as it is. */
export function unitText(unit, t) {
  return UNIT_KEYS[unit] ? t[UNIT_KEYS[unit]] : unit;
}

/** Axis title in textbook notation for outputs that share a unit: "u₃₁, м", "s, s₂, м". */
export function axisTitle(mechanism, outputs, t) {
  return `${outputs.map(symbol).join(", ")}, ${unitText(unitOf(mechanism, outputs[0]), t)}`;
}

/**
 * A slider's label with its value: "λ = l₂/l₁" → "λ = l₂/l₁ = 3,00"; a label that ends in its unit puts
 * the unit after the value: "P_c (нагрузка), Н" → "P_c (нагрузка) = 2000 Н", "φ, °" → "φ = 30°".
 */
export function labelledValue(label, valueText) {
  const [, name, unit] = label.match(/^(.+), ([^,]+)$/) ?? [];
  if (!unit) return `${label} = ${valueText}`;
  return `${name} = ${valueText}${unit === "°" ? "" : " "}${unit}`;
}

/** Parameter name as printed: "l2" → "l₂", "params.l2" → "l₂". */
export function paramSymbol(name) {
  return name.split(".").pop().replace(/\d/g, (digit) => SUBSCRIPT_DIGITS[digit]);
}

/** "мёртвая точка" → "Мёртвая точка", for interface texts that start a line. */
export function capitalized(text) {
  return text.charAt(0).toUpperCase() + text.slice(1);
}

export function degrees(radians) {
  return radians * 180 / Math.PI;
}

const formats = new Map();

function numberFormat(lang, options) {
  const key = `${lang}|${JSON.stringify(options)}`;
  if (!formats.has(key)) {
    formats.set(key, new Intl.NumberFormat(lang, { ...options, useGrouping: false, signDisplay: "negative" }));
  }
  return formats.get(key);
}

const MINUS = "\u2212";

/**
 * A formatted number with a true minus sign (U+2212); a value that rounds to zero has no sign ("0", never
 * "−0"): Intl's signDisplay "negative".
 */
function written(format, value) {
  return format.format(value).replace("-", MINUS);
}

/** value with the given decimals, or with 3 significant digits when decimals is omitted. */
export function formatNumber(value, lang, decimals) {
  return written(numberFormat(lang, decimals === undefined ? { maximumSignificantDigits: 3 }
    : { minimumFractionDigits: decimals, maximumFractionDigits: decimals }), value);
}

const SUPERSCRIPTS = { "-": "⁻", 0: "⁰", 1: "¹", 2: "²", 3: "³", 4: "⁴", 5: "⁵", 6: "⁶", 7: "⁷", 8: "⁸", 9: "⁹" };
const PLAIN_RANGE = [1e-3, 1e6];     // magnitudes written without a power of ten

/** value with digits significant digits; very small or large ones as "1,43·10⁻⁹". */
export function formatQuantity(value, lang, digits = 3) {
  const format = numberFormat(lang, { maximumSignificantDigits: digits });
  const size = Math.abs(value);
  if (size === 0 || (size >= PLAIN_RANGE[0] && size < PLAIN_RANGE[1])) return written(format, value);
  let exponent = Math.floor(Math.log10(size));
  if (Math.abs(Number((value / 10 ** exponent).toPrecision(digits))) >= 10) exponent += 1;   // 9,999… → 10
  const power = String(exponent).replace(/./g, (c) => SUPERSCRIPTS[c]);
  return `${written(format, value / 10 ** exponent)}·10${power}`;
}

/** A tolerance as written in a table of solvers: a power of ten as "10⁻⁵", any other value as formatQuantity. */
export function toleranceText(value, lang) {
  const exponent = Math.log10(value);
  if (!Number.isInteger(exponent)) return formatQuantity(value, lang, 2);
  return `10${String(exponent).replace(/./g, (c) => SUPERSCRIPTS[c])}`;
}

/** Plotly's `separators` layout property: decimal point and thousands separator of the language. */
export function plotSeparators(lang) {
  return lang === "en" ? ".," : ", ";
}

const MARKUP = /\\([_^])|([_^])(?:\{([^{}]*)\}|([\p{L}\p{Nd}\p{M}]+))/gu;

/** text split into its runs: [{text, shift: ""|"sub"|"sup"}], e.g. "M_c0 = 1" → M, c0 (sub), " = 1". */
export function notationParts(text) {
  const parts = [];
  let last = 0;
  text = String(text);
  for (const match of text.matchAll(MARKUP)) {
    if (match.index === 0 && !match[1]) continue;                 // nothing to lower or raise before it
    if (match.index > last) parts.push({ text: text.slice(last, match.index), shift: "" });
    if (match[1]) parts.push({ text: match[1], shift: "" });
    else parts.push({ text: match[3] ?? match[4], shift: match[2] === "_" ? "sub" : "sup" });
    last = match.index + match[0].length;
  }
  if (last < text.length) parts.push({ text: text.slice(last), shift: "" });
  return parts.reduce((joined, part) => {                          // neighbouring plain runs as one
    const previous = joined.at(-1);
    if (previous && !previous.shift && !part.shift) previous.text += part.text;
    else joined.push({ ...part });
    return joined;
  }, []);
}

const SVG_NS = "http://www.w3.org/2000/svg";
const SVG_RISE = { "": 0, sub: -0.3, sup: 0.5 };               // em of the text above its base line
const SVG_SMALLER = 0.75;                                        // a lowered or raised run's font size

function htmlPart(part) {
  if (!part.shift) return document.createTextNode(part.text);
  const node = document.createElement(part.shift);
  node.textContent = part.text;
  return node;
}

/**
 * An interface text as DOM nodes: a DocumentFragment of text nodes and <sub>/<sup> elements, or, with
 * { svg: true }, of <tspan>s (for a <text> in a drawing): a lowered or raised run set at 75 %, each run
 * moved by dy from the previous one's line (baseline-shift is not drawn by every browser), the text after
 * it back on the base line.
 */
export function richText(text, { svg = false } = {}) {
  const fragment = document.createDocumentFragment();
  const parts = notationParts(text ?? "");
  if (!svg) {
    fragment.append(...parts.map(htmlPart));
    return fragment;
  }
  let rise = 0;
  for (const part of parts) {
    const span = document.createElementNS(SVG_NS, "tspan");
    const shift = (SVG_RISE[part.shift] - rise) / (part.shift ? SVG_SMALLER : 1);   // in the run's own em
    if (shift) span.setAttribute("dy", `${-shift}em`);
    if (part.shift) span.setAttribute("font-size", `${100 * SVG_SMALLER}%`);
    span.textContent = part.text;
    fragment.append(span);
    rise = SVG_RISE[part.shift];
  }
  return fragment;
}

/**
 * An interface text where only plain text can stand (aria-label, <option>, <title>): the markup dropped,
 * digits lowered or raised as Unicode glyphs ("u_31" → "u₃₁", "M_с0" → "Mс₀", "R^{1/3}" → "R¹/³").
 */
export function plainText(text) {
  return notationParts(text ?? "").map((part) => (part.shift
    ? part.text.replace(/\d/g, (digit) => (part.shift === "sub" ? SUBSCRIPT_DIGITS[digit] : SUPERSCRIPTS[digit]))
    : part.text)).join("");
}

/** node's content replaced by text as rich text (an SVG node gets shifted tspans). */
export function setRichText(node, text) {
  node.replaceChildren(richText(text, { svg: node.namespaceURI === SVG_NS }));
  return node;
}

const ESCAPES = { "&": "&amp;", "<": "&lt;", ">": "&gt;" };
const escapePlot = (text) => text.replace(/[&<>]/g, (c) => ESCAPES[c]);

/** An interface text for Plotly (titles, legends, hover): its markup as <sub>/<sup>, the rest escaped. */
export function plotText(text) {
  return notationParts(text ?? "").map((part) => (part.shift
    ? `<${part.shift}>${escapePlot(part.text)}</${part.shift}>` : escapePlot(part.text))).join("");
}
