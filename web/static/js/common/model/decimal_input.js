/**
 * Numbers typed by a person, read the same way in every browser and locale (an <input type="number"> in
 * Chromium with ru-RU reads "2,5" as 25). The decimal separator is a comma or a point. Anything that could
 * mean two numbers is refused rather than guessed: both a comma and a point ("1,234.5", "1.234,5"), two
 * separators ("2,5,1"), and on an English page a comma before exactly three digits ("1,234": a thousands
 * separator there; in ru and uk a comma is always the decimal one).
 * Spaces between digit groups ("1 234,5") are dropped; a typographic minus "−" is a minus.
 */
const PLAIN = /^[-+]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?$/;
const COMMA_LANGUAGES = new Set(["ru", "uk"]);

/** { value } for a number, else { error: "empty" | "ambiguous" | "invalid" }. */
export function parseDecimal(text, lang) {
  let s = String(text ?? "").trim().replace(/\u2212/g, "-").replace(/(\d)[\s\u00a0\u202f]+(?=\d)/g, "$1");
  if (s === "") return { error: "empty" };
  const commas = (s.match(/,/g) ?? []).length;
  const points = (s.match(/\./g) ?? []).length;
  const thousands = commas === 1 && !COMMA_LANGUAGES.has(lang) && /,\d{3}(?:\D|$)/.test(s);
  if (commas + points > 1 || thousands) return { error: "ambiguous" };
  s = s.replace(",", ".");
  const value = Number(s);
  return PLAIN.test(s) && Number.isFinite(value) ? { value } : { error: "invalid" };
}

/** The reason a text is refused, in the page's language (t: the interface texts). */
export function decimalMessage(error, text, t) {
  return (t[`number_${error}`] ?? t.number_invalid).replace("{text}", String(text).trim());
}
