/**
 * Textbook notation (Eremyants, ch. 2) of the outputs, their units for each mechanism, and numbers
 * written the way the reader's language writes them (decimal comma in Russian and Ukrainian).
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
  if (!formats.has(key)) formats.set(key, new Intl.NumberFormat(lang, { ...options, useGrouping: false }));
  return formats.get(key);
}

/** value with the given decimals, or with 3 significant digits when decimals is omitted. */
export function formatNumber(value, lang, decimals) {
  return numberFormat(lang, decimals === undefined ? { maximumSignificantDigits: 3 }
    : { minimumFractionDigits: decimals, maximumFractionDigits: decimals }).format(value);
}

const SUPERSCRIPTS = { "-": "⁻", 0: "⁰", 1: "¹", 2: "²", 3: "³", 4: "⁴", 5: "⁵", 6: "⁶", 7: "⁷", 8: "⁸", 9: "⁹" };
const PLAIN_RANGE = [1e-3, 1e6];     // magnitudes written without a power of ten

/** value with digits significant digits; very small or large ones as "1,43·10⁻⁹". */
export function formatQuantity(value, lang, digits = 3) {
  const format = numberFormat(lang, { maximumSignificantDigits: digits });
  const size = Math.abs(value);
  if (size === 0 || (size >= PLAIN_RANGE[0] && size < PLAIN_RANGE[1])) return format.format(value);
  let exponent = Math.floor(Math.log10(size));
  if (Math.abs(Number((value / 10 ** exponent).toPrecision(digits))) >= 10) exponent += 1;   // 9,999… → 10
  const power = String(exponent).replace(/./g, (c) => SUPERSCRIPTS[c]);
  return `${format.format(value / 10 ** exponent)}·10${power}`;
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
