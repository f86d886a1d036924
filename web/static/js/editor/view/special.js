/**
 * The special positions of the turn in words (per group: limits of assembly, dead positions, the position
 * closest to a dead one, output reversals), from the API's `special` list (each with its text in the request's
 * language); and the API's warnings (already in the reader's language).
 */
import { element } from "../../common/view/dom.js";
import { formatNumber } from "../../common/view/notation.js";

const DEG = 180 / Math.PI;

/**
 * One special position as a sentence in the reader's language: the angle, then the server's own sentence,
 * said from the position's fields (group, group_kind, link or slide, value) in the request's language.
 */
export function specialText(sp, lang) {
  return `φ = ${formatNumber(sp.phi * DEG, lang, 1)}°: ${sp.text}`;
}

/** The special positions (the API's `special`) as buttons that turn the crank there, and the warnings. */
export function renderSpecial(listHost, warningsHost, special, warnings, lang, onPick) {
  warningsHost.replaceChildren(...warnings.map((w) => element("p", { className: "notice", textContent: w })));
  listHost.replaceChildren(...special.map((sp) => element("li", {},
    element("button", { type: "button", className: "link-button", textContent: specialText(sp, lang),
      onclick: () => onPick(sp.phi) }))));
}
