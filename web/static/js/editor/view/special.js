/**
 * The special positions of the turn in words (per group: limits of assembly, dead positions, the position
 * closest to a dead one, output reversals), from the API's `special` list (each with its text in the request's
 * language); and the API's warnings (already in the reader's language).
 */
import { element } from "../../common/view/dom.js";
import { formatNumber } from "../../common/view/notation.js";

const DEG = 180 / Math.PI;

/**
 * One special position as a sentence in the reader's language: the angle (or the input slider's s, in
 * `metre`s), then the server's own sentence,
 * said from the position's fields (group, group_kind, link or slide, value) in the request's language.
 */
export function specialText(sp, lang, slider, metre) {
  const at = slider ? `s = ${formatNumber(sp.phi, lang, 3)} ${metre}` : `φ = ${formatNumber(sp.phi * DEG, lang, 1)}°`;
  return `${at}: ${sp.text}`;
}

/** The special positions (the API's `special`) as buttons that turn the crank there, and the warnings. */
export function renderSpecial(listHost, warningsHost, special, warnings, lang, onPick, slider = false, metre = "m") {
  warningsHost.replaceChildren(...warnings.map((w) => element("p", { className: "notice", textContent: w })));
  listHost.replaceChildren(...special.map((sp) => element("li", {},
    element("button", { type: "button", className: "link-button", textContent: specialText(sp, lang, slider, metre),
      onclick: () => onPick(sp.phi) }))));
}
