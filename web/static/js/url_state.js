/**
 * The scene's state in the page address (?lang=ru&variant=slider_crank&lambda=3.2&overlay=1, or
 * …&convention=textbook for a toggle with words for options), so that a link or a reload shows the same
 * set-up, and the language switch keeps the scene as it is.
 */

/** A value as written in the address: a number ("3.2", "-1"), or a toggle's word ("textbook"). */
function parseValue(text) {
  const number = Number(text);
  return text.trim() !== "" && Number.isFinite(number) ? number : text;
}

/** {variant, values, overlay} read from the address; the model ignores what does not fit the variant. */
export function readState(search = location.search) {
  const query = new URLSearchParams(search);
  const values = {};
  for (const [key, text] of query) {
    if (!["lang", "variant", "overlay", "student"].includes(key)) values[key] = parseValue(text);
  }
  return { variant: query.get("variant"), values, overlay: query.get("overlay") === "1" };
}

const ADDRESS_DELAY = 300;     // ms; a slider drag rewrites the address a few times a second, not per event
let pendingAddress = null;

/**
 * Write the model's state into the language links at once, and into the address shortly after; an
 * assignment page keeps its student (?student=…) in both.
 */
export function writeState(model, lang) {
  const query = new URLSearchParams({ lang, variant: model.variant.id });
  const student = new URLSearchParams(location.search).get("student");
  if (student) query.set("student", student);
  for (const [id, value] of Object.entries(model.values)) query.set(id, String(value));
  if (model.overlay) query.set("overlay", "1");
  if (pendingAddress === null) {
    setTimeout(() => {
      history.replaceState(null, "", pendingAddress);
      pendingAddress = null;
    }, ADDRESS_DELAY);
  }
  pendingAddress = `?${query}`;
  for (const link of document.querySelectorAll("a[data-with-state]")) link.href = `${link.dataset.withState}?${query}`;
  for (const link of document.querySelectorAll("a[data-lang]")) {
    query.set("lang", link.dataset.lang);
    link.href = `?${query}`;
  }
}
