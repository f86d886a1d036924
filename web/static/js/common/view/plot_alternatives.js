/**
 * Text alternatives of the plots (WCAG 1.1.1), for readers who do not see them: every Plotly graph on the
 * page gets, from the curves it actually draws (its data after each redraw), a summary read by screen
 * readers (visually hidden; the graph is an image named by its panel's title and described by it: the
 * range of each axis and of each curve) and a button that shows its table of values (up to TABLE_ROWS rows
 * evenly over the curve, the numbers in the reader's language). Graphs are found as they appear, so the
 * scenes' views need not know about this.
 */
import { element } from "./dom.js";
import { formatQuantity } from "./notation.js";

const TABLE_ROWS = 25;
const DIGITS = 4;
const SETTLE_MS = 250;            // redraws while a slider is dragged: describe once they pause
const SUBSCRIPTS = "₀₁₂₃₄₅₆₇₈₉";
const SUPERSCRIPTS = "⁰¹²³⁴⁵⁶⁷⁸⁹";
const ENTITIES = { "&amp;": "&", "&lt;": "<", "&gt;": ">" };
let count = 0;

/** Plotly's pseudo-HTML as plain text: "M<sub>c0</sub>" → "Mc₀" (digits lowered as glyphs), tags dropped. */
export function plotlyPlain(text) {
  return String(text ?? "")
    .replace(/<sub>(.*?)<\/sub>/g, (_, run) => run.replace(/\d/g, (d) => SUBSCRIPTS[d]))
    .replace(/<sup>(.*?)<\/sup>/g, (_, run) => run.replace(/\d/g, (d) => SUPERSCRIPTS[d]))
    .replace(/<br>/g, " ").replace(/<[^>]*>/g, "").replace(/&(amp|lt|gt);/g, (entity) => ENTITIES[entity]);
}

const fill = (template, values) => template.replace(/\{(\w+)\}/g, (_, key) => values[key]);
const finite = (values) => (values ?? []).filter((v) => typeof v === "number" && Number.isFinite(v));

/** The drawn curves of a graph: {name, x, y, xTitle, yTitle} (a polar curve's angle as x, radius as y). */
function curves(graph) {
  const layout = graph.layout ?? {};
  const axisTitle = (axis) => plotlyPlain(axis?.title?.text ?? axis?.title ?? "");
  return (graph.data ?? []).filter((trace) => trace.visible !== false).map((trace, i) => {
    const polar = trace.type === "scatterpolar";
    const yAxis = layout[trace.yaxis && trace.yaxis !== "y" ? `yaxis${trace.yaxis.slice(1)}` : "yaxis"];
    return {
      name: plotlyPlain(trace.name) || `${i + 1}`,
      x: Array.from(polar ? trace.theta ?? [] : trace.x ?? []), y: Array.from(polar ? trace.r ?? [] : trace.y ?? []),
      xTitle: polar ? `${layout.polar?.angularaxis?.title?.text ?? "θ"}, °` : axisTitle(layout.xaxis),
      yTitle: polar ? plotlyPlain(layout.polar?.radialaxis?.title?.text) : axisTitle(yAxis),
    };
  }).filter((curve) => finite(curve.y).length > 0);
}

/** "ось φ, °: от 0 до 360; u₃₁: от −0,1 до 0,1; …" from the drawn curves. */
function summary(list, { t, lang }) {
  const number = (v) => formatQuantity(v, lang, DIGITS);
  const range = (values) => {
    const defined = finite(values);
    return { min: number(Math.min(...defined)), max: number(Math.max(...defined)) };
  };
  const parts = [];
  const xs = list.flatMap((curve) => finite(curve.x));
  if (xs.length && list[0].xTitle) parts.push(fill(t.plot_summary_axis, { axis: list[0].xTitle, ...range(xs) }));
  for (const curve of list) parts.push(fill(t.plot_summary_curve, { name: curve.name, ...range(curve.y) }));
  return `${parts.join("; ")}.`;
}

/** The table of values: the x of the longest curve at TABLE_ROWS points, each curve drawn over the same x. */
function valuesTable(list, title, { t, lang }) {
  const main = list.reduce((longest, curve) => (curve.x.length > longest.x.length ? curve : longest), list[0]);
  const columns = list.filter((curve) => curve.x.length === main.x.length);
  const step = Math.max(1, Math.ceil(main.x.length / TABLE_ROWS));
  const rows = [];
  for (let i = 0; i < main.x.length; i += step) rows.push(i);
  if (rows.at(-1) !== main.x.length - 1) rows.push(main.x.length - 1);
  const number = (v) => (typeof v === "number" && Number.isFinite(v) ? formatQuantity(v, lang, DIGITS) : "—");
  return element("table", { className: "rows" },
    element("caption", { textContent: fill(t.plot_table_caption, { title }) }),
    element("thead", {}, element("tr", {},
      element("th", { scope: "col", textContent: main.xTitle || "x" }),
      ...columns.map((curve) => element("th", { scope: "col", textContent: curve.name })))),
    element("tbody", {}, ...rows.map((i) => element("tr", {},
      element("th", { scope: "row", textContent: number(main.x[i]) }),
      ...columns.map((curve) => element("td", { textContent: number(curve.y[i]) }))))));
}

/** Give one graph its alternative (once) and keep it up to date with the graph's redraws. */
function describe(graph, texts) {
  if (graph.dataset.described) return;
  graph.dataset.described = "yes";
  count += 1;
  const id = `plot-alternative-${count}`;
  const title = () => graph.closest("figure")?.querySelector("h2, h3")?.textContent.trim() ?? "";
  const text = element("p", { className: "visually-hidden", id: `${id}-summary` });
  const frame = element("div", { className: "table-frame plot-table", id: `${id}-table`, tabIndex: 0,
    role: "region", "aria-label": texts.t.plot_table, hidden: true });
  const button = element("button", { type: "button", className: "plot-table-toggle", textContent: texts.t.plot_table,
    "aria-expanded": "false", "aria-controls": frame.id });
  const box = element("div", { className: "plot-alternative" }, text, button, frame);
  (graph.closest(".graph-frame") ?? graph).after(box);
  graph.setAttribute("role", "img");
  graph.setAttribute("aria-describedby", text.id);
  let timer = null;
  const update = () => {
    timer = null;
    const list = curves(graph);
    box.hidden = list.length === 0;
    graph.setAttribute("aria-label", title() || texts.t.plots);
    if (!list.length) return;
    text.textContent = summary(list, texts);
    if (!frame.hidden) frame.replaceChildren(valuesTable(list, title(), texts));
  };
  button.addEventListener("click", () => {
    frame.hidden = !frame.hidden;
    button.setAttribute("aria-expanded", String(!frame.hidden));
    update();
  });
  graph.on?.("plotly_afterplot", () => {
    clearTimeout(timer);
    timer = setTimeout(update, SETTLE_MS);
  });
  update();
}

/** Describe every Plotly graph under root, now and as graphs are added (texts: {t, lang}). */
export function describePlots(root, texts) {
  const scan = () => {
    for (const graph of root.querySelectorAll(".js-plotly-plot")) describe(graph, texts);
  };
  new MutationObserver(scan).observe(root, { childList: true, subtree: true });
  scan();
}
