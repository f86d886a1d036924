/**
 * View of what the answer says in words: the configuration (Grashof class, λ, swing of the lever,
 * stroke time ratio, smallest transmission angle), the special positions, the warnings, and the
 * overlay values for which the mechanism cannot be assembled.
 */
import { element } from "../../common/view/dom.js";
import { errorReason } from "../../common/view/messages.js";
import { capitalized, degrees, formatNumber } from "../../common/view/notation.js";
import { specialPositions } from "../../common/model/positions_table.js";

/** Entries of the answer's `info` shown, in this order: label and value in the reader's language. */
const INFO_ITEMS = [
  ["grashof_class", (t) => t.grashof_class, (v, t) => t[v === "change_point" ? "change_point_linkage" : v]],
  ["scheme", (t) => t.scheme, (v, t, lang) => formatNumber(v, lang)],
  ["lambda", () => "λ", (v, t, lang) => formatNumber(v, lang)],
  ["max_rod_angle", (t) => t.max_rod_angle, (v, t, lang) => `${formatNumber(degrees(v), lang, 1)}°`],
  ["swing", (t) => t.lever_swing, (v, t, lang) => `${formatNumber(degrees(v), lang, 1)}°`],
  ["time_ratio", (t) => capitalized(t.stroke_ratio), (v, t, lang) => formatNumber(v, lang)],
  ["min_transmission_angle", (t) => capitalized(t.min_transmission_angle), (v, t, lang) => `${formatNumber(degrees(v), lang, 1)}°`],
];

export class StatusView {
  constructor(container, { t, lang }) {
    this.container = container;
    this.t = t;
    this.lang = lang;
  }

  /** answer: the current kinematics answer; overlays: Map λ → answer. */
  show(answer, overlays) {
    const sections = [];
    if (answer?.ok) {
      const info = this.#info(answer.data);
      if (info) sections.push(info);
      const specials = this.#specials(answer.data);
      if (specials) sections.push(specials);
      if (answer.data.warnings.length) {
        sections.push(this.#list("warnings", this.t.warnings, answer.data.warnings));
      }
    }
    const failed = [...overlays].filter(([, a]) => !a.ok).map(([lambda, a]) =>
      `λ = ${formatNumber(lambda, this.lang)}: ${errorReason(a.error, this.t)}`);
    if (failed.length) sections.push(this.#list("overlay-failures", this.t.invalid_geometry, failed));
    this.container.replaceChildren(...sections);
  }

  #info(data) {
    const info = data.outputs.info ?? {};
    const rows = INFO_ITEMS.filter(([key]) => key in info)
      .map(([key, label, value]) => [label(this.t), value(info[key], this.t, this.lang)]);
    const ratio = (data.outputs.special ?? []).find((sp) => sp.kind === "stroke_ratio");
    if (ratio) rows.push([capitalized(this.t.stroke_ratio), formatNumber(ratio.value, this.lang)]);
    if (!rows.length) return null;
    return element("dl", { className: "info" },
      ...rows.flatMap(([label, value]) => [element("dt", { rich: label }), element("dd", { rich: value })]));
  }

  /** "dead centre: 0,0°, 180,0°" — one line per kind. */
  #specials(data) {
    const byKind = new Map();
    for (const sp of specialPositions(data)) {
      byKind.set(sp.kind, [...(byKind.get(sp.kind) ?? []), `${formatNumber(degrees(sp.phi), this.lang, 1)}°`]);
    }
    if (!byKind.size) return null;
    return this.#list("special-positions", this.t.special_positions,
      [...byKind].map(([kind, angles]) => `${capitalized(this.t[kind])}: φ = ${angles.join("; ")}`));
  }

  #list(className, heading, lines) {
    return element("section", { className },
      element("h2", { textContent: heading }),
      element("ul", {}, ...lines.map((line) => element("li", { rich: line }))));
  }
}
