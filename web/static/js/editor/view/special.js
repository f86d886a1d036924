/**
 * The special positions of the turn in words (per group: limits of assembly, dead positions, the position
 * closest to a dead one, output reversals), from the API's `special` list, translated by their kind; and the
 * API's warnings (already in the reader's language).
 */
import { element } from "../../common/view/dom.js";
import { formatNumber } from "../../common/view/notation.js";

const DEG = 180 / Math.PI;

/** {group, kind, what} read from the server's description ("group 1 (RRP): …", "group 0: slide E/ram reverses"). */
function parts(description) {
  const group = description.match(/^group (\d+)/)?.[1];
  const kind = description.match(/^group \d+ \((\w+)\)/)?.[1] ?? "";
  const link = description.match(/: link (\d+) reverses/)?.[1];
  const slide = description.match(/: slide (\S+) reverses/)?.[1];
  return { group: group ?? "?", kind, link, slide };      // numbered as the API numbers them (linkage.groups.k)
}

/**
 * A slide as the server names it, in words: "E/ram" (slider E on the guide ram) → "E, направляющая ram";
 * "B/slot" (the block at B in its slot, RPP) → "B в кулисе"; a slot of RPR ("s23") as it is.
 */
function slideLabel(key, t) {
  const [joint, guide] = key.split("/");
  if (guide === undefined) return key;
  return guide === "slot" ? `${joint} ${t.editor_in_slot}` : `${joint} (${t.editor_guide_word} ${guide})`;
}

/** One special position as a sentence in the reader's language. */
export function specialText(sp, t, lang) {
  const p = parts(sp.description);
  const phi = `φ = ${formatNumber(sp.phi * DEG, lang, 1)}°`;
  const what = p.link ? `${t.editor_link} ${p.link}` : p.slide ? `${t.editor_slide} ${slideLabel(p.slide, t)}` : "";
  const template = t[`editor_sp_${sp.kind}`] ?? sp.description;
  return `${phi}: ${template.replace("{group}", p.group).replace("{kind}", p.kind).replace("{what}", what)
    .replace("{value}", sp.value === null ? "" : formatNumber(sp.value, lang, 3))}`;
}

/** The special positions (the API's `special`) as buttons that turn the crank there, and the warnings. */
export function renderSpecial(listHost, warningsHost, special, warnings, t, lang, onPick) {
  warningsHost.replaceChildren(...warnings.map((w) => element("p", { className: "notice", textContent: w })));
  listHost.replaceChildren(...special.map((sp) => element("li", {},
    element("button", { type: "button", className: "link-button", textContent: specialText(sp, t, lang),
      onclick: () => onPick(sp.phi) }))));
}
