/**
 * Panel view of Merzalov's construction as the drawing sheet has it (Lecture 10 §10.6, (L15)–(L24)): one SVG whose
 * user unit is the sheet's millimetre, three diagrams over the cycle's base b drawn to the server's scales.
 *   M_д(φ)  the driving moment's ordinates y_M, the mean ordinate of each interval carried to the ordinate axis,
 *           the pole P at k₁ to the left and its rays (the graphical integration, (L19));
 *   A(φ)    the works: y_Aд (the integral curve, its chords parallel to the rays), y_Aс and y_A = y_Aд + y_Aс;
 *   ΔT_I(φ) y_ΔTI = y_A − y*_TII (L21)–(L22), its swing y_ΔTImax, and the same curve read as Δω in μ_ω (L24).
 * Every number comes from the answer (merzalov_sheet: scales, ordinates and drawing); the page only draws.
 * Each ordinate drawn is a line marked data-key (the ordinates table's column) and data-position.
 */
import { pathValue } from "../../common/model/dotted_paths.js";
import { element } from "../../common/view/dom.js";
import { formatNumber, formatQuantity, plainText, setRichText } from "../../common/view/notation.js";
import { svgElement } from "../../common/view/svg.js";

const LEFT = 64;            // mm from the sheet's left edge to the ordinate axis (the pole stands k₁ to its left)
const RIGHT = 16;           // mm beyond the base
const TITLE = 9;            // mm above a diagram for its title and scale
const BELOW = 9;            // mm below a diagram for the positions' numbers and the abscissa's scale
const FONT = 3.5;           // mm, the sheet's lettering
const INK = { main: "#1b4f8a", second: "#b5532a", thin: "#666", axis: "#222" };

export class MerzalovSheetView {
  constructor(body, spec, { t, lang }) {
    this.spec = spec;
    this.t = t;
    this.lang = lang;
    this.svg = svgElement("svg", { class: "merzalov-sheet", role: "img", "aria-label": plainText(spec.words.sheet[lang]) });
    this.svg.style.width = "100%";
    this.svg.style.height = "auto";
    this.svg.style.maxWidth = "1000px";
    const note = spec.note ? [element("p", { className: "note", rich: spec.note[lang] })] : [];
    body.append(this.svg, ...note);
  }

  holds(data) {
    return Boolean(pathValue(data, this.spec.path)?.drawing);
  }

  show(data) {
    const sheet = pathValue(data, this.spec.path);
    this.scales = Object.fromEntries(sheet.scales.map((row) => [row.symbol, row]));
    this.rows = sheet.ordinates;
    this.drawing = sheet.drawing;
    this.svg.replaceChildren();
    const width = LEFT + this.drawing.base + RIGHT;
    let top = 0;
    for (const diagram of [this.#moment, this.#works, this.#energy]) top = diagram.call(this, top);
    this.svg.setAttribute("viewBox", `0 0 ${width} ${top}`);
  }

  /** "μ_M = 0,05 мм/(Н·м)": a scale row of the answer as written on the sheet. */
  #scale(symbol) {
    const row = this.scales[symbol];
    return `${symbol} = ${formatQuantity(row.value, this.lang, 3)} ${this.t[`sheet_unit_${row.unit}`] ?? ""}`;
  }

  #word(key) {
    return this.spec.words[key][this.lang];
  }

  #text(parent, x, y, text, { anchor = "start", size = FONT, color = INK.axis, cls = "" } = {}) {
    const node = svgElement("text", { x, y, "font-size": size, fill: color, "text-anchor": anchor, class: cls }, parent);
    return setRichText(node, text);
  }

  #line(parent, x1, y1, x2, y2, color, stroke = 0.3, extra = {}) {
    return svgElement("line", { x1, y1, x2, y2, stroke: color, "stroke-width": stroke, ...extra }, parent);
  }

  #polyline(parent, xs, ys, color, stroke, extra = {}) {
    return svgElement("polyline", { points: xs.map((x, i) => `${x},${ys[i]}`).join(" "), fill: "none",
      stroke: color, "stroke-width": stroke, ...extra }, parent);
  }

  /**
   * One diagram's frame below ``top``: its title with the ordinate's scale, the abscissa with the positions'
   * numbers and μ_φ; returns {group, X(mm), Y(mm), bottom} with Y(y) the sheet's y (mm, up) on the page.
   */
  #frame(top, key, title, values) {
    const group = svgElement("g", { class: `sheet-diagram ${key}` }, this.svg);
    const high = Math.max(0, ...values) + 3;
    const low = Math.min(0, ...values) - 3;
    const axisY = top + TITLE + high;
    const X = (x) => LEFT + x;
    const Y = (y) => axisY - y;
    this.#text(group, 2, top + FONT + 1, title, { cls: "diagram-title" });
    const base = this.drawing.base;
    this.#line(group, X(0), Y(high), X(0), Y(low), INK.axis, 0.35, { class: "ordinate-axis" });
    this.#line(group, X(0), axisY, X(base + 6), axisY, INK.axis, 0.35, { class: "abscissa" });
    this.drawing.x.forEach((x, k) => {
      this.#line(group, X(x), axisY - 0.8, X(x), axisY + 0.8, INK.axis, 0.3);
      this.#text(group, X(x) + 0.6, axisY + FONT + 0.4, String(k), { size: FONT * 0.75, color: INK.thin });
    });
    const bottom = axisY - low + BELOW;
    this.#text(group, X(base + 6), bottom - 2, `φ_1, ${this.#scale("μ_φ")}`, { anchor: "end", cls: "axis-scale x" });
    return { group, X, Y, axisY, bottom };
  }

  #ordinates(frame, key, color) {
    this.rows.forEach((row, k) => {
      const x = frame.X(this.drawing.x[k]);
      this.#line(frame.group, x, frame.axisY, x, frame.Y(row[key]), color, 0.25,
        { class: "ordinate", "data-key": key, "data-position": row.position });
    });
  }

  #curve(frame, key, color, stroke, extra = {}) {
    const xs = this.drawing.x.map(frame.X);
    return this.#polyline(frame.group, xs, this.rows.map((row) => frame.Y(row[key])), color, stroke,
      { class: `curve ${key}`, ...extra });
  }

  /** M_д(φ) in μ_M, the intervals' mean ordinates, the pole and its rays. */
  #moment(top) {
    const rays = this.drawing.rays;
    const values = [...this.rows.map((row) => row.y_M), ...rays.map((ray) => ray.y_mean)];
    const frame = this.#frame(top, "moment", `${this.#word("moment")}: y_M, ${this.#scale("μ_M")}`, values);
    const { group, X, Y, axisY } = frame;
    this.#ordinates(frame, "y_M", INK.thin);
    const pole = -this.drawing.pole;
    for (const ray of rays) {
      this.#line(group, X(ray.x_from), Y(ray.y_mean), X(ray.x_to), Y(ray.y_mean), INK.second, 0.3,
        { class: "mean-ordinate", "data-interval": ray.interval });
      this.#line(group, X(0), Y(ray.y_mean), X(0.5 * (ray.x_from + ray.x_to)), Y(ray.y_mean), INK.second, 0.15,
        { "stroke-dasharray": "1 1" });
      this.#line(group, X(pole), axisY, X(0), Y(ray.y_mean), INK.second, 0.2, { class: "ray", "data-interval": ray.interval });
    }
    this.#curve(frame, "y_M", INK.main, 0.6);
    this.#line(group, X(pole), axisY, X(0), axisY, INK.axis, 0.35, { class: "pole-distance" });
    svgElement("circle", { cx: X(pole), cy: axisY, r: 0.9, fill: INK.axis, class: "pole" }, group);
    this.#text(group, X(pole) - 1.2, axisY - 1.5, "P", { anchor: "end" });
    this.#text(group, X(pole) - 1.5, axisY + FONT + 0.5, `k_1 = ${formatNumber(this.drawing.pole, this.lang, 0)} ${this.t.sheet_unit_mm}`,
      { anchor: "end", size: FONT * 0.85, cls: "axis-scale pole" });
    return frame.bottom;
  }

  /** The works in μ_A: y_Aд by the rays' chords, y_Aс, y_A = y_Aд + y_Aс. */
  #works(top) {
    const keys = ["y_A_d", "y_A_c", "y_A"];
    const values = this.rows.flatMap((row) => keys.map((key) => row[key]));
    const frame = this.#frame(top, "works", `${this.#word("works")}: ${this.#scale("μ_A")} = μ_M μ_φ/k_1`, values);
    this.#ordinates(frame, "y_A", INK.thin);
    this.#curve(frame, "y_A_d", INK.second, 0.4);
    this.#curve(frame, "y_A_c", INK.second, 0.4, { "stroke-dasharray": "2 1" });
    this.#curve(frame, "y_A", INK.main, 0.6);
    const last = this.rows.length - 1;
    const labelAt = (key) => frame.Y(this.rows[last][key]);
    const names = Object.fromEntries(keys.map((key, i) => [key, this.spec.words.work_names[this.lang][i]]));
    const placed = [];
    for (const key of keys) {            // each curve named at its end, the names kept apart vertically
      let y = labelAt(key) + 1.2;
      while (placed.some((other) => Math.abs(other - y) < FONT)) y += FONT;
      placed.push(y);
      this.#text(frame.group, frame.X(this.drawing.base) + 5, y, names[key], { size: FONT * 0.85 });   // beyond "12"
    }
    return frame.bottom;
  }

  /** ΔT_I = A − T_II in μ_A, its swing, and the same ordinates read as Δω in μ_ω. */
  #energy(top) {
    const values = this.rows.map((row) => row.y_dTI);
    const frame = this.#frame(top, "energy", `${this.#word("energy")}: y_ΔTI = y_A − y*_TII, ${this.#scale("μ_A")}`, values);
    const { group, X, Y } = frame;
    this.#ordinates(frame, "y_dTI", INK.thin);
    this.#curve(frame, "y_dTI", INK.main, 0.6);
    const high = Math.max(...values);
    const low = Math.min(...values);
    const end = X(this.drawing.base + 4);
    this.#line(group, X(0), Y(high), end, Y(high), INK.thin, 0.2, { "stroke-dasharray": "1.5 1" });
    this.#line(group, X(0), Y(low), end, Y(low), INK.thin, 0.2, { "stroke-dasharray": "1.5 1" });
    this.#line(group, end - 2, Y(high), end - 2, Y(low), INK.axis, 0.3, { class: "swing" });
    this.#text(group, end - 3.5, Y(low) - 1.5, `${this.#scale("y_ΔTImax")} → ${this.#scale("ΔT_Imax")}`,
      { anchor: "end", size: FONT * 0.85, cls: "swing-label" });
    this.#text(group, 2, frame.bottom - 2, `${this.#word("speed")}: ${this.#scale("μ_ω")} (L24)`, { cls: "axis-scale omega" });
    return frame.bottom;
  }
}
