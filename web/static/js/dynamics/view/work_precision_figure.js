/**
 * The work–precision study (work_precision_study.js) as a Plotly figure; no DOM. Run time (ms) along x
 * and relative error along y, both logarithmic, so lower left is better: less error in less time. Each
 * method is one line with markers through its tolerances, from the loosest to the tightest, every marker
 * labelled with its rtol (markers of one method that fall on one spot, e.g. a method that meets a loose
 * tolerance with the accuracy of a tight one, share one label); the app's own method (a row with `ours`,
 * server/api/messages.py) is drawn bold. The method names come translated from the server.
 */
import { formatQuantity, plotText, toleranceText, unitText } from "../../common/view/notation.js";
import { baseLayout, LEVEL_COLOR, TRACE_COLORS, traceDashes, valueAxis } from "../../common/view/plot_style.js";

const OURS_COLOR = TRACE_COLORS[1];
const COLORS = [TRACE_COLORS[0], TRACE_COLORS[3], TRACE_COLORS[2], TRACE_COLORS[4], LEVEL_COLOR];   // 3:1 and more
const SYMBOLS = ["circle", "square", "diamond", "triangle-up", "cross", "x", "star", "hexagon"];
const HEIGHT = 440;
const SAME_SPOT = { x: 0.08, y: 0.25 };      // decades apart in run time and in error below which markers overlap
const LABELLED_DECADES = 2;      // run times spanning fewer decades get ticks at 2 and 5 of each decade too


/** The rows a log–log chart can place: a positive run time and a positive error (null: not finite). */
export function plottedRows(rows) {
  return rows.filter((row) => row.runtime_ms > 0 && row.error > 0);
}

/** Rows grouped by method, in the order the answer lists the methods, each from the loosest tolerance. */
function byMethod(rows) {
  const methods = new Map();
  for (const row of rows) methods.set(row.method, [...(methods.get(row.method) ?? []), row]);
  for (const points of methods.values()) points.sort((a, b) => b.rtol - a.rtol);
  return methods;
}

/** Marker labels of one method's points: each tolerance, or all tolerances of markers on one spot at the first. */
function toleranceLabels(points, lang) {
  const labels = points.map(() => []);
  let first = 0;
  points.forEach((point, i) => {
    const apart = (key, decades) => Math.abs(Math.log10(point[key] / points[first][key])) > decades;
    if (apart("runtime_ms", SAME_SPOT.x) || apart("error", SAME_SPOT.y)) first = i;
    labels[first].push(toleranceText(point.rtol, lang));
  });
  return labels.map((tolerances) => tolerances.join(", "));
}

/** Ticks of the run-time axis, written out in full: 10, 100, 1000 ms, or 100, 200, 500, … over a short span. */
function timeTicks(times, lang) {
  const [low, high] = [Math.min(...times), Math.max(...times)].map(Math.log10);
  const steps = high - low < LABELLED_DECADES ? [1, 2, 5] : [1];
  const values = [];
  for (let decade = Math.floor(low); decade <= Math.floor(high); decade += 1) {
    values.push(...steps.map((step) => step * 10 ** decade));
  }
  return { tickmode: "array", tickvals: values, ticktext: values.map((value) => formatQuantity(value, lang, 1)) };
}

/** Plotly figure {data, layout} of the study's rows. */
export function workPrecisionFigure(rows, { t, lang }) {
  const ms = unitText("ms", t);
  const plotted = plottedRows(rows);
  let others = 0;
  const methods = [...byMethod(plotted)];
  const dashes = traceDashes(methods.map(([, points]) => (points[0].ours ? "solid" : null)));   // told apart by dash and marker too
  const data = methods.map(([method, points], i) => {
    const ours = points[0].ours;
    const name = plotText(method);
    const color = ours ? OURS_COLOR : COLORS[others++ % COLORS.length];
    return {
      type: "scatter", mode: "lines+markers+text", name: ours ? `<b>${name}</b>` : name,
      x: points.map((row) => row.runtime_ms), y: points.map((row) => row.error),
      text: toleranceLabels(points, lang), textposition: "top right", textfont: { size: 10, color }, cliponaxis: false,
      line: { color, width: ours ? 4 : 1.6, dash: dashes[i] },
      marker: { color, size: ours ? 10 : 7, symbol: SYMBOLS[i % SYMBOLS.length] },
      customdata: points.map((row) => [toleranceText(row.rtol, lang), formatQuantity(row.runtime_ms, lang, 3),
        formatQuantity(row.error, lang, 2)]),
      hovertemplate: `${name}<br>rtol = %{customdata[0]}<br>${t.study_runtime} = %{customdata[1]} ${ms}`
        + `<br>${t.study_error} = %{customdata[2]}<extra></extra>`,
    };
  });
  const base = baseLayout({ lang }, HEIGHT);
  const layout = {
    ...base, margin: { ...base.margin, r: 90 }, hovermode: "closest", showlegend: true,
    xaxis: valueAxis(`${t.study_runtime}, ${ms}`, {
      type: "log", ...timeTicks(plotted.map((row) => row.runtime_ms), lang) }),
    yaxis: valueAxis(t.study_error, { type: "log" }),
  };
  return { data, layout };
}
