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

/** The unit in the reader's language: t.units_m, t.units_rad, t.units_1. */
export function unitText(unit, t) {
  return t[{ m: "units_m", rad: "units_rad", 1: "units_1" }[unit]];
}

/** Axis title in textbook notation for outputs that share a unit: "u₃₁, м", "s, s₂, м". */
export function axisTitle(mechanism, outputs, t) {
  return `${outputs.map(symbol).join(", ")}, ${unitText(unitOf(mechanism, outputs[0]), t)}`;
}

/** Parameter name as printed: "l2" → "l₂". */
export function paramSymbol(name) {
  return name.replace(/\d/g, (digit) => SUBSCRIPT_DIGITS[digit]);
}

/** "мёртвая точка" → "Мёртвая точка", for interface texts that start a line. */
export function capitalized(text) {
  return text.charAt(0).toUpperCase() + text.slice(1);
}

export function degrees(radians) {
  return radians * 180 / Math.PI;
}

const formats = new Map();

/** value with the given decimals, or with 3 significant digits when decimals is omitted. */
export function formatNumber(value, lang, decimals) {
  const key = `${lang}|${decimals}`;
  if (!formats.has(key)) {
    const options = decimals === undefined ? { maximumSignificantDigits: 3 }
      : { minimumFractionDigits: decimals, maximumFractionDigits: decimals };
    formats.set(key, new Intl.NumberFormat(lang, { ...options, useGrouping: false }));
  }
  return formats.get(key).format(value);
}

/** Plotly's `separators` layout property: decimal point and thousands separator of the language. */
export function plotSeparators(lang) {
  return lang === "en" ? ".," : ", ";
}
