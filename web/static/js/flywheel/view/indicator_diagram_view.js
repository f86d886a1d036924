/**
 * Panel view that edits a piston engine's indicator diagram in the request: p/p_max at the 11 piston
 * positions x/H = 0, 0.1, …, 1 from top dead centre, for expansion and compression (spec.paths, dotted
 * paths into the request such as "motor.expansion"). Drag a point up or down, or type its value in the
 * table; each edit goes to the model as a new request. The starting values are the scene's (an assumed
 * polytrope, not measured data), and a button puts them back.
 */
import { pathValue } from "../../common/model/dotted_paths.js";
import { element } from "../../common/view/dom.js";
import { formatNumber, plainText, richText } from "../../common/view/notation.js";
import { setAttributes, svgElement } from "../../common/view/svg.js";

const WIDTH = 420;
const HEIGHT = 230;
const PLOT = { left: 46, right: 12, top: 12, bottom: 38 };
const DECIMALS = 3;
const STROKES = ["expansion", "compression"];
const TICKS = [0, 0.2, 0.4, 0.6, 0.8, 1];

const x = (i, count) => PLOT.left + (WIDTH - PLOT.left - PLOT.right) * i / (count - 1);
const y = (ratio) => HEIGHT - PLOT.bottom - (HEIGHT - PLOT.top - PLOT.bottom) * ratio;
const ratioAt = (svgY) => Math.min(1, Math.max(0, (HEIGHT - PLOT.bottom - svgY) / (HEIGHT - PLOT.top - PLOT.bottom)));
const rounded = (value) => Number(value.toFixed(DECIMALS));

export class IndicatorDiagramView {
  constructor(body, spec, { t, lang }, model) {
    this.spec = spec;
    this.t = t;
    this.lang = lang;
    this.model = model;
    const request = model.request();
    this.initial = Object.fromEntries(STROKES.map((s) => [s, pathValue(model.variant.request, spec.paths[s])]));
    this.values = Object.fromEntries(STROKES.map((s) => [s, [...pathValue(request, spec.paths[s])]]));
    this.svg = svgElement("svg", { viewBox: `0 0 ${WIDTH} ${HEIGHT}`, class: "indicator-plot", role: "img",
      "aria-label": plainText(t.indicator_plot) });
    this.#axes();
    this.strokes = Object.fromEntries(STROKES.map((stroke) => [stroke, this.#stroke(stroke)]));
    this.inputs = Object.fromEntries(STROKES.map((s) => [s, []]));
    const reset = element("button", { type: "button", className: "reset", textContent: t.indicator_reset });
    reset.addEventListener("click", () => {
      for (const stroke of STROKES) this.#set(stroke, [...this.initial[stroke]]);
    });
    const note = spec.note ? [element("p", { className: "note", rich: spec.note[lang] })] : [];
    body.append(this.svg, element("p", { className: "legend" },
      ...STROKES.map((s) => element("span", { className: `key ${s}`, textContent: t[`indicator_${s}`] })), reset),
    this.#table(), ...note);
    this.#showAll();
  }

  holds() {
    return true;
  }

  #axes() {
    const grid = svgElement("g", { class: "axes" }, this.svg);
    for (const tick of TICKS) {
      svgElement("line", { x1: PLOT.left, x2: WIDTH - PLOT.right, y1: y(tick), y2: y(tick), class: "grid" }, grid);
      svgElement("text", { x: PLOT.left - 6, y: y(tick), class: "tick y" }, grid).textContent = formatNumber(tick, this.lang, 1);
      const tx = x(tick * 10, 11);
      // 17 units down: the first one's box clear of the y axis's "0,0"
      svgElement("text", { x: tx, y: HEIGHT - PLOT.bottom + 17, class: "tick x" }, grid).textContent = formatNumber(tick, this.lang, 1);
    }
    svgElement("text", { x: (PLOT.left + WIDTH - PLOT.right) / 2, y: HEIGHT - 4, class: "axis-title" }, grid)
      .textContent = this.t.indicator_x;
    svgElement("text", { x: 12, y: (PLOT.top + HEIGHT - PLOT.bottom) / 2, class: "axis-title y",
      transform: `rotate(-90 12 ${(PLOT.top + HEIGHT - PLOT.bottom) / 2})` }, grid).append(richText("p/p_max", { svg: true }));
  }

  /** The polyline and draggable points of one stroke. */
  #stroke(stroke) {
    const layer = svgElement("g", { class: `stroke ${stroke}` }, this.svg);
    const line = svgElement("polyline", { class: "diagram-line" }, layer);
    const points = this.values[stroke].map((_, i) => {
      const point = svgElement("circle", { class: "diagram-point", r: 6, "data-stroke": stroke, "data-index": i }, layer);
      svgElement("title", {}, point).textContent = `${this.t[`indicator_${stroke}`]}, x/H = ${formatNumber(i / 10, this.lang, 1)}`;
      point.addEventListener("pointerdown", (event) => {
        point.setPointerCapture(event.pointerId);
        point.classList.add("dragging");
      });
      point.addEventListener("pointermove", (event) => {
        if (!point.hasPointerCapture(event.pointerId)) return;
        const matrix = this.svg.getScreenCTM().inverse();
        const svgY = new DOMPoint(event.clientX, event.clientY).matrixTransform(matrix).y;
        this.#setPoint(stroke, i, rounded(ratioAt(svgY)));
      });
      point.addEventListener("lostpointercapture", () => point.classList.remove("dragging"));
      return point;
    });
    return { line, points };
  }

  #table() {
    const { t, lang } = this;
    const rows = this.values.expansion.map((_, i) => element("tr", {},
      element("th", { scope: "row", textContent: formatNumber(i / 10, lang, 1) }),
      ...STROKES.map((stroke) => {
        const input = element("input", { type: "number", min: 0, max: 1, step: 0.001,
          "aria-label": `${t[`indicator_${stroke}`]}, x/H = ${formatNumber(i / 10, lang, 1)}` });
        input.addEventListener("change", () => {
          const value = Number(input.value);
          if (input.value !== "" && value >= 0 && value <= 1) this.#setPoint(stroke, i, rounded(value));
          else input.value = this.values[stroke][i];
        });
        this.inputs[stroke].push(input);
        return element("td", {}, input);
      })));
    return element("details", { className: "indicator-table" }, element("summary", { textContent: t.indicator_table }),
      element("table", {}, element("thead", {}, element("tr", {}, element("th", { textContent: "x/H" }),
        ...STROKES.map((s) => element("th", { textContent: t[`indicator_${s}`] })))), element("tbody", {}, ...rows)));
  }

  #setPoint(stroke, i, value) {
    if (this.values[stroke][i] === value) return;
    const values = [...this.values[stroke]];
    values[i] = value;
    this.#set(stroke, values);
  }

  #set(stroke, values) {
    this.values[stroke] = values;
    this.#show(stroke);
    this.model.edit(this.spec.paths[stroke], values);
  }

  #showAll() {
    for (const stroke of STROKES) this.#show(stroke);
  }

  #show(stroke) {
    const values = this.values[stroke];
    const { line, points } = this.strokes[stroke];
    line.setAttribute("points", values.map((v, i) => `${x(i, values.length)},${y(v)}`).join(" "));
    points.forEach((point, i) => setAttributes(point, { cx: x(i, values.length), cy: y(values[i]) }));
    this.inputs[stroke].forEach((input, i) => {
      if (Number(input.value) !== values[i] || input.value === "") input.value = values[i];
    });
  }
}
