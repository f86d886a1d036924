/**
 * The scene's state in the page address (?lang=ru&variant=slider_crank&lambda=3.2&overlay=1, or
 * …&convention=textbook for a toggle with words for options), so that a link or a reload shows the same
 * set-up, and the language switch keeps the scene as it is. The whole state: a list edited in a panel (the
 * indicator diagram's points) as edit.<its dotted path in the request>=0.1,0.25,… and the chosen preset of
 * a slider (the [δ] table's row) as preset=<its index in the scene's presets>. A reader's own mechanism (m, d:
 * address_mechanism.js) is the address's and stays in it as it is.
 */
const EDIT = "edit.";
const DOCUMENTS = ["m", "d"];       // the reader's own mechanism, written by the editor

/** A value as written in the address: a number ("3.2", "-1"), or a toggle's word ("textbook"). */
function parseValue(text) {
  const number = Number(text);
  return text.trim() !== "" && Number.isFinite(number) ? number : text;
}

/** {variant, values, overlay, edits, preset} read from the address; the model ignores what does not fit. */
export function readState(search = location.search) {
  const query = new URLSearchParams(search);
  const values = {};
  const edits = new Map();
  for (const [key, text] of query) {
    if (key.startsWith(EDIT)) edits.set(key.slice(EDIT.length), text.split(",").map(Number));
    else if (!["lang", "variant", "overlay", "student", "preset", ...DOCUMENTS].includes(key)) values[key] = parseValue(text);
  }
  const preset = query.has("preset") ? Number(query.get("preset")) : null;
  return { variant: query.get("variant"), values, overlay: query.get("overlay") === "1", edits, preset };
}

/** The model's whole state as the query of an address (without the student of an assignment page). */
export function stateQuery(model, lang) {
  const query = new URLSearchParams({ lang, variant: model.variant.id });
  for (const [id, value] of Object.entries(model.values)) query.set(id, String(value));
  if (model.overlay) query.set("overlay", "1");
  for (const [path, values] of model.edits ?? []) query.set(`${EDIT}${path}`, values.join(","));
  if (Number.isInteger(model.preset)) query.set("preset", String(model.preset));
  const address = new URLSearchParams(location.search);
  for (const key of DOCUMENTS) if (address.has(key)) query.set(key, address.get(key));
  return query;
}

const ADDRESS_DELAY = 300;     // ms; a slider drag rewrites the address a few times a second, not per event
let pendingAddress = null;

/**
 * Write the model's state into the language links at once, and into the address shortly after; an
 * assignment page keeps its student (?student=…) in both.
 */
export function writeState(model, lang) {
  const query = stateQuery(model, lang);
  const student = new URLSearchParams(location.search).get("student");
  if (student) query.set("student", student);
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
