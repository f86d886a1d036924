/**
 * The look shared by every Plotly figure of the app: fonts, grid, legend above the plot, numbers
 * written the way the reader's language writes them, and the crank-angle axis in degrees.
 */
import { degrees, plotSeparators } from "./notation.js";

const FONT = 'system-ui, -apple-system, "Segoe UI", Roboto, "Noto Sans", "DejaVu Sans", sans-serif';
const TURN = 2 * Math.PI;
export const GRID = "#e4e8ee";

/** Layout of a figure height pixels high, before its axes. */
export function baseLayout({ lang }, height) {
  return {
    height, margin: { l: 64, r: 18, t: 30, b: 44 }, separators: plotSeparators(lang),
    font: { family: FONT, size: 12, color: "#1d2733" },
    paper_bgcolor: "rgba(0,0,0,0)", plot_bgcolor: "#ffffff",
    legend: { orientation: "h", x: 0, xanchor: "left", y: 1.02, yanchor: "bottom", font: { size: 11 } },
    hovermode: "x", hoverlabel: { namelength: -1 },
  };
}

/** The crank angle φ in degrees over one cycle (rad): ticks every 45°, or every 90° for a 4π cycle. */
export function phiAxis(cycle, { t }) {
  return {
    title: { text: `${t.crank_angle}, °` }, range: [0, degrees(cycle)], autorange: false, fixedrange: true,
    tick0: 0, dtick: cycle > TURN * 1.01 ? 90 : 45, ticks: "outside", gridcolor: GRID, zeroline: false,
  };
}

/**
 * A value axis titled title ("u₃₁, м"), with extra Plotly axis properties. Hovered values ("%{y}" in a
 * hovertemplate) are written by the axis, 4 significant digits, so Plotly gives them the language's
 * decimal separator and a true minus sign like the ticks.
 */
export function valueAxis(title, extra = {}) {
  return { title: { text: title }, fixedrange: true, automargin: true, gridcolor: GRID,
    zerolinecolor: "#aab4c2", exponentformat: "power", hoverformat: ".4g", ...extra };
}

/**
 * Trace colours, each at least 3:1 against the plot's white (WCAG 2.1, 1.4.11 non-text contrast; the
 * ratios 8,7 · 5,5 · 3,7 · 5,1 · 6,9, checked from the drawn curves by tests/browser/test_accessibility.py):
 * blue, red, dark orange, green, violet. LEVEL_COLOR for level lines (a mean, 5,6:1).
 */
export const TRACE_COLORS = ["#1f4e79", "#b5442f", "#c07400", "#2e7d4f", "#6a4c93"];
export const LEVEL_COLOR = "#5d6978";

/**
 * Dash patterns (Plotly's names, then two of our own), so that the curves of one plot differ by dash as
 * well as by colour and are told apart in grey print and by readers who do not see the colours.
 */
const TRACE_DASHES = ["solid", "dash", "dot", "dashdot", "longdash", "longdashdot", "8px,3px,2px,3px,2px,3px", "2px,5px"];
export const LEVEL_DASH = "longdash";

/**
 * One dash per curve of a plot, all different: the requested ones (a name of TRACE_DASHES, or null for
 * "any") first, each kept if no earlier curve has it, then every other curve the first pattern still free.
 */
export function traceDashes(requested) {
  const taken = new Set();
  const dashes = requested.map((dash) => {
    if (dash === null || taken.has(dash)) return null;
    taken.add(dash);
    return dash;
  });
  return dashes.map((dash) => {
    if (dash !== null) return dash;
    const free = TRACE_DASHES.find((candidate) => !taken.has(candidate)) ?? "solid";
    taken.add(free);
    return free;
  });
}

const PLOTLY_CONFIG = { displayModeBar: false, responsive: true };

/**
 * Draw a figure into its graph (Plotly.react, resizing with the window). The graph's box gets the figure's
 * height: on a window resize Plotly forgets layout.height and takes the box's, which without a height of
 * its own would be 0 px once a redraw has made the plot fill the box.
 */
export function drawFigure(graph, { data, layout }) {
  if (Number.isFinite(layout.height)) graph.style.height = `${layout.height}px`;
  return Plotly.react(graph, data, layout, PLOTLY_CONFIG);
}
