/**
 * Wittenbauer's energy–mass diagram (lecture 10) as a Plotly figure, from an answer of /flywheel; no DOM.
 * x is group II's reduced inertia I_II(φ) (kg·m²), y the work of all forces A_Σ(φ) = ΔT(φ) (J): over a
 * cycle the point (I_II, A_Σ) runs round a closed curve. The two tangents with slopes ω²_max/2 and
 * ω²_min/2 are y = b + slope·x; they cut the energy axis (I_II = 0) at a (b_up) and b (b_low), and meet
 * at O′ = (origin_inertia, origin_energy), where origin_inertia = −I_I. O′ is usually far below and to
 * the left: the axes then keep the curve and the segment ab in view and an arrow points towards O′.
 */
import { pathValue } from "../../common/model/dotted_paths.js";
import { formatQuantity, plotText, unitText } from "../../common/view/notation.js";
import { sampleAt } from "../../common/model/phi_samples.js";
import { baseLayout, GRID, TRACE_COLORS, valueAxis } from "../../common/view/plot_style.js";

const CURVE_COLOR = TRACE_COLORS[0];
const TANGENT_COLORS = { up: TRACE_COLORS[1], low: TRACE_COLORS[3] };
const TANGENT_DASHES = { up: "dash", low: "dot" };     // told apart without their colours too
const SEGMENT_COLOR = TRACE_COLORS[2];
const ORIGIN_REACH = 3;     // O′ is drawn when it lies within this many spans of the curve from it
const MARGIN = 0.12;        // of the curve's span, around it

const span = (values) => [Math.min(...values), Math.max(...values)];

/** The closed curve's points [x], [y] and the tangency points, from the answer's data. */
export function energyMass(panel, data) {
  const x = pathValue(data, panel.x);
  const y = pathValue(data, panel.y);
  const diagram = pathValue(data, panel.diagram);
  const at = (phi) => [sampleAt(data.phi, x, phi), sampleAt(data.phi, y, phi)];
  return { x, y, diagram, touch: { up: at(diagram.phi_up), low: at(diagram.phi_low) } };
}

/** True if the answer's O′ is near enough to the curve to draw both to one scale. */
export function originInView({ x, y, diagram }) {
  const [[x0, x1], [y0, y1]] = [span(x), span(y)];
  const [dx, dy] = [Math.max(x1, 0) - Math.min(x0, 0), y1 - y0];
  return diagram.origin_inertia >= Math.min(x0, 0) - ORIGIN_REACH * dx
    && diagram.origin_energy >= y0 - ORIGIN_REACH * dy && diagram.origin_energy <= y1 + ORIGIN_REACH * dy;
}

/** Plotly figure {data, layout} of a wittenbauer panel. */
export function wittenbauerFigure(panel, data, texts) {
  const { t, lang } = texts;
  const diagram = energyMass(panel, data);
  const { x, y, touch } = diagram;
  const { b_up: up, b_low: low, slope_up: slopeUp, slope_low: slopeLow, origin_inertia: ox, origin_energy: oy } = diagram.diagram;
  const withOrigin = originInView(diagram);
  const [xLow, xHigh] = [Math.min(0, ...x, ...(withOrigin ? [ox] : [])), Math.max(0, ...x)];
  const xEnd = xHigh + MARGIN * (xHigh - xLow);
  const xStart = withOrigin ? xLow - MARGIN * (xHigh - xLow) : 0;
  const ys = [...y, up, low, ...(withOrigin ? [oy] : [])];
  const [yLow, yHigh] = span(ys);
  const yMargin = MARGIN * (yHigh - yLow);
  const lineFrom = withOrigin ? ox : 0;
  const energy = unitText("J", t);
  const number = (v) => formatQuantity(v, lang, 4);
  const tangent = (b, slope, key, name) => ({
    type: "scatter", mode: "lines", name, x: [lineFrom, xEnd], y: [b + slope * lineFrom, b + slope * xEnd],
    line: { color: TANGENT_COLORS[key], width: 1.5, dash: TANGENT_DASHES[key] }, hoverinfo: "skip" });
  const traces = [
    { type: "scatter", mode: "lines", name: plotText(t.wittenbauer_curve), x, y, line: { color: CURVE_COLOR, width: 2.5 },
      hovertemplate: `${plotText(t.symbol_inertia_group_II)} = %{x}, ${plotText("A_Σ")} = %{y}<extra></extra>` },
    tangent(up, slopeUp, "up", plotText(t.wittenbauer_tangent_up)),
    tangent(low, slopeLow, "low", plotText(t.wittenbauer_tangent_low)),
    { type: "scatter", mode: "markers", x: [touch.up[0], touch.low[0]], y: [touch.up[1], touch.low[1]],
      marker: { color: [TANGENT_COLORS.up, TANGENT_COLORS.low], size: 8, symbol: "circle-open", line: { width: 2 } },
      showlegend: false, hoverinfo: "skip" },
    { type: "scatter", mode: "lines+markers+text", name: `ab = ${number(up - low)} ${energy}`, x: [0, 0], y: [up, low],
      text: ["a", "b"], textposition: ["top right", "bottom right"], textfont: { size: 14, color: SEGMENT_COLOR },
      line: { color: SEGMENT_COLOR, width: 5, dash: "dashdot" }, marker: { color: SEGMENT_COLOR, size: 8 },
      hovertemplate: `%{text}: %{y} ${energy}<extra></extra>` },
  ];
  if (withOrigin) {
    traces.push({ type: "scatter", mode: "markers+text", x: [ox], y: [oy], text: ["O′"], textposition: "top left",
      marker: { color: "#1d2733", size: 8 }, showlegend: false,
      hovertemplate: `O′: I = %{x}, ΔT = %{y}<extra></extra>` });
  }
  return {
    data: traces,
    layout: {
      ...baseLayout(texts, 380), hovermode: "closest", showlegend: true,
      xaxis: { title: { text: plotText(panel.x_title[lang]) }, range: [xStart, xEnd], fixedrange: true, ticks: "outside",
        gridcolor: GRID, zerolinecolor: "#7d8998", zerolinewidth: 1.5, exponentformat: "power", hoverformat: ".4g" },
      yaxis: valueAxis(plotText(panel.y_title[lang]), { range: [yLow - yMargin, yHigh + yMargin] }),
      annotations: withOrigin ? [] : [{
        xref: "paper", yref: "paper", x: 0, y: 0, ax: 70, ay: -45, showarrow: true, arrowhead: 2, arrowsize: 1.2,
        arrowwidth: 1.5, arrowcolor: "#1d2733", xanchor: "left", yanchor: "bottom", align: "left",
        text: `O′ (${plotText(t.wittenbauer_off_plot)})`, font: { size: 11 }, bgcolor: "rgba(255,255,255,0.85)" }],
    },
  };
}
