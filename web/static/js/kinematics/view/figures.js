/**
 * Plotly figures of the scene's plot panels, built from an answer of POST /api/v1/kinematics; no DOM.
 *   functions       outputs against the crank angle φ in degrees, special positions as dashed lines,
 *                   overlay tables (other λ) as dashed traces
 *   approximations  each exact transfer function with its textbook approximation, one row each
 *   harmonics       amplitudes of the harmonics of u₃₁ (or u′₃₁, harmonics_du31) as bars
 * Values the API leaves null (singular positions) are gaps in the curves.
 */
import { axisTitle, degrees, exactName, formatNumber, formatQuantity, symbol, unitOf, unitText } from "../../common/view/notation.js";
import { baseLayout, GRID, phiAxis, TRACE_COLORS, traceDashes, valueAxis } from "../../common/view/plot_style.js";
import { specialPositions } from "../../common/model/positions_table.js";

const LINK_COLORS = { s: TRACE_COLORS[0], s2: TRACE_COLORS[1] };     // output link 3, intermediate link 2
const APPROXIMATION_COLOR = TRACE_COLORS[2];
const AMPLITUDE_FLOOR = 0.01;   // the amplitude axis reaches at least 1 % of the function's peak: round-off
                                // (a constant u₃₁ at λ = 1) never fills the plot

/** Plotly figure {data, layout} of a panel (content/scenes "panels" entry) for the answer's table. */
export function panelFigure(panel, table, overlays, texts) {
  const spectrum = panel.outputs.find(isSpectrum);
  if (spectrum) return harmonicsFigure(table, table.outputs[spectrum], texts);
  if (panel.outputs.some((name) => name.endsWith("_approx"))) return approximationsFigure(panel, table, texts);
  return functionsFigure(panel, table, overlays, texts);
}

/** "Maximum error: u₃₁ 0,00668 м; u′₃₁ 0,0103 м" for a panel showing approximations, else "". */
export function approximationErrors(panel, table, { t, lang }) {
  const errors = table.outputs.approx_error;
  if (!panel.outputs.includes("approx_error") || !errors) return "";
  const parts = exactOutputs(panel).map((name) =>
    `${symbol(name)} ${formatNumber(errors[name], lang)} ${unitText(unitOf(table.mechanism, name), t)}`);
  return `${t.max_error}: ${parts.join("; ")}`;
}

/** True for an output that is a spectrum (harmonics of u₃₁ or of u′₃₁), drawn as bars without a cursor. */
export function isSpectrum(name) {
  return name === "harmonics" || name === "harmonics_du31";
}

/**
 * Eremyants (2.17)'s claim on the 4φ harmonic of u′₃₁, checked: "A₄/A₁ = 1,01 %: the book says < 0,5 %
 * (printed 1/(8λ³) = 0,463 %); corrected 1/(4λ³) = 0,926 %", or "" without the claim (not a central crank-slider).
 */
export function harmonicClaim(panel, table, { t, lang }) {
  const claim = panel.outputs.includes("harmonics_du31") ? table.outputs.harmonics_du31?.claim : undefined;
  if (!claim) return "";
  const percent = (value) => `${formatQuantity(100 * value, lang, 3)} %`;
  return t.harmonic_claim.replace("{computed}", percent(claim.computed)).replace("{below}", percent(claim.claimed_below))
    .replace("{printed}", percent(claim.printed)).replace("{corrected}", percent(claim.corrected));
}

/** The exact position and transfer functions a panel shows (not approximations, errors or spectra). */
export function exactOutputs(panel) {
  return panel.outputs.filter((name) => name === exactName(name) && symbol(name));
}

function color(name) {
  return LINK_COLORS[["s", "u31", "du31"].includes(exactName(name)) ? "s" : "s2"];
}

/** Dashed vertical lines at the special positions, labelled at the bottom with their kinds (one label per angle). */
function specialMarks(table, { t }) {
  const byAngle = new Map();
  for (const sp of specialPositions(table)) {
    const x = Math.round(degrees(sp.phi) * 10) / 10;
    byAngle.set(x, [...new Set([...(byAngle.get(x) ?? []), t[sp.kind]])]);
  }
  const angles = [...byAngle.keys()];
  return {
    shapes: angles.map((x) => ({
      type: "line", xref: "x", yref: "paper", x0: x, x1: x, y0: 0, y1: 1,
      line: { color: "#8a96a6", width: 1, dash: "dash" }, layer: "below" })),
    annotations: angles.map((x) => ({
      xref: "x", yref: "paper", x, y: 0, text: byAngle.get(x).join("<br>"), showarrow: false,
      textangle: -90, xanchor: "left", yanchor: "bottom", font: { size: 10, color: "#5d6978" } })),
  };
}

function functionsFigure(panel, table, overlays, texts) {
  const mechanism = table.mechanism;
  const outputs = exactOutputs(panel);
  const units = outputs.map((name) => unitOf(mechanism, name));
  const secondAxis = new Set(units).size > 1;         // e.g. slider travel in m, rod angle in rad
  const axisOf = (i) => (secondAxis && i > 0 ? "y2" : "y");
  const x = table.phi.map(degrees);
  const tables = [...overlays].filter(([, answer]) => answer.ok).sort(([a], [b]) => a - b);
  // every curve its own dash: the outputs, then each overlay value of λ in its output's colour
  const dashes = traceDashes(Array((1 + tables.length) * outputs.length).fill(null));
  const data = outputs.map((name, i) => ({
    type: "scatter", mode: "lines", x, y: table.outputs[name], yaxis: axisOf(i), connectgaps: false,
    name: legendName(name, texts), line: { color: color(name), width: 2, dash: dashes[i] },
    hovertemplate: `${symbol(name)} = %{y}<extra></extra>` }));
  tables.forEach(([lambda, answer], k) => {
    const lambdaText = `λ = ${formatNumber(lambda, texts.lang)}`;
    outputs.forEach((name, i) => data.push({
      type: "scatter", mode: "lines", x: answer.data.phi.map(degrees), y: answer.data.outputs[name],
      yaxis: axisOf(i), connectgaps: false, opacity: 0.75,
      line: { color: color(name), width: 1.5, dash: dashes[(k + 1) * outputs.length + i] },
      name: lambdaText, legendgroup: lambdaText, showlegend: i === 0,
      hovertemplate: `${symbol(name)} (${lambdaText}) = %{y}<extra></extra>` }));
  });
  const layout = {
    ...baseLayout(texts, 260), ...specialMarks(table, texts), showlegend: data.length > 1,
    xaxis: phiAxis(table.cycle, texts),
    yaxis: valueAxis(axisTitle(mechanism, secondAxis ? outputs.slice(0, 1) : outputs, texts.t)),
  };
  if (secondAxis) {
    layout.yaxis2 = valueAxis(axisTitle(mechanism, outputs.slice(1), texts.t),
      { overlaying: "y", side: "right", showgrid: false, zeroline: false, tickmode: "auto" });
    layout.margin = { ...layout.margin, r: 64 };
  }
  return { data, layout };
}

function legendName(name, { t }) {
  if (name === "s") return t.output_s;
  if (name === "s2") return `${symbol(name)} — ${t.output_s2}`;
  return symbol(name);
}

function approximationsFigure(panel, table, texts) {
  const outputs = exactOutputs(panel);
  const x = table.phi.map(degrees);
  const gap = 0.12;
  const rowHeight = (1 - gap * (outputs.length - 1)) / outputs.length;
  const layout = { ...baseLayout(texts, 200 + 150 * outputs.length), ...specialMarks(table, texts), showlegend: true };
  const data = [];
  outputs.forEach((name, row) => {
    const axis = row ? `y${row + 1}` : "y";
    const top = 1 - row * (rowHeight + gap);
    layout[row ? `yaxis${row + 1}` : "yaxis"] = valueAxis(axisTitle(table.mechanism, [name], texts.t),
      { domain: [top - rowHeight, top] });
    for (const [output, style, label] of [
      [name, { color: LINK_COLORS.s, width: 2 }, texts.t.exact],
      [`${name}_approx`, { color: APPROXIMATION_COLOR, width: 2, dash: "dash" }, texts.t.approximate]]) {
      data.push({ type: "scatter", mode: "lines", x, y: table.outputs[output], yaxis: axis, connectgaps: false,
        name: label, legendgroup: label, showlegend: row === 0, line: style,
        hovertemplate: `${symbol(name)} ${label} = %{y}<extra></extra>` });
    }
  });
  layout.xaxis = { ...phiAxis(table.cycle, texts), anchor: outputs.length > 1 ? `y${outputs.length}` : "y" };
  return { data, layout };
}

function harmonicsFigure(table, spectrum, texts) {
  const { t } = texts;
  const unit = unitText(unitOf(table.mechanism, spectrum.output), t);
  const peak = Math.max(...(table.outputs[spectrum.output] ?? spectrum.amplitude).map((v) => Math.abs(v ?? 0)));
  const top = 1.1 * Math.max(...spectrum.amplitude, AMPLITUDE_FLOOR * peak);
  return {
    data: [{ type: "bar", x: spectrum.k, y: spectrum.amplitude, marker: { color: LINK_COLORS.s },
      hovertemplate: `A<sub>%{x}</sub> = %{y} ${unit}<extra></extra>` }],
    layout: {
      ...baseLayout(texts, 260), showlegend: false,
      xaxis: { title: { text: t.harmonic_number }, dtick: 1, fixedrange: true, gridcolor: GRID },
      yaxis: valueAxis(`${t.amplitude} A<sub>k</sub>(${symbol(spectrum.output)}), ${unit}`,
        { range: [0, top], autorange: false }),
    },
  };
}
