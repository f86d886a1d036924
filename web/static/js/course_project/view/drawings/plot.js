/**
 * A diagram drawn as the textbook draws it over the crank's turn: the abscissa φ from the first angle of the
 * answer's grid, 2π over TURN mm (μ_φ = 2π/TURN rad/mm, also written in degrees), ticked at φ's multiples of 30°; the
 * ordinate at a standard scale μ_y (1, 2, 2.5, 4, 5 × 10ᵏ per mm) at which the curves' range fits HEIGHT mm,
 * ticked at round values; the positions of the plan marked by thin lines with their numbers; each curve a
 * polyline of its values, named at its largest magnitude. Points of a quantity (x, y) → paper (mm, y down).
 */
import { degrees, formatNumber, formatQuantity } from "../../../common/view/notation.js";
import { roundTicks, standardScale, FONT } from "../../model/drawing_layout.js";
import { perMillimetre } from "./captions.js";

const TURN = 180;                // mm of the abscissa for 2π
const MU_PHI = 2 * Math.PI / TURN;
const HEIGHT = 50;                      // mm: the ordinate's range at most
const LEFT = 20;                        // mm left of the ordinate for its tick values
const TOP = 9;                          // mm above the plot for its title and scale
const BOTTOM = 10;                      // mm below it for the degrees
const TICK = 1.5;                       // mm
const TWO_PI = 2 * Math.PI;

/** "μ_φ = 0,0349 рад/мм (2°/мм)": the abscissa's scale. */
export function phiScaleText(t, lang) {
  return `μ_φ = ${formatQuantity(MU_PHI, lang, 3)} ${perMillimetre(t.units_rad, t)} (${formatNumber(degrees(MU_PHI), lang)}°/${t.editor_mm})`;
}

/**
 * Draws one diagram into figure with its top left corner at [left, top] (mm); spec: {phi (rad, the grid),
 * curves: [{values, label (markup), kind (a line of figure.js), name, atEnd (named beyond its end)}], symbol (markup, the ordinate's title),
 * unit (written, may be ""), muSymbol ("μ_s"), marks: [{label, phi}] (positions), height (mm, optional), zero
 * (false: the ordinate's range is the curves' alone, the φ axis at its bottom: a false origin)};
 * returns {bottom (mm below the diagram), mu (the ordinate's scale), at (quantity → paper)}.
 */
export function anglePlot(figure, [left, top], spec, t, lang) {
  const start = spec.phi[0];
  const values = spec.curves.flatMap((curve) => curve.values).filter(Number.isFinite);
  const zero = spec.zero !== false;            // the ordinate from 0, or (zero: false) a false origin near the curves
  const low = Math.min(...(zero ? [0] : []), ...values);
  const high = Math.max(...(zero ? [0] : []), ...values);
  const mu = standardScale(Math.max(high - low, 1e-12 * Math.max(1, Math.abs(high))), spec.height ?? HEIGHT);
  const { ticks } = roundTicks(low, high, mu, 8);
  const step = ticks.length > 1 ? ticks[1] - ticks[0] : mu * 10;
  const [y0, y1] = [Math.min(low, Math.floor(low / step) * step), Math.max(high, Math.ceil(high / step) * step)];
  const axis = zero ? 0 : y0;                   // the value the φ axis stands at
  const origin = [left + LEFT, top + TOP + (y1 - axis) / mu];
  const at = ([phi, y]) => [origin[0] + (phi - start) / MU_PHI, origin[1] - (y - axis) / mu];
  const bottom = top + TOP + (y1 - y0) / mu;

  const title = spec.unit ? `${spec.symbol}, ${spec.unit}` : spec.symbol;
  figure.text(title, [origin[0] + 2, top + FONT.label], { size: FONT.label, attrs: { class: "cp-axis-title" } });
  figure.text(`${spec.muSymbol} = ${formatQuantity(mu, lang, 3)} ${perMillimetre(spec.unit, t)}`,
    [origin[0] + TURN, top + FONT.label], { size: FONT.small, anchor: "end", attrs: { class: "cp-scale" } });
  figure.arrow([origin[0], bottom + 2], [origin[0], top + TOP - 3], "thin", { "data-role": "axis-y" });
  figure.arrow([origin[0], origin[1]], [origin[0] + TURN + 6, origin[1]], "thin", { "data-role": "axis-phi" });
  figure.text("φ", [origin[0] + TURN + 7, origin[1] + 1.2], { size: FONT.label });
  for (const value of ticks) {
    const y = at([start, value])[1];
    figure.line([origin[0] - TICK, y], [origin[0], y], "thin");
    figure.text(formatQuantity(value, lang, 3), [origin[0] - TICK - 0.8, y + 0.9], { size: FONT.small, anchor: "end" });
  }
  const first = Math.ceil(degrees(start) / 30 - 1e-9) * 30;            // φ ticked at its multiples of 30°
  for (let d = first; d <= degrees(start) + 360 + 1e-9; d += 30) {
    const x = at([d * Math.PI / 180, 0])[0];
    const labelled = d % 90 === 0;
    figure.line([x, bottom], [x, bottom + (labelled ? 2 * TICK : TICK)], "thin");
    if (labelled) {
      figure.text(`${formatNumber(d % 360, lang, 0)}°`, [x, bottom + 2 * TICK + FONT.small + 0.5], { size: FONT.small, anchor: "middle" });
    }
  }
  figure.line([origin[0], bottom], [origin[0] + TURN, bottom], "thin");
  for (const mark of spec.marks ?? []) {
    const offset = ((mark.phi - start) % TWO_PI + TWO_PI) % TWO_PI;
    const x = origin[0] + offset / MU_PHI;
    figure.line([x, top + TOP - 1], [x, bottom], "dashed", { "data-position": mark.label });
    figure.label(mark.label, [x, top + TOP - 1.5], { size: FONT.small, target: [x, top + TOP - 1], attrs: { "data-role": "position-number" } });
  }
  for (const curve of spec.curves) {
    figure.polyline(spec.phi.map((phi, i) => (Number.isFinite(curve.values[i]) ? at([phi, curve.values[i]]) : null)),
      curve.kind ?? "main", { "data-curve": curve.name ?? curve.label });
    if (curve.label && curve.atEnd) {          // a level line: named beyond its right end
      const p = at([spec.phi.at(-1), curve.values.at(-1)]);
      figure.label(curve.label, [p[0] + 2, p[1] + 1.2], { anchor: "start", target: p, attrs: { "data-role": "curve-name" } });
    } else if (curve.label) {
      const k = largestAt(curve.values);
      const p = at([spec.phi[k], curve.values[k]]);
      figure.label(curve.label, [p[0] + 1.5, p[1] + (curve.values[k] >= 0 ? -1.5 : 4)],
        { target: p, attrs: { "data-role": "curve-name" } });
    }
  }
  return { bottom: bottom + BOTTOM, mu, at };
}

/** The index of the largest magnitude of finite values (0 if none). */
function largestAt(values) {
  let best = 0;
  values.forEach((v, i) => {
    if (Number.isFinite(v) && !(Math.abs(v) <= Math.abs(values[best]))) best = i;
  });
  return best;
}
