/**
 * The special positions of the turn in words (per group: limits of assembly, dead positions, the position
 * closest to a dead one, output reversals), from the API's `special` list (each with its text in the request's
 * language, the group named as in the structural formula, every value with its unit).
 */
import { element } from "../../common/view/dom.js";
import { formatNumber } from "../../common/view/notation.js";

const DEG = 180 / Math.PI;
const EXACT = new Set(["limit_of_assembly", "output_reversal"]);     // found by root finding, not on the grid

/**
 * One special position as a sentence in the reader's language: the angle (or the input slider's s, in
 * `metre`s; to 0.01° where it was found exactly, to 0.1° where on the 0.5° grid), then the server's sentence.
 */
export function specialText(sp, lang, slider, metre) {
  const at = slider ? `s = ${formatNumber(sp.phi, lang, 4)} ${metre}`
    : `φ = ${formatNumber(sp.phi * DEG, lang, EXACT.has(sp.kind) ? 2 : 1)}°`;
  return `${at}: ${sp.text}`;
}

/** The special positions (the API's `special`) as buttons that turn the crank there. */
export function renderSpecial(listHost, special, lang, onPick, slider = false, metre = "m") {
  listHost.replaceChildren(...special.map((sp) => element("li", { "data-kind": sp.kind },
    element("button", { type: "button", className: "link-button", textContent: specialText(sp, lang, slider, metre),
      onclick: () => onPick(sp.phi) }))));
}
